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
import io
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
#: Largest coordinate of an input region or tile, user units: beyond it areas overflow.
MAX_COORDINATE = 1e100
#: Deepest chain of ``<use>`` references followed.
MAX_USE_DEPTH = 32
#: Presentation properties that are not inherited but change how a plain motif looks.
OWN_LOOK = ("opacity", "clip-path", "mask", "filter")
#: Attribute of the region element giving the period of a repeating tile (see Exemplar.period).
PERIOD_ATTR = "{urn:svgtile:run:1}period"


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
    period : (2,) tuple of float or None, user units
        The exemplar is one tile of a pattern that repeats with this horizontal and vertical
        period (given by ``svgtile:period="W H"`` on the region element, as ``svgtile import``
        writes it); :func:`svgtile.analysis.analyze` then measures across the tile's edges.
    """

    source: str
    kinds: tuple[Kind, ...]
    motifs: Arrangement
    region: shapely.Polygon
    defs: tuple[ET.Element, ...]
    warnings: tuple[str, ...] = ()
    period: tuple[float, float] | None = None

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
        # boundary included: an imported tile may have a motif centred on its edge
        centroid_in = shapely.intersects_xy(region, arrangement.xy[:, 0], arrangement.xy[:, 1])
        if not centroid_in.any():
            raise self.error("no motif lies inside the input region")
        if not centroid_in.all():
            self.warn(f"{int((~centroid_in).sum())} motif(s) outside the input region are ignored")
            arrangement = arrangement.take(centroid_in)
        period = self._period()
        return Exemplar(self.source, tuple(kinds), arrangement, region, tuple(defs), tuple(self.warnings), period)

    def _period(self) -> tuple[float, float] | None:
        """The ``svgtile:period`` of the region element, if any (see :attr:`Exemplar.period`)."""
        el = self.ids.get("region")
        text = None if el is None else el.attrib.get(PERIOD_ATTR)
        if text is None:
            return None
        try:
            w, h = (float(v) for v in re.split(r"[\s,]+", text.strip()))
        except ValueError:
            raise self.error(f"unreadable svgtile:period {text!r} (expected two numbers)") from None
        if not (w > 0 and h > 0 and math.isfinite(w) and math.isfinite(h)):
            raise self.error(f"svgtile:period {text!r} must be two positive numbers")
        return (w, h)

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
        if not (vw > 0 and vh > 0 and all(abs(v) <= MAX_COORDINATE for v in (vx, vy, vw, vh))):
            raise self.error(f"{_describe(target)} has an empty or unbounded viewBox {box!r}")
        w = use.attrib.get("width") or target.attrib.get("width")
        h = use.attrib.get("height") or target.attrib.get("height")
        if not w or not h or "%" in w + h:
            raise self.error(
                f"{_describe(target)} has a viewBox, so its <use> needs width and height "
                "(svgtile will not guess a percentage viewport)"
            )
        width, height = _number(w, 0), _number(h, 0)
        if not (0 < width <= MAX_COORDINATE and 0 < height <= MAX_COORDINATE):
            raise self.error(f"{_describe(target)} is used with an empty or unbounded viewport ({w} x {h})")
        if not all(1 / MAX_COORDINATE <= r <= MAX_COORDINATE for r in (width / vw, height / vh)):
            raise self.error(f"{_describe(target)}: its viewBox {box!r} in a {w} x {h} viewport scales by more than {MAX_COORDINATE:g}")
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
            if not all(map(math.isfinite, (x, y, w, h))):
                raise self.error(f"the root viewBox {box!r} is not finite")
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
        coords = shapely.get_coordinates(geom)
        if not (np.abs(coords) <= MAX_COORDINATE).all():  # also NaN: GEOS would overflow or fail
            raise self.error(f"the input region ({what}) has coordinates that are not finite or beyond ±{MAX_COORDINATE:g}")
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


def _match_rotation(ref: _Shape, shape: _Shape, tolerance: float = SHAPE_TOLERANCE) -> float | None:
    """Angle (degrees) rotating ``ref`` onto ``shape`` (both centred), or None if not congruent.

    Candidates: no rotation (kept on ties, so symmetric motifs get angle 0), the alignment of the
    principal axes both ways, and the shape's farthest point onto each of the reference's far
    points; the best is accepted if its Hausdorff distance is within ``tolerance`` × the
    reference's radius.
    """
    tol = tolerance * ref.radius
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


# ----------------------------------------------------------------------------- pattern tiles
#
# A pattern tile (FGDC lithology, OSM area fill …) is not an exemplar: one element may hold many
# motifs and one motif many elements.  :func:`read_tile` flattens it into *pieces* — one per
# drawn subpath, with its footprint and polyline in tile coordinates — that
# :mod:`svgtile.tileimport` groups into motifs.

#: Paint properties a piece keeps for redrawing it (stroke-width is converted to tile units).
PIECE_PAINT = (
    "fill", "fill-rule", "fill-opacity", "stroke", "stroke-width", "stroke-linecap",
    "stroke-linejoin", "stroke-miterlimit", "stroke-opacity", "opacity",
)  # fmt: skip


@dataclass(frozen=True, eq=False)
class TilePieces:
    """The drawn subpaths of a pattern tile, in the tile's user units.

    Attributes
    ----------
    source : str
    box : (4,) tuple of float
        The tile ``(x, y, width, height)``: the root viewBox, else ``0 0 width height``.
    footprint : (n,) object array of shapely geometries
        Each piece's footprint (interior if closed or filled, plus stroke band; dots are discs).
    points : list of n (k, 2) float arrays
        Each piece's flattened subpath in tile coordinates (k = 1 for a dot).
    closed : (n,) bool array
    element : (n,) int array
        Index of the element a piece comes from (its subpaths are redrawn together).
    paint : list of n tuples of (name, value)
        The piece's effective paint (:data:`PIECE_PAINT`, stroke width in tile units).
    frames : list of str
        Descriptions of dropped frame/background elements equal to the tile.
    filled_frame : bool
        One of them is painted (a solid fill or a background colour).
    warnings : list of str
    """

    source: str
    box: tuple[float, float, float, float]
    footprint: np.ndarray
    points: list[np.ndarray]
    closed: np.ndarray
    element: np.ndarray
    paint: list[tuple[tuple[str, str], ...]]
    frames: list[str]
    filled_frame: bool
    warnings: list[str]


def read_tile(path: str | Path) -> TilePieces:
    """Read a pattern tile SVG file into pieces (see :func:`parse_tile`)."""
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise ExemplarError(f"cannot read file ({exc.strerror or exc})", source=str(path)) from None
    return parse_tile(data, source=str(path))


def parse_tile(data: bytes | str, *, source: str = "<tile>") -> TilePieces:
    """Flatten a pattern tile into pieces, one per drawn subpath.

    Transforms are applied, styles cascaded (CSS ``style``, presentation attributes, inheritance),
    ``<use>`` elements expanded; a shape whose footprint is the whole tile (a frame or background
    rectangle) is dropped and reported in ``frames``.  A subpath that draws nothing (moveto only,
    neither filled nor stroked) is no piece.

    Raises
    ------
    ExemplarError
        Malformed XML, no tile size, unreadable geometry.
    """
    if isinstance(data, str):
        data = data.encode()
    try:
        root = ET.fromstring(data)
    except (ET.ParseError, ValueError, LookupError) as exc:
        raise ExemplarError(f"not a well-formed XML file ({_oneline(exc)})", source=source) from None
    if _local(root.tag) != "svg" or _ns(root.tag) not in ("", SVG_NS):
        raise ExemplarError(f"not an SVG document (root element is <{_local(root.tag)}>)", source=source)
    reader = _Reader(root, source)
    reader._refuse_external_references()
    box = _tile_box(root, source)
    walk = _TileWalk(reader, box)
    try:
        walk.visit(root, _style(root, INITIAL), np.eye(3), ())
    except RecursionError:
        raise ExemplarError("elements are nested too deeply", source=source) from None
    footprint = np.empty(len(walk.footprint), dtype=object)
    footprint[:] = walk.footprint
    if not (np.abs(shapely.get_coordinates(footprint)) <= MAX_COORDINATE).all() or shapely.is_empty(footprint).any():
        raise ExemplarError(
            f"a drawn shape has no area or coordinates beyond ±{MAX_COORDINATE:g} (a degenerate viewBox or transform?)",
            source=source,
        )
    return TilePieces(
        source, box, footprint, walk.points, np.array(walk.closed, dtype=bool),
        np.array(walk.element, dtype=np.int64), walk.paint, walk.frames, walk.filled_frame,
        reader.warnings,
    )  # fmt: skip


def _tile_box(root: ET.Element, source: str) -> tuple[float, float, float, float]:
    box = root.attrib.get("viewBox")
    if box:
        try:
            x, y, w, h = (float(v) for v in re.split(r"[\s,]+", box.strip()))
        except ValueError:
            raise ExemplarError(f"unreadable root viewBox {box!r}", source=source) from None
    else:
        x = y = 0.0
        try:
            w = _absolute_length(root.attrib.get("width", ""))
            h = _absolute_length(root.attrib.get("height", ""))
        except ValueError:
            raise ExemplarError(
                "the tile size is unknown (the root <svg> has no viewBox and no absolute width/height)",
                source=source,
            ) from None
    if not (abs(x) <= MAX_COORDINATE and abs(y) <= MAX_COORDINATE and 0 < w <= MAX_COORDINATE and 0 < h <= MAX_COORDINATE):
        what = "has no area" if w <= 0 or h <= 0 else f"is not finite or beyond ±{MAX_COORDINATE:g}"
        raise ExemplarError(f"the tile ({w:g} x {h:g} at {x:g}, {y:g}) {what}", source=source)
    return (x, y, w, h)


class _TileWalk:
    """Collects the pieces of a tile (see :func:`parse_tile`)."""

    #: A shape is a frame when its footprint's bounds match the tile's within this share of its size.
    FRAME_TOLERANCE = 0.01

    def __init__(self, reader: _Reader, box: tuple[float, float, float, float]) -> None:
        self.reader, self.box = reader, box
        self.footprint: list[shapely.Geometry] = []
        self.points: list[np.ndarray] = []
        self.closed: list[bool] = []
        self.element: list[int] = []
        self.paint: list[tuple[tuple[str, str], ...]] = []
        self.frames: list[str] = []
        self.filled_frame = False
        self.elements = 0

    def visit(self, el: ET.Element, style: dict[str, str], m: np.ndarray, stack: tuple[str, ...]) -> None:
        for child in el:
            if not _rendered(child):
                continue
            tag = _local(child.tag)
            cstyle = _style(child, style)
            if _hidden(cstyle):
                continue
            cm = m @ _matrix(child.attrib.get("transform"))
            if "clip-path" in cstyle or "mask" in cstyle:
                self.reader.warn(f"clip paths and masks are ignored ({_describe(child)}); the tile's edge is the clip")
            if tag in SHAPES:
                self.shape(child, cstyle, cm)
            elif tag in CONTAINERS:
                self.visit(child, cstyle, cm, stack)
            elif tag == "svg":
                if "viewBox" in child.attrib:
                    raise self.reader.error(f"nested {_describe(child)} with a viewBox is not supported; flatten it first")
                x, y = _number(child.attrib.get("x"), 0), _number(child.attrib.get("y"), 0)
                self.visit(child, cstyle, cm @ _translate(x, y), stack)
            elif tag == "use":
                ref, target = self.reader._target(child)
                if ref in stack or len(stack) >= MAX_USE_DEPTH:
                    raise self.reader.error(f"{_describe(target)} is referenced recursively")
                view, _ = self.reader._viewport(child, target)
                x, y = _number(child.attrib.get("x"), 0), _number(child.attrib.get("y"), 0)
                holder = ET.Element("g")
                holder.append(target)
                tm = cm @ _translate(x, y) @ view
                if _local(target.tag) in ("symbol", "svg"):
                    self.visit(target, _style(target, cstyle), tm, (*stack, ref))
                else:
                    self.visit(holder, cstyle, tm, (*stack, ref))
            elif tag in ("text", "image"):
                self.reader.warn(f"{_describe(child)} is ignored (only shapes are motifs)")

    def shape(self, el: ET.Element, style: dict[str, str], m: np.ndarray) -> None:
        det = float(np.linalg.det(m[:2, :2]))
        if abs(det) < 1e-12:
            return
        filled = _painted(style.get("fill", INITIAL["fill"]))
        width = _number(style.get("stroke-width"), 1.0)
        stroked = _painted(style.get("stroke", INITIAL["stroke"])) and width > 0
        if not (filled or stroked):
            return  # draws nothing (e.g. a fill:none frame or mapnik_workaround rect)
        subpaths = _subpaths(el, self.reader.source)
        if not subpaths:
            return
        cap = _CAPS.get(style.get("stroke-linecap", "butt"), "flat")
        join = _JOINS.get(style.get("stroke-linejoin", "miter"), "mitre")
        limit = max(_number(style.get("stroke-miterlimit"), 4.0), 1.0)
        geoms, kept = [], []
        for pts, closed in subpaths:
            geom = _subpath_footprint(pts, closed, filled, width if stroked else 0.0, cap, join, limit)
            if geom is not None:
                geoms.append(_apply(m, geom))
                kept.append((pts @ m[:2, :2].T + m[:2, 2], closed))
        if not geoms:
            return
        if self.is_frame(shapely.union_all(geoms), width * math.sqrt(abs(det)) if stroked else 0.0):
            self.frames.append(_describe(el))
            self.filled_frame |= filled
            return
        paint = {k: style[k] for k in PIECE_PAINT if k in style}
        paint["fill"] = style.get("fill", INITIAL["fill"])
        if stroked:
            paint["stroke-width"] = _fmt(width * math.sqrt(abs(det)))
        else:
            for k in ("stroke", "stroke-width", "stroke-linecap", "stroke-linejoin", "stroke-miterlimit", "stroke-opacity"):
                paint.pop(k, None)
        key = tuple(sorted(paint.items()))
        for geom, (pts, closed) in zip(geoms, kept, strict=True):
            self.footprint.append(geom)
            self.points.append(pts)
            self.closed.append(closed)
            self.element.append(self.elements)
            self.paint.append(key)
        self.elements += 1

    def is_frame(self, geom: shapely.Geometry, stroke: float) -> bool:
        """Does ``geom`` (a footprint with a stroke band ``stroke`` wide) cover the tile exactly?"""
        x, y, w, h = self.box
        tol = self.FRAME_TOLERANCE * max(w, h) + stroke / 2
        x0, y0, x1, y1 = geom.bounds
        covers = geom.area >= 0.9 * w * h or _fill_holes(geom).area >= 0.9 * w * h
        return covers and max(abs(x0 - x), abs(y0 - y), abs(x1 - x - w), abs(y1 - y - h)) <= tol


def _subpath_footprint(
    pts: np.ndarray, closed: bool, filled: bool, width: float, cap: str, join: str, limit: float
) -> shapely.Geometry | None:
    """Footprint of one flattened subpath in its own user space (as in :func:`_leaf_footprint`).

    ``width`` 0 means not stroked.  A zero-length subpath is a dot of diameter ``width`` with
    round caps (a square with square caps).  None if it covers no area.
    """
    distinct = len(np.unique(np.round(pts, 12), axis=0))
    parts = []
    if distinct >= 3 and (closed or filled):
        parts.append(shapely.make_valid(shapely.Polygon(pts)))
    if width > 0:
        if distinct == 1:
            if cap == "round":
                parts.append(shapely.Point(pts[0]).buffer(width / 2, quad_segs=16))
            elif cap == "square":
                x, y = pts[0]
                parts.append(shapely.box(x - width / 2, y - width / 2, x + width / 2, y + width / 2))
        else:
            line = np.vstack([pts, pts[:1]]) if closed else pts
            parts.append(shapely.LineString(line).buffer(width / 2, quad_segs=16, cap_style=cap, join_style=join, mitre_limit=limit))
    parts = [p for p in parts if not p.is_empty and p.area > 0]
    return shapely.union_all(parts) if parts else None


def match_kinds(
    geoms: list[shapely.Geometry], paints: list[tuple], tolerance: float = SHAPE_TOLERANCE
) -> tuple[np.ndarray, np.ndarray]:
    """Kinds of centred footprints, identical up to rotation within ``tolerance``.

    The rule of plain exemplars (:meth:`_Reader._plain_kind`): a motif takes the kind of the first
    earlier one of the same paint whose shape it matches after a rotation: areas within
    2 × ``tolerance``, radii within ``tolerance`` and Hausdorff distance within ``tolerance`` ×
    radius.

    Parameters
    ----------
    geoms : n footprints, each centred on its centroid
    paints : n hashable paint keys
    tolerance : relative shape tolerance

    Returns
    -------
    kind : (n,) int array, numbered in order of first appearance
    angle : (n,) float array, degrees rotating the kind's first motif onto each motif
    """
    kind = np.zeros(len(geoms), dtype=np.int64)
    angle = np.zeros(len(geoms))
    reps: list[tuple[_Shape, tuple]] = []
    for n, (geom, paint) in enumerate(zip(geoms, paints, strict=True)):
        shape = _Shape.of(geom)
        for k, (ref, ref_paint) in enumerate(reps):
            if ref_paint != paint:
                continue
            if abs(ref.area - shape.area) > 2 * tolerance * ref.area:
                continue
            if abs(ref.radius - shape.radius) > tolerance * ref.radius:
                continue
            turn = _match_rotation(ref, shape, tolerance)
            if turn is not None:
                kind[n], angle[n] = k, turn
                break
        else:
            kind[n] = len(reps)
            reps.append((shape, paint))
    return kind, angle


def warn_all(exemplar: Exemplar) -> None:
    """Issue the exemplar's warnings through :mod:`warnings` (the CLI shows them on stderr)."""
    for message in exemplar.warnings:
        warnings.warn(f"{exemplar.source}: {message}", stacklevel=2)


# ----------------------------------------------------------------------------- map geometry
#
# The same flattening serves map regions and avoid zones (issue 5): a map SVG is not an exemplar,
# but its shapes are read with the helpers above, so svgelements stays in this module.

#: Text without a measurable font is taken as this many user units high (the CSS default).
DEFAULT_FONT_SIZE = 16.0
#: Width of an average glyph as a fraction of the font size, for estimated text boxes.
GLYPH_WIDTH = 0.6
#: A text line's box reaches this far above and below its baseline, in font sizes.
ASCENT, DESCENT = 0.8, 0.25


def winding_fill(rings: list[np.ndarray], rule: str = "nonzero") -> shapely.Geometry:
    """The area SVG paints for closed rings under a fill rule, holes included.

    The rings' linework is noded and polygonized into faces; a face is painted when the winding
    number of its interior point is non-zero (``nonzero``) or odd (``evenodd``), as in SVG 1.1
    §11.3.  Works for self-intersecting rings and rings drawn in any direction.

    Parameters
    ----------
    rings : list of (k, 2) float arrays, user units (closing point optional)
    rule : "nonzero" or "evenodd"

    Returns
    -------
    shapely (Multi)Polygon, possibly empty.
    """
    rings = [np.asarray(r, dtype=np.float64) for r in rings if len(np.unique(np.round(r, 12), axis=0)) >= 3]
    if not rings:
        return shapely.Polygon()
    closed = [r if np.array_equal(r[0], r[-1]) else np.vstack([r, r[:1]]) for r in rings]
    lines = shapely.union_all(shapely.linestrings(np.concatenate(closed), indices=np.repeat(
        np.arange(len(closed)), [len(r) for r in closed])))
    faces = np.array(shapely.get_parts(shapely.polygonize(shapely.get_parts(lines))), dtype=object)
    if len(faces) == 0:
        return shapely.Polygon()
    probe = shapely.get_coordinates(shapely.point_on_surface(faces))  # (f, 2)
    wind = np.zeros(len(faces), dtype=np.int64)
    for r in closed:  # a loop over rings; faces and edges are vectorised
        a, b = r[:-1], r[1:]
        px, py = probe[:, 0, None], probe[:, 1, None]
        left = (b[:, 0] - a[:, 0]) * (py - a[:, 1]) - (px - a[:, 0]) * (b[:, 1] - a[:, 1])
        up = (a[:, 1] <= py) & (b[:, 1] > py) & (left > 0)
        down = (a[:, 1] > py) & (b[:, 1] <= py) & (left < 0)
        wind += up.sum(axis=1) - down.sum(axis=1)
    painted = wind % 2 == 1 if rule == "evenodd" else wind != 0
    return shapely.union_all(faces[painted]) if painted.any() else shapely.Polygon()


def _font_size(chain: list[ET.Element]) -> float:
    """The font size in user units inherited along ``chain`` (root first)."""
    size = DEFAULT_FONT_SIZE
    for node in chain:
        value = node.attrib.get("font-size")
        for decl in node.attrib.get("style", "").split(";"):
            if ":" in decl and decl.split(":", 1)[0].strip() == "font-size":
                value = decl.split(":", 1)[1]
        if value is not None:
            try:
                size = _absolute_length(value)
            except ValueError:
                match = _LENGTH.match(value)
                if match and match.group(2) in ("em", "%"):  # relative to the parent's size
                    size *= float(match.group(1)) / (100.0 if match.group(2) == "%" else 1.0)
    return size


class SvgShapes:
    """Shapes of a map SVG as shapely geometry in the root's user units (map regions, avoid zones).

    Reads what :func:`read_exemplar` reads — paths, basic shapes and groups, transforms of the
    element and its ancestors, inherited style — plus text, as estimated boxes.
    """

    def __init__(self, data: bytes, source: str, *, comments: bool = False) -> None:
        """Parse ``data``; with ``comments`` the tree keeps comments and processing instructions
        (to be written back, as ``svgtile map`` does), and :attr:`namespaces` lists the prefixes
        the file declares."""
        try:
            builder = ET.TreeBuilder(insert_comments=comments, insert_pis=comments)
            root = ET.fromstring(data, parser=ET.XMLParser(target=builder))
            self.namespaces = [ns for _, ns in ET.iterparse(io.BytesIO(data), events=("start-ns",))]
        except (ET.ParseError, ValueError, LookupError) as exc:
            raise ExemplarError(f"not a well-formed XML file ({_oneline(exc)})", source=source) from None
        if _local(root.tag) != "svg" or _ns(root.tag) not in ("", SVG_NS):
            raise ExemplarError(f"not an SVG document (root element is <{_local(root.tag)}>)", source=source)
        self.root, self.source = root, source
        self.reader = _Reader(root, source)
        self.parents = {c: p for p in root.iter() for c in p}

    @classmethod
    def read(cls, path: str | Path, *, comments: bool = False) -> SvgShapes:
        path = Path(path)
        try:
            data = path.read_bytes()
        except OSError as exc:
            raise ExemplarError(f"cannot read file ({exc.strerror or exc})", source=str(path)) from None
        return cls(data, str(path), comments=comments)

    def error(self, message: str) -> ExemplarError:
        return ExemplarError(_oneline(message), source=self.source)

    def element(self, ident: str) -> ET.Element:
        el = self.reader.ids.get(ident)
        if el is None:
            raise self.error(f"no element with id {_short(ident)!r}")
        return el

    def chain(self, el: ET.Element) -> list[ET.Element]:
        """``el`` and its ancestors, root first."""
        out = [el]
        while out[-1] in self.parents:
            out.append(self.parents[out[-1]])
        return out[::-1]

    def matrix(self, el: ET.Element) -> np.ndarray:
        """(3, 3) matrix from ``el``'s own user space to the root's (its transform included)."""
        m = np.eye(3)
        for node in self.chain(el)[1:]:
            m = m @ _matrix(node.attrib.get("transform"))
        return m

    def style(self, el: ET.Element) -> dict[str, str]:
        """Effective (cascaded) presentation properties of ``el``."""
        style = INITIAL
        for node in self.chain(el):
            style = _style(node, style)
        return style

    def area(self, el: ET.Element) -> shapely.Geometry:
        """The area ``el`` (a closed shape or a group of them) encloses, holes by its fill rule.

        Every subpath counts as closed (as when SVG fills it), whatever the fill paint; a group
        is the union of its shapes.  Hidden elements and text are left out.
        """
        tag = _local(el.tag)
        if tag not in SHAPES and tag not in (*CONTAINERS, "svg"):
            raise self.error(f"{_describe(el)} cannot be a region (use a closed shape or a group of them)")
        parent = self.parents.get(el)
        parent_style = self.style(parent) if parent is not None else INITIAL
        m = self.matrix(parent) if parent is not None else np.eye(3)
        geom = self._area(el, parent_style, m)
        return shapely.Polygon() if geom is None else geom

    def _area(self, el: ET.Element, parent_style: dict[str, str], m: np.ndarray) -> shapely.Geometry | None:
        style = _style(el, parent_style)
        # as in _keep_clear, id="region" is an ordinary element here: it only marks an exemplar's region
        if _hidden(style) or not _is_svg(el) or _local(el.tag) in NOT_RENDERED:
            return None
        m = m @ _matrix(el.attrib.get("transform"))
        tag = _local(el.tag)
        if tag in SHAPES:
            rings = [pts for pts, _ in _subpaths(el, self.source, REGION_FLATNESS)]
            geom = winding_fill(rings, style.get("fill-rule", "nonzero").strip())
            return _apply(m, geom)
        if tag in (*CONTAINERS, "svg"):
            parts = [self._area(c, style, m) for c in el]
            parts = [p for p in parts if p is not None and not p.is_empty]
            return shapely.union_all(parts) if parts else None
        return None

    def keep_clear(self, el: ET.Element, margin: float) -> shapely.Geometry:
        """The zone motifs must keep out of around ``el``, grown by ``margin`` user units.

        A shape's footprint (its closed outlines' interior and its stroke band; a line is its
        stroke), a text's estimated box (:data:`GLYPH_WIDTH` per character, :data:`ASCENT` and
        :data:`DESCENT` about each line's baseline, ``text-anchor`` honoured), a group's union.
        """
        parent = self.parents.get(el)
        parent_style = self.style(parent) if parent is not None else INITIAL
        m = self.matrix(parent) if parent is not None else np.eye(3)
        parts: list[shapely.Geometry] = []
        self._keep_clear(el, parent_style, m, parts)
        parts = [p for p in parts if not p.is_empty]
        if not parts:
            return shapely.Polygon()
        grown = shapely.buffer(np.array(parts, dtype=object), margin, quad_segs=4) if margin > 0 else parts
        return shapely.union_all(grown)

    def _keep_clear(self, el, parent_style, m, out: list) -> None:
        style = _style(el, parent_style)
        if _hidden(style) or not _is_svg(el) or _local(el.tag) in NOT_RENDERED:
            return
        m = m @ _matrix(el.attrib.get("transform"))
        tag = _local(el.tag)
        if tag in SHAPES:
            geom = _leaf_footprint(el, style, self.source)
            if geom is None:  # an unstroked line: the line itself, grown by the margin later
                geom = shapely.union_all([shapely.LineString(p) if len(p) > 1 else shapely.Point(p[0])
                                          for p, _ in _subpaths(el, self.source)])
            out.append(_apply(m, geom))
        elif tag == "text":
            out.extend(_apply(m, box) for box in self._text_boxes(el))
        elif tag in (*CONTAINERS, "svg"):
            for child in el:
                self._keep_clear(child, style, m, out)

    def _text_boxes(self, text: ET.Element) -> list[shapely.Polygon]:
        """Estimated boxes of a ``<text>``'s lines in its own user space (a ``tspan`` with its
        own ``x`` or ``y`` starts a line, as Inkscape writes multi-line text)."""
        lines: list[list] = []  # [x, y, anchor, size, characters]

        def walk(node: ET.Element, x: float, y: float, anchor: str) -> None:
            chain = self.chain(node)
            size = _font_size(chain)
            anchor = self._text_anchor(node, anchor)
            if "x" in node.attrib or "y" in node.attrib or not lines:
                x = _number((node.attrib.get("x") or "").split(",")[0].split(" ")[0] or None, x)
                y = _number((node.attrib.get("y") or "").split(",")[0].split(" ")[0] or None, y)
                lines.append([x, y, anchor, size, 0])
            lines[-1][3] = max(lines[-1][3], size)
            lines[-1][4] += len((node.text or "").strip())
            for child in node:
                if _local(child.tag) == "tspan":
                    walk(child, lines[-1][0], lines[-1][1], anchor)
                lines[-1][4] += len((child.tail or "").strip())

        anchor = "start"
        for node in self.chain(text)[:-1]:  # text-anchor is inherited
            anchor = self._text_anchor(node, anchor)
        walk(text, 0.0, 0.0, anchor)
        boxes = []
        for x, y, anchor, size, chars in lines:
            if chars == 0:
                continue
            width = GLYPH_WIDTH * size * chars
            x0 = x - {"start": 0.0, "middle": 0.5, "end": 1.0}.get(anchor, 0.0) * width
            boxes.append(shapely.box(x0, y - ASCENT * size, x0 + width, y + DESCENT * size))
        return boxes

    @staticmethod
    def _text_anchor(node: ET.Element, inherited: str) -> str:
        value = node.attrib.get("text-anchor")
        for decl in node.attrib.get("style", "").split(";"):
            if ":" in decl and decl.split(":", 1)[0].strip() == "text-anchor":
                value = decl.split(":", 1)[1]
        return value.strip() if value else inherited
