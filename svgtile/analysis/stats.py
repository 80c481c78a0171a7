"""What synthesis must reproduce: distance matrix, density, orientation arcs, kind frequencies.

Implements the exemplar analysis of almeraj2013: the minimum-distance matrix ``d_ij`` of §3.1, the
density ρ of §3.4 and the smallest orientation arc per kind of §3.5.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.classes import pooled_distance, shape_classes
from svgtile.core.arrangement import Arrangement, periodic_block
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import (
    Prototype,
    motif_radius,
    near_pairs,
    overlapping,
    world_footprints,
)

#: An ordered kind pair (i, j) has a nearest-gap distribution only if at least this many exemplar
#: motifs of kind i have a motif of kind j to measure to (each gives one sample of it).
GAP_MIN_SAMPLES = 5


@dataclass(frozen=True, eq=False)
class Stats:
    """Exemplar statistics.

    Attributes
    ----------
    distance : (k, k) float array, user units
        ``d_ij``: the smallest footprint distance between an instance of kind i and one of kind j.
    measured : (k, k) bool array
        False where the exemplar has no such pair and ``distance`` holds the fallback
        (see :func:`distance_matrix`).
    density : float
        ρ, the fraction of the input region covered by motif footprints (area sum / region area).
    count_density : float
        Motifs per square user unit in the input region.
    arc_start, arc_width : (k,) float arrays, degrees
        Each kind's smallest arc of orientations ``[start, start + width]`` (§3.5).
    frequency : (k,) float array
        Fraction of the motifs that are of each kind.
    overlaps : int
        Pairs of exemplar motifs whose footprints share area (the paper assumes none).
    classes : (k,) int array or None
        Each kind's shape class (:func:`svgtile.analysis.classes.shape_classes`, issue 12.3):
        kinds drawn fewer than :data:`~svgtile.analysis.classes.RARE_BELOW` times share a class
        with rare kinds of like shape, every other kind is its own class.  The distance rule and
        the kind mix are kept per class.  None (a :class:`Stats` made by hand): every kind is its
        own class.
    """

    distance: np.ndarray
    measured: np.ndarray
    density: float
    count_density: float
    arc_start: np.ndarray
    arc_width: np.ndarray
    frequency: np.ndarray
    overlaps: int
    classes: np.ndarray | None = None

    @property
    def kind_classes(self) -> np.ndarray:
        """(k,) int, :attr:`classes`, or each kind its own class where it is None."""
        return np.arange(len(self.frequency)) if self.classes is None else np.asarray(self.classes)

    @property
    def spacing(self) -> float:
        """The exemplar's mean spacing ``s = 1 / sqrt(λ)``, λ its motifs per unit area (user
        units; inf without motifs)."""
        return 1.0 / math.sqrt(self.count_density) if self.count_density > 0 else math.inf


def analyze(exemplar: Exemplar) -> Stats:
    """Compute :class:`Stats` for an exemplar.

    Kinds drawn fewer than :data:`~svgtile.analysis.classes.RARE_BELOW` times are pooled into
    shape classes for the distance rule (:mod:`svgtile.analysis.classes`, issue 12.3): their own
    few pairs do not measure it.

    For a repeating tile (``exemplar.period`` set) distances and overlaps are measured across the
    tile's edges (:func:`periodic_distance_matrix`); the density needs no correction there, since
    the tile holds exactly one copy of every motif of the pattern.
    """
    motifs, protos = exemplar.motifs, exemplar.prototypes
    k = len(protos)
    period = getattr(exemplar, "period", None)
    if period is None:
        distance, measured, overlaps = distance_matrix(motifs, protos)
    else:
        distance, measured, overlaps = periodic_distance_matrix(motifs, protos, period)
    counts = np.bincount(motifs.kind, minlength=k)
    # rare kinds keep the distances of their shape class, not of their few instances
    classes = shape_classes(protos, counts)
    distance, measured = pooled_distance(distance, measured, classes)
    area = footprint_areas(motifs, protos)
    region_area = exemplar.region.area
    start, width = orientation_arcs(motifs.angle, motifs.kind, k)
    return Stats(
        distance=distance,
        measured=measured,
        density=float(area.sum() / region_area),
        count_density=len(motifs) / region_area,
        arc_start=start,
        arc_width=width,
        frequency=counts / max(int(counts.sum()), 1),  # a cellular exemplar may have no motifs
        overlaps=overlaps,
        classes=classes,
    )


def motif_estimate(exemplar: Exemplar, stats: Stats, region) -> float:
    """About how many motifs synthesis puts in ``region`` (a :class:`svgtile.core.region.Region`).

    The exemplar's motifs per unit² times the region's area — or, for a strip thinner than the
    exemplar, the area of the exemplar-sized copies covering its bounds (0.01 × 1e8 costs as much
    as a strip an exemplar wide), since every engine lays whole copies.
    """
    x0, y0, x1, y1 = region.bounds
    ex0, ey0, ex1, ey1 = exemplar.region.bounds
    return stats.count_density * max(region.area, max(x1 - x0, ex1 - ex0) * max(y1 - y0, ey1 - ey0))


def footprint_areas(arr: Arrangement, protos: list[Prototype]) -> np.ndarray:
    """(n,) footprint area of each motif, square user units."""
    return np.array([p.area for p in protos])[arr.kind] * arr.scale**2


def distance_matrix(arr: Arrangement, protos: list[Prototype]) -> tuple[np.ndarray, np.ndarray, int]:
    """The symmetric matrix ``d_ij`` of almeraj2013 §3.1, exactly.

    ``d_ij`` is the minimum footprint distance over all pairs of an instance of kind i and a
    different instance of kind j.  Neighbours (bounding discs closer than the largest motif
    radius) are measured first; this settles every kind pair found closer than that reach and
    counts the overlaps.  The kind pairs left, whose instances are far apart, are settled by
    branch and bound (:func:`_far_minimum`), so a sparse exemplar with many kinds does not cost a
    distance for every pair of motifs.

    A kind pair the exemplar cannot measure (a kind with one instance has no i–i pair) falls back
    to the smaller of the two kinds' smallest measured distances to any kind, and to 0 when
    nothing was measured at all: the rule then never forbids what the exemplar shows elsewhere.

    Returns
    -------
    distance : (k, k) float array
    measured : (k, k) bool array
    overlaps : int, number of pairs whose footprints share area.
    """
    k = len(protos)
    geoms = world_footprints(arr, protos)
    radius = motif_radius(arr, protos)
    counts = np.bincount(arr.kind, minlength=k)
    possible = np.outer(counts, counts) - np.diag(counts) > 0
    distance = np.full((k, k), np.inf)
    reach = max(float(radius.max(initial=0.0)), 1e-9)
    i, j = near_pairs(arr.xy, radius, reach)
    dist = shapely.distance(geoms[i], geoms[j])
    overlaps = int(overlapping(geoms, i, j, dist).sum())
    ki, kj = arr.kind[i], arr.kind[j]
    np.minimum.at(distance, (ki, kj), dist)
    np.minimum.at(distance, (kj, ki), dist)
    # a minimum below the reach is exact: every closer pair passed the bounding-disc filter
    todo = np.triu(possible & ~(distance < reach))
    if todo.any():
        a, b = np.nonzero(todo)
        best = _far_minimum(arr, protos, geoms, radius, a, b, distance[a, b], reach)
        distance[a, b] = distance[b, a] = best
    measured = np.isfinite(distance)
    row_min = np.where(measured, distance, np.inf).min(axis=1, initial=np.inf)
    fallback = np.minimum.outer(row_min, row_min)
    fallback[~np.isfinite(fallback)] = 0.0
    distance = np.where(measured, distance, fallback)
    return distance, measured, overlaps


def periodic_distance_matrix(
    arr: Arrangement, protos: list[Prototype], period: tuple[float, float]
) -> tuple[np.ndarray, np.ndarray, int]:
    """:func:`distance_matrix` of a pattern that repeats with ``period`` (w, h), user units.

    The tile's motifs are copied onto the 3 × 3 block of tiles around it, so a motif near an edge
    meets its neighbours across that edge, and a kind with one motif per tile meets its own
    repeats.  Every pair in the block is a translate of a pair of the infinite pattern, and every
    pair of motifs closer than a tile width has a translate in the block, so the minima are those
    of the pattern.  Overlaps are counted once per pair of the pattern: pairs within the tile,
    and half of the pairs between the tile and a copy (each such pair appears from both ends).

    Returns
    -------
    distance : (k, k) float array
    measured : (k, k) bool array
    overlaps : int
    """
    n = len(arr)
    block = periodic_block(arr, period)
    distance, measured, _ = distance_matrix(block, protos)
    geoms = world_footprints(block, protos)
    radius = motif_radius(block, protos)
    i, j = near_pairs(block.xy, radius, 1e-9)
    first = i < n  # pairs are i < j, and the tile's own motifs come first
    i, j = i[first], j[first]
    dist = shapely.distance(geoms[i], geoms[j])
    hit = overlapping(geoms, i, j, dist)
    inner = j < n
    overlaps = int(hit[inner].sum()) + int(hit[~inner].sum()) // 2
    return distance, measured, overlaps


#: Most motif pairs :func:`_kind_pairs` holds in memory at once.
_CHUNK = 1 << 22


def _far_minimum(
    arr: Arrangement,
    protos: list[Prototype],
    geoms: np.ndarray,
    radius: np.ndarray,
    ka: np.ndarray,
    kb: np.ndarray,
    upper: np.ndarray,
    reach: float,
) -> np.ndarray:
    """Exact minimum footprint distance for the kind pairs ``(ka[t], kb[t])``.

    Branch and bound over the motif pairs of those kinds: the distance of a pair is at least its
    bounding-disc gap ``|xy_i - xy_j| - r_i - r_j`` and at most the distance between one point of
    each footprint.  Kind pairs without an upper bound get one from those points; then only motif
    pairs whose gap is below their kind pair's bound are measured, smallest gaps first, while the
    bound tightens, until no such pair is left.  Candidates of kind pairs with a small bound come
    from the k-d tree (:func:`near_pairs`), the others from a scan of their motifs' pairs.

    Parameters
    ----------
    ka, kb : (t,) int arrays, kind pairs.
    upper : (t,) float array, a known upper bound of each (``inf`` if none).
    reach : float, user units; bounds up to a few times this count as small.

    Returns
    -------
    (t,) float array; ``inf`` where the kinds have no such pair.
    """
    k = len(protos)
    best = np.asarray(upper, dtype=np.float64).copy()

    def ids(select: np.ndarray) -> np.ndarray:
        """(k, k) index into ``best`` of the selected kind pairs, -1 elsewhere."""
        out = np.full((k, k), -1, dtype=np.int64)
        t = np.flatnonzero(select)
        out[ka[t], kb[t]] = out[kb[t], ka[t]] = t
        return out

    unbounded = ~np.isfinite(best)
    if unbounded.any():
        inside = np.array([shapely.get_coordinates(shapely.point_on_surface(p.geometry()))[0] for p in protos])
        turn = np.radians(arr.angle)
        c, s = np.cos(turn) * arr.scale, np.sin(turn) * arr.scale
        loc = inside[arr.kind]
        point = arr.xy + np.stack([c * loc[:, 0] - s * loc[:, 1], s * loc[:, 0] + c * loc[:, 1]], axis=1)
        # widen a k-d tree search while it stays local, then scan what is left
        span = float(np.ptp(arr.xy, axis=0).max())
        grow = 2 * reach
        while unbounded.any() and grow <= span / 2:
            sub = np.flatnonzero((ids(unbounded) >= 0).any(axis=1)[arr.kind])
            bound = np.where(ids(unbounded) >= 0, grow, -np.inf)
            i, j = near_pairs(arr.xy[sub], radius[sub], bound, arr.kind[sub])
            i, j = sub[i], sub[j]
            t = ids(unbounded)[arr.kind[i], arr.kind[j]]
            np.minimum.at(best, t[t >= 0], np.hypot(*(point[i] - point[j]).T)[t >= 0])
            unbounded = ~np.isfinite(best)
            grow *= 2
        if unbounded.any():
            for i, j, t in _kind_pairs(arr.kind, ids(unbounded)):
                np.minimum.at(best, t, np.hypot(*(point[i] - point[j]).T))
    small = best <= 4 * reach
    found = []
    if small.any():
        bound = np.full((k, k), -np.inf)
        bound[ka[small], kb[small]] = bound[kb[small], ka[small]] = best[small]
        i, j = near_pairs(arr.xy, radius, bound, arr.kind)
        found.append((i, j, ids(small)[arr.kind[i], arr.kind[j]]))
    if (~small).any():
        found.extend(_kind_pairs(arr.kind, ids(~small)))
    i, j, t = (np.concatenate(p) for p in zip(*found, strict=True))
    gap = np.hypot(*(arr.xy[i] - arr.xy[j]).T) - radius[i] - radius[j]
    keep = gap < best[t]
    order = np.lexsort((gap[keep], t[keep]))
    i, j, t, gap = i[keep][order], j[keep][order], t[keep][order], gap[keep][order]
    done = np.zeros(len(i), dtype=bool)
    batch = 1
    while True:
        live = np.flatnonzero(~done & (gap < best[t]))
        if len(live) == 0:
            return best
        # the `batch` smallest gaps of every kind pair still open
        first = np.r_[True, t[live[1:]] != t[live[:-1]]]
        start = np.maximum.accumulate(np.where(first, np.arange(len(live)), 0))
        take = live[np.arange(len(live)) - start < batch]
        np.minimum.at(best, t[take], shapely.distance(geoms[i[take]], geoms[j[take]]))
        done[take] = True
        batch *= 2


def _kind_pairs(kind: np.ndarray, ids: np.ndarray):
    """Motif pairs ``i < j`` whose kind pair has ``ids[kind_i, kind_j] >= 0``, in chunks.

    Yields ``(i, j, ids[kind_i, kind_j])`` int arrays; scans the pairs of the motifs whose kind
    takes part, ``_CHUNK`` at a time.
    """
    involved = np.flatnonzero((ids >= 0).any(axis=1)[kind])
    rows = max(1, _CHUNK // max(len(involved), 1))
    for start in range(0, len(involved), rows):
        block = involved[start : start + rows]
        i = np.repeat(block, len(involved))
        j = np.tile(involved, len(block))
        t = ids[kind[i], kind[j]]
        keep = (i < j) & (t >= 0)
        yield i[keep], j[keep], t[keep]


def nearest_gaps(
    arr: Arrangement, protos: list[Prototype], sources: np.ndarray, kind: int, *, geoms: np.ndarray | None = None,
    tree: cKDTree | None = None,
) -> np.ndarray:  # fmt: skip
    """Footprint distance from each source motif to the nearest other motif of ``kind``.

    Parameters
    ----------
    arr : Arrangement of n motifs
    protos : kind prototypes
    sources : (m,) int array, indices into ``arr``
    kind : the kind of the neighbours
    geoms : (n,) world footprints, if built
    tree : k-d tree of the centroids of the motifs of ``kind`` (in index order), if built

    Returns
    -------
    (m,) float array, user units (0 for an overlap); ``inf`` where there is no such neighbour.
    """
    targets = np.flatnonzero(arr.kind == kind)
    if len(sources) == 0 or len(targets) == 0:
        return np.full(len(sources), np.inf)
    radius = motif_radius(arr, protos)
    if geoms is None:
        need = np.unique(np.concatenate([sources, targets]))
        geoms = np.empty(len(arr), dtype=object)
        geoms[need] = world_footprints(arr.take(need), protos)
    if tree is None:
        tree = cKDTree(arr.xy[targets])
    return nearest_distances(
        arr.xy[sources], radius[sources], geoms[sources], tree, radius[targets], geoms[targets],
        ids=(sources, targets),
    )  # fmt: skip


def nearest_distances(
    xy: np.ndarray, r: np.ndarray, geom: np.ndarray, tree: cKDTree, t_r: np.ndarray, t_geom: np.ndarray,
    *, ids: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:  # fmt: skip
    """(m,) exact distance from each source geometry to the nearest target geometry.

    Targets are tried in order of the k nearest centroids (k doubling until sure): exact GEOS
    distances are taken only for candidates whose bounding-disc gap ``|x_a − x_b| − r_a − r_b``
    is below the best distance found, and a source is done once the k-th centroid is too far
    for any target beyond it to come closer.  With ``ids = (source ids, target ids)``, a target
    with the same id as the source (the motif itself) is skipped.
    """
    m, n = len(xy), tree.n
    best = np.full(m, np.inf)
    if m == 0 or n == 0:
        return best
    r_max = float(t_r.max())
    todo = np.arange(m)
    k = min(8, n)
    while len(todo):
        d, idx = tree.query(xy[todo], k=k)
        d, idx = d.reshape(len(todo), k), idx.reshape(len(todo), k)
        lower = d - r[todo, None] - t_r[idx]
        if ids is not None:
            lower[ids[1][idx] == ids[0][todo, None]] = np.inf
        rows = np.arange(len(todo))
        first = np.argmin(lower, axis=1)
        b = np.full(len(todo), np.inf)
        ok = np.isfinite(lower[rows, first])
        b[ok] = shapely.distance(geom[todo[ok]], t_geom[idx[rows[ok], first[ok]]])
        more = lower < b[:, None]
        more[rows, first] = False
        a, c = np.nonzero(more)
        if len(a):
            np.minimum.at(b, a, shapely.distance(geom[todo[a]], t_geom[idx[a, c]]))
        best[todo] = np.minimum(best[todo], b)
        if k >= n:
            break
        todo = todo[d[:, -1] - r[todo] - r_max < best[todo]]
        k = min(2 * k, n)
    return best


def exemplar_gaps(exemplar: Exemplar) -> list[list[np.ndarray]]:
    """``gaps[i][j]``: the footprint distance from each exemplar motif of kind i to its nearest
    other motif of kind j (:func:`nearest_gaps`, finite values only; across the tile's edges for
    a repeating tile), user units."""
    ex, protos = exemplar.motifs, exemplar.prototypes
    k, n = len(protos), len(ex)
    period = getattr(exemplar, "period", None)
    if period is not None:  # the tile amid its eight neighbours: gaps across the edges are seen
        ex = periodic_block(ex, period)
    geoms = world_footprints(ex, protos)
    out = []
    for i in range(k):
        sources = np.flatnonzero(ex.kind[:n] == i)
        row = [nearest_gaps(ex, protos, sources, j, geoms=geoms) for j in range(k)]
        out.append([g[np.isfinite(g)] for g in row])
    return out


def junction_distance(
    exemplar: Exemplar, stats: Stats, quantile: float, gaps: list[list[np.ndarray]] | None = None
) -> np.ndarray:
    """(k, k) distance, user units, that motifs placed independently of each other must keep.

    The distance rule ``d_ij`` is the *smallest* gap the exemplar shows; the typical gap is
    larger.  Where two exemplar copies meet, or a pasted disc meets the texture (almeraj2013
    §3.3, §3.4), the rule alone lets motifs of the two pack at ``d_ij``, and the seam shows as a
    band of gaps smaller than the exemplar's.  The junction rule asks them to keep the
    ``quantile`` of the exemplar's nearest gaps instead:

    ``J_ij = max(d_ij, min(Q_ij(q), Q_ji(q)))``,

    ``Q_ij(q)`` the q-quantile of the footprint distances from each exemplar motif of kind i to
    its nearest other motif of kind j (:func:`nearest_gaps`; across the tile's edges for a
    repeating tile).  Where only one direction has :data:`GAP_MIN_SAMPLES` gaps, its quantile is
    taken; where neither has, or either kind is drawn once, ``d_ij`` is kept; ``quantile = 0`` gives ``d_ij`` everywhere.  ``J``
    is symmetric and ``J ≥ d``, so an arrangement that keeps ``J`` keeps the distance rule.
    ``gaps`` are :func:`exemplar_gaps`, if already measured.
    """
    d = stats.distance
    if quantile <= 0:
        return d.copy()
    gaps = exemplar_gaps(exemplar) if gaps is None else gaps
    k = len(gaps)
    q = np.full((k, k), np.nan)
    for i in range(k):
        for j in range(k):
            if len(gaps[i][j]) >= GAP_MIN_SAMPLES:
                q[i, j] = np.quantile(gaps[i][j], quantile)
    # a kind drawn once has gaps to *that one motif* only (dots to one breccia fragment: as far as
    # the exemplar put them); its class's distance rule stands for it (analysis.classes)
    once = np.bincount(exemplar.motifs.kind, minlength=k) == 1
    q[once, :] = np.nan
    q[:, once] = np.nan
    pair = np.fmin(q, q.T)  # nan only where neither direction was measured
    return np.where(np.isnan(pair), d, np.maximum(d, pair))


def orientation_arcs(angle: np.ndarray, kind: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Smallest arc of the circle holding every orientation of each kind (almeraj2013 §3.5).

    Parameters
    ----------
    angle : (n,) float array, degrees.
    kind : (n,) int array.
    k : number of kinds.

    Returns
    -------
    start : (k,) float array, degrees in [-180, 180); the arc runs counter-clockwise from here.
    width : (k,) float array, degrees in [0, 360).  A kind without instances gets width 0.
    """
    start = np.zeros(k)
    width = np.zeros(k)
    for c in range(k):
        a = np.sort(np.mod(angle[kind == c], 360.0))
        if len(a) == 0:
            continue
        gaps = np.diff(np.append(a, a[0] + 360.0))
        g = int(np.argmax(gaps))
        start[c] = (a[(g + 1) % len(a)] + 180.0) % 360.0 - 180.0
        width[c] = max(0.0, 360.0 - gaps[g])
    return start, width


#: Degrees an orientation may lie outside its arc and still count as in it: angles are written with
#: 4 decimals, so an exemplar angle at the end of an arc may come back 5e-5 outside.
ARC_TOLERANCE = 1e-4


def in_arcs(angle: np.ndarray, kind: np.ndarray, stats: Stats, tol: float = ARC_TOLERANCE) -> np.ndarray:
    """(n,) bool: does each motif's orientation lie in its kind's arc, within ``tol`` degrees?"""
    offset = np.mod(angle - stats.arc_start[kind] + tol, 360.0)
    return offset <= stats.arc_width[kind] + 2 * tol
