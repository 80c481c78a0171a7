"""Feature-based cellular textures (Legakis, Dorsey & Gortler 2001) behind the engine protocol.

A map unit is the paper's base mesh in 2-D (:mod:`.mesh`, §3.1): corners, edges (holes
included, labelled by the map's lines), the face.  Its features are textured in the paper's
order (§4.2) — corners, then edges, then the face — each by the generator the tree of
:mod:`.tree` routes it to (§4.1), each filling only what is still empty (occupancy maps, §3.3:
1-D intervals of arc length per edge, exact polygon bookkeeping with shapely for the face).
Faces are laid on a course frame (:mod:`.frame`, §3.2): a strike angle, the unit's long axis, or
the ``--flow`` control.  Cells claim their space-filling shapes and are drawn shrunk by the
mortar (§5.4); bedding lines follow the courses; exemplar motifs may be set in cells.

The output is a :class:`~svgtile.core.cells.Cellwork` (cells and lines) beside the motifs
(:meth:`~svgtile.engines.cellular.CellularEngine.place_cells`: :func:`description`, :func:`read_labels`,
:func:`texture`); :meth:`~svgtile.engines.cellular.CellularEngine.place` returns the motifs alone.

What a run keeps (the guarantees the tests hold it to): cells lie in the region whatever the
boundary mode (edge cells follow the boundary instead of being cut by it), no two cells overlap,
face cells are world-anchored (the same strike gives the same courses in every unit, and an edit
of the boundary changes only the cells within about a course and a cell of it).
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.cells import CORNER, EDGE, FACE, LINE, Cellwork, geometry_array
from svgtile.core.conflicts import cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import world_footprints
from svgtile.engines.base import Context
from svgtile.engines.cellular import CellularParams
from svgtile.errors import ParameterError

from . import generators as gen
from .frame import FlowFrame, RotatedFrame, long_axis_angle
from .joints import draw_joints
from .mesh import BaseMesh, base_mesh
from .tree import Description, parse_description, read_description

_KIND, _ANGLE, _SCALE, _TAKE, _PRIORITY = range(5)
#: Most cells a run may lay, and most points it may sample (the unit's outline every half course,
#: its bedding lines): a description with a tiny course, cell length, dash or wave period would
#: otherwise allocate without bound.
MAX_CELLS = 2_000_000
MAX_SAMPLES = 20_000_000
#: The RGB blocks of §4.1, for debugging a tree: corners red, edges green, faces blue.
RGB = {CORNER: "fill:#e41a1c;stroke:#ffffff;stroke-width:0.2", EDGE: "fill:#4daf4a;stroke:#ffffff;stroke-width:0.2",
       FACE: "fill:#377eb8;stroke:#ffffff;stroke-width:0.2"}  # fmt: skip
#: How a line is drawn when neither its description nor the cells give a style.
LINE_STYLE = "fill:none;stroke:#000000;stroke-width:0.3"
#: Face cells with less than this share of a whole cell inside the free space are not made.
SLIVER = 0.02
#: Cell outlines closer than this share of a course are one joint (:func:`.joints.draw_joints`).
JOINT_TOLERANCE = 1e-4


def description(exemplar: Exemplar, p: CellularParams) -> Description:
    """The pattern: the ``tree`` file, else the exemplar's own, else bricks sized to its motifs;
    sizes given as parameters override the description's."""
    if p.tree:
        d = read_description(p.tree)
    elif getattr(exemplar, "cellular", None):
        d = parse_description(exemplar.cellular, exemplar.source)
    else:
        d = Description(motifs={"share": 1.0})
    course = p.course_height or d.course
    if not course:  # one motif's share of the exemplar's area, as a square's side
        course = math.sqrt(exemplar.region.area / max(len(exemplar.motifs), 1))
    length = p.cell_length or d.length or 2.0 * course
    bands = d.bands.scaled(course / d.course) if d.bands is not None and d.course else d.bands
    return Description(course, length, d.offset, p.mortar or d.mortar, d.cell_style, d.tree, d.lines, d.motifs,
                       d.ashlar, d.rhomb_angle, d.angle, bands)  # fmt: skip


def _check_cells(face: shapely.Geometry, d: Description) -> None:
    """Refuse a description whose cells would number beyond :data:`MAX_CELLS` over ``face``, or
    whose course is so fine that the unit's outline, sampled every half course to find the
    courses' extent (:func:`.generators.st_bounds`), takes beyond :data:`MAX_SAMPLES` points."""
    if not (d.course > 0 and d.length > 0):
        raise ParameterError("the cells' course height and length must be positive")
    cells = face.area / (d.course * d.length)
    if cells > MAX_CELLS:
        raise ParameterError(f"cells of {d.course:g} x {d.length:g} would number about {cells:,.0f} in the region "
                             f"(limit {MAX_CELLS:,}): choose larger cells or a smaller region")  # fmt: skip
    samples = face.length / (d.course / 2)
    if samples > MAX_SAMPLES:
        raise ParameterError(f"courses of {d.course:g} are too fine for the region: its outline would take about "
                             f"{samples:,.0f} points (limit {MAX_SAMPLES:,})")  # fmt: skip


def read_labels(spec: str, course: float, *, unit: float = 1.0) -> dict[str, shapely.Geometry]:
    """``NAME=MAP.svg#ID,…`` -> name -> the element's geometry grown by a tenth of a course, in
    user units (the file's units divided by ``unit``)."""
    from svgtile.svg.mapdoc import SvgShapes

    out: dict[str, shapely.Geometry] = {}
    for item in filter(None, (s.strip() for s in spec.split(","))):
        name, eq, where = item.partition("=")
        path, sep, ident = where.partition("#")
        if not (eq and sep and name.strip() and path and ident):
            raise ParameterError(f"--label {item!r}: expected NAME=MAP.svg#ID")
        doc = SvgShapes.read(path)
        zone = doc.keep_clear(doc.element(ident), 0.1 * course * unit)
        out[name.strip()] = zone if unit == 1.0 else shapely.transform(zone, lambda c, u=unit: c / u)
    return out


def texture(ctx: Context, d: Description, p: CellularParams, labels: dict[str, shapely.Geometry]
            ) -> tuple[Arrangement, Cellwork]:  # fmt: skip
    """The whole run on a parsed description (see the module docstring)."""
    face = ctx.region.shape
    h, length = d.course, d.length
    _check_cells(face, d)
    mesh = base_mesh(face, corner_angle=p.corner_angle, tolerance=0.01 * h, labels=labels, label_distance=0.0)
    if ctx.controls.flow is not None:
        frame = FlowFrame(ctx.controls.flow, face, h / 2)
    else:
        frame = RotatedFrame(long_axis_angle(face) if p.courses == "long-axis" else p.strike or d.angle)
    styles: list[str] = [d.cell_style]
    shapes, feature, style = [], [], []

    def add(cells: np.ndarray, kind: int, css: str | None) -> None:
        css = d.cell_style if css is None else css
        if css not in styles:
            styles.append(css)
        shapes.append(cells)
        feature.append(np.full(len(cells), kind))
        style.append(np.full(len(cells), styles.index(css)))

    # 1. corners and 2. edges, in the edge strip (§4.2)
    ctx.progress("corners and edges", 0.0)
    claimed = _corners_and_edges(mesh, d, h, length, add)
    # 3. the face: what is still free (its occupancy map)
    ctx.progress("face", 0.4)
    free = shapely.difference(face, claimed) if claimed is not None else face
    leaf = d.tree.route({"feature": "face", "label": ""})
    if leaf is not None and leaf.generator != "none" and not free.is_empty:
        cells = face_cells(frame, free, leaf.generator, d, key=ctx.key, fewest_halves=p.halves == "fewest")
        add(cells, FACE, RGB[FACE] if leaf.generator == "blocks" and leaf.style is None else leaf.style)
    # bedding lines along the courses, over the face
    if d.lines:
        ctx.progress("lines", 0.7)
        for lines, css in zip(*bedding(frame, face, d), strict=True):
            add(lines, LINE, css or d.cell_style or LINE_STYLE)
    work = Cellwork(np.concatenate(shapes) if shapes else np.empty(0, dtype=object),
                    np.concatenate(feature).astype(np.int64) if feature else np.zeros(0, np.int64),
                    np.concatenate(style).astype(np.int64) if style else np.zeros(0, np.int64), tuple(styles))  # fmt: skip
    if d.mortar > 0:
        cell = work.feature != LINE
        shrunk = work.shapes.copy()
        shrunk[cell] = gen.shrink(work.shapes[cell], d.mortar)
        work = Cellwork(shrunk, work.feature, work.style, work.styles)
    work = work.take(np.flatnonzero(~shapely.is_empty(work.shapes)))
    motifs = Arrangement.empty()
    if d.motifs is not None and len(ctx.exemplar.motifs):
        ctx.progress("motifs in cells", 0.85)
        motifs = motifs_in_cells(ctx, work.shapes[work.feature != LINE], frame, float(d.motifs.get("share", 1.0)),
                                 over=bool(d.motifs.get("over", False)), bearing=d.angle)  # fmt: skip
    # cells with no style were only claimed (to hold motifs, to keep the order): not drawn
    blank = np.array([not css for css in work.styles], dtype=bool)
    if len(work) and blank.any():
        work = work.take(np.flatnonzero(~blank[work.style]))
    if d.mortar == 0:  # neighbours share their sides: each joint stroked once, as the tile does
        work = draw_joints(work, face, JOINT_TOLERANCE * h)
    return motifs, work.in_reading_order(DECIMALS)


def _corners_and_edges(mesh: BaseMesh, d: Description, h: float, length: float, add) -> shapely.Geometry | None:
    """Route every corner and edge through the tree, cut the edge strip into their cells, add them;
    returns the union of what they claim (None if nothing).

    Each ring's arc length is the edges' 1-D occupancy map: a corner claims ``[a − r, a + r]``
    around its vertex (:func:`.generators.corner_reach`, at most half of either adjacent edge),
    then each edge divides what is left of it (:func:`.generators.divide`)."""
    n_rings = len(mesh.rings)
    ring_len = mesh.ring_length
    hole = _hole_sides(mesh)
    direction = mesh.edge_direction()
    edge_len = mesh.edge_end - mesh.edge_start
    c_leaf = [d.tree.route({"feature": "corner", "convex": bool(t > 0), "label": ""}) for t in mesh.corner_turn]
    e_leaf = [d.tree.route({"feature": "edge", "label": str(mesh.labels[e]), "direction": float(direction[e]),
                            "hole": hole[e]}) for e in range(len(mesh.edges))]  # fmt: skip
    on = [leaf is not None and leaf.generator != "none" for leaf in c_leaf]
    reach = gen.corner_reach(mesh.corner_turn, h, length)
    cuts: list[list[float]] = [[] for _ in range(n_rings)]
    owners: list[list[tuple[int, int]]] = [[] for _ in range(n_rings)]  # (feature, index) after each cut
    edges_of = [np.flatnonzero(mesh.edge_ring == r) for r in range(n_rings)]
    for r in range(n_rings):
        es = edges_of[r]
        corners = np.flatnonzero(mesh.corner_ring == r)  # corner j starts edge es[j], ends es[j - 1]
        ra = np.zeros(len(es))  # what the corner at each edge's start claims of it
        rb = np.zeros(len(es))  # … and the corner at its end
        for j, c in enumerate(corners.tolist()):
            if not on[c]:
                continue
            nxt, prv = es[j], es[j - 1]
            x = min(float(reach[c]), 0.5 * float(edge_len[nxt]), 0.5 * float(edge_len[prv]))
            ra[j], rb[(j - 1) % len(es)] = x, x
            a = float(mesh.edge_start[nxt])
            cuts[r].append(a - x)
            owners[r].append((CORNER, c))
        for j, e in enumerate(es.tolist()):
            a, b = float(mesh.edge_start[e]) + ra[j], float(mesh.edge_end[e]) - rb[j]
            cuts[r].append(a)
            owners[r].append((EDGE, e))
            leaf = e_leaf[e]
            if leaf is not None and leaf.generator != "none":
                name = "edge_blocks" if leaf.generator == "blocks" else leaf.generator
                for x in gen.divide(b - a, length, name, _anchor(mesh, e, a)).tolist():
                    cuts[r].append(a + x)
                    owners[r].append((EDGE, e))
        if cuts[r]:
            arr = np.array(cuts[r]) % ring_len[r]
            order = np.argsort(arr, kind="stable")
            cuts[r] = arr[order].tolist()
            owners[r] = [owners[r][i] for i in order]
    pieces, ring, arc = gen.strip_pieces(mesh.face, mesh.rings, [np.array(c) for c in cuts], h)
    keyed: dict[tuple[int, str], list] = {}
    for r in range(n_rings):
        sel = np.flatnonzero(ring == r)
        if len(sel) == 0 or not cuts[r]:
            continue
        k = (np.searchsorted(np.array(cuts[r]), arc[sel], side="right") - 1) % len(cuts[r])
        for idx, kk in zip(sel.tolist(), k.tolist(), strict=True):
            kind, i = owners[r][kk]
            leaf = c_leaf[i] if kind == CORNER else e_leaf[i]
            if leaf is None or leaf.generator == "none":
                continue
            css = RGB[kind] if leaf.generator == "blocks" and leaf.style is None else (leaf.style or "")
            keyed.setdefault((kind, css), []).append(pieces[idx])
    if not keyed:
        return None
    claimed = []
    for (kind, css), geoms in sorted(keyed.items()):
        cells = geometry_array(geoms)
        add(cells, kind, css or None)
        claimed.append(cells)
    return shapely.union_all(np.concatenate(claimed))


def _anchor(mesh: BaseMesh, e: int, at: float) -> float | None:
    """World coordinate, along a straight edge's direction, of the point at arc length ``at`` of its
    ring (None for a curved edge: its length differs from its chord's by more than 0.1 %)."""
    edge = mesh.edges[e]
    xy = np.asarray(edge.coords)
    chord = xy[-1] - xy[0]
    span = float(np.hypot(*chord))
    if span <= 0 or edge.length > 1.001 * span:
        return None
    d = chord / span
    return float(np.dot(xy[0], d) + (at - float(mesh.edge_start[e])))


def _arc_of(ring: np.ndarray, vertex: int) -> float:
    seg = np.hypot(*np.diff(ring[: vertex + 1], axis=0).T)
    return float(seg.sum())


def _hole_sides(mesh: BaseMesh) -> list[str]:
    """Per edge: ``outer`` on an exterior ring, else ``top`` or ``bottom`` of its hole (its
    midpoint above or below the hole's centre; y grows downwards on a page)."""
    exterior = set()
    k = 0
    for poly in shapely.get_parts(mesh.face):
        exterior.add(k)
        k += 1 + len(poly.interiors)
    out = []
    for e in range(len(mesh.edges)):
        r = int(mesh.edge_ring[e])
        if r in exterior:
            out.append("outer")
            continue
        mid = shapely.get_coordinates(shapely.line_interpolate_point(mesh.edges[e], 0.5, normalized=True))[0]
        out.append("top" if mid[1] < mesh.rings[r][:, 1].mean() else "bottom")
    return out


def face_cells(frame, free: shapely.Geometry, generator: str, d: Description, *, key: int, fewest_halves: bool = True
               ) -> np.ndarray:  # fmt: skip
    """Cells of a face generator clipped to the free space (§3.3, Figure 3b); slivers dropped.

    Bricks (and rhombs) have two ways of pairing the grid's half-brick blocks into bricks, the
    bond and the bond shifted by half a brick; "since both fill the same area, picking the option
    that creates the least number of bricks yields the better pattern" (§5.2).  Both are laid and
    the one cutting fewer cells (then making fewer) is kept: whole bricks along the face's sides
    rather than halves.  The choice is the face's, so an edit that tips it shifts the face's
    bond by half a brick; without ``fewest_halves`` the bond is the world's (phase 0)."""
    phases = (0.0, 0.5) if fewest_halves and generator in ("bricks", "rhombs") else (0.0,)
    best = None
    for phase in phases:
        cells, whole = _laid(frame, free, generator, d, phase, key=key)
        score = (int((~whole).sum()), len(cells))
        if best is None or score < best[0]:
            best = (score, cells)
    return best[1]


def _laid(frame, free: shapely.Geometry, generator: str, d: Description, phase: float, *, key: int
          ) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """(cells, whole): the generator's cells with the bond shifted by ``phase`` lengths, clipped to
    ``free``, and which of them are whole."""
    step = d.course / 2
    bounds = gen.st_bounds(frame, free, step)
    quads, _ = gen.face_rectangles(generator, bounds, d.course, d.length, d.offset, key=key, ashlar=d.ashlar,
                                   rhomb_angle=d.rhomb_angle, bands=d.bands, phase=phase)  # fmt: skip
    straight = isinstance(frame, RotatedFrame)
    subdivide = 1 if straight else max(2, math.ceil(d.length / step))
    cells = gen.map_quads(frame, quads, subdivide, None if straight else step)
    cells = cells[cells != None]  # noqa: E711 - an object array of geometries
    shapely.prepare(free)
    cells = cells[shapely.intersects(free, cells)]
    full = shapely.area(cells)
    inside = shapely.covered_by(cells, free)
    clipped = cells.copy()
    clipped[~inside] = shapely.intersection(cells[~inside], free)
    clipped = _polygonal(clipped)
    # a cell the edge cells cut in two is two cells
    parts, index = shapely.get_parts(clipped, return_index=True)
    keep = shapely.area(parts) > SLIVER * full[index]
    return parts[keep], inside[index[keep]]


def _polygonal(geoms: np.ndarray) -> np.ndarray:
    """The polygonal part of each geometry (an intersection may add lines and points)."""
    out = geoms.copy()
    odd = ~np.isin(shapely.get_type_id(out), (3, 6))
    for i in np.flatnonzero(odd):
        parts = [g for g in shapely.get_parts(out[i]) if shapely.get_type_id(g) in (3, 6)]
        out[i] = shapely.union_all(parts) if parts else shapely.Polygon()
    return out


def bedding(frame, face: shapely.Geometry, d: Description) -> tuple[list[np.ndarray], list[str | None]]:
    """Bedding lines over ``face`` (solid or dashed), clipped to it: per line spec of the
    description, the lines and their style."""
    x0, y0, x1, y1 = face.bounds
    diag = math.hypot(x1 - x0, y1 - y0)  # bounds the face's extent along and across any course
    for spec in d.lines or ():  # before any sampling: a tiny course, dash or wave would not end
        points = _line_points(spec, d, _sample_step(frame, spec, d.course, diag), diag)
        if points > MAX_SAMPLES:
            raise ParameterError(f"the bedding lines would take about {points:,.0f} points (limit {MAX_SAMPLES:,}): "
                                 "their course, dashes or wave period are too small for the region")  # fmt: skip
    bounds = gen.st_bounds(frame, face, d.course / 2)
    out, styles = [], []
    for spec in d.lines or ():
        dash = spec.get("dash")
        s_step = _sample_step(frame, spec, d.course, bounds[2] - bounds[0])
        wave = None
        if spec.get("wave") is not None:
            wave = (np.asarray(spec["wave"], dtype=np.float64), float(spec["wave_period"]))
        lines = gen.course_lines(frame, bounds, d.course, every=int(spec["every"]), start=int(spec["start"]),
                                 dash=None if dash is None else (float(dash[0]), float(dash[1])),
                                 offset=float(spec["offset"]), shift=float(spec["shift"]), step=s_step,
                                 bands=d.bands, wave=wave)  # fmt: skip
        if len(lines):
            clipped = shapely.intersection(lines, face)
            parts = shapely.get_parts(shapely.line_merge(clipped[~shapely.is_empty(clipped)]))
            parts = parts[shapely.get_type_id(parts) == 1]
            lines = parts[shapely.length(parts) > 1e-6]
        out.append(lines)
        styles.append(spec.get("style"))
    return out, styles


def _sample_step(frame, spec: dict, course: float, extent: float) -> float:
    """The spacing along the courses of the points a line of ``spec`` is drawn with, for a face
    ``extent`` long: a curved frame maps a point every half course; a straight frame only a solid
    line's ends (one step longer than the face) or a dash's; a wavy line is sampled finely enough
    to follow its profile."""
    dash = spec.get("dash")
    if not isinstance(frame, RotatedFrame):
        step = course / 2
    else:
        step = extent + 2 * course if dash is None else max(dash)
    if spec.get("wave") is not None:
        step = min(step, float(spec["wave_period"]) / len(spec["wave"]))
    return step


def _line_points(spec: dict, d: Description, step: float, extent: float) -> float:
    """About how many points :func:`.generators.course_lines` makes for ``spec`` over a face at
    most ``extent`` long and wide, at ``step``: lines per course boundary crossed, points per line
    (per dash, and dashes per line, when dashed)."""
    per_t = len(d.bands.rows) / d.bands.period if d.bands is not None else 1.0 / d.course
    lines = extent * per_t / int(spec["every"]) + 3
    dash = spec.get("dash")
    if dash is None:
        return lines * (extent / step + 4)
    return lines * (extent / (dash[0] + dash[1]) + 4) * (max(1, math.ceil(dash[0] / step)) + 1)


def motifs_in_cells(ctx: Context, cells: np.ndarray, frame, share: float, *, over: bool = False, bearing: float = 0.0
                    ) -> Arrangement:  # fmt: skip
    """Exemplar motifs set in cells (chert nodules in limestone, fossils): one in a ``share`` of
    the cells, at the cell's inner point, turned with the courses; the kind by the exemplar's
    frequencies, the angle in its arc (almeraj2013 §3.5), the scale of a random instance.  A motif
    must lie in its cell — unless ``over``: motifs larger than a cell, drawn over the linework as
    the tile draws them (FGDC 657's peat fragments, 733's ore lenses), need only keep in the
    region (the boundary mode) — and conflicts between motifs (overlap, distance rule) are culled.
    The exemplar's angles are measured in a tile whose courses run along ``bearing`` (the
    description's ``angle``): a motif turns by how far the courses turn from that bearing.
    Randomness is keyed by the cell's position (world-anchored)."""
    ex, stats = ctx.exemplar, ctx.stats
    if len(cells) == 0:
        return Arrangement.empty()
    pts = shapely.get_coordinates(shapely.point_on_surface(cells))
    cell_id = np.round(pts * 1000).astype(np.int64)
    u = [cellrng.uniform(ctx.key, s, cell_id[:, 0], cell_id[:, 1]) for s in (_KIND, _ANGLE, _SCALE, _TAKE, _PRIORITY)]
    take = u[3] < share
    cdf = np.cumsum(stats.frequency)
    kind = np.minimum(np.searchsorted(cdf, u[0] * cdf[-1], side="right"), len(cdf) - 1)
    angle = stats.arc_start[kind] + u[1] * stats.arc_width[kind] + frame.course_angle(pts) - bearing
    scale = np.ones(len(pts))
    motifs = ex.motifs
    for k in np.unique(kind).tolist():
        inst = np.flatnonzero(motifs.kind == k)
        sel = kind == k
        if len(inst):
            scale[sel] = motifs.scale[inst[np.minimum((u[2][sel] * len(inst)).astype(np.int64), len(inst) - 1)]]
    arr = Arrangement(kind, pts, (angle + 180.0) % 360.0 - 180.0, scale).quantized(DECIMALS)
    fits = take if over else take & shapely.covered_by(world_footprints(arr, ex.prototypes), cells)
    arr, pri = arr.take(fits), u[4][fits]
    if len(arr) == 0:
        return arr
    keep = cull(len(arr), find_conflicts(arr, ex.prototypes, stats.distance), pri)
    return arr.take(keep)
