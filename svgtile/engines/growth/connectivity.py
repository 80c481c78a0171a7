"""Connectivity of the exemplar and its ring shapes (Ijiri, Měch, Igarashi & Miller 2008, §4).

The exemplar's motif centres are triangulated (Delaunay); the skewed triangles the triangulation
leaves along the border (an angle above 2π/3) are removed and only edges of at least one
remaining triangle are kept (§4).  Each element's *ring shape* is then the counter-clockwise list
of its immediate neighbours: their positions relative to it, their kinds (the paper's symbol
ids) and which exemplar motif each is (the sub-ids).

Two refinements, both about consistency with the synthesis side:

* a repeating tile (``exemplar.period``) is triangulated as a 3 × 3 block of its copies, so the
  connectivity is periodic across the tile's edges and every motif has a whole ring (§4 drops
  border elements of a finite exemplar; a tile has none);
* an edge is kept only if it passes the Gabriel test (no other centre inside the circle on the
  edge as diameter, enlarged by :data:`GABRIEL_SLACK`).  During growth the neighbourhood of a
  seed is found among placed motifs without a triangulation (:func:`ring_of`), by the same test,
  so reference and target rings are made by one rule.  On a square lattice this drops the
  arbitrary diagonals Delaunay picks between cocircular points — the correction the paper's
  Fig. 3 asks the user to make by hand.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import Delaunay

from svgtile.core.exemplar import Exemplar
from svgtile.engines.growth.kernel import GABRIEL_SLACK, ring_order

__all__ = ["GABRIEL_SLACK", "Rings", "is_regular", "reference_rings", "regularity", "ring_of"]

#: A triangle with an angle above this is skewed (§4: 2π/3).
SKEW = 2.0 * np.pi / 3.0


@dataclass(frozen=True, eq=False)
class Rings:
    """The reference ring shapes: one per exemplar motif with a whole neighbourhood.

    Attributes
    ----------
    element : (r,) int array — the exemplar motif (sub-id) whose ring each row is
    kind : (r,) int array — its kind (symbol id)
    angle, scale : (r,) float arrays — its orientation (degrees) and scale
    size : (r,) int array — ring size m_r (neighbours), at most M
    rel : (r, M, 2) float array, user units — neighbours relative to the element, counter-
        clockwise by angle from +x; rows padded past ``size`` with zeros
    nkind, nsub : (r, M) int arrays — the neighbours' kinds and sub-ids (−1 past ``size``)
    edges : (e, 2) int array — the connectivity over the exemplar motifs (sub-id pairs, i < j;
        for a tile, an edge across the tile's edge joins the two motifs it connects)
    mean_length, short_length : float, user units — l, the mean edge length (§5.1's 5·l rule),
        and the shortest edge (r_short is half of it, §5.4)
    rolled, rolled_kind, rolled_sub : (r, M, M, 2), (r, M, M), (r, M, M) — the rings under every
        cyclic shift k: ``rolled[r, k, i] = rel[r, (k + i) mod size[r]]`` (matching reads slices)
    """

    element: np.ndarray
    kind: np.ndarray
    angle: np.ndarray
    scale: np.ndarray
    size: np.ndarray
    rel: np.ndarray
    nkind: np.ndarray
    nsub: np.ndarray
    edges: np.ndarray
    mean_length: float
    short_length: float
    rolled: np.ndarray
    rolled_kind: np.ndarray
    rolled_sub: np.ndarray

    def __len__(self) -> int:
        return len(self.element)

    @property
    def radius(self) -> float:
        """The farthest neighbour of any ring, user units."""
        return float(np.hypot(self.rel[..., 0], self.rel[..., 1]).max()) if len(self) else 0.0


def triangles(xy: np.ndarray) -> np.ndarray:
    """(t, 3) int array: the Delaunay triangles of ``xy`` that are not skewed (§4)."""
    if len(xy) < 3 or np.linalg.matrix_rank(xy - xy.mean(0)) < 2:
        return np.zeros((0, 3), np.int64)
    tri = Delaunay(xy).simplices.astype(np.int64)
    p = xy[tri]  # (t, 3, 2)
    a = p[:, [1, 2, 0]] - p
    b = p[:, [2, 0, 1]] - p
    cos = (a * b).sum(-1) / np.maximum(np.hypot(*a.T).T * np.hypot(*b.T).T, 1e-300)
    return tri[(np.arccos(np.clip(cos, -1, 1)) <= SKEW).all(1)]


def gabriel(xy: np.ndarray, i: np.ndarray, j: np.ndarray, others: np.ndarray) -> np.ndarray:
    """(e,) bool: edges ``(i, j)`` of ``xy`` with no point of ``others`` in their Gabriel circle.

    ``others`` is an (e, q) int array of candidate shadowing points per edge (−1 = none).
    """
    mid = (xy[i] + xy[j]) / 2
    r = np.hypot(*(xy[j] - xy[i]).T) / 2 * GABRIEL_SLACK
    q = xy[np.maximum(others, 0)]
    d = np.hypot(q[..., 0] - mid[:, None, 0], q[..., 1] - mid[:, None, 1])
    inside = (d < r[:, None]) & (others >= 0) & (others != i[:, None]) & (others != j[:, None])
    return ~inside.any(1)


def edges_of(xy: np.ndarray) -> np.ndarray:
    """(e, 2) int array, i < j: the kept Delaunay edges of ``xy`` that pass the Gabriel test."""
    tri = triangles(xy)
    if not len(tri):
        return np.zeros((0, 2), np.int64)
    e = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    e = np.unique(e, axis=0)
    # a Delaunay edge's Gabriel circle can only hold the apexes of its own triangles
    apex = np.full((len(e), 2), -1, np.int64)
    code = e[:, 0] * len(xy) + e[:, 1]
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        lo, hi = np.minimum(tri[:, a], tri[:, b]), np.maximum(tri[:, a], tri[:, b])
        at = np.searchsorted(code, lo * len(xy) + hi)
        free = apex[at, 0] < 0
        apex[at[free], 0] = tri[free, c]
        apex[at[~free], 1] = tri[~free, c]
    return e[gabriel(xy, e[:, 0], e[:, 1], apex)]


def reference_rings(exemplar: Exemplar) -> Rings:
    """The ring shapes of ``exemplar`` (§4), periodic for a repeating tile.

    For a finite exemplar, a motif whose neighbourhood reaches the border is no reference (its
    ring is open: the angle between two successive neighbours exceeds π, or it lies on the hull).
    """
    motifs = exemplar.motifs
    m = len(motifs)
    if exemplar.period is not None:
        w, h = exemplar.period
        da, db = (v.ravel() for v in np.meshgrid([0, -1, 1], [0, -1, 1]))  # the tile itself first
        xy = (motifs.xy[None] + np.stack([da * w, db * h], -1)[:, None]).reshape(-1, 2)
        sub = np.tile(np.arange(m), 9)
    else:
        xy, sub = motifs.xy, np.arange(m)
    e = edges_of(xy)
    both = np.concatenate([e, e[:, ::-1]])
    centre = both[both[:, 0] < m]  # edges from a motif of the tile itself
    order = np.lexsort((np.arctan2(*(xy[centre[:, 1]] - xy[centre[:, 0]])[:, ::-1].T), centre[:, 0]))
    centre = centre[order]
    count = np.bincount(centre[:, 0], minlength=m)
    start = np.r_[0, np.cumsum(count)[:-1]]
    rel_all = xy[centre[:, 1]] - xy[centre[:, 0]]
    ang = np.arctan2(rel_all[:, 1], rel_all[:, 0])
    # a ring is closed when no gap between successive neighbours reaches π
    gap = np.zeros(m)
    nxt = np.arange(len(centre)) + 1
    last = start + count - 1
    wrap = np.zeros(len(centre), bool)
    wrap[last[count > 0]] = True
    nxt[wrap] = start[centre[wrap, 0]]
    d = (ang[nxt] - ang) % (2 * np.pi)
    d[wrap & (count[centre[:, 0]] == 1)] = 2 * np.pi
    np.maximum.at(gap, centre[:, 0], d)
    whole = (count >= 3) & (gap < np.pi - 1e-9)
    if exemplar.period is None:
        hull = np.zeros(m, bool)
        if m >= 3:
            from scipy.spatial import ConvexHull

            hull[ConvexHull(xy).vertices] = True
        whole &= ~hull
    if not whole.any():  # too few motifs for a closed ring: take the fullest rings there are
        whole = count == count.max()
    M = int(count.max()) if m else 0
    elem = np.flatnonzero(whole)
    rel = np.zeros((len(elem), M, 2))
    nkind = np.full((len(elem), M), -1, np.int64)
    nsub = np.full((len(elem), M), -1, np.int64)
    for slot in range(M):
        has = count[elem] > slot
        at = start[elem[has]] + slot
        rel[has, slot] = rel_all[at]
        nkind[has, slot] = motifs.kind[sub[centre[at, 1]]]
        nsub[has, slot] = sub[centre[at, 1]]
    lengths = np.hypot(*rel_all.T) if len(rel_all) else np.ones(1)
    edges = np.unique(np.sort(sub[e], axis=1), axis=0) if len(e) else np.zeros((0, 2), np.int64)
    size = count[elem]
    at = (np.arange(M)[:, None] + np.arange(M)[None, :])[None] % np.maximum(size, 1)[:, None, None]  # (r, M, M)
    rows = np.arange(len(elem))[:, None, None]
    return Rings(elem, motifs.kind[elem], motifs.angle[elem], motifs.scale[elem], size, rel, nkind, nsub,
                 edges, float(lengths.mean()), float(lengths.min()), rel[rows, at], nkind[rows, at], nsub[rows, at])  # fmt: skip


def ring_of(xy: np.ndarray, centre: np.ndarray) -> np.ndarray:
    """Indices of the points ``xy`` that are Gabriel neighbours of ``centre``, counter-clockwise,
    starting after the widest angular gap (§5.2: "we start with the element on the boundary").

    Parameters
    ----------
    xy : (q, 2) float array, user units — the placed motifs near the seed
    centre : (2,) float array — the seed
    """
    rel = np.ascontiguousarray(np.asarray(xy, float).reshape(-1, 2) - centre)
    out = np.empty(len(rel), np.int64)
    return out[: ring_order(rel, out)]


#: Two ring shapes are alike when, under some cyclic shift, every neighbour is within this many
#: mean edge lengths of its counterpart and of the same kind.
ALIKE = 0.1


def ring_classes(rings: Rings, tol: float = ALIKE) -> np.ndarray:
    """(r,) int: a class label per reference ring; rings alike up to translation share one.

    A perfect lattice has one class per motif of its primitive cell (one for a square or hex
    lattice, two for bricks with a half offset), an irregular exemplar about one per motif.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    r = len(rings)
    if r == 0:
        return np.zeros(0, np.int64)
    M = rings.rel.shape[1]
    same = (rings.size[:, None] == rings.size[None, :]) & (rings.kind[:, None] == rings.kind[None, :])
    a, b = np.nonzero(np.triu(same, 1))
    alike = np.zeros(len(a), bool)
    valid = np.arange(M)[None, :] < rings.size[a][:, None]  # (p, M)
    for k in range(M):  # ring b under shift k against ring a
        d = np.hypot(*(rings.rolled[b, k] - rings.rel[a]).transpose(2, 0, 1))
        kinds = rings.rolled_kind[b, k] == rings.nkind[a]
        ok = ((d < tol * rings.mean_length) & kinds) | ~valid
        alike |= ok.all(1) & (k < rings.size[b])
    graph = coo_matrix((np.ones(alike.sum()), (a[alike], b[alike])), shape=(r, r))
    return connected_components(graph, directed=False)[1].astype(np.int64)


def regularity(rings: Rings) -> float:
    """1 − (ring classes − 1) / reference rings: 1 for a lattice or rows, near 0 when every
    neighbourhood differs (the measure behind :func:`is_regular`)."""
    if len(rings) == 0:
        return 0.0
    return 1.0 - (len(np.unique(ring_classes(rings))) - 1) / len(rings)


#: An exemplar is regular (rows, a lattice) when at least this regularity is found: at most one
#: ring shape per four motifs.
REGULAR = 0.75


def is_regular(rings: Rings) -> bool:
    """Does the exemplar show rows or a lattice (§4's connectivity repeats)?"""
    return regularity(rings) >= REGULAR
