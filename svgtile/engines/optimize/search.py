"""The search step (Ma, Wei & Tong 2011 §4.2): each output element's best exemplar sample.

Output neighbourhoods are the ``k`` nearest elements (§3.2), turned into the exemplar's frame by
the local orientation (§5, eq. (7)).  Candidates are gathered by k-coherence: each neighbour
``s'_o``, matched to ``s'_i``, proposes the sample found where ``s_o`` stands relative to ``s'_o``,
i.e. nearest to ``p(s'_i) − p̂(s'_o)`` in the exemplar (wrapped on a tile); the element's own
current match proposes itself; and each proposal brings its similarity set.  The candidates
are scored by eq. (1) (:mod:`.match`) and the best is kept — a constant amount of work per
element, so an iteration costs O(n).

The first search has no matches to propagate: each element then tries samples of its own kind,
all of them up to :data:`FIRST_CANDIDATES`, else that many picked by a hash of the run's key and
the element's rounded position (world-anchored, :mod:`svgtile.core.cellrng`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from svgtile.core import cellrng
from svgtile.core.footprint import rotation
from svgtile.engines.optimize.match import best_candidates, pairings
from svgtile.engines.optimize.samples import Samples

#: Samples tried per element by the first search (§4.1's initial assignment).
FIRST_CANDIDATES = 48
_FIRST = 71  # hash stream of the first candidates
#: Neighbours first asked for, as a multiple of the k + 1 nearest, so that a tie group at the
#: k-th is whole and goes by position (rows where it may not be are asked again for more).
TIES = 2


@dataclass(frozen=True, eq=False)
class Neighbourhoods:
    """The output's neighbourhoods (§3.2) in the exemplar's frame.

    Attributes
    ----------
    index : (n, k) int, the neighbours (−1 absent)
    rel : (n, k, 2) float, spacings, ``R(−θ)(p(s'_o) − p(s_o))``; NaN where absent
    kind : (n, k) int, −1 where absent
    turn : (n,) float, degrees — θ, the local orientation of each element (0 without flow)
    """

    index: np.ndarray
    rel: np.ndarray
    kind: np.ndarray
    turn: np.ndarray


def output_neighbourhoods(xy: np.ndarray, kind: np.ndarray, k: int, spacing: float,
                          turn: np.ndarray) -> Neighbourhoods:  # fmt: skip
    """The ``k`` nearest neighbours of every output element, relative, turned by ``−turn``.

    Parameters
    ----------
    xy : (n, 2) float, user units; kind : (n,) int
    k : neighbours; spacing : user units; turn : (n,) degrees
    """
    n = len(xy)
    index = np.full((n, k), -1, dtype=np.int64)
    rel = np.full((n, k, 2), np.nan)
    if n > 1:
        q = min(k + 1, n)
        nb = _nearest_by_position(xy, q)
        # drop the element itself (not merely the first hit: a coincident element may come first)
        is_self = nb == np.arange(n)[:, None]
        drop = np.where(is_self.any(axis=1), is_self.argmax(axis=1), q - 1)
        keep = np.ones_like(nb, dtype=bool)
        keep[np.arange(n), drop] = False
        nb = nb[keep].reshape(n, q - 1)
        index[:, : q - 1] = nb
        d = (xy[nb] - xy[:, None, :]) / spacing
        back = rotation(-turn)  # (n, 2, 2)
        rel[:, : q - 1] = np.einsum("nij,nkj->nki", back, d)
    kinds = np.where(index >= 0, kind[np.maximum(index, 0)], -1)
    return Neighbourhoods(index, rel, kinds, turn)


def _nearest_by_position(xy: np.ndarray, q: int) -> np.ndarray:
    """(n, q) int: each point's ``q`` nearest points (itself among them), equidistant ones by
    position (x, then y).

    Equidistant neighbours (the copies of a repeating tile) come from the tree in an order that
    depends on every point in it, so an edit anywhere changed which of them completed a far
    element's k.  ``TIES · q`` are asked for; a row whose last one is still as near as its q-th
    may have more of that tie group unseen, and is asked again for twice as many until its tie
    group is whole (a square lattice at k = 14 has 8 points at its 15th distance).
    """
    n = len(xy)
    tree = cKDTree(xy)
    out = np.empty((n, q), dtype=np.int64)
    rows, want = np.arange(n), min(TIES * q, n)
    while len(rows):
        dist, nb = tree.query(xy[rows], k=want)
        dist, nb = dist.reshape(len(rows), want), np.asarray(nb, dtype=np.int64).reshape(len(rows), want)
        order = np.lexsort((xy[nb, 1], xy[nb, 0], dist), axis=-1)[:, :q]
        out[rows] = np.take_along_axis(nb, order, axis=1)
        if want == n:
            break
        rows, want = rows[dist[:, -1] <= dist[:, q - 1]], min(2 * want, n)
    return out


def first_candidates(samples: Samples, xy: np.ndarray, kind: np.ndarray, *, key: int) -> np.ndarray:
    """(n, C) int: the samples each element tries before it has a match (see the module notes)."""
    n, m = len(xy), len(samples)
    c = min(FIRST_CANDIDATES, m)
    order = np.argsort(samples.kind, kind="stable")
    kinds = np.arange(max(int(samples.kind.max()), int(kind.max(initial=0))) + 1)
    count = np.bincount(samples.kind, minlength=len(kinds))
    start = np.r_[0, np.cumsum(count)[:-1]]
    own = count[kind] > 0
    lo = np.where(own, start[kind], 0)
    size = np.where(own, count[kind], m)
    cells = np.round(xy * 1e3).astype(np.int64)
    u = cellrng.uniform(key, _FIRST, cells[:, 0, None], cells[:, 1, None], np.arange(c)[None, :])
    every = size[:, None] <= c  # few enough: every one, in turn
    pick = np.where(every, np.arange(c)[None, :] % size[:, None], np.floor(u * size[:, None]).astype(np.int64))
    return order[lo[:, None] + pick] if n else np.zeros((0, c), np.int64)


def coherent_candidates(samples: Samples, hoods: Neighbourhoods, match: np.ndarray, wrap) -> np.ndarray:
    """(n, (k + 1)(K + 1)) int: the k-coherence candidates of every element (§4.2)."""
    n = len(hoods.index)
    nb = np.maximum(hoods.index, 0)
    q = samples.xy[match[nb]] - hoods.rel * samples.spacing  # where s_o stands, seen from s'_i
    proposed = samples.nearest(wrap(np.nan_to_num(q)))
    proposed = np.where(hoods.index >= 0, proposed, match[:, None])
    base = np.concatenate([match[:, None], proposed], axis=1)  # (n, k + 1)
    return np.concatenate([base, samples.similar[base].reshape(n, -1)], axis=1)


def search(samples: Samples, hoods: Neighbourhoods, kind: np.ndarray, candidates: np.ndarray,
           alpha: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """The best candidate of every element and its pairing (§4.2, eq. (1)).

    Returns
    -------
    match : (n,) int, the chosen sample (the first of equal costs)
    cost : (n,) float, its eq. (1) distance, squared spacings
    slots : (n, k) int, the exemplar neighbour slot paired with each output neighbour, −1 unpaired
    """
    cand = np.ascontiguousarray(candidates, dtype=np.int64)
    best, cost = best_candidates(hoods.rel, hoods.kind, kind, cand, samples.rel, samples.nkind, samples.kind, alpha)
    match = cand[np.arange(len(cand)), best]
    slots = pairings(hoods.rel, hoods.kind, match, samples.rel, samples.nkind, alpha)
    return match, cost, slots
