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

Work is done once per kind: a referenced element's footprint is computed once per inherited style
and viewport, and each ``<use>`` only contributes its matrix.
"""

from __future__ import annotations

import copy
import math
import re
import warnings
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import shapely
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
#: Chord tolerance for flattening curves, as a fraction of the element's size (a circle loses
#: about 0.2 % of its area).
FLATNESS = 0.0005
#: The same for the input region, whose area sets the density.
REGION_FLATNESS = 1e-5
#: Decimals kept for a kind's local origin, so output transforms reproduce it exactly.
ORIGIN_DECIMALS = 4
#: Most points one footprint may have: a guard against ``<use>`` fan-out ("billion laughs").
MAX_COORDINATES = 200_000
#: Deepest chain of ``<use>`` references followed.
MAX_USE_DEPTH = 32
#: Presentation properties that are not inherited but change how a plain motif looks.
OWN_LOOK = ("opacity", "clip-path", "mask", "filter")


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
    footprint : shapely (Multi)Polygon or None
        The exact footprint in the local frame (the prototype is a simplified cover of it, see
        :meth:`Prototype.from_geometry`).
    """

    name: str
    href: str
    prototype: Prototype
    offset: np.ndarray
    residual: np.ndarray
    use_attrs: tuple[tuple[str, str], ...] = ()
    footprint: shapely.Geometry | None = None


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
    except (ET.ParseError, ValueError, LookupError) as exc:  # LookupError: unknown encoding
        raise ExemplarError(f"not a well-formed XML file ({_oneline(exc)})", source=source) from None
    if _local(root.tag) != "svg" or _ns(root.tag) not in ("", SVG_NS):
        raise ExemplarError(f"not an SVG document (root element is <{_local(root.tag)}>)", source=source)
    try:
        return _Reader(root, source).read()
    except RecursionError:
        raise ExemplarError("elements are nested too deeply", source=source) from None


# ----------------------------------------------------------------------------- helpers


def _oneline(text: object) -> str:
    """``text`` as one line (messages must fit the CLI's single line)."""
    return " ".join(str(text).split())


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _ns(tag: str) -> str:
    return tag[1:].split("}", 1)[0] if isinstance(tag, str) and tag.startswith("{") else ""


def _is_svg(el: ET.Element) -> bool:
    return isinstance(el.tag, str) and _ns(el.tag) in ("", SVG_NS)


def _href(el: ET.Element) -> str | None:
    """The element's ``href`` or ``xlink:href`` (SVG 2 ``href`` wins), or None.

    ElementTree resolves prefixes, so an ad-hoc prefix bound to the xlink namespace (jsdotpattern
    writes ``NS1:href`` with ``xmlns:NS1``) arrives as ``{xlink}href`` too; an ``href`` in any
    other namespace is not a reference.
    """
    for key in ("href", f"{{{XLINK_NS}}}href"):
        if key in el.attrib:
            return el.attrib[key].strip()
    return None


def _style(el: ET.Element, parent: dict[str, str]) -> dict[str, str]:
    """Effective presentation properties of ``el`` given its parent's (CSS cascade, simplified)."""
    own: dict[str, str] = {}
    for key in (*INHERITED, "display", *OWN_LOOK):
        if key in el.attrib:
            own[key] = el.attrib[key].strip()
    for decl in el.attrib.get("style", "").split(";"):
        if ":" in decl:
            key, value = decl.split(":", 1)
            own[key.strip()] = value.replace("!important", "").strip()
    style = {k: v for k, v in parent.items() if k in INHERITED}
    style.update({k: v for k, v in own.items() if v != "inherit"})
    return style


def _inherited(style: dict[str, str]) -> tuple[tuple[str, str], ...]:
    """The inherited properties of ``style`` that differ from their initial values, sorted."""
    return tuple(sorted((k, v) for k, v in style.items() if k in INHERITED and INITIAL.get(k) != v))


def _hidden(style: dict[str, str]) -> bool:
    return (
        style.get("display") == "none"
        or style.get("visibility") in ("hidden", "collapse")
        or _number(style.get("opacity", "1"), 1.0) <= 0
    )


def _painted(value: str | None) -> bool:
    return value is not None and value.strip() not in ("none", "transparent")


def _number(text: str | None, default: float) -> float:
    """An absolute length or number in user units; ``default`` if missing, relative or unreadable."""
    if text is None:
        return default
    try:
        return _absolute_length(text)
    except ValueError:
        return default


_LENGTH = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([a-zA-Z%]*)\s*$")
_RELATIVE_UNITS = {"%", "em", "ex", "ch", "rem", "vw", "vh", "vmin", "vmax", "vi", "vb", "cap", "ic", "lh", "rlh"}
_UNITS = {"": 1.0, "px": 1.0, "mm": 96 / 25.4, "cm": 96 / 2.54, "q": 96 / 101.6, "in": 96.0, "pt": 96 / 72, "pc": 16.0}


def _absolute_length(text: str) -> float:
    """A geometry length in user units; relative units (%, em, ex) and junk raise ValueError."""
    match = _LENGTH.match(text)
    if match is None:
        raise ValueError(f"unreadable length {text.strip()!r}")
    number, unit = match.groups()
    if unit.lower() in _RELATIVE_UNITS:
        raise ValueError(f"length {text.strip()!r} is relative (svgtile resolves only absolute units)")
    if unit.lower() not in _UNITS:
        raise ValueError(f"unreadable length {text.strip()!r}")
    return float(number) * _UNITS[unit.lower()]


def _matrix(text: str | None) -> np.ndarray:
    """3×3 affine matrix of an SVG ``transform`` attribute."""
    if not text:
        return np.eye(3)
    m = se.Matrix(text)
    return np.array([[m.a, m.c, m.e], [m.b, m.d, m.f], [0.0, 0.0, 1.0]])


def _translate(x: float, y: float) -> np.ndarray:
    return np.array([[1.0, 0.0, x], [0.0, 1.0, y], [0.0, 0.0, 1.0]])


def _linear(lin: np.ndarray) -> np.ndarray:
    m = np.eye(3)
    m[:2, :2] = lin
    return m


def _apply(m: np.ndarray, geom: shapely.Geometry) -> shapely.Geometry:
    return shapely.transform(geom, lambda c: c @ m[:2, :2].T + m[:2, 2])


def _fmt(v: float) -> str:
    s = f"{v:.6f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _matrix_attr(m: np.ndarray) -> str:
    return "matrix({})".format(" ".join(_fmt(v) for v in (m[0, 0], m[1, 0], m[0, 1], m[1, 1], m[0, 2], m[1, 2])))


def _rendered(el: ET.Element) -> bool:
    """Can ``el`` draw as part of its parent (the input region never does)?"""
    return _is_svg(el) and _local(el.tag) not in NOT_RENDERED and el.attrib.get("id") != "region"


def _drawable(el: ET.Element) -> list[ET.Element]:
    """Children of ``el`` that may draw something."""
    return [c for c in el if _rendered(c)]


def _holds_motifs(group: ET.Element, *, alone: bool) -> bool:
    """Is ``group`` a container of motifs rather than a motif itself?

    Yes for Inkscape layers, for groups holding ``<use>`` instances, and for a group that is the
    only drawable child of its container yet holds several shapes or another group (an exporter's
    wrapper, possibly nested).
    """
    if group.attrib.get(f"{{{INKSCAPE_NS}}}groupmode") == "layer":
        return True
    if any(_local(e.tag) == "use" for e in group.iter()):
        return True
    if not alone:
        return False
    children = _drawable(group)
    return len(children) > 1 or (len(children) == 1 and _local(children[0].tag) in CONTAINERS)


def _describe(el: ET.Element) -> str:
    ident = el.attrib.get("id")
    return f"<{_local(el.tag)} id={ident!r}>" if ident else f"<{_local(el.tag)}>"


def _short(ref: str, limit: int = 80) -> str:
    return ref if len(ref) <= limit else ref[: limit - 1] + "…"


# ----------------------------------------------------------------------------- geometry

_GEOMETRY = {
    "rect": (se.Rect, ("x", "y", "width", "height", "rx", "ry")),
    "circle": (se.Circle, ("cx", "cy", "r")),
    "ellipse": (se.Ellipse, ("cx", "cy", "rx", "ry")),
    "line": (se.SimpleLine, ("x1", "y1", "x2", "y2")),
}


def _se_shape(el: ET.Element) -> se.Shape | None:
    """The svgelements shape for a basic shape element, without its transform (None: no shape).

    Lengths are converted here, so svgelements never guesses a unit; a relative length raises
    ValueError.
    """
    tag = _local(el.tag)
    if tag == "path":
        return se.Path(el.attrib.get("d", ""))
    if tag in ("polyline", "polygon"):
        return (se.Polyline if tag == "polyline" else se.Polygon)({"points": el.attrib.get("points", "")})
    if tag not in _GEOMETRY:
        return None
    cls, names = _GEOMETRY[tag]
    attrs = {}
    for name in names:
        text = el.attrib.get(name)
        if text is not None and text.strip() not in ("", "auto"):
            attrs[name] = repr(_absolute_length(text))
    return cls(attrs)


def _control_points(seg: se.PathSegment) -> list[tuple[float, float]]:
    """Points whose hull contains ``seg`` (to size the flattening tolerance without evaluating it)."""
    if isinstance(seg, se.Arc):
        r = max(abs(seg.rx), abs(seg.ry))
        c = seg.center
        return [(c.x - r, c.y - r), (c.x + r, c.y + r)]
    names = ("start", "control", "control1", "control2", "end")
    return [(p.x, p.y) for p in (getattr(seg, n, None) for n in names) if p is not None]


def _sample(seg: se.PathSegment, tol: float) -> np.ndarray:
    """Points of a curved segment after its start, within ``tol`` of it ((k, 2), last = end)."""
    if isinstance(seg, se.CubicBezier):
        p = np.array([[q.x, q.y] for q in (seg.start, seg.control1, seg.control2, seg.end)])
        bend = max(math.hypot(*(p[0] - 2 * p[1] + p[2])), math.hypot(*(p[1] - 2 * p[2] + p[3])))
        n = math.sqrt(0.75 * bend / tol)  # Wang's bound
    elif isinstance(seg, se.QuadraticBezier):
        p = np.array([[q.x, q.y] for q in (seg.start, seg.control, seg.end)])
        n = math.sqrt(0.25 * math.hypot(*(p[0] - 2 * p[1] + p[2])) / tol)
    elif isinstance(seg, se.Arc):
        r = max(abs(seg.rx), abs(seg.ry), tol)
        step = 2 * math.acos(max(-1.0, 1 - tol / r))
        n = abs(seg.sweep) / max(step, 1e-3)
    else:
        n = 16
    n = int(min(256, max(1, math.ceil(n))))
    t = np.linspace(0.0, 1.0, n + 1)[1:, None]
    s = 1.0 - t
    if isinstance(seg, se.CubicBezier):
        pts = s**3 * p[0] + 3 * s * s * t * p[1] + 3 * s * t * t * p[2] + t**3 * p[3]
    elif isinstance(seg, se.QuadraticBezier):
        pts = s * s * p[0] + 2 * s * t * p[1] + t * t * p[2]
    else:
        pts = np.asarray(seg.npoint(t[:, 0]), dtype=np.float64).reshape(-1, 2)
    pts[-1] = (seg.end.x, seg.end.y)
    return pts


def _flatten(path: se.Path, flatness: float = FLATNESS) -> list[tuple[np.ndarray, bool]]:
    """Subpaths of ``path`` as ``((k, 2) points, closed)`` polylines.

    A subpath that is only a moveto draws nothing (not even a cap) and is dropped; ``M x y Z`` and
    ``M x y L x y`` are kept, as one-point polylines, because their caps draw.
    """
    segments = list(path)
    hull = [p for seg in segments for p in _control_points(seg)]
    if not hull:
        return []
    hull_array = np.array(hull, dtype=np.float64)
    size = float(np.hypot(*(hull_array.max(axis=0) - hull_array.min(axis=0))))
    tol = max(size * flatness, 1e-9)
    out: list[tuple[np.ndarray, bool]] = []
    pts: list[np.ndarray] = []
    drawn = False

    def flush(closed: bool) -> None:
        if pts and drawn:
            out.append((np.vstack(pts), closed))

    for seg in segments:
        if isinstance(seg, se.Move):
            flush(False)
            pts, drawn = [np.array([[seg.end.x, seg.end.y]])], False
            continue
        if seg.start is None:
            raise ValueError("path data must begin with a moveto")
        if not pts:  # drawing resumes after a close
            pts = [np.array([[seg.start.x, seg.start.y]])]
        drawn = True
        if isinstance(seg, se.Close):
            flush(True)
            pts, drawn = [], False
        elif isinstance(seg, se.Line):
            pts.append(np.array([[seg.end.x, seg.end.y]]))
        elif seg.end is not None:
            pts.append(_sample(seg, tol))
    flush(False)
    return out


_CAPS = {"round": "round", "square": "square", "butt": "flat"}
_JOINS = {"round": "round", "bevel": "bevel", "miter": "mitre", "miter-clip": "mitre", "arcs": "mitre"}


def _subpaths(el: ET.Element, source: str, flatness: float = FLATNESS) -> list[tuple[np.ndarray, bool]]:
    """Flattened subpaths of a shape element in its own user space; bad data is an ExemplarError."""
    try:
        shape = _se_shape(el)
        return _flatten(se.Path(shape), flatness) if shape is not None else []
    except Exception as exc:  # svgelements raises bare ValueErrors/TypeErrors on bad data
        detail = "malformed path data" if _local(el.tag) == "path" else _oneline(exc) or type(exc).__name__
        raise ExemplarError(f"cannot read the geometry of {_describe(el)} ({detail})", source=source) from None


def _leaf_footprint(el: ET.Element, style: dict[str, str], source: str) -> shapely.Geometry | None:
    """Footprint of one shape element in its own user space (before its transform).

    The interior of every closed subpath (filled or not) and of every filled one, plus the stroke
    band of half the stroke width with its caps and joins (a subpath that returns to its start
    without ``Z`` gets its interior when holes are filled).  A zero-length subpath is a dot with
    round caps and a square with square caps.
    """
    subpaths = _subpaths(el, source)
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
        if distinct == 1:
            if cap == "round":
                parts.append(shapely.Point(pts[0]).buffer(width / 2, quad_segs=16))
            elif cap == "square":
                x, y = pts[0]
                parts.append(shapely.box(x - width / 2, y - width / 2, x + width / 2, y + width / 2))
            continue
        line = np.vstack([pts, pts[:1]]) if closed else pts
        parts.append(
            shapely.LineString(line).buffer(
                width / 2, quad_segs=16, cap_style=cap, join_style=join, mitre_limit=max(limit, 1.0)
            )
        )
    parts = [p for p in parts if not p.is_empty and p.area > 0]
    return shapely.union_all(parts) if parts else None


def _polygons(geom: shapely.Geometry) -> list[shapely.Polygon]:
    """The polygons of ``geom`` at any depth of collection."""
    out = []
    for part in shapely.get_parts(geom):
        if isinstance(part, shapely.Polygon):
            out.append(part)
        elif isinstance(part, (shapely.MultiPolygon, shapely.GeometryCollection)):
            out.extend(_polygons(part))
    return out


def _fill_holes(geom: shapely.Geometry) -> shapely.Geometry:
    return shapely.union_all([shapely.Polygon(p.exterior) for p in _polygons(geom) if not p.is_empty])


# ----------------------------------------------------------------------------- the reader


@dataclass
class _Instance:
    key: tuple  # what makes two instances the same kind (before plain-shape matching)
    geom: shapely.Geometry  # footprint in the instance frame, holes filled
    matrix: np.ndarray  # 3x3, instance frame -> world
    element: ET.Element
    style: dict[str, str]  # effective style of the element's parent (plain) or of the <use>

    @property
    def world(self) -> shapely.Geometry:
        return _apply(self.matrix, self.geom)


@dataclass
class _Shape:
    """A centred footprint with what plain-shape matching compares."""

    geom: shapely.Geometry
    coords: np.ndarray  # (v, 2) outline points
    r: np.ndarray  # (v,) their distances from the origin
    area: float
    radius: float
    axis: float | None  # principal axis, degrees (None: no clear axis)

    @classmethod
    def of(cls, geom: shapely.Geometry) -> _Shape:
        coords = shapely.get_coordinates(geom)
        r = np.hypot(coords[:, 0], coords[:, 1])
        return cls(geom, coords, r, float(geom.area), float(r.max()), _principal_axis(geom))


@dataclass
class _PlainKinds:
    """The plain kinds found so far, with arrays for a quick first filter."""

    kind: list[int] = field(default_factory=list)
    rep: list[_Instance] = field(default_factory=list)
    shape: list[_Shape] = field(default_factory=list)
    paint: list[tuple] = field(default_factory=list)
    area: list[float] = field(default_factory=list)
    radius: list[float] = field(default_factory=list)


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
        self.warned: set[str] = set()
        self.raw_cache: dict[tuple, shapely.Geometry | None] = {}  # referenced content, own frame
        self.kind_cache: dict[tuple, shapely.Geometry | None] = {}  # <use> footprint, use frame

    def error(self, message: str) -> ExemplarError:
        return ExemplarError(_oneline(message), source=self.source)

    def warn(self, message: str) -> None:
        if message not in self.warned:
            self.warned.add(message)
            self.warnings.append(_oneline(message))

    # -- document walk -------------------------------------------------------------------

    def read(self) -> Exemplar:
        self._refuse_external_references()
        if any(_local(el.tag) == "style" and (el.text or "").strip() for el in self.root.iter()):
            self.warn("CSS <style> sheets are not applied; use presentation attributes or style=")
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
            self.warn(f"{int((~centroid_in).sum())} motif(s) outside the input region are ignored")
            arrangement = arrangement.take(centroid_in)
        return Exemplar(self.source, tuple(kinds), arrangement, region, tuple(defs), tuple(self.warnings))

    def _refuse_external_references(self) -> None:
        """A ``<use>`` may only reference this file (other hrefs are links, images … and never drawn)."""
        for el in self.root.iter():
            if not (_is_svg(el) and _local(el.tag) == "use"):
                continue
            ref = _href(el)
            if ref and not ref.startswith("#"):
                if ref.startswith("data:"):
                    raise self.error(f"{_describe(el)} refers to a data: URL; only references to ids in this file are supported")
                raise self.error(
                    f"{_describe(el)} refers to {_short(ref)!r} outside this file; svgtile never fetches external files"
                )

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
                inst = self._use_instance(child, cm, cstyle)
                if inst is not None:
                    out.append(inst)
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
                self.warn(f"{_describe(child)} is ignored (only shapes and <use> are motifs)")

    # -- instances -----------------------------------------------------------------------

    def _plain_instance(self, el: ET.Element, parent_m: np.ndarray, parent_style: dict[str, str]) -> _Instance | None:
        """A top-level shape or group drawn in place."""
        if abs(np.linalg.det(parent_m[:2, :2])) < 1e-12:
            return None
        geom = self._content(el, parent_style, np.eye(3), stack=())
        if geom is None:
            return None
        geom = _fill_holes(geom)
        if geom.is_empty or geom.area <= 0:
            return None
        return _Instance(("plain", _paint_key(el, parent_style)), geom, parent_m, el, parent_style)

    def _target(self, use: ET.Element) -> tuple[str, ET.Element]:
        ref = _href(use)
        if not ref:
            raise self.error(f"{_describe(use)} has no href")
        target = self.ids.get(ref[1:])
        if target is None:
            raise self.error(f"{_describe(use)} refers to {_short(ref)!r}, which is not in the file")
        return ref, target

    def _use_instance(self, use: ET.Element, m: np.ndarray, style: dict[str, str]) -> _Instance | None:
        """A ``<use>`` motif: its footprint in the ``<use>``'s frame (after x/y), once per kind.

        The frame is the one the output ``<use>`` draws in: a symbol's viewBox mapping is applied by
        the ``width``/``height`` the output ``<use>`` carries, so it is part of the footprint, not
        of the instance matrix.
        """
        ref, target = self._target(use)
        x, y = _number(use.attrib.get("x"), 0.0), _number(use.attrib.get("y"), 0.0)
        m = m @ _translate(x, y)
        if abs(np.linalg.det(m[:2, :2])) < 1e-12:
            self.warn(f"{_describe(use)} is scaled to nothing; ignored")
            return None
        view, use_attrs = self._viewport(use, target)
        inherited = _inherited(style)
        key = (ref, use_attrs, inherited)
        if key not in self.kind_cache:
            raw = self._referenced(ref, target, style, stack=())
            geom = None if raw is None else _fill_holes(_apply(view, raw))
            self.kind_cache[key] = geom if geom is not None and geom.area > 0 else None
            if geom is not None and _local(target.tag) == "symbol":
                self._check_overflow(target, geom)
        geom = self.kind_cache[key]
        if geom is None:
            self.warn(f"<use> elements referring to {_short(ref)!r} draw nothing svgtile can measure; ignored")
            return None
        return _Instance(("use", ref[1:], use_attrs, inherited), geom, m, use, style)

    def _check_overflow(self, symbol: ET.Element, geom: shapely.Geometry) -> None:
        overflow = _style(symbol, {}).get("overflow", symbol.attrib.get("overflow", "hidden"))
        x0, y0, _, _ = geom.bounds
        if overflow.strip() not in ("visible", "auto") and min(x0, y0) < -1e-9:
            self.warn(
                f"{_describe(symbol)} draws at negative coordinates but has overflow hidden (the SVG "
                'default), so viewers clip it; add overflow="visible"'
            )

    def _referenced(self, ref: str, target: ET.Element, style: dict[str, str], stack: tuple[str, ...]) -> shapely.Geometry | None:
        """Footprint of a referenced element in its own frame, computed once per inherited style."""
        if ref in stack or len(stack) >= MAX_USE_DEPTH:
            raise self.error(f"{_describe(target)} is referenced recursively (through {' → '.join((*stack, ref))})")
        key = (ref, _inherited(style))
        if key not in self.raw_cache:
            self.raw_cache[key] = self._content(target, style, np.eye(3), (*stack, ref))
        return self.raw_cache[key]

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
        par = (target.attrib.get("preserveAspectRatio") or "").split()
        if par and par[0] == "defer":
            par = par[1:]
        align = par[0] if par else "xMidYMid"
        if align != "none" and not re.fullmatch(r"x(Min|Mid|Max)Y(Min|Mid|Max)", align):
            align, par = "xMidYMid", []  # an invalid value means the default
        sx, sy = width / vw, height / vh
        tx = ty = 0.0
        if align != "none":
            s = max(sx, sy) if len(par) > 1 and par[1] == "slice" else min(sx, sy)
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
            ref, target = self._target(el)
            view, _ = self._viewport(el, target)
            offset = _translate(_number(el.attrib.get("x"), 0), _number(el.attrib.get("y"), 0))
            raw = self._referenced(ref, target, est, stack)
            return None if raw is None else _apply(m @ offset @ view, raw)
        if tag == "svg" and el is not self.root:
            if "viewBox" in el.attrib:
                raise self.error(f"nested {_describe(el)} with a viewBox is not supported; flatten it first")
            m = m @ _translate(_number(el.attrib.get("x"), 0), _number(el.attrib.get("y"), 0))
        if tag in (*CONTAINERS, "symbol", "svg"):
            parts = [self._content(c, est, m, stack) for c in el if _rendered(c)]
            parts = [p for p in parts if p is not None and not p.is_empty]
            if sum(shapely.get_num_coordinates(p) for p in parts) > MAX_COORDINATES:
                raise self.error(f"{_describe(el)} is too complex (over {MAX_COORDINATES} outline points)")
            return shapely.union_all(parts) if parts else None
        return None

    # -- kinds ---------------------------------------------------------------------------

    def _kinds(self, instances: list[_Instance]) -> tuple[list[Kind], Arrangement, list[ET.Element]]:
        """Group instances into kinds and express each instance in its kind's local frame."""
        kinds: list[Kind] = []
        kind_of_key: dict[tuple, int] = {}
        rows: list[tuple[int, float, float, float, float]] = []
        plain = _PlainKinds()
        for inst in instances:
            if inst.key[0] == "use":
                k, angle, scale, xy = self._use_kind(inst, kinds, kind_of_key)
            else:
                k, angle, scale, xy = self._plain_kind(inst, kinds, plain)
            rows.append((k, xy[0], xy[1], angle, scale))
        table = np.array(rows, dtype=np.float64)
        arrangement = Arrangement(table[:, 0].astype(np.int64), table[:, 1:3], table[:, 3], table[:, 4])
        defs = self._defs(kinds, list(zip(plain.kind, plain.rep, strict=True)))
        return kinds, arrangement, defs

    def _use_kind(self, inst: _Instance, kinds: list[Kind], kind_of_key: dict[tuple, int]):
        """Split the instance matrix into translation · rotation · uniform scale · residual."""
        lin = inst.matrix[:2, :2]
        scale = math.sqrt(abs(float(np.linalg.det(lin))))
        angle = math.degrees(math.atan2(lin[1, 0], lin[0, 0]))
        rot = np.array([[math.cos(math.radians(angle)), -math.sin(math.radians(angle))],
                        [math.sin(math.radians(angle)), math.cos(math.radians(angle))]])  # fmt: skip
        residual = rot.T @ lin / scale
        if np.allclose(residual, np.eye(2), atol=1e-6):
            residual = np.eye(2)
        key = (*inst.key, tuple(np.round(residual, 6).ravel()))
        if key not in kind_of_key:
            # the footprint in the residual frame: the instance frame mapped by the residual only
            local = _apply(_linear(residual), inst.geom)
            c = np.round(np.array(local.centroid.coords[0]), ORIGIN_DECIMALS)
            exact = shapely.transform(local, lambda p: p - c)
            _, ref, use_attrs, inherited = inst.key
            variants = sum(1 for k in kinds if k.href == ref)
            name = ref if variants == 0 else f"{ref}~{variants}"
            kind_of_key[key] = len(kinds)
            kinds.append(Kind(name, ref, Prototype.from_geometry(exact), -c, residual, use_attrs + inherited, exact))
        k = kind_of_key[key]
        xy = inst.matrix[:2, 2] + scale * rot @ (-kinds[k].offset)
        return k, angle, scale, xy

    def _plain_kind(self, inst: _Instance, kinds: list[Kind], plain: _PlainKinds):
        """The kind of a plain motif: the first earlier one of the same paint and shape up to rotation."""
        world = inst.world
        c = np.round(np.array(world.centroid.coords[0]), ORIGIN_DECIMALS)
        shape = _Shape.of(shapely.transform(world, lambda p: p - c))
        paint = inst.key[1]
        if plain.kind:
            area, radius = np.asarray(plain.area), np.asarray(plain.radius)
            similar = (np.abs(area - shape.area) <= 2 * SHAPE_TOLERANCE * area) & (
                np.abs(radius - shape.radius) <= SHAPE_TOLERANCE * radius
            )
            for i in np.flatnonzero(similar):
                if plain.paint[i] != paint:
                    continue
                angle = _match_rotation(plain.shape[i], shape)
                if angle is not None:
                    return plain.kind[i], angle, 1.0, c
        k = len(kinds)
        ident = f"svgtile-kind-{len(plain.kind) + 1}"
        kinds.append(Kind(ident, ident, Prototype.from_geometry(shape.geom), -c, np.eye(2), (), shape.geom))
        for name, value in (("kind", k), ("rep", inst), ("shape", shape), ("paint", paint),
                            ("area", shape.area), ("radius", shape.radius)):  # fmt: skip
            getattr(plain, name).append(value)
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
            return self._checked_region(shapely.box(x, y, x + max(w, 0), y + max(h, 0)), "the root viewBox")
        w, h = self.root.attrib.get("width"), self.root.attrib.get("height")
        if w and h and "%" not in w + h:
            width, height = max(_number(w, 0), 0), max(_number(h, 0), 0)
            return self._checked_region(shapely.box(0, 0, width, height), "the root width/height")
        lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
        for k, kind in enumerate(kinds):  # the exact footprints' bounds, in bulk per kind
            arr = arrangement.take(arrangement.kind == k)
            turn = np.radians(arr.angle)
            c, s = np.cos(turn) * arr.scale, np.sin(turn) * arr.scale
            pts = shapely.get_coordinates(kind.footprint)
            x = c[:, None] * pts[:, 0] - s[:, None] * pts[:, 1] + arr.xy[:, :1]
            y = s[:, None] * pts[:, 0] + c[:, None] * pts[:, 1] + arr.xy[:, 1:]
            lo = np.minimum(lo, [x.min(initial=np.inf), y.min(initial=np.inf)])
            hi = np.maximum(hi, [x.max(initial=-np.inf), y.max(initial=-np.inf)])
        return self._checked_region(shapely.box(*lo, *hi), "the motifs' bounds")

    def _region_element(self, el: ET.Element) -> shapely.Polygon:
        tag = _local(el.tag)
        if tag not in ("rect", "circle", "ellipse", "polygon", "path"):
            raise self.error(f"{_describe(el)} cannot be the input region (use rect, circle, ellipse, polygon or path)")
        m = np.eye(3)
        for node in self._ancestors(el):
            m = m @ _matrix(node.attrib.get("transform"))
        rings = [
            shapely.make_valid(shapely.Polygon(p))
            for p, _ in _subpaths(el, self.source, REGION_FLATNESS)
            if len(np.unique(p, axis=0)) >= 3
        ]
        geom = shapely.union_all(rings) if rings else shapely.Polygon()
        return self._checked_region(_apply(m, geom), _describe(el))

    def _ancestors(self, el: ET.Element) -> list[ET.Element]:
        """``el`` and its ancestors, root first."""
        parents = {c: p for p in self.root.iter() for c in p}
        chain = [el]
        while chain[-1] in parents:
            chain.append(parents[chain[-1]])
        return chain[::-1]

    def _checked_region(self, geom: shapely.Geometry, what: str) -> shapely.Polygon:
        geom = shapely.union_all(_polygons(shapely.make_valid(geom)))
        if geom.is_empty or geom.area <= 0:
            raise self.error(f"the input region ({what}) has no area")
        if isinstance(geom, shapely.MultiPolygon):
            raise self.error(f"the input region ({what}) must be one connected shape")
        return geom


def _paint_key(el: ET.Element, parent_style: dict[str, str]) -> tuple:
    """What besides shape tells two plain motifs apart: the effective paint of every leaf and the
    opacity, clip, mask and filter of every element, styles cascaded from ``el``'s parent."""
    keys = set()
    todo = [(el, parent_style)]
    while todo:
        node, inherited = todo.pop()
        style = _style(node, inherited)
        look = tuple((k, style[k]) for k in OWN_LOOK if k in style)
        if _local(node.tag) in SHAPES:
            keys.add((_inherited(style), look))
        elif look:
            keys.add(((), look))
        todo.extend((c, style) for c in node if _rendered(c))
    return tuple(sorted(keys))


def _principal_axis(geom: shapely.Geometry) -> float | None:
    """Direction (degrees, mod 180) of the major principal axis of ``geom`` about the origin, or
    None when the second moments are nearly isotropic (no axis to align)."""
    sxx = syy = sxy = 0.0
    for poly in _polygons(geom):
        xy = shapely.get_coordinates(poly.exterior)
        x0, y0, x1, y1 = xy[:-1, 0], xy[:-1, 1], xy[1:, 0], xy[1:, 1]
        cross = x0 * y1 - x1 * y0
        sign = 1.0 if cross.sum() > 0 else -1.0  # ring orientation
        sxx += sign * float(np.sum(cross * (x0 * x0 + x0 * x1 + x1 * x1))) / 12
        syy += sign * float(np.sum(cross * (y0 * y0 + y0 * y1 + y1 * y1))) / 12
        sxy += sign * float(np.sum(cross * (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0))) / 24
    if math.hypot(sxx - syy, 2 * sxy) < 0.05 * (sxx + syy):
        return None
    return math.degrees(0.5 * math.atan2(2 * sxy, sxx - syy))


def _rotated(geom: shapely.Geometry, angle: float) -> shapely.Geometry:
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    return shapely.transform(geom, lambda p: p @ np.array([[c, s], [-s, c]]))


def _match_rotation(ref: _Shape, shape: _Shape) -> float | None:
    """Angle (degrees) rotating ``ref`` onto ``shape`` (both centred), or None if not congruent.

    Candidates: no rotation (kept on ties, so symmetric motifs get angle 0), the alignment of the
    principal axes both ways, and the shape's farthest point onto each of the reference's far
    points; the best is accepted if its Hausdorff distance is within the tolerance.
    """
    tol = SHAPE_TOLERANCE * ref.radius
    exact = 1e-6 * ref.radius
    candidates = [0.0]
    if ref.axis is not None and shape.axis is not None:
        turn = shape.axis - ref.axis
        candidates += [turn, turn + 180.0]
    p = shape.coords[int(np.argmax(shape.r))]
    far = ref.coords[ref.r >= ref.radius - tol]
    if len(far) > 24:
        far = far[np.linspace(0, len(far) - 1, 24).astype(int)]
    candidates += list(np.degrees(math.atan2(p[1], p[0]) - np.arctan2(far[:, 1], far[:, 0])))
    best_d, best_angle = math.inf, 0.0
    for angle in candidates:
        d = shapely.hausdorff_distance(_rotated(ref.geom, angle), shape.geom)
        if d < best_d - exact:
            best_d, best_angle = d, float(angle)
        if best_d <= exact:
            break
    if best_d > tol:
        return None
    return (best_angle + 180.0) % 360.0 - 180.0


def warn_all(exemplar: Exemplar) -> None:
    """Issue the exemplar's warnings through :mod:`warnings` (the CLI shows them on stderr)."""
    for message in exemplar.warnings:
        warnings.warn(f"{exemplar.source}: {message}", stacklevel=2)
