"""The repetition rule of tile import (stage 4b of :mod:`svgtile.tiles.importer`): parts that
recur at the same offset and relative rotation in every copy are one motif, unless the offset is
a lattice step."""

from __future__ import annotations

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from svgtile.core.footprint import rotation

#: Repetition rule (stage 4b): two parts are one motif when the offset between them (in the first
#: part's frame, with their relative rotation) recurs, within this share of the larger kind's radius …
REPEAT_TOLERANCE = 0.05
#: … and this many degrees of relative rotation …
REPEAT_TURN = 3.0
#: … for at least this share of the parts of either kind (swamp's rarer arrangement: 0.45) …
REPEAT_SHARE = 0.25
#: … and at least this many times.  Each part is compared with this many nearest parts.
MIN_REPEATS, NEIGHBOURS = 3, 12
#: A recurring offset that pairs more than this share of its parts twice is a lattice step (every
#: part of a lattice has a neighbour both at +v and at −v), not a motif.
AMBIGUOUS = 0.1
#: Motifs so joined must stand apart: the nearest part outside a motif lies farther than this many
#: times its longest link (a single-linkage gap; the osm-carto marsh, reed, bog, mangrove and swamp
#: tufts have ≥ 1.5, the near-lattices of FGDC 710, 711 and 716 about 1.0) …
SEPARATION = 1.3
#: … for all but this share of the motifs.
CROWDED = 0.1


def radii(geoms: np.ndarray) -> np.ndarray:
    """(n,) farthest outline point of each geometry from the origin."""
    coords, index = shapely.get_coordinates(geoms, return_index=True)
    out = np.zeros(len(geoms))
    np.maximum.at(out, index, np.hypot(coords[:, 0], coords[:, 1]))
    return out


def repeat_groups(
    xy: np.ndarray, kind: np.ndarray, angle: np.ndarray, radius: np.ndarray, period: np.ndarray, origin: np.ndarray,
    order: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Join parts that always occur together: the motifs of a tile whose parts do not touch.

    A tuft of separate blades (osm-carto marsh) or a shape beside a dot (swamp) is drawn as parts
    that neither touch nor pair up as parallel strokes, but a motif is copied whole, so the offset
    from one of its parts to another — taken in the first part's frame, with their relative
    rotation — is the same in every copy, while offsets between separate motifs scatter (Gestalt
    common fate / the repetition AlMeraj et al. 2013 §3.1 look for).  Offsets to the
    :data:`NEIGHBOURS` nearest parts (across the tile's edges) are clustered per ordered pair of
    part kinds, within :data:`REPEAT_TOLERANCE` of the larger kind's radius and
    :data:`REPEAT_TURN` degrees; a cluster holding at least :data:`REPEAT_SHARE` of either kind's
    parts (and :data:`MIN_REPEATS`) is a *recurring offset*, and its pairs are links.

    A part with rotational symmetry (a dash, a cross) has its angle only up to that symmetry, so
    offsets from it are taken in its frame with their direction folded into one sector of the
    symmetry; offsets from a round part (a dot) are taken in its partner's frame (in the tile's
    if both are round), and relative rotations are folded the same way: rotated copies of an
    L-and-dot motif still share one offset.

    A regular lattice makes every neighbour offset recur, so a recurring offset is kept only if it
    is one-to-one (at most :data:`AMBIGUOUS` of its parts have a partner both ways, as every
    lattice point has at +v and −v), and the joined groups must be finite (not reach their own
    repeat) and stand apart (the nearest outside part farther than
    :data:`SEPARATION` times the group's longest link, for all but :data:`CROWDED` of them); while
    they do not, the longest recurring offset is dropped.

    Parameters
    ----------
    xy : (n, 2) part centroids inside the tile, user units
    kind : (n,) part kinds; angle : (n,) degrees, each part's rotation from its kind's first part
    radius : (n,) each part's farthest outline point from its centroid, user units
    period, origin : (2,) the tile's size and corner
    order : (k,) each kind's order of rotational symmetry (1 none, 0 round; see
        :func:`_symmetry`); default all 1

    Returns
    -------
    group : (n,) motif of each part, numbered from 0 by each motif's first part
    join : (n, 2) whole periods moving each part next to the other parts of its motif
    """
    n = len(xy)
    alone = (np.arange(n), np.zeros((n, 2)))
    if n < 2 * MIN_REPEATS:
        return alone
    pos = np.mod(xy - origin, period)
    pos[pos >= period] = 0.0
    k = min(NEIGHBOURS, n - 1)
    dist, nb = cKDTree(pos, boxsize=period).query(pos, k=k + 1)
    i, j, dist = np.repeat(np.arange(n), k), nb[:, 1:].ravel(), dist[:, 1:].ravel()
    ok = (j < n) & (j != i)
    i, j, dist = i[ok], j[ok], dist[ok]
    d = _min_image(pos[j] - pos[i], period)
    order = np.ones(int(kind.max()) + 1, dtype=np.int64) if order is None else np.asarray(order)
    # each part's angle is known up to its symmetry's sector (360° / order; a round part: none)
    sector_of = np.where(order > 0, 360.0 / np.maximum(order, 1), 0.0)
    sector_i, sector_j = sector_of[kind[i]], sector_of[kind[j]]
    # the frame of the offset: the first part's, else (round) its partner's, else (both round)
    # the tile's, whose copies then must not be turned
    length_d = np.hypot(d[:, 0], d[:, 1])
    frame = np.where(sector_i > 0, angle[i], np.where(sector_j > 0, angle[j], 0.0))
    sector = np.where(sector_i > 0, sector_i, np.where(sector_j > 0, sector_j, 360.0))
    direction = np.mod(np.degrees(np.arctan2(d[:, 1], d[:, 0])) - frame, sector)
    t = np.radians(direction)
    local = np.c_[length_d * np.cos(t), length_d * np.sin(t)]
    kind_radius = np.zeros(len(order))
    np.maximum.at(kind_radius, kind, radius)
    scale = REPEAT_TOLERANCE * np.maximum(kind_radius[kind[i]], kind_radius[kind[j]])
    # the relative rotation is known up to the sectors of both parts (their gcd; none if round)
    fold = np.where((sector_i > 0) & (sector_j > 0), np.gcd(sector_i.astype(np.int64), sector_j.astype(np.int64)), 0)
    turn = np.where(fold > 0, np.mod(angle[j] - angle[i], np.where(fold > 0, fold, 360.0)), 0.0)
    turn = np.where(turn > fold / 2, turn - fold, turn)
    # in these coordinates two links repeat each other when no coordinate differs by more than 1
    feat = np.c_[local / np.maximum(scale, 1e-12)[:, None], turn / REPEAT_TURN, 3.0 * kind[i], 3.0 * kind[j]]
    links = cKDTree(feat)
    support = _support(feat)
    per_kind = np.bincount(kind)
    need = np.maximum(MIN_REPEATS, REPEAT_SHARE * np.maximum(per_kind[kind[i]], per_kind[kind[j]]))
    recurring = np.flatnonzero(support >= need)
    if len(recurring) == 0:
        return alone

    # recurring links into clusters, the best-supported offset first (a few dozen clusters)
    cluster = np.full(len(i), -1)
    count = 0
    for r in recurring[np.argsort(-support[recurring], kind="stable")]:
        if cluster[r] >= 0:
            continue
        near = np.asarray(links.query_ball_point(feat[r], r=1.0, p=np.inf), dtype=np.int64)
        near = near[(cluster[near] < 0) & (support[near] >= need[near])]
        cluster[near] = count
        count += 1
    use = cluster >= 0
    ci, a, b, length, step = cluster[use], i[use], j[use], dist[use], d[use]

    # one-to-one: a part with two partners under one offset is a lattice point
    # a pair seen from both sides (i -> j and j -> i) counts once
    key = ci * n * n + np.minimum(a, b) * n + np.maximum(a, b)
    _, unique = np.unique(key, return_index=True)
    ends = np.r_[ci[unique] * n + a[unique], ci[unique] * n + b[unique]]
    node, times = np.unique(ends, return_counts=True)
    twice = node[times > 1]
    involved = np.bincount(node // n, minlength=count)
    ambiguous = np.bincount(twice // n, minlength=count)
    fine = ambiguous <= AMBIGUOUS * involved
    keep = fine[ci] & ~np.isin(ci * n + a, twice) & ~np.isin(ci * n + b, twice)
    ci, a, b, length, step = ci[keep], a[keep], b[keep], length[keep], step[keep]
    if len(ci) == 0:
        return alone
    size = np.zeros(count)
    np.maximum.at(size, ci, length)
    active = np.unique(ci)
    active = active[np.argsort(size[active], kind="stable")]
    while len(active):
        on = np.isin(ci, active)
        graph = coo_matrix((np.ones(int(on.sum())), (a[on], b[on])), shape=(n, n))
        m, group = connected_components(graph, directed=False)
        root = np.full(m, n)
        np.minimum.at(root, group, np.arange(n))
        rel = _min_image(pos - pos[root[group]], period)
        wraps = np.zeros(m, dtype=bool)
        np.logical_or.at(wraps, group[a[on]], np.abs(rel[b[on]] - rel[a[on]] - step[on]).max(axis=1) > 1e-6 * period.max())
        longest = np.zeros(m)
        np.maximum.at(longest, group[a[on]], length[on])
        outside = np.full(m, np.inf)
        apart = group[i] != group[j]
        np.minimum.at(outside, group[i[apart]], dist[apart])
        multi = np.bincount(group, minlength=m) > 1
        crowded = multi & (outside <= SEPARATION * longest)
        if not wraps.any() and crowded.sum() <= CROWDED * multi.sum():
            join = np.round((pos[root[group]] + rel - pos) / period) * period
            return group, join
        active = active[:-1]
    return alone


def _support(feat: np.ndarray) -> np.ndarray:
    """(m,) how many of the rows of ``feat`` (m, f) lie within 1 of each row (max norm, itself
    included).

    The links of a lattice all sit at a few points, so counting pairs of links directly costs
    O(m²); rows are counted instead as distinct points on a grid of 0.1 with their
    multiplicities, so the count is exact to that grid and costs O(distinct points × neighbours).
    """
    cell, inverse, weight = np.unique(np.round(feat * 10.0).astype(np.int64), axis=0, return_inverse=True, return_counts=True)
    centres = cell / 10.0
    tree = cKDTree(centres)
    pairs = tree.sparse_distance_matrix(tree, 1.0 + 1e-9, p=np.inf, output_type="ndarray")
    same = pairs["i"] == pairs["j"]
    count = np.bincount(pairs["i"][~same], weights=weight[pairs["j"][~same]], minlength=len(cell)) + weight
    return count[inverse.reshape(-1)]


def symmetry_orders(centred: np.ndarray, tolerance: float) -> np.ndarray:
    """(k,) order of rotational symmetry of each centred footprint: 0 if round (it matches
    itself turned by any angle), else the largest of 6, 4, 3, 2 it matches itself turned by
    360° / order, else 1; within ``tolerance`` / 2 × its radius (the import's :data:`~svgtile.tiles.importer.KIND_TOLERANCE`)."""
    radius = np.maximum(radii(centred), 1e-12)
    order = np.ones(len(centred), dtype=np.int64)
    undecided = np.ones(len(centred), dtype=bool)
    for m, turn in ((0, 37.0), (6, 60.0), (4, 90.0), (3, 120.0), (2, 180.0)):
        at = np.flatnonzero(undecided)
        rot = rotation(turn).T
        turned = shapely.transform(centred[at], lambda p, rot=rot: p @ rot)
        same = at[shapely.hausdorff_distance(centred[at], turned) <= 0.5 * tolerance * radius[at]]
        order[same] = m
        undecided[same] = False
    return order


def _min_image(d: np.ndarray, period: np.ndarray) -> np.ndarray:
    """(k, 2) offsets moved by whole periods to their shortest form."""
    return d - np.round(d / period) * period


