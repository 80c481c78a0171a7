"""The SVG dialect svgtile reads: namespaces, inherited style, lengths, transforms, and shapes
flattened to footprints.

This package (:mod:`svgtile.svg`) is the only one that imports svgelements; it is used for what it
does well (path data, shapes, transforms, lengths) while the document structure is walked with
ElementTree.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import shapely
import svgelements as se

from svgtile.errors import ExemplarError
from svgtile.files import read_input

SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"
SODIPODI_NS = "http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"
#: svgtile's own namespace: run metadata, a tile's period, a cellular pattern description.
META_NS = "urn:svgtile:run:1"
# ElementTree's namespace registry is process-wide; these are the prefixes any SVG tool expects.
# Registered here, where every module that writes SVG (texture, map, tile import) gets them
# whatever else was imported first: the bytes written must not depend on import order.
ET.register_namespace("", SVG_NS)
ET.register_namespace("xlink", XLINK_NS)
ET.register_namespace("svgtile", META_NS)
ET.register_namespace("inkscape", INKSCAPE_NS)
ET.register_namespace("sodipodi", SODIPODI_NS)

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
#: Elements nested deeper than this are refused before any walk (maps and exemplars alike): no
#: drawing needs it, and the walks recurse.
MAX_DEPTH = 200
#: The most elements an exemplar or a tile may hold (a map: ten times as many); the largest
#: real pattern tile of ../shared/data has some 5,000.
MAX_ELEMENTS = 100_000
#: The most characters of path data (``d``, ``points``) one element may have: some 500,000
#: points (osm-carto marsh.svg flattened has 2 million characters in one path).
MAX_PATH_CHARS = 8_000_000
#: The most kinds of motif an exemplar may have: the analysis compares every pair of kinds.
MAX_KINDS = 500
#: The most a transform may stretch one direction against another (ratio of its singular values):
#: beyond it (``skewX(89.99999)``) outlines become slivers GEOS cannot buffer or compare.
MAX_SQUASH = 1e6
#: Presentation properties that are not inherited but change how a plain motif looks.
OWN_LOOK = ("opacity", "clip-path", "mask", "filter")
#: Attribute of the region element giving the period of a repeating tile (see Exemplar.period).
PERIOD_ATTR = f"{{{META_NS}}}period"
#: A cellular pattern's description on the region element (JSON; svgtile.engines.cellular.tree).
CELLULAR_ATTR = "{urn:svgtile:run:1}cellular"
#: The ground a pattern is drawn on (a colour; FGDC 659's black), on the region element: a tile's
#: painted background, which the import drops as a frame, kept for the textures to paint.
GROUND_ATTR = f"{{{META_NS}}}ground"
#: What a ground may be: a colour name, #hex or rgb(), nothing that could leave a style value.
GROUND_VALUE = re.compile(r"#[0-9A-Fa-f]{3,8}|[A-Za-z]{3,30}|rgba?\([0-9.,%\s]+\)")




def one_line(text: object) -> str:
    """``text`` as one line (messages must fit the CLI's single line)."""
    return " ".join(str(text).split())


def local_tag(tag: str) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def tag_ns(tag: str) -> str:
    return tag[1:].split("}", 1)[0] if isinstance(tag, str) and tag.startswith("{") else ""


def is_svg(el: ET.Element) -> bool:
    return isinstance(el.tag, str) and tag_ns(el.tag) in ("", SVG_NS)


def href_of(el: ET.Element) -> str | None:
    """The element's ``href`` or ``xlink:href`` (SVG 2 ``href`` wins), or None.

    ElementTree resolves prefixes, so an ad-hoc prefix bound to the xlink namespace (jsdotpattern
    writes ``NS1:href`` with ``xmlns:NS1``) arrives as ``{xlink}href`` too; an ``href`` in any
    other namespace is not a reference.
    """
    for key in ("href", f"{{{XLINK_NS}}}href"):
        if key in el.attrib:
            return el.attrib[key].strip()
    return None


def cascade_style(el: ET.Element, parent: dict[str, str]) -> dict[str, str]:
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


def inherited_items(style: dict[str, str]) -> tuple[tuple[str, str], ...]:
    """The inherited properties of ``style`` that differ from their initial values, sorted."""
    return tuple(sorted((k, v) for k, v in style.items() if k in INHERITED and INITIAL.get(k) != v))


def is_hidden(style: dict[str, str]) -> bool:
    return (
        style.get("display") == "none"
        or style.get("visibility") in ("hidden", "collapse")
        or number_attr(style.get("opacity", "1"), 1.0) <= 0
    )


def is_painted(value: str | None) -> bool:
    return value is not None and value.strip() not in ("none", "transparent")


def number_attr(text: str | None, default: float) -> float:
    """An absolute length or number in user units; ``default`` if missing, relative or unreadable."""
    if text is None:
        return default
    try:
        return absolute_length(text)
    except ValueError:
        return default


LENGTH_RE = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([a-zA-Z%]*)\s*$")
_RELATIVE_UNITS = {"%", "em", "ex", "ch", "rem", "vw", "vh", "vmin", "vmax", "vi", "vb", "cap", "ic", "lh", "rlh"}
_UNITS = {"": 1.0, "px": 1.0, "mm": 96 / 25.4, "cm": 96 / 2.54, "q": 96 / 101.6, "in": 96.0, "pt": 96 / 72, "pc": 16.0}


def absolute_length(text: str) -> float:
    """A geometry length in user units; relative units (%, em, ex) and junk raise ValueError."""
    match = LENGTH_RE.match(text)
    if match is None:
        raise ValueError(f"unreadable length {text.strip()!r}")
    number, unit = match.groups()
    if unit.lower() in _RELATIVE_UNITS:
        raise ValueError(f"length {text.strip()!r} is relative (svgtile resolves only absolute units)")
    if unit.lower() not in _UNITS:
        raise ValueError(f"unreadable length {text.strip()!r}")
    return float(number) * _UNITS[unit.lower()]


def check_tree(root: ET.Element, source: str, *, max_elements: int = MAX_ELEMENTS) -> None:
    """Refuse a document nested deeper than :data:`MAX_DEPTH` or larger than ``max_elements``
    elements, before anything walks it (without recursion, so any depth is measured)."""
    stack, count = [(root, 1)], 0
    while stack:
        el, depth = stack.pop()
        count += 1
        if depth > MAX_DEPTH:
            raise ExemplarError(f"elements are nested too deeply (over {MAX_DEPTH} levels, at {describe(el)})", source=source)
        if count > max_elements:
            raise ExemplarError(f"more than {max_elements:,} elements; svgtile reads smaller files", source=source)
        stack.extend((c, depth + 1) for c in el)


def geometry_error(exc: Exception, source: str) -> ExemplarError:
    """The error for input geometry the geometry engine (GEOS) or float arithmetic cannot handle."""
    return ExemplarError(f"geometry too extreme to compute with ({one_line(exc)}); check the coordinates "
                         "and transforms", source=source)  # fmt: skip


_NUM = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"
_TRANSFORM_RE = re.compile(
    rf"[\s,]*(?:(?:matrix|translate|scale|rotate|skewX|skewY)\s*\(\s*(?:{_NUM}(?:\s*,?\s*{_NUM})*)?\s*\)[\s,]*)*"
)


def parse_matrix(text: str | None) -> np.ndarray:
    """3×3 affine matrix of an SVG ``transform`` attribute.

    Raises
    ------
    ValueError
        The transform is unreadable, not finite, scales beyond :data:`MAX_COORDINATE` or squashes
        beyond :data:`MAX_SQUASH` (``skewX(90)``, ``rotate(nan)``, ``scale(1e308)``), or is
        singular (``scale(0)``, ``matrix(1 2 2 4 0 0)``): SVG draws nothing under a singular
        transform, and what the author meant by it is unknowable — a motif silently gone, a map
        unit silently empty, are worse than a refusal naming the element.  The message completes
        "has a transform '…' that …".
    """
    if not text:
        return np.eye(3)
    if not _TRANSFORM_RE.fullmatch(text):  # svgelements would skip what it cannot read (nan, inf …)
        raise ValueError("cannot be read")
    try:
        m = se.Matrix(text)
        out = np.array([[m.a, m.c, m.e], [m.b, m.d, m.f], [0.0, 0.0, 1.0]], dtype=np.float64)
    except (ValueError, TypeError, IndexError, ArithmeticError):  # svgelements' bare errors on bad data
        raise ValueError("cannot be read") from None
    if not (np.abs(out) <= MAX_COORDINATE).all():  # also NaN
        raise ValueError(f"is not finite, or reaches beyond ±{MAX_COORDINATE:g}")
    sv = np.linalg.svd(out[:2, :2], compute_uv=False)
    if not sv[0] > 0 or sv[1] <= sv[0] * 1e-12:
        raise ValueError("is singular (it collapses what it draws to a line or a point, so SVG draws nothing)")
    if sv[0] / sv[1] > MAX_SQUASH:
        raise ValueError(f"skews or squashes by more than {MAX_SQUASH:g} to 1")
    return out


def element_matrix(el: ET.Element, source: str) -> np.ndarray:
    """:func:`parse_matrix` of ``el``'s ``transform``; a bad one is an ExemplarError naming ``el``."""
    text = el.attrib.get("transform")
    try:
        return parse_matrix(text)
    except ValueError as exc:
        raise ExemplarError(f"{describe(el)} has a transform {shorten(text or '', 60)!r} that {exc}",
                            source=source) from None  # fmt: skip


def translation(x: float, y: float) -> np.ndarray:
    return np.array([[1.0, 0.0, x], [0.0, 1.0, y], [0.0, 0.0, 1.0]])


def linear_part(lin: np.ndarray) -> np.ndarray:
    m = np.eye(3)
    m[:2, :2] = lin
    return m


def apply_matrix(m: np.ndarray, geom: shapely.Geometry) -> shapely.Geometry:
    return shapely.transform(geom, lambda c: c @ m[:2, :2].T + m[:2, 2])


def fmt_number(v: float) -> str:
    s = f"{v:.6f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def matrix_attr(m: np.ndarray) -> str:
    return "matrix({})".format(" ".join(fmt_number(v) for v in (m[0, 0], m[1, 0], m[0, 1], m[1, 1], m[0, 2], m[1, 2])))


def is_rendered(el: ET.Element) -> bool:
    """Can ``el`` draw as part of its parent (the input region never does)?"""
    return is_svg(el) and local_tag(el.tag) not in NOT_RENDERED and el.attrib.get("id") != "region"


def drawable_children(el: ET.Element) -> list[ET.Element]:
    """Children of ``el`` that may draw something."""
    return [c for c in el if is_rendered(c)]


def holds_motifs(group: ET.Element, *, alone: bool) -> bool:
    """Is ``group`` a container of motifs rather than a motif itself?

    Yes for Inkscape layers, for groups holding ``<use>`` instances, and for a group that is the
    only drawable child of its container yet holds several shapes or another group (an exporter's
    wrapper, possibly nested).
    """
    if group.attrib.get(f"{{{INKSCAPE_NS}}}groupmode") == "layer":
        return True
    if any(local_tag(e.tag) == "use" for e in group.iter()):
        return True
    if not alone:
        return False
    children = drawable_children(group)
    return len(children) > 1 or (len(children) == 1 and local_tag(children[0].tag) in CONTAINERS)


def describe(el: ET.Element) -> str:
    ident = el.attrib.get("id")
    return f"<{local_tag(el.tag)} id={ident!r}>" if ident else f"<{local_tag(el.tag)}>"


def shorten(ref: str, limit: int = 80) -> str:
    return ref if len(ref) <= limit else ref[: limit - 1] + "…"


# ----------------------------------------------------------------------------- geometry

_GEOMETRY = {
    "rect": (se.Rect, ("x", "y", "width", "height", "rx", "ry")),
    "circle": (se.Circle, ("cx", "cy", "r")),
    "ellipse": (se.Ellipse, ("cx", "cy", "rx", "ry")),
    "line": (se.SimpleLine, ("x1", "y1", "x2", "y2")),
}


def se_shape(el: ET.Element) -> se.Shape | None:
    """The svgelements shape for a basic shape element, without its transform (None: no shape).

    Lengths are converted here, so svgelements never guesses a unit; a relative length raises
    ValueError.
    """
    tag = local_tag(el.tag)
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
            attrs[name] = repr(absolute_length(text))
    return cls(attrs)


def control_points(seg: se.PathSegment) -> list[tuple[float, float]]:
    """Points whose hull contains ``seg`` (to size the flattening tolerance without evaluating it)."""
    if isinstance(seg, se.Arc):
        r = max(abs(seg.rx), abs(seg.ry))
        c = seg.center
        return [(c.x - r, c.y - r), (c.x + r, c.y + r)]
    names = ("start", "control", "control1", "control2", "end")
    return [(p.x, p.y) for p in (getattr(seg, n, None) for n in names) if p is not None]


def sample_segment(seg: se.PathSegment, tol: float) -> np.ndarray:
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


def flatten_path(path: se.Path, flatness: float = FLATNESS) -> list[tuple[np.ndarray, bool]]:
    """Subpaths of ``path`` as ``((k, 2) points, closed)`` polylines.

    A subpath that is only a moveto draws nothing (not even a cap) and is dropped; ``M x y Z`` and
    ``M x y L x y`` are kept, as one-point polylines, because their caps draw.
    """
    segments = list(path)
    hull = [p for seg in segments for p in control_points(seg)]
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
            pts.append(sample_segment(seg, tol))
    flush(False)
    return out


CAPS = {"round": "round", "square": "square", "butt": "flat"}
JOINS = {"round": "round", "bevel": "bevel", "miter": "mitre", "miter-clip": "mitre", "arcs": "mitre"}


def flat_subpaths(el: ET.Element, source: str, flatness: float = FLATNESS) -> list[tuple[np.ndarray, bool]]:
    """Flattened subpaths of a shape element in its own user space; bad data is an ExemplarError."""
    data = el.attrib.get("d") or el.attrib.get("points") or ""
    if len(data) > MAX_PATH_CHARS:
        raise ExemplarError(f"{describe(el)} has {len(data):,} characters of path data (more than "
                            f"{MAX_PATH_CHARS:,}); simplify it first", source=source)  # fmt: skip
    try:
        shape = se_shape(el)
        subpaths = flatten_path(se.Path(shape), flatness) if shape is not None else []
    except Exception as exc:  # svgelements raises bare ValueErrors/TypeErrors on bad data
        detail = "malformed path data" if local_tag(el.tag) == "path" else one_line(exc) or type(exc).__name__
        raise ExemplarError(f"cannot read the geometry of {describe(el)} ({detail})", source=source) from None
    if sum(len(pts) for pts, _ in subpaths) > MAX_COORDINATES:
        raise ExemplarError(f"{describe(el)} is too complex (over {MAX_COORDINATES} outline points)", source=source)
    if not all((np.abs(pts) <= MAX_COORDINATE).all() for pts, _ in subpaths):  # also NaN
        raise ExemplarError(f"{describe(el)} has coordinates that are not finite or beyond ±{MAX_COORDINATE:g}",
                            source=source)  # fmt: skip
    return subpaths


def leaf_footprint(el: ET.Element, style: dict[str, str], source: str) -> shapely.Geometry | None:
    """Footprint of one shape element in its own user space (before its transform).

    The interior of every closed subpath (filled or not) and of every filled one, plus the stroke
    band of half the stroke width with its caps and joins (a subpath that returns to its start
    without ``Z`` gets its interior when holes are filled).  A zero-length subpath is a dot with
    round caps and a square with square caps.
    """
    subpaths = flat_subpaths(el, source)
    filled = is_painted(style.get("fill", INITIAL["fill"]))
    width = number_attr(style.get("stroke-width"), 1.0)
    stroked = is_painted(style.get("stroke", INITIAL["stroke"])) and width > 0
    cap = CAPS.get(style.get("stroke-linecap", "butt"), "flat")
    join = JOINS.get(style.get("stroke-linejoin", "miter"), "mitre")
    limit = number_attr(style.get("stroke-miterlimit"), 4.0)
    if stroked and not width <= MAX_COORDINATE:
        raise ExemplarError(f"{describe(el)} has a stroke width beyond {MAX_COORDINATE:g}", source=source)
    parts = []
    for pts, closed in subpaths:
        distinct = len(np.unique(np.round(pts, 12), axis=0))
        if distinct >= 3 and (closed or filled):
            parts.append(shapely.make_valid(shapely.Polygon(pts)))
        if not stroked:
            continue
        if distinct == 1:
            parts.extend(dot_footprint(pts[0], width, cap))
            continue
        line = np.vstack([pts, pts[:1]]) if closed else pts
        parts.append(
            shapely.LineString(line).buffer(
                width / 2, quad_segs=16, cap_style=cap, join_style=join, mitre_limit=max(limit, 1.0)
            )
        )
    parts = [p for p in parts if not p.is_empty and p.area > 0]
    return shapely.union_all(parts) if parts else None


def polygons_of(geom: shapely.Geometry) -> list[shapely.Polygon]:
    """The polygons of ``geom`` at any depth of collection."""
    out = []
    for part in shapely.get_parts(geom):
        if isinstance(part, shapely.Polygon):
            out.append(part)
        elif isinstance(part, (shapely.MultiPolygon, shapely.GeometryCollection)):
            out.extend(polygons_of(part))
    return out


def fill_holes(geom: shapely.Geometry) -> shapely.Geometry:
    return shapely.union_all([shapely.Polygon(p.exterior) for p in polygons_of(geom) if not p.is_empty])


# ----------------------------------------------------------------------------- the reader


def dot_footprint(point: np.ndarray, width: float, cap: str) -> list[shapely.Geometry]:
    """The footprint of a zero-length stroke: a disc (round cap) or a square (square cap) of the
    stroke's width around ``point`` (2,), user units; none for a butt cap, which draws nothing."""
    if cap == "round":
        return [shapely.Point(point).buffer(width / 2, quad_segs=16)]
    if cap == "square":
        x, y = point
        return [shapely.box(x - width / 2, y - width / 2, x + width / 2, y + width / 2)]
    return []


def read_svg_bytes(path: str | Path) -> bytes:
    """The bytes of an SVG file; an unreadable file is an :class:`ExemplarError` naming it."""
    return read_input(path, error=ExemplarError)


_EXTERNAL_URL = re.compile(r"url\(\s*(?![\s'\"]*#)[^)]*\)")
#: Properties whose ``url(…)`` is a paint server: an external one becomes ``none``; elsewhere
#: (``mask``, ``filter``, ``clip-path``, markers) the property is removed.
_PAINT = ("fill", "stroke")


def neutralise_external(elements: list[ET.Element]) -> list[str]:
    """Drop from ``elements`` (in place) every reference to outside the file a viewer could fetch.

    An ``href`` that is not ``#id`` (``<image>``, ``<feImage>``, ``<a>``) is removed; a
    ``url(…)`` that is not ``url(#id)`` makes ``fill``/``stroke`` ``none`` and removes any other
    property (``mask``, ``filter``, ``clip-path``, ``marker-*``), in attributes and in ``style``;
    a ``<style>`` sheet with ``@import`` or an external ``url(…)`` is emptied.  Returns one
    description per dropped reference (``<image id="i"> href``).
    """
    dropped: list[str] = []
    for el in elements:
        for node in el.iter():
            if not isinstance(node.tag, str):
                continue
            for key in [k for k in node.attrib if local_tag(k) == "href"]:
                if not node.attrib[key].startswith("#"):
                    dropped.append(f"{describe(node)} href")
                    del node.attrib[key]
            for key in list(node.attrib):
                value = node.attrib[key]
                if key == "style":
                    kept = []
                    for decl in value.split(";"):
                        name, _, v = decl.partition(":")
                        if _EXTERNAL_URL.search(v):
                            dropped.append(f"{describe(node)} {name.strip()}")
                            if name.strip() in _PAINT:
                                kept.append(f"{name.strip()}:none")
                        else:
                            kept.append(decl)
                    node.set("style", ";".join(kept))
                elif _EXTERNAL_URL.search(value):
                    dropped.append(f"{describe(node)} {local_tag(key)}")
                    if local_tag(key) in _PAINT:
                        node.set(key, "none")
                    else:
                        del node.attrib[key]
            if local_tag(node.tag) == "style" and node.text and ("@import" in node.text or _EXTERNAL_URL.search(node.text)):
                dropped.append(f"{describe(node)} @import or url()")
                node.text = ""
    return dropped
