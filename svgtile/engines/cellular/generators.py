"""Pattern generators (legakis2001 §5.2) and the tools they share (§5.1, §5.4).

Corners and edges are textured in the *edge strip*, the band of the face within one course of
its boundary: each ring's arc length (§3.2) is cut into intervals — a corner's interval around its
vertex, then the edge's free intervals (its 1-D occupancy map, §3.3) divided into cells — and the
strip is split along the inward normals at the cuts.  Face generators then lay cells on the
course frame (s, t) of :mod:`.frame` and clip them against what is still free.

Every random choice is a hash of the run's key and world-anchored integers (course and cell
numbers, :mod:`svgtile.core.cellrng`).
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from svgtile.core import cellrng
from svgtile.core.cells import geometry_array

# hash streams
_ASHLAR_SPLIT, _ASHLAR_SHIFT, _ASHLAR_CUT = range(3)


# ----------------------------------------------------------------------------- corners and edges


def corner_reach(turn: np.ndarray, course: float, length: float) -> np.ndarray:
    """(c,) how far along the boundary, each way, a corner cell reaches, user units.

    Half a cell length, and at a convex corner at least far enough that the inward normals at its
    ends meet the strip's inner side before they meet each other (``course · tan(turn / 2)``).
    """
    turn = np.minimum(np.abs(turn), 160.0) * (np.asarray(turn) > 0)
    return np.maximum(length / 2, 1.05 * course * np.tan(np.radians(turn) / 2))


def divide(length: float, cell: float, generator: str, anchor: float | None = None) -> np.ndarray:
    """Cuts dividing a free interval of an edge (its 1-D occupancy map) into cells: positions
    in ``(0, length)``, relative to the interval's start.

    ``edge_blocks`` makes cells ``cell`` long, ``edge_bricks`` alternates whole and half bricks
    (stretchers and headers seen from above: §5.2's "bricks in alternating directions").  On a
    straight edge, ``anchor`` is the world coordinate of the interval's start along the edge's
    direction: the cuts then fall where that coordinate is a whole number of cells, so a moved
    vertex elsewhere leaves them be (edits stay local), and a cell shorter than a third of one at
    either end joins its neighbour.  Without an anchor (a curved edge, a closed ring) the interval
    is divided into whole cells stretched to fit it exactly.
    """
    if length <= 0:
        return np.zeros(0)
    pattern = np.array([1.0, 0.5]) * cell if generator == "edge_bricks" else np.array([cell])
    period = pattern.sum()
    if anchor is None:
        n = max(1, round(length / (period / len(pattern))))
        pieces = np.resize(pattern, n)
        return (np.cumsum(pieces) / pieces.sum() * length)[:-1]
    offsets = np.r_[0.0, np.cumsum(pattern)[:-1]]  # cut positions within a period
    k = np.arange(math.floor(anchor / period) - 1, math.ceil((anchor + length) / period) + 1)
    cuts = np.sort((k[:, None] * period + offsets[None, :]).ravel()) - anchor
    margin = min(pattern) / 3
    return cuts[(cuts > margin) & (cuts < length - margin)]


def strip_pieces(face: shapely.Geometry, rings: list[np.ndarray], cuts: list[np.ndarray], depth: float
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """Split the edge strip along the inward normals at arc lengths ``cuts`` of each ring.

    Parameters
    ----------
    face : the face, user units
    rings : (m_r, 2) float arrays, face on the left (:class:`.mesh.BaseMesh`)
    cuts : per ring, (k_r,) sorted arc lengths in [0, ring length)
    depth : user units, the strip's width (one course)

    Returns
    -------
    pieces : (p,) Polygons, the strip split
    ring : (p,) int, the ring each piece lies along
    arc : (p,) float, the arc length on that ring of the point nearest to the piece
    """
    from .mesh import point_at

    inner = shapely.buffer(face, -depth, join_style="mitre", mitre_limit=2.0)
    strip = shapely.difference(face, inner)
    segs = []
    for ring, c in zip(rings, cuts, strict=True):
        if len(c) == 0:
            continue
        p, n = point_at(ring, c)
        a, b = p - 0.01 * depth * n, p + 1.01 * depth * n
        segs.append(shapely.linestrings(np.stack([a, b], axis=1)))
    lines = [shapely.boundary(strip), *[g for s in segs for g in s]]
    noded = shapely.node(shapely.union_all(np.array(lines, dtype=object)))
    polys = np.array(shapely.get_parts(shapely.polygonize(shapely.get_parts(noded))), dtype=object)
    if len(polys) == 0:
        return polys, np.zeros(0, np.int64), np.zeros(0)
    inside = shapely.contains(strip, shapely.point_on_surface(polys))
    polys = polys[inside]
    pts = shapely.point_on_surface(polys)
    ring_lines = [shapely.LineString(np.vstack([r, r[:1]])) for r in rings]
    dist = np.stack([shapely.distance(pts, line) for line in ring_lines], axis=1)
    which = np.argmin(dist, axis=1)
    arc = np.zeros(len(polys))
    for r, line in enumerate(ring_lines):
        sel = which == r
        if sel.any():
            arc[sel] = shapely.line_locate_point(line, pts[sel])
    return polys, which, arc


# ----------------------------------------------------------------------------- faces


def courses(t0: float, t1: float, course: float, bands=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The courses covering ``t0 ≤ t ≤ t1`` with a margin: world-anchored numbers ``j`` and each
    one's lower and upper side ``t``, user units.  Courses are ``course`` high, or the interbedded
    courses of ``bands`` (:class:`.tree.Bands`)."""
    if bands is None:
        j = np.arange(math.floor(t0 / course) - 1, math.ceil(t1 / course) + 1)
        return j, j * course, j * course + course
    k = len(bands.rows)
    j = np.arange((math.floor(t0 / bands.period) - 1) * k, (math.ceil(t1 / bands.period) + 1) * k)
    return j, _row_t(j, bands), _row_t(j + 1, bands)


def _row_t(j: np.ndarray, bands) -> np.ndarray:
    k = len(bands.rows)
    return np.floor_divide(j, k) * bands.period + np.asarray(bands.rows)[j % k]



def st_bounds(frame, shape: shapely.Geometry, step: float) -> tuple[float, float, float, float]:
    """(s0, t0, s1, t1) bounds of ``shape`` in the frame's parameters (its outline projected)."""
    xy = shapely.get_coordinates(shapely.segmentize(shapely.boundary(shape), step))
    st = frame.project(xy)
    return float(st[:, 0].min()), float(st[:, 1].min()), float(st[:, 0].max()), float(st[:, 1].max())


def face_rectangles(generator: str, bounds: tuple[float, float, float, float], course: float, length: float,
                    offset: float, *, key: int, ashlar: tuple[int, int] = (4, 2), rhomb_angle: float = 45.0,
                    bands=None, phase: float = 0.0) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Cells of a face generator in parameter space, before clipping (§5.1's grid tool).

    Parameters
    ----------
    generator : ``blocks`` (a grid), ``bricks`` (running bond: course ``j`` shifted by
        ``offset · j`` lengths), ``ashlar`` (random ashlar, below) or ``rhombs`` (bricks whose
        joints slant by ``rhomb_angle``: dolomite)
    bounds : (s0, t0, s1, t1), what to cover, user units
    course, length : cell height and length, user units
    bands : interbedded courses (:class:`.tree.Bands`): only the cut ones get cells, and the bond's
        offset steps from one cut course to the next; None for courses all ``course`` high
    phase : share of a length the whole bond is shifted by (bricks and rhombs: §5.2's two ways of
        pairing blocks into bricks are phases 0 and 0.5)

    Returns
    -------
    quads : (n, 4, 2) float array, each cell's corners in (s, t), counter-clockwise
    ident : (n, 2) int array, world-anchored (course, cell) numbers

    Random ashlar (§5.2) lays a grid of a third of a course and merges its squares into stones of
    at most ``ashlar`` = (length, height) squares: here each block of that size (blocks shifted
    course by course at random) is cut into stones by one random guillotine cut or none, so
    merging is random and the size limit holds by construction.
    """
    s0, t0, s1, t1 = bounds
    if generator == "ashlar":
        j = np.arange(math.floor(t0 / course) - 1, math.ceil(t1 / course) + 1)
        return _ashlar(j, s0, s1, course, length, key=key, limit=ashlar)
    j, t_lo, t_hi = courses(t0, t1, course, bands)
    bond = j  # the courses' numbers in the bond: with bands, the cut ones counted alone
    if bands is not None:
        k, cut = len(bands.rows), np.asarray(bands.cut, dtype=np.int64)
        keep = np.isin(j % k, cut)
        j, t_lo, t_hi = j[keep], t_lo[keep], t_hi[keep]
        bond = np.floor_divide(j, k) * len(cut) + np.searchsorted(cut, j % k)
    shift = (offset * bond + phase) % 1.0 if generator in ("bricks", "rhombs") else np.zeros(len(j))
    lo = np.floor(s0 / length - shift).astype(np.int64) - 1 - (generator == "rhombs") * 2
    hi = np.ceil(s1 / length - shift).astype(np.int64) + 1 + (generator == "rhombs") * 2
    count = hi - lo
    jj = np.repeat(j, count)
    ii = np.concatenate([np.arange(a, b) for a, b in zip(lo.tolist(), hi.tolist(), strict=True)] or [np.zeros(0, np.int64)])
    sa = (ii + np.repeat(shift, count)) * length
    ta, tb = np.repeat(t_lo, count), np.repeat(t_hi, count)
    slant = (course if bands is None else tb - ta) * math.tan(math.radians(rhomb_angle)) if generator == "rhombs" else 0.0
    quads = np.stack([
        np.stack([sa, ta], 1), np.stack([sa + length, ta], 1),
        np.stack([sa + length + slant, tb], 1), np.stack([sa + slant, tb], 1),
    ], axis=1)  # fmt: skip
    return quads, np.stack([jj, ii], axis=1)


def _ashlar(j: np.ndarray, s0: float, s1: float, course: float, length: float, *, key: int,
            limit: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    g = course / 3.0
    bw, bh = limit[0] * g, limit[1] * g
    rows = np.arange(math.floor(j[0] * course / bh), math.ceil((j[-1] + 1) * course / bh))
    shift = cellrng.uniform(key, _ASHLAR_SHIFT, rows) * bw
    lo = np.floor((s0 - shift) / bw).astype(np.int64) - 1
    hi = np.ceil((s1 - shift) / bw).astype(np.int64) + 1
    count = hi - lo
    rr = np.repeat(rows, count)
    ii = np.concatenate([np.arange(a, b) for a, b in zip(lo.tolist(), hi.tolist(), strict=True)])
    sa, ta = ii * bw + np.repeat(shift, count), rr * bh
    # one guillotine cut per block, or none: 0 none, 1 across s, 2 across t
    how = (cellrng.uniform(key, _ASHLAR_SPLIT, rr, ii) * 3).astype(np.int64)
    how[(how == 1) & (limit[0] < 2)] = 0
    how[(how == 2) & (limit[1] < 2)] = 0
    at = cellrng.uniform(key, _ASHLAR_CUT, rr, ii)
    cut_s = sa + (1 + np.floor(at * (limit[0] - 1))) * g
    cut_t = ta + (1 + np.floor(at * (limit[1] - 1))) * g
    boxes = [np.stack([sa, ta, sa + bw, ta + bh], 1)[how == 0]]
    m = how == 1
    boxes += [np.stack([sa, ta, cut_s, ta + bh], 1)[m], np.stack([cut_s, ta, sa + bw, ta + bh], 1)[m]]
    m = how == 2
    boxes += [np.stack([sa, ta, sa + bw, cut_t], 1)[m], np.stack([sa, cut_t, sa + bw, ta + bh], 1)[m]]
    ids = [np.stack([rr, ii * 4], 1)[how == 0]]
    ids += [np.stack([rr, ii * 4 + 1], 1)[how == 1], np.stack([rr, ii * 4 + 2], 1)[how == 1]]
    ids += [np.stack([rr, ii * 4 + 1], 1)[how == 2], np.stack([rr, ii * 4 + 3], 1)[how == 2]]
    b = np.concatenate(boxes)
    quads = np.stack([b[:, [0, 1]], b[:, [2, 1]], b[:, [2, 3]], b[:, [0, 3]]], axis=1)
    return quads, np.concatenate(ids)


def map_quads(frame, quads: np.ndarray, subdivide: int, step: float | None = None) -> np.ndarray:
    """(n,) world Polygons of parameter-space quads (each side cut in ``subdivide`` pieces, so
    a curved frame bends them); quads the frame cannot map (outside a flow grid) are None.

    With ``step`` (a curved frame), a side along a course boundary is cut instead at the world
    grid ``s = k·step`` and at every quad corner on that boundary: a brick's top then has the very
    vertices of the two bricks above it, which share it in part, so curved neighbours meet
    without overlapping (straight chords between different points would cross by a sliver)."""
    n = len(quads)
    if step is None or n == 0:
        u = np.arange(subdivide) / subdivide
        sides = [quads[:, k, None, :] + u[None, :, None] * (quads[:, (k + 1) % 4, None, :] - quads[:, k, None, :])
                 for k in range(4)]  # fmt: skip
        pts = np.concatenate(sides, axis=1)  # (n, 4·subdivide, 2)
        world = frame.map(pts.reshape(-1, 2)).reshape(n, -1, 2)
        ok = np.isfinite(world).all(axis=(1, 2))
        out = np.full(n, None, dtype=object)
        if ok.any():
            out[ok] = shapely.make_valid(shapely.polygons(np.concatenate([world[ok], world[ok, :1]], axis=1)))
        return out
    a, b = quads, np.roll(quads, -1, axis=1)  # (n, 4, 2) each side's start and end
    flat = np.abs(a[..., 1] - b[..., 1]) <= 1e-9 * max(step, 1.0)  # (n, 4) sides along a course boundary
    # the interior points of every side, as (quad, side, order, s, t) rows
    rows = [_uniform_points(a[~flat], b[~flat], np.argwhere(~flat), subdivide)]
    level = np.round(a[..., 1], 9)
    for t in np.unique(level[flat]).tolist():  # one course boundary at a time
        at = flat & (level == t)
        corners = np.round(np.concatenate([quads[..., 0][np.round(quads[..., 1], 9) == t]]), 9)
        lo, hi = np.minimum(a[at][:, 0], b[at][:, 0]), np.maximum(a[at][:, 0], b[at][:, 0])
        grid = np.arange(math.floor(lo.min() / step), math.ceil(hi.max() / step) + 1) * step
        knots = np.unique(np.concatenate([corners, np.round(grid, 9)]))
        i0 = np.searchsorted(knots, np.round(lo, 9), side="right")
        i1 = np.searchsorted(knots, np.round(hi, 9), side="left")
        count = np.maximum(i1 - i0, 0)
        which = np.repeat(np.arange(len(count)), count)
        pos = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)  # 0.. along each side
        forward = (b[at][:, 0] >= a[at][:, 0])[which]
        idx = np.where(forward, i0[which] + pos, i1[which] - 1 - pos)
        qs = np.argwhere(at)[which]
        rows.append(np.column_stack([qs, pos, knots[idx], np.full(len(idx), t)]))
    inner = np.concatenate(rows)
    corner_rows = np.column_stack([np.repeat(np.arange(n), 4), np.tile(np.arange(4), n), np.full(4 * n, -1.0),
                                   quads.reshape(-1, 2)])  # fmt: skip
    table = np.concatenate([corner_rows, inner])
    order = np.lexsort((table[:, 2], table[:, 1], table[:, 0]))  # quad, side, corner first then along
    table = table[order]
    quad = table[:, 0].astype(np.int64)
    world = frame.map(table[:, 3:5])
    ok = np.bincount(quad, weights=~np.isfinite(world).all(axis=1), minlength=n) == 0
    out = np.full(n, None, dtype=object)
    if ok.any():
        keep = ok[quad]
        _, index = np.unique(quad[keep], return_inverse=True)
        rings = shapely.linearrings(world[keep], indices=index)
        out[ok] = shapely.make_valid(shapely.polygons(rings))
    return out


def _uniform_points(a: np.ndarray, b: np.ndarray, where: np.ndarray, subdivide: int) -> np.ndarray:
    """(m, 5) rows (quad, side, order, s, t): the points cutting sides ``a`` -> ``b`` (each (k, 2),
    ``where`` their (quad, side)) into ``subdivide`` equal pieces, their ends left out."""
    u = np.arange(1, subdivide) / subdivide
    if len(a) == 0 or len(u) == 0:
        return np.zeros((0, 5))
    pts = a[:, None, :] + u[None, :, None] * (b - a)[:, None, :]  # (k, subdivide − 1, 2)
    k = len(a)
    return np.column_stack([np.repeat(where, len(u), axis=0), np.tile(np.arange(len(u)), k), pts.reshape(-1, 2)])


def course_lines(frame, bounds: tuple[float, float, float, float], course: float, *, every: int = 1, start: int = 0,
                 dash: tuple[float, float] | None = None, offset: float = 0.0, shift: float = 0.0,
                 step: float, bands=None, wave: tuple[np.ndarray, float] | None = None) -> np.ndarray:  # fmt: skip
    """Bedding lines along the course boundaries ``t = j·course`` with ``j % every == start``, solid
    or dashed (``dash`` = on, off lengths; the dashes of course ``j`` shifted by ``offset · j +
    shift`` periods, world-anchored), in the world; ``step`` is the spacing of the points a curved
    frame maps; with ``bands`` (:class:`.tree.Bands`) course ``j`` starts at its row; a ``wave``
    (offsets across the course at even steps of ``s``, and their period along it, user units) bends
    every line by that periodic profile, world-anchored.  Not clipped."""
    s0, t0, s1, t1 = bounds
    j, t, _ = courses(t0, t1 + course, course, bands)
    keep = j % every == start % every
    j, t = j[keep], t[keep]
    if len(j) == 0:
        return np.empty(0, dtype=object)
    if dash is None:
        s = np.arange(math.floor(s0 / step) - 1, math.ceil(s1 / step) + 2) * step
        st = np.stack(np.broadcast_arrays(s[None, :], t[:, None]), axis=-1)  # (c, m, 2)
        st = _waved(st, wave)
        world = frame.map(st.reshape(-1, 2)).reshape(st.shape)
        lines = []
        for row in world:  # one course line at a time: NaNs (outside a flow grid) split it
            good = np.isfinite(row).all(axis=1)
            if good.sum() >= 2:
                lines.append(shapely.linestrings(row[good]))
        return geometry_array(lines)
    period = dash[0] + dash[1]
    sh = ((offset * j + shift) % 1.0) * period
    k = np.arange(math.floor(s0 / period) - 2, math.ceil(s1 / period) + 2)
    a = k[None, :] * period + sh[:, None]  # (c, m) dash starts
    pieces = max(1, math.ceil(dash[0] / step))
    u = np.linspace(0.0, dash[0], pieces + 1)
    s = a[:, :, None] + u[None, None, :]
    tt = np.broadcast_to(t[:, None, None], s.shape)
    st = _waved(np.stack([s, tt], axis=-1).reshape(-1, pieces + 1, 2), wave)
    world = frame.map(st.reshape(-1, 2)).reshape(st.shape)
    return shapely.linestrings(world[np.isfinite(world).all(axis=(1, 2))])


def _waved(st: np.ndarray, wave: tuple[np.ndarray, float] | None) -> np.ndarray:
    """(..., 2) points (s, t) moved across the course by the periodic ``wave`` profile."""
    if wave is None:
        return st
    profile, period = wave
    x = np.arange(len(profile)) * (period / len(profile))
    out = st.copy()
    out[..., 1] += np.interp(st[..., 0] % period, x, profile, period=period)
    return out


def shrink(cells: np.ndarray, mortar: float) -> np.ndarray:
    """Cells shrunk by half the mortar joint on every side (§5.4); the claimed shapes stay."""
    if mortar <= 0:
        return cells
    return shapely.buffer(cells, -mortar / 2, join_style="mitre")
