"""Reading an exemplar SVG into kinds, motif instances and an input region (almeraj2013 §3.1).

This is the only module that imports svgelements; it is used for what it does well — parsing path
data, shapes, transforms and lengths — while the document structure (``<symbol>``, ``<use>``,
groups, inherited style) is walked here with ElementTree, because svgelements ignores a symbol's
``viewBox`` and expands ``<use>`` elements, losing which kind an instance is.

Two kinds of exemplar are read:

* ``<symbol>``/``<use>`` exemplars: every ``<use>`` at any depth is a motif instance whose kind is
  the referenced element (with its ``viewBox`` mapping, and any skew, non-uniform scale or mirror of
  the instance folded into the kind); transforms of groups, of the ``<use>`` and its ``x``/``y``
  are composed and split into position, rotation and uniform scale.
* plain drawings: every top-level shape or group (inside Inkscape layers and lone wrapper groups)
  is a motif; motifs identical up to translation and rotation share a kind, and a ``<symbol>`` is
  generated for each kind in the output.

The input region is the element with ``id="region"``, else the root ``viewBox``, else
``width``/``height``, else the motifs' bounds.  Nothing outside the file is ever fetched.
"""

from __future__ import annotations

import copy
import math
import re
import warnings
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
import shapely.affinity
import svgelements as se

from .arrangement import Arrangement
from .errors import ExemplarError
from .footprint import Prototype

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"

SHAPES = {"path", "rect", "circle", "ellipse", "line", "polyline", "polygon"}
CONTAINERS = {"g", "a", "switch"}
NOT_RENDERED = {
    "defs", "symbol", "clipPath", "mask", "marker", "pattern", "metadata", "title", "desc",
    "style", "script", "linearGradient", "radialGradient", "filter", "foreignObject", "view",
}  # fmt: skip
INHERITED = (
    "fill", "stroke", "stroke-width", "stroke-linecap", "stroke-linejoin", "stroke-miterlimit",
    "fill-rule", "visibility", "color", "fill-opacity", "stroke-opacity",
)  # fmt: skip
INITIAL = {
    "fill": "black", "stroke": "none", "stroke-width": "1", "stroke-linecap": "butt",
    "stroke-linejoin": "miter", "stroke-miterlimit": "4", "visibility": "visible",
}  # fmt: skip

#: Relative tolerance for deciding that two plain motifs are the same shape up to rotation.
SHAPE_TOLERANCE = 0.03
#: Chord tolerance for flattening curves, as a fraction of the element's size.
FLATNESS = 0.002
#: Decimals kept for a kind's local origin, so output transforms reproduce it exactly.
ORIGIN_DECIMALS = 4


@dataclass(frozen=True, eq=False)
class Kind:
    """A motif kind (almeraj2013's primitive shape S_i) and how to draw it.

    The kind's local frame has its origin at the footprint centroid.  An instance at ``xy`` with
    ``angle`` and ``scale`` is written as
    ``<use href="#{href}" transform="translate(xy) rotate(angle) scale(scale)
    translate(offset) matrix(residual)" {use_attrs}/>``.

    Attributes
    ----------
    name : str
        Human-readable name (the symbol id, with a suffix for variants).
    href : str
        Id of the element the output ``<use>`` references.
    prototype : Prototype
        Footprint in the local frame.
    offset : (2,) float array
        Translation from the residual frame to the local frame (minus the centroid).
    residual : (2, 2) float array
        Linear part that is not rotation or uniform scale (identity for most kinds).
    use_attrs : tuple of (name, value)
        Attributes the output ``<use>`` must carry (viewport size, inherited style).
    """

    name: str
    href: str
    prototype: Prototype
    offset: np.ndarray
    residual: np.ndarray
    use_attrs: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True, eq=False)
class Exemplar:
    """A parsed exemplar.

    Attributes
    ----------
    source : str
        File name used in messages.
    kinds : tuple of Kind
    motifs : Arrangement
        The instances whose centroid lies in the region.
    region : shapely Polygon
        The input region, user units.
    defs : tuple of ET.Element
        Elements the output copies into its ``<defs>`` (referenced symbols and what they reference,
        or the generated symbols of a plain drawing), in a stable order.
    warnings : tuple of str
        Non-fatal problems (overlapping motifs, ignored elements …).
    """

    source: str
    kinds: tuple[Kind, ...]
    motifs: Arrangement
    region: shapely.Polygon
    defs: tuple[ET.Element, ...]
    warnings: tuple[str, ...] = ()

    @property
    def prototypes(self) -> list[Prototype]:
        return [k.prototype for k in self.kinds]


# ----------------------------------------------------------------------------- entry points


def read_exemplar(path: str | Path) -> Exemplar:
    """Read an exemplar SVG file.

    Raises
    ------
    ExemplarError
        With the file name and a one-line description of what is wrong.
    """
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise ExemplarError(f"cannot read file ({exc.strerror or exc})", source=str(path)) from None
    return parse_exemplar(data, source=str(path))


def parse_exemplar(data: bytes | str, *, source: str = "<exemplar>") -> Exemplar:
    """Parse exemplar SVG text (see :func:`read_exemplar`)."""
    if isinstance(data, str):
        data = data.encode()
    try:
        root = ET.fromstring(data)
    except ET.ParseError as exc:
        raise ExemplarError(f"not a well-formed XML file ({exc})", source=source) from None
    if _local(root.tag) != "svg" or _ns(root.tag) not in ("", SVG_NS):
        raise ExemplarError(f"not an SVG document (root element is <{_local(root.tag)}>)", source=source)
    return _Reader(root, source).read()


# ----------------------------------------------------------------------------- helpers


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _ns(tag: str) -> str:
    return tag[1:].split("}", 1)[0] if isinstance(tag, str) and tag.startswith("{") else ""


def _is_svg(el: ET.Element) -> bool:
    return isinstance(el.tag, str) and _ns(el.tag) in ("", SVG_NS)


def _href(el: ET.Element) -> str | None:
    """The element's ``href`` or ``xlink:href`` (SVG 2 ``href`` wins), or None."""
    for key in ("href", f"{{{XLINK_NS}}}href"):
        if key in el.attrib:
            return el.attrib[key].strip()
    for key, value in el.attrib.items():  # prefixes declared ad hoc still resolve to xlink
        if key.endswith("}href"):
            return value.strip()
    return None


def _style(el: ET.Element, parent: dict[str, str]) -> dict[str, str]:
    """Effective presentation properties of ``el`` given its parent's (CSS cascade, simplified)."""
    own: dict[str, str] = {}
    for key in (*INHERITED, "display", "opacity"):
        if key in el.attrib:
            own[key] = el.attrib[key].strip()
    for decl in el.attrib.get("style", "").split(";"):
        if ":" in decl:
            key, value = decl.split(":", 1)
            own[key.strip()] = value.replace("!important", "").strip()
    style = {k: v for k, v in parent.items() if k in INHERITED}
    style.update({k: v for k, v in own.items() if v != "inherit"})
    return style


def _hidden(style: dict[str, str]) -> bool:
    return (
        style.get("display") == "none"
        or style.get("visibility") in ("hidden", "collapse")
        or _number(style.get("opacity", "1"), 1.0) <= 0
    )


def _painted(value: str | None) -> bool:
    return value is not None and value.strip() not in ("none", "transparent")


def _number(text: str | None, default: float) -> float:
    if text is None:
        return default
    try:
        return float(se.Length(text.strip()).value(ppi=96, relative_length=100.0))
    except (ValueError, TypeError, AttributeError):
        return default


def _matrix(text: str | None) -> np.ndarray:
    """3×3 affine matrix of an SVG ``transform`` attribute."""
    if not text:
        return np.eye(3)
    m = se.Matrix(text)
    return np.array([[m.a, m.c, m.e], [m.b, m.d, m.f], [0.0, 0.0, 1.0]])


def _translate(x: float, y: float) -> np.ndarray:
    return np.array([[1.0, 0.0, x], [0.0, 1.0, y], [0.0, 0.0, 1.0]])


def _apply(m: np.ndarray, geom: shapely.Geometry) -> shapely.Geometry:
    return shapely.transform(geom, lambda c: c @ m[:2, :2].T + m[:2, 2])


def _fmt(v: float) -> str:
    s = f"{v:.6f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _matrix_attr(m: np.ndarray) -> str:
    return "matrix({})".format(" ".join(_fmt(v) for v in (m[0, 0], m[1, 0], m[0, 1], m[1, 1], m[0, 2], m[1, 2])))


def _drawable(el: ET.Element) -> list[ET.Element]:
    """Children of ``el`` that may draw something (the input region is not a motif)."""
    return [
        c for c in el
        if _is_svg(c) and _local(c.tag) not in NOT_RENDERED and c.attrib.get("id") != "region"
    ]  # fmt: skip


def _holds_motifs(group: ET.Element, *, alone: bool) -> bool:
    """Is ``group`` a container of motifs rather than a motif itself?

    Yes for Inkscape layers, for groups holding ``<use>`` instances, and for a group that is the
    only drawable child of its container yet holds several shapes (an exporter's wrapper).
    """
    if group.attrib.get(f"{{{INKSCAPE_NS}}}groupmode") == "layer":
        return True
    if any(_local(e.tag) == "use" for e in group.iter()):
        return True
    return alone and len(_drawable(group)) > 1


def _describe(el: ET.Element) -> str:
    ident = el.attrib.get("id")
    return f"<{_local(el.tag)} id={ident!r}>" if ident else f"<{_local(el.tag)}>"


# ----------------------------------------------------------------------------- geometry


def _se_shape(el: ET.Element) -> se.Shape | None:
    """The svgelements shape for a basic shape element (None when it renders nothing)."""
    tag, a = _local(el.tag), {k: v for k, v in el.attrib.items() if "}" not in k}
    a.pop("transform", None)  # composed by the walker
    a.pop("style", None)
    if tag == "path":
        return se.Path(a.get("d", ""))
    if tag == "rect":
        return se.Rect(a)
    if tag == "circle":
        return se.Circle(a)
    if tag == "ellipse":
        return se.Ellipse(a)
    if tag == "line":
        return se.SimpleLine(a)
    if tag == "polyline":
        return se.Polyline(a)
    if tag == "polygon":
        return se.Polygon(a)
    return None


def _segments(seg: se.PathSegment, tol: float) -> int:
    """How many chords flatten ``seg`` within ``tol`` (Wang's bound for Béziers)."""
    pts = lambda *ps: [np.array([p.x, p.y]) for p in ps]  # noqa: E731
    if isinstance(seg, se.CubicBezier):
        p0, p1, p2, p3 = pts(seg.start, seg.control1, seg.control2, seg.end)
        m = max(np.linalg.norm(p0 - 2 * p1 + p2), np.linalg.norm(p1 - 2 * p2 + p3))
        n = math.sqrt(0.75 * m / tol)
    elif isinstance(seg, se.QuadraticBezier):
        p0, p1, p2 = pts(seg.start, seg.control, seg.end)
        n = math.sqrt(0.25 * np.linalg.norm(p0 - 2 * p1 + p2) / tol)
    elif isinstance(seg, se.Arc):
        r = max(abs(seg.rx), abs(seg.ry), tol)
        step = 2 * math.acos(max(-1.0, 1 - tol / r))
        n = abs(seg.sweep) / max(step, 1e-3)
    else:
        n = 1
    return int(min(256, max(1, math.ceil(n))))


def _flatten(path: se.Path) -> list[tuple[np.ndarray, bool]]:
    """Subpaths of ``path`` as ``((k, 2) points, closed)`` polylines."""
    bbox = path.bbox()
    size = 0.0 if bbox is None else math.hypot(bbox[2] - bbox[0], bbox[3] - bbox[1])
    tol = max(size * FLATNESS, 1e-9)
    out: list[tuple[np.ndarray, bool]] = []
    pts: list[tuple[float, float]] = []
    start = None

    def flush(closed: bool) -> None:
        if pts:
            out.append((np.array(pts, dtype=np.float64), closed))

    for seg in path:
        if isinstance(seg, se.Move):
            flush(False)
            pts, start = [(seg.end.x, seg.end.y)], (seg.end.x, seg.end.y)
            continue
        if not pts and seg.start is not None:  # drawing resumes after a close
            pts = [(seg.start.x, seg.start.y)]
            start = pts[0]
        if isinstance(seg, se.Close):
            flush(True)
            pts = []
        elif isinstance(seg, se.Line):
            pts.append((seg.end.x, seg.end.y))
        elif seg.end is not None:
            n = _segments(seg, tol)
            pts.extend(map(tuple, seg.npoint(np.linspace(0, 1, n + 1)[1:])))
    flush(False)
    del start
    return out


_CAPS = {"round": "round", "square": "square", "butt": "flat"}
_JOINS = {"round": "round", "bevel": "bevel", "miter": "mitre", "miter-clip": "mitre", "arcs": "mitre"}


def _leaf_footprint(el: ET.Element, style: dict[str, str], source: str) -> shapely.Geometry | None:
    """Footprint of one shape element in its own user space (before its transform)."""
    try:
        shape = _se_shape(el)
        subpaths = _flatten(se.Path(shape)) if shape is not None else []
    except Exception as exc:  # svgelements raises bare ValueErrors/IndexErrors on bad data
        raise ExemplarError(f"cannot read the geometry of {_describe(el)} ({exc or type(exc).__name__})", source=source) from None
    filled = _painted(style.get("fill", INITIAL["fill"]))
    width = _number(style.get("stroke-width"), 1.0)
    stroked = _painted(style.get("stroke", INITIAL["stroke"])) and width > 0
    cap = _CAPS.get(style.get("stroke-linecap", "butt"), "flat")
    join = _JOINS.get(style.get("stroke-linejoin", "miter"), "mitre")
    limit = _number(style.get("stroke-miterlimit"), 4.0)
    parts = []
    for pts, closed in subpaths:
        distinct = len(np.unique(np.round(pts, 12), axis=0))
        if distinct >= 3 and (closed or filled):
            parts.append(shapely.make_valid(shapely.Polygon(pts)))
        if not stroked:
            continue
        if distinct == 1:  # a zero-length subpath: a dot with round caps, a square with square caps
            if cap == "round":
                parts.append(shapely.Point(pts[0]).buffer(width / 2, quad_segs=8))
            elif cap == "square":
                x, y = pts[0]
                parts.append(shapely.box(x - width / 2, y - width / 2, x + width / 2, y + width / 2))
            continue
        line = np.vstack([pts, pts[:1]]) if closed else pts
        parts.append(
            shapely.LineString(line).buffer(
                width / 2, quad_segs=8, cap_style=cap, join_style=join, mitre_limit=max(limit, 1.0)
            )
        )
    parts = [p for p in parts if not p.is_empty and p.area > 0]
    return shapely.union_all(parts) if parts else None


def _fill_holes(geom: shapely.Geometry) -> shapely.Geometry:
    polys = [shapely.Polygon(p.exterior) for p in shapely.get_parts(geom) if isinstance(p, shapely.Polygon)]
    return shapely.union_all(polys)


# ----------------------------------------------------------------------------- the reader


@dataclass
class _Instance:
    key: tuple  # what makes two instances the same kind (before plain-shape matching)
    world: shapely.Geometry  # footprint in world coordinates
    matrix: np.ndarray  # 3x3, kind content frame -> world
    element: ET.Element
    style: dict[str, str]


class _Reader:
    """Walks one document; see the module docstring for the rules."""

    def __init__(self, root: ET.Element, source: str) -> None:
        self.root, self.source = root, source
        self.ids: dict[str, ET.Element] = {}
        for el in root.iter():
            ident = el.attrib.get("id")
            if ident is not None and ident not in self.ids:
                self.ids[ident] = el
        self.warnings: list[str] = []
        self.content_cache: dict[tuple, shapely.Geometry | None] = {}

    def error(self, message: str) -> ExemplarError:
        return ExemplarError(message, source=self.source)

    # -- document walk -------------------------------------------------------------------

    def read(self) -> Exemplar:
        self._refuse_external_references()
        if any(_local(el.tag) == "style" and (el.text or "").strip() for el in self.root.iter()):
            self.warnings.append("CSS <style> sheets are not applied; use presentation attributes or style=")
        instances: list[_Instance] = []
        self._walk(self.root, np.eye(3), _style(self.root, INITIAL), instances)
        if not instances:
            raise self.error("no motifs found (expected <use> elements or top-level shapes)")
        kinds, arrangement, defs = self._kinds(instances)
        region = self._region(arrangement, kinds)
        centroid_in = shapely.contains_xy(region, arrangement.xy[:, 0], arrangement.xy[:, 1])
        if not centroid_in.any():
            raise self.error("no motif lies inside the input region")
        if not centroid_in.all():
            self.warnings.append(f"{int((~centroid_in).sum())} motif(s) outside the input region are ignored")
            arrangement = arrangement.take(centroid_in)
        return Exemplar(self.source, tuple(kinds), arrangement, region, tuple(defs), tuple(self.warnings))

    def _refuse_external_references(self) -> None:
        for el in self.root.iter():
            ref = _href(el)
            if ref and not ref.startswith("#") and not ref.startswith("data:"):
                raise self.error(f"{_describe(el)} refers to {ref!r} outside this file; svgtile never fetches external files")

    def _walk(self, el: ET.Element, m: np.ndarray, style: dict[str, str], out: list[_Instance]) -> None:
        """Collect motif instances below ``el`` (a container whose children may be motifs)."""
        drawable = _drawable(el)
        for child in drawable:
            tag = _local(child.tag)
            cstyle = _style(child, style)
            if _hidden(cstyle):
                continue
            cm = m @ _matrix(child.attrib.get("transform"))
            if tag == "use":
                out.append(self._use_instance(child, cm, cstyle))
            elif tag == "svg":
                if "viewBox" in child.attrib:
                    raise self.error(f"nested {_describe(child)} with a viewBox is not supported; flatten it first")
                x, y = _number(child.attrib.get("x"), 0), _number(child.attrib.get("y"), 0)
                self._walk(child, m @ _translate(x, y), cstyle, out)
            elif tag in CONTAINERS and _holds_motifs(child, alone=len(drawable) == 1):
                self._walk(child, cm, cstyle, out)
            elif tag in SHAPES or tag in CONTAINERS:
                inst = self._plain_instance(child, m, style)
                if inst is not None:
                    out.append(inst)
            elif tag in ("text", "image"):
                self.warnings.append(f"{_describe(child)} is ignored (only shapes and <use> are motifs)")

    # -- instances -----------------------------------------------------------------------

    def _plain_instance(self, el: ET.Element, parent_m: np.ndarray, parent_style: dict[str, str]) -> _Instance | None:
        """A top-level shape or group drawn in place."""
        geom = self._content(el, parent_style, np.eye(3), stack=())
        if geom is None:
            return None
        world = _apply(parent_m, geom)
        if world.is_empty or world.area <= 0:
            return None
        return _Instance(("plain",), _fill_holes(world), parent_m, el, parent_style)

    def _use_instance(self, use: ET.Element, m: np.ndarray, style: dict[str, str]) -> _Instance:
        ref = _href(use)
        target = self.ids.get(ref[1:]) if ref else None
        if target is None:
            raise self.error(f"{_describe(use)} refers to {ref!r}, which is not in the file")
        x, y = _number(use.attrib.get("x"), 0.0), _number(use.attrib.get("y"), 0.0)
        m = m @ _translate(x, y)
        view, use_attrs = self._viewport(use, target)
        inherited = tuple(sorted((k, v) for k, v in style.items() if k in INHERITED and INITIAL.get(k) != v))
        cache_key = (ref, use_attrs, inherited)
        if cache_key not in self.content_cache:
            self.content_cache[cache_key] = self._content(target, style, view, stack=(ref,))
        geom = self.content_cache[cache_key]
        if geom is None:
            raise self.error(f"{_describe(use)} refers to {ref!r}, which draws nothing")
        world = _fill_holes(_apply(m, geom))
        return _Instance(("use", ref[1:], use_attrs, inherited), world, m @ view, use, style)

    def _viewport(self, use: ET.Element, target: ET.Element) -> tuple[np.ndarray, tuple[tuple[str, str], ...]]:
        """Matrix from a symbol's viewBox to the ``<use>`` viewport, and the attributes that make it."""
        if _local(target.tag) != "symbol":
            return np.eye(3), ()
        if "transform" in target.attrib:
            raise self.error(f"{_describe(target)} has a transform attribute (SVG 2 only; viewers disagree); move it to the <use>")
        box = target.attrib.get("viewBox")
        if not box:
            return np.eye(3), ()
        try:
            vx, vy, vw, vh = (float(v) for v in re.split(r"[\s,]+", box.strip()))
        except ValueError:
            raise self.error(f"{_describe(target)} has an unreadable viewBox {box!r}") from None
        w = use.attrib.get("width") or target.attrib.get("width")
        h = use.attrib.get("height") or target.attrib.get("height")
        if not w or not h or "%" in w + h:
            raise self.error(
                f"{_describe(target)} has a viewBox, so its <use> needs width and height "
                "(svgtile will not guess a percentage viewport)"
            )
        width, height = _number(w, 0), _number(h, 0)
        if vw <= 0 or vh <= 0 or width <= 0 or height <= 0:
            raise self.error(f"{_describe(target)} has an empty viewBox or viewport")
        par = (target.attrib.get("preserveAspectRatio") or "xMidYMid meet").split()
        sx, sy = width / vw, height / vh
        tx = ty = 0.0
        if par[0] != "none":
            s = max(sx, sy) if len(par) > 1 and par[1] == "slice" else min(sx, sy)
            align = par[0]
            fx = {"xMin": 0.0, "xMid": 0.5, "xMax": 1.0}[align[:4]]
            fy = {"YMin": 0.0, "YMid": 0.5, "YMax": 1.0}[align[4:]]
            tx, ty = fx * (width - vw * s), fy * (height - vh * s)
            sx = sy = s
        view = np.array([[sx, 0, tx - vx * sx], [0, sy, ty - vy * sy], [0, 0, 1.0]])
        return view, (("width", _fmt(width)), ("height", _fmt(height)))

    def _content(self, el: ET.Element, style: dict[str, str], m: np.ndarray, stack: tuple[str, ...]) -> shapely.Geometry | None:
        """Footprint of ``el`` (a shape, group, symbol or use) in the frame ``m`` maps it to."""
        est = _style(el, style)
        if _hidden(est):
            return None
        tag = _local(el.tag)
        if tag != "symbol":
            m = m @ _matrix(el.attrib.get("transform"))
        if tag in SHAPES:
            geom = _leaf_footprint(el, est, self.source)
            return None if geom is None else _apply(m, geom)
        if tag == "use":
            ref = _href(el)
            target = self.ids.get(ref[1:]) if ref else None
            if target is None:
                raise self.error(f"{_describe(el)} refers to {ref!r}, which is not in the file")
            if ref in stack or len(stack) > 32:
                raise self.error(f"{_describe(el)} refers to {ref!r} recursively")
            view, _ = self._viewport(el, target)
            offset = _translate(_number(el.attrib.get("x"), 0), _number(el.attrib.get("y"), 0))
            return self._content(target, est, m @ offset @ view, (*stack, ref))
        if tag in (*CONTAINERS, "symbol", "svg"):
            parts = [self._content(c, est, m, stack) for c in el if _is_svg(c) and _local(c.tag) not in NOT_RENDERED]
            parts = [p for p in parts if p is not None and not p.is_empty]
            return shapely.union_all(parts) if parts else None
        return None

    # -- kinds ---------------------------------------------------------------------------

    def _kinds(self, instances: list[_Instance]) -> tuple[list[Kind], Arrangement, list[ET.Element]]:
        """Group instances into kinds and express each instance in its kind's local frame."""
        kinds: list[Kind] = []
        kind_of_key: dict[tuple, int] = {}
        rows: list[tuple[int, float, float, float, float]] = []
        plain_reps: list[tuple[int, _Instance]] = []
        for inst in instances:
            if inst.key[0] == "use":
                k, angle, scale, xy = self._use_kind(inst, kinds, kind_of_key)
            else:
                k, angle, scale, xy = self._plain_kind(inst, kinds, plain_reps)
            rows.append((k, xy[0], xy[1], angle, scale))
        table = np.array(rows, dtype=np.float64)
        arrangement = Arrangement(table[:, 0].astype(np.int64), table[:, 1:3], table[:, 3], table[:, 4])
        defs = self._defs(kinds, plain_reps)
        return kinds, arrangement, defs

    def _use_kind(self, inst: _Instance, kinds: list[Kind], kind_of_key: dict[tuple, int]):
        lin = inst.matrix[:2, :2]
        det = float(np.linalg.det(lin))
        if abs(det) < 1e-12:
            raise self.error(f"{_describe(inst.element)} is scaled to nothing")
        angle = math.degrees(math.atan2(lin[1, 0], lin[0, 0]))
        scale = math.sqrt(abs(det))
        rot = np.array([[math.cos(math.radians(angle)), -math.sin(math.radians(angle))],
                        [math.sin(math.radians(angle)), math.cos(math.radians(angle))]])  # fmt: skip
        residual = rot.T @ lin / scale
        if np.allclose(residual, np.eye(2), atol=1e-6):
            residual = np.eye(2)
        key = (*inst.key, tuple(np.round(residual, 6).ravel()))
        # content footprint in the residual frame: world footprint mapped back by (scale · R)^-1
        inv = np.eye(3)
        inv[:2, :2] = rot.T / scale
        inv[:2, 2] = -inv[:2, :2] @ inst.matrix[:2, 2]
        if key not in kind_of_key:
            local = _apply(inv, inst.world)
            c = np.round(np.array(local.centroid.coords[0]), ORIGIN_DECIMALS)
            proto = Prototype.from_geometry(shapely.transform(local, lambda p: p - c))
            _, ref, use_attrs, inherited = inst.key
            variants = sum(1 for k in kinds if k.href == ref)
            name = ref if variants == 0 else f"{ref}~{variants}"
            kind_of_key[key] = len(kinds)
            kinds.append(Kind(name, ref, proto, -c, residual, use_attrs + inherited))
        k = kind_of_key[key]
        xy = inst.matrix[:2, 2] + scale * rot @ (-kinds[k].offset)
        return k, angle, scale, xy

    def _plain_kind(self, inst: _Instance, kinds: list[Kind], reps: list[tuple[int, _Instance]]):
        world = inst.world
        c = np.round(np.array(world.centroid.coords[0]), ORIGIN_DECIMALS)
        local = shapely.transform(world, lambda p: p - c)
        paint = _paint_key(inst.element, inst.style)
        for k, rep in reps:
            if rep.key[1:] != paint:
                continue
            angle = _match_rotation(kinds[k].prototype, local)
            if angle is not None:
                return k, angle, 1.0, c
        k = len(kinds)
        ident = f"svgtile-kind-{len(reps) + 1}"
        proto = Prototype.from_geometry(local)
        kinds.append(Kind(ident, ident, proto, -c, np.eye(2)))
        reps.append((k, _Instance(("plain", *paint), world, inst.matrix, inst.element, inst.style)))
        return k, 0.0, 1.0, c

    def _defs(self, kinds: list[Kind], reps: list[tuple[int, _Instance]]) -> list[ET.Element]:
        """Elements to copy to the output: referenced elements (closure), then generated symbols."""
        wanted: list[str] = []
        todo = [k.href for k in kinds if k.href in self.ids and not k.href.startswith("svgtile-kind-")]
        while todo:
            ident = todo.pop(0)
            if ident in wanted or ident not in self.ids:
                continue
            wanted.append(ident)
            for el in self.ids[ident].iter():
                ref = _href(el)
                if ref and ref.startswith("#"):
                    todo.append(ref[1:])
                for value in el.attrib.values():
                    todo.extend(re.findall(r"url\(\s*#([^)\s]+)\s*\)", value))
        order = {id(el): i for i, el in enumerate(self.root.iter())}
        defs = sorted((self.ids[i] for i in wanted), key=lambda el: order[id(el)])
        # an element nested in another copied element is copied with it
        inside = {id(sub) for el in defs for sub in el.iter() if sub is not el}
        defs = [el for el in defs if id(el) not in inside]
        for k, rep in reps:
            symbol = ET.Element(f"{{{SVG_NS}}}symbol", {"id": kinds[k].href, "overflow": "visible"})
            wrapper = ET.SubElement(symbol, f"{{{SVG_NS}}}g")
            if not np.allclose(rep.matrix, np.eye(3)):
                wrapper.set("transform", _matrix_attr(rep.matrix))
            for key, value in sorted(rep.style.items()):
                if key in INHERITED and INITIAL.get(key) != value:
                    wrapper.set(key, value)
            wrapper.append(copy.deepcopy(rep.element))
            defs.append(symbol)
        return defs

    # -- region --------------------------------------------------------------------------

    def _region(self, arrangement: Arrangement, kinds: list[Kind]) -> shapely.Polygon:
        el = self.ids.get("region")
        if el is not None:
            return self._region_element(el)
        box = self.root.attrib.get("viewBox")
        if box:
            try:
                x, y, w, h = (float(v) for v in re.split(r"[\s,]+", box.strip()))
            except ValueError:
                raise self.error(f"unreadable root viewBox {box!r}") from None
            return self._checked_region(shapely.box(x, y, x + w, y + h), "the root viewBox")
        w, h = self.root.attrib.get("width"), self.root.attrib.get("height")
        if w and h and "%" not in w + h:
            return self._checked_region(shapely.box(0, 0, _number(w, 0), _number(h, 0)), "the root width/height")
        radius = np.array([k.prototype.radius for k in kinds])[arrangement.kind] * arrangement.scale
        lo = (arrangement.xy - radius[:, None]).min(axis=0)
        hi = (arrangement.xy + radius[:, None]).max(axis=0)
        return self._checked_region(shapely.box(*lo, *hi), "the motifs' bounds")

    def _region_element(self, el: ET.Element) -> shapely.Polygon:
        tag = _local(el.tag)
        if tag not in ("rect", "circle", "ellipse", "polygon", "path"):
            raise self.error(f"{_describe(el)} cannot be the input region (use rect, circle, ellipse, polygon or path)")
        m = np.eye(3)
        chain = self._ancestors(el)
        for node in chain:
            m = m @ _matrix(node.attrib.get("transform"))
        try:
            subpaths = _flatten(se.Path(_se_shape(el)))
        except Exception:
            raise self.error(f"cannot read the geometry of {_describe(el)}") from None
        rings = [shapely.make_valid(shapely.Polygon(p)) for p, _ in subpaths if len(np.unique(p, axis=0)) >= 3]
        geom = shapely.union_all(rings) if rings else shapely.Polygon()
        return self._checked_region(_apply(m, geom), _describe(el))

    def _ancestors(self, el: ET.Element) -> list[ET.Element]:
        parents = {c: p for p in self.root.iter() for c in p}
        chain = [el]
        while chain[-1] in parents:
            chain.append(parents[chain[-1]])
        return chain[::-1]

    def _checked_region(self, geom: shapely.Geometry, what: str) -> shapely.Polygon:
        geom = shapely.union_all(
            [p for p in shapely.get_parts(shapely.make_valid(geom)) if isinstance(p, shapely.Polygon)]
        )
        if geom.is_empty or geom.area <= 0:
            raise self.error(f"the input region ({what}) has no area")
        if isinstance(geom, shapely.MultiPolygon):
            raise self.error(f"the input region ({what}) must be one connected shape")
        return geom


def _paint_key(el: ET.Element, style: dict[str, str]) -> tuple:
    """What besides shape tells two plain motifs apart: the paint of every leaf."""
    keys = []
    for node in el.iter():
        if _local(node.tag) in SHAPES:
            s = _style(node, style)
            keys.append((s.get("fill", "black"), s.get("stroke", "none"), s.get("stroke-width", "1")))
    return tuple(sorted(set(keys)))


def _match_rotation(proto: Prototype, local: shapely.Geometry) -> float | None:
    """Angle (degrees) rotating ``proto`` onto ``local`` (both centred), or None if not congruent.

    Candidates: no rotation first (so symmetric motifs keep angle 0), then every pairing of the
    farthest outline points of both shapes, each verified by the Hausdorff distance.
    """
    ref = proto.geometry()
    tol = SHAPE_TOLERANCE * proto.radius
    if abs(local.area - proto.area) > 2 * SHAPE_TOLERANCE * proto.area:
        return None
    pts = shapely.get_coordinates(local)
    r = np.hypot(pts[:, 0], pts[:, 1])
    if abs(r.max() - proto.radius) > tol:
        return None
    if shapely.hausdorff_distance(ref, local) <= tol:
        return 0.0
    ref_pts = np.concatenate(proto.rings)
    ref_r = np.hypot(ref_pts[:, 0], ref_pts[:, 1])
    far = pts[r >= r.max() - tol][:8]
    ref_far = ref_pts[ref_r >= ref_r.max() - tol][:8]
    best = None
    for p in far:
        for q in ref_far:
            angle = math.degrees(math.atan2(p[1], p[0]) - math.atan2(q[1], q[0]))
            rotated = shapely.affinity.rotate(ref, angle, origin=(0, 0))
            d = shapely.hausdorff_distance(rotated, local)
            if d <= tol and (best is None or d < best[0]):
                best = (d, angle)
    if best is None:
        return None
    return (best[1] + 180.0) % 360.0 - 180.0


def warn_all(exemplar: Exemplar) -> None:
    """Issue the exemplar's warnings through :mod:`warnings` (the CLI shows them on stderr)."""
    for message in exemplar.warnings:
        warnings.warn(f"{exemplar.source}: {message}", stacklevel=2)
