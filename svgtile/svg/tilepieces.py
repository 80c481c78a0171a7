"""A pattern tile flattened into drawn pieces, for :mod:`svgtile.tiles.importer`."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import shapely

from svgtile.errors import ExemplarError
from svgtile.svg.dialect import (
    CAPS,
    CONTAINERS,
    GROUND_VALUE,
    INITIAL,
    JOINS,
    MAX_COORDINATE,
    MAX_USE_DEPTH,
    SHAPES,
    SVG_NS,
    absolute_length,
    apply_matrix,
    cascade_style,
    check_tree,
    describe,
    dot_footprint,
    element_matrix,
    fill_holes,
    flat_subpaths,
    fmt_number,
    is_hidden,
    is_painted,
    is_rendered,
    local_tag,
    number_attr,
    one_line,
    read_svg_bytes,
    tag_ns,
    translation,
)
from svgtile.svg.reader import DocumentReader

# A pattern tile (FGDC lithology, OSM area fill …) is not an exemplar: one element may hold many
# motifs and one motif many elements.  :func:`read_tile` flattens it into *pieces* — one per
# drawn subpath, with its footprint and polyline in tile coordinates — that
# :mod:`svgtile.tiles.importer` groups into motifs.

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
    groups : list of n tuples of int
        The drawn groups each piece lies in, outermost first: one id per ``<g>`` (``<a>``,
        ``<switch>``) and per ``<use>`` expansion walked, so that the subpaths of an icon drawn as
        a group (or ``<use>``d once per place) can be kept together.
    ground : str
        The colour of the painted frame drawn last (the ground the pattern is drawn on, FGDC
        659's black), or "" (none, or a paint that is no plain colour)
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
    groups: list[tuple[int, ...]] = field(default_factory=list)
    ground: str = ""


def _alpha(text: str | None) -> float:
    """An opacity value (a number, or a percentage); 1 if missing, 0 if unreadable."""
    if text is None:
        return 1.0
    t = text.strip()
    try:
        return float(t[:-1]) / 100.0 if t.endswith("%") else float(t)
    except ValueError:
        return 0.0


def read_tile(path: str | Path) -> TilePieces:
    """Read a pattern tile SVG file into pieces (see :func:`parse_tile`)."""
    return parse_tile(read_svg_bytes(path), source=str(path))


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
        raise ExemplarError(f"not a well-formed XML file ({one_line(exc)})", source=source) from None
    if local_tag(root.tag) != "svg" or tag_ns(root.tag) not in ("", SVG_NS):
        raise ExemplarError(f"not an SVG document (root element is <{local_tag(root.tag)}>)", source=source)
    check_tree(root, source)
    reader = DocumentReader(root, source)
    reader.refuse_external_references()
    box = _tile_box(root, source)
    walk = _TileWalk(reader, box)
    try:
        walk.visit(root, cascade_style(root, INITIAL), np.eye(3), ())
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
        reader.warnings, walk.groups, walk.ground,
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
            w = absolute_length(root.attrib.get("width", ""))
            h = absolute_length(root.attrib.get("height", ""))
        except ValueError:
            raise ExemplarError(
                "the tile size is unknown (the root <svg> has no viewBox and no absolute width/height)",
                source=source,
            ) from None
    if not (abs(x) <= MAX_COORDINATE and abs(y) <= MAX_COORDINATE and 0 < w <= MAX_COORDINATE and 0 < h <= MAX_COORDINATE):
        what = "has no area" if w <= 0 or h <= 0 else f"is not finite or beyond ±{MAX_COORDINATE:g}"
        raise ExemplarError(f"the tile ({w:g} x {h:g} at {x:g}, {y:g}) {what}", source=source)
    return (x, y, w, h)


#: The most elements a tile may draw, each ``<use>`` expansion counted: the largest real tile of
#: ../shared/data (osm-carto reef.svg) has 6,727 elements, some 30,000 when expanded.
MAX_EXPANDED = 100_000


class _TileWalk:
    """Collects the pieces of a tile (see :func:`parse_tile`)."""

    #: A shape is a frame when its footprint's bounds match the tile's within this share of its size.
    FRAME_TOLERANCE = 0.01

    def __init__(self, reader: DocumentReader, box: tuple[float, float, float, float]) -> None:
        self.reader, self.box = reader, box
        self.footprint: list[shapely.Geometry] = []
        self.points: list[np.ndarray] = []
        self.closed: list[bool] = []
        self.element: list[int] = []
        self.paint: list[tuple[tuple[str, str], ...]] = []
        self.frames: list[str] = []
        self.filled_frame = False
        self.ground = ""
        self.elements = 0
        self.visited = 0  # elements walked, each <use> expansion counted again
        self.local: dict[tuple, list] = {}  # (element, paint) -> [(points, closed, footprint)], own frame
        self.groups: list[tuple[int, ...]] = []
        self.chain: tuple[int, ...] = ()  # the groups being walked, outermost first
        self.opened = 0  # groups walked so far (the next group's id)

    def enter(self, visit, *args) -> None:
        """``visit(*args)`` inside a new drawn group (see :attr:`TilePieces.groups`)."""
        outer = self.chain
        self.chain = (*outer, self.opened)
        self.opened += 1
        try:
            visit(*args)
        finally:
            self.chain = outer

    def visit(self, el: ET.Element, style: dict[str, str], m: np.ndarray, stack: tuple[str, ...]) -> None:
        for child in el:
            if not is_rendered(child):
                continue
            self.visited += 1
            if self.visited > MAX_EXPANDED:  # <use> fan-out: 30 levels of two make a billion
                raise self.reader.error(f"its <use> elements expand to more than {MAX_EXPANDED:,} elements")
            tag = local_tag(child.tag)
            cstyle = cascade_style(child, style)
            if is_hidden(cstyle):
                continue
            cm = m @ element_matrix(child, self.reader.source)
            if "clip-path" in cstyle or "mask" in cstyle:
                self.reader.warn(f"clip paths and masks are ignored ({describe(child)}); the tile's edge is the clip")
            if tag in SHAPES:
                self.shape(child, cstyle, cm)
            elif tag in CONTAINERS:
                self.enter(self.visit, child, cstyle, cm, stack)
            elif tag == "svg":
                if "viewBox" in child.attrib:
                    raise self.reader.error(f"nested {describe(child)} with a viewBox is not supported; flatten it first")
                x, y = number_attr(child.attrib.get("x"), 0), number_attr(child.attrib.get("y"), 0)
                self.visit(child, cstyle, cm @ translation(x, y), stack)
            elif tag == "use":
                ref, target = self.reader.target(child)
                if ref in stack or len(stack) >= MAX_USE_DEPTH:
                    raise self.reader.error(f"{describe(target)} is referenced recursively")
                view, _ = self.reader.viewport(child, target)
                x, y = number_attr(child.attrib.get("x"), 0), number_attr(child.attrib.get("y"), 0)
                holder = ET.Element("g")
                holder.append(target)
                tm = cm @ translation(x, y) @ view
                if local_tag(target.tag) in ("symbol", "svg"):
                    self.enter(self.visit, target, cascade_style(target, cstyle), tm, (*stack, ref))
                else:
                    self.enter(self.visit, holder, cstyle, tm, (*stack, ref))
            elif tag in ("text", "image"):
                self.reader.warn(f"{describe(child)} is ignored (only shapes are motifs)")

    def shape(self, el: ET.Element, style: dict[str, str], m: np.ndarray) -> None:
        det = float(np.linalg.det(m[:2, :2]))
        if abs(det) < 1e-12:
            return
        filled = is_painted(style.get("fill", INITIAL["fill"]))
        width = number_attr(style.get("stroke-width"), 1.0)
        stroked = is_painted(style.get("stroke", INITIAL["stroke"])) and width > 0
        if not (filled or stroked):
            return  # draws nothing (e.g. a fill:none frame or mapnik_workaround rect)
        cap = CAPS.get(style.get("stroke-linecap", "butt"), "flat")
        join = JOINS.get(style.get("stroke-linejoin", "miter"), "mitre")
        limit = max(number_attr(style.get("stroke-miterlimit"), 4.0), 1.0)
        key = (el, filled, width if stroked else 0.0, cap, join, limit)
        if key not in self.local:  # a <use>d shape is measured once, however often it is drawn
            self.local[key] = [(pts, closed, _subpath_footprint(pts, closed, *key[1:]))
                               for pts, closed in flat_subpaths(el, self.reader.source)]  # fmt: skip
        geoms, kept = [], []
        for pts, closed, geom in self.local[key]:
            if geom is not None:
                geoms.append(apply_matrix(m, geom))
                kept.append((pts @ m[:2, :2].T + m[:2, 2], closed))
        if not geoms:
            return
        if self.is_frame(shapely.union_all(geoms), width * math.sqrt(abs(det)) if stroked else 0.0):
            self.frames.append(describe(el))
            self.filled_frame |= filled
            if filled:  # the ground the pattern is drawn on, where it is a plain colour
                fill = style.get("fill", INITIAL["fill"]).strip()
                # a translucent or inherited paint is no plain colour to paint a map unit with
                opaque = all(_alpha(style.get(k)) >= 1.0 for k in ("opacity", "fill-opacity"))
                plain = fill.lower() not in ("none", "currentcolor", "inherit", "transparent")
                self.ground = fill if opaque and plain and GROUND_VALUE.fullmatch(fill) else ""
            return
        paint = {k: style[k] for k in PIECE_PAINT if k in style}
        paint["fill"] = style.get("fill", INITIAL["fill"])
        if stroked:
            paint["stroke-width"] = fmt_number(width * math.sqrt(abs(det)))
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
            self.groups.append(self.chain)
        self.elements += 1

    def is_frame(self, geom: shapely.Geometry, stroke: float) -> bool:
        """Does ``geom`` (a footprint with a stroke band ``stroke`` wide) cover the tile exactly?"""
        x, y, w, h = self.box
        tol = self.FRAME_TOLERANCE * max(w, h) + stroke / 2
        x0, y0, x1, y1 = geom.bounds
        covers = geom.area >= 0.9 * w * h or fill_holes(geom).area >= 0.9 * w * h
        return covers and max(abs(x0 - x), abs(y0 - y), abs(x1 - x - w), abs(y1 - y - h)) <= tol


def _subpath_footprint(
    pts: np.ndarray, closed: bool, filled: bool, width: float, cap: str, join: str, limit: float
) -> shapely.Geometry | None:
    """Footprint of one flattened subpath in its own user space (as in :func:`leaf_footprint`).

    ``width`` 0 means not stroked.  A zero-length subpath is a dot of diameter ``width`` with
    round caps (a square with square caps).  None if it covers no area.
    """
    distinct = len(np.unique(np.round(pts, 12), axis=0))
    parts = []
    if distinct >= 3 and (closed or filled):
        parts.append(shapely.make_valid(shapely.Polygon(pts)))
    if width > 0:
        if distinct == 1:
            parts.extend(dot_footprint(pts[0], width, cap))
        else:
            line = np.vstack([pts, pts[:1]]) if closed else pts
            parts.append(shapely.LineString(line).buffer(width / 2, quad_segs=16, cap_style=cap, join_style=join, mitre_limit=limit))
    parts = [p for p in parts if not p.is_empty and p.area > 0]
    return shapely.union_all(parts) if parts else None

