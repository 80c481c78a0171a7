"""The kinds of a grown piece re-chosen against the exemplar's k-nearest neighbourhoods
(Ma, Wei & Tong 2011, §3.2 eq. 1), after the ring pass of :mod:`.kinds`.

The ring pass (Ijiri et al. 2008, §5.2) matches each motif's complete 1-ring against the reference
rings of its kind, one ring at a time, and stops where no single change lowers the sum of those
ring errors.  On marsh (two kinds of tuft in runs along offset rows) that leaves E — the mean
neighbourhood distance likeness is made of — at 0.64–0.67 on seeds 1–3, where L ≥ 0.8 asks
≤ 0.66.  A ring's error is the best over many references of a hand-drawn exemplar, each
matched on its own; it is a looser judge of a kind than the score's, which pairs each of a
motif's k nearest with an exemplar neighbourhood's (the earlier session's bound: kinds alone,
flipped greedily against the score's E, reached L 0.85–0.86).

This pass lowers ma2011's own neighbourhood energy (§3.2 eq. 1, the energy of the optimize
engine's solver, §4) by changing kinds alone.  Positions stay, and the texture's neighbourhoods
(each motif's ``k`` nearest) and their greedy pairing with every exemplar neighbourhood (the
exemplar's ``2k`` nearest, closest pair first: :func:`svgtile.analysis.neighbourhood.neighbourhood_distance`)
depend on positions alone, so they are found once: each centre ``c`` and exemplar motif ``e``
have a position cost ``P[c, e]`` and, for each of ``c``'s neighbours, the exemplar kind it is
paired with.  Then a centre's energy with kinds ``q`` is::

    E_c(q) = min_e  P[c, e] + α·([q_c ≠ q_e] + Σ_j [q(n_j(c)) ≠ q_e(pair_j)])

and the pass is iterated conditional modes: motif by motif, in index order, a motif that may
change takes the kind that lowers the sum of ``E_c`` over the centres that read it (itself and
those whose neighbourhood holds it) the most, among the kinds the mix allows
(:func:`svgtile.engines.growth.kinds.mix_bounds`: left free, the pass moved marsh's mix by 0.03–0.04
on top of the ring pass's 0.06), until a sweep changes nothing or :data:`SWEEPS`.
The pass reads only positions and kinds, with no draws: deterministic and world-anchored
(the engine calls it on the same motifs as the ring pass).  The compiled loops are
:func:`_tables` (the pairing, one centre × exemplar motif at a time) and :func:`_sweeps`.
"""

from __future__ import annotations

import numba
import numpy as np
from scipy.spatial import cKDTree

from svgtile.analysis.neighbourhood import EXEMPLAR_FACTOR, neighbourhoods
from svgtile.engines.growth.kinds import mix_bounds

#: Neighbours per neighbourhood (ma2011 §3.2; the likeness score's k).
K = 6
#: Cost of a kind mismatch, squared exemplar spacings (the likeness score's α).
ALPHA = 1.0
#: At most this many sweeps (marsh 300 × 300, seeds 1–3, before the pass held the kind mix: every
#: piece's pass ended within 2–6, the last one changing nothing; most in 3).
SWEEPS = 8


@numba.njit(cache=True)
def _tables(rel, pe, ke, alpha):  # pragma: no cover
    """Position costs and pairings of texture neighbourhoods ``rel`` ((c, k, 2) spacings) with
    exemplar neighbourhoods ``pe`` ((m, ke, 2) spacings, NaN absent; kinds ``ke`` (m, ke)).

    Returns ``cost`` (c, m): Σ |Δp|² of the greedy pairing (closest pair first), a lone
    neighbour costing |p̂|² + α; ``pair`` (c, m, k): the exemplar kind each neighbour is paired
    with, −1 when lone (a kind never equal to a texture kind)."""
    c, k = rel.shape[0], rel.shape[1]
    m, kk = pe.shape[0], pe.shape[1]
    cost = np.zeros((c, m))
    pair = np.full((c, m, k), -1, np.int64)
    d = np.empty((k, kk))
    low = np.empty(k)  # each texture neighbour's nearest free exemplar neighbour: distance, index
    at = np.empty(k, np.int64)
    for a in range(c):
        for e in range(m):
            for i in range(k):
                low[i], at[i] = np.inf, -1
                for j in range(kk):
                    if np.isnan(pe[e, j, 0]):
                        d[i, j] = np.inf
                    else:
                        dx, dy = rel[a, i, 0] - pe[e, j, 0], rel[a, i, 1] - pe[e, j, 1]
                        d[i, j] = dx * dx + dy * dy
                        if d[i, j] < low[i]:
                            low[i], at[i] = d[i, j], j
            total = 0.0
            # closest pair first, the first in row-major order on a tie (as _greedy_costs): the
            # smallest row minimum, rows kept with their minima so each round reads k of them
            for _ in range(k):
                bi, bd = -1, np.inf
                for i in range(k):
                    if low[i] < bd:
                        bi, bd = i, low[i]
                if bi < 0:
                    break
                bj = at[bi]
                total += bd
                pair[a, e, bi] = ke[e, bj]
                low[bi], at[bi] = np.inf, -1
                for j in range(kk):
                    d[bi, j] = np.inf
                for i in range(k):
                    d[i, bj] = np.inf
                    if at[i] == bj:  # its nearest is taken: the next free one
                        low[i], at[i] = np.inf, -1
                        for j in range(kk):
                            if d[i, j] < low[i]:
                                low[i], at[i] = d[i, j], j
            for i in range(k):
                if pair[a, e, i] < 0:
                    total += rel[a, i, 0] ** 2 + rel[a, i, 1] ** 2 + alpha
            cost[a, e] = total
    return cost, pair


@numba.njit(cache=True)
def _energy(a, centre, kind, nb, cost, pair, ce, alpha):  # pragma: no cover
    """E_c of table row ``a`` (motif ``centre``) with kinds ``kind``."""
    best = np.inf
    k = nb.shape[1]
    for e in range(cost.shape[1]):
        v = cost[a, e] + alpha * (kind[centre] != ce[e])
        if v >= best:
            continue
        for j in range(k):
            if kind[nb[a, j]] != pair[a, e, j]:
                v += alpha
        if v < best:
            best = v
    return best


@numba.njit(cache=True)
def _sweeps(
    kind, movable, rows, centre, nb, hptr, hidx, cost, pair, ce, nkind, alpha, sweeps, count, lo, hi
):  # pragma: no cover
    """Iterated conditional modes over ``kind`` ((n,) int, changed in place); returns the sweeps
    made.  ``rows[i]`` is motif ``i``'s table row (−1: none); ``hidx[hptr[i]:hptr[i + 1]]`` the
    table rows whose neighbourhood holds motif ``i``.  A motif is looked at again only when a
    kind its choice reads has changed since it was last looked at (it would choose as before).
    A change from kind ``a`` to ``q`` is made only while ``count[a] > lo[a]`` and ``count[q] <
    hi[q]`` (:func:`svgtile.engines.growth.kinds.mix_bounds`; ``count`` updated in place)."""
    n = kind.shape[0]
    k = nb.shape[1]
    dirty = movable.copy()
    done = 0
    for _ in range(sweeps):
        if not dirty.any():
            break
        done += 1
        for i in range(n):
            if not dirty[i]:
                continue
            dirty[i] = False
            old = kind[i]
            base = _energy(rows[i], i, kind, nb, cost, pair, ce, alpha)
            for h in range(hptr[i], hptr[i + 1]):
                a = hidx[h]
                base += _energy(a, centre[a], kind, nb, cost, pair, ce, alpha)
            best, pick = base, old
            for q in range(nkind):
                if q == old or count[old] <= lo[old] or count[q] >= hi[q]:
                    continue
                kind[i] = q
                v = _energy(rows[i], i, kind, nb, cost, pair, ce, alpha)
                for h in range(hptr[i], hptr[i + 1]):
                    a = hidx[h]
                    v += _energy(a, centre[a], kind, nb, cost, pair, ce, alpha)
                if v < best - 1e-9:
                    best, pick = v, q
            kind[i] = pick
            if pick == old:
                continue
            count[old] -= 1
            count[pick] += 1
            # the energies that read i's kind: its own and its holders'; each is read by its
            # centre and by the members of its neighbourhood
            for h in range(hptr[i] - 1, hptr[i + 1]):
                a = rows[i] if h < hptr[i] else hidx[h]
                dirty[centre[a]] = movable[centre[a]]
                for j in range(k):
                    dirty[nb[a, j]] = movable[nb[a, j]]
    return done


def energies(xy: np.ndarray, kind: np.ndarray, centres: np.ndarray, exemplar_xy: np.ndarray,
             exemplar_kind: np.ndarray, spacing: float) -> np.ndarray:  # fmt: skip
    """E_c of each of ``centres`` — the energy the pass lowers, and the term
    :func:`svgtile.analysis.neighbourhood.neighbourhood_distance` averages (α = :data:`ALPHA`,
    k = :data:`K`, no turns).

    Parameters
    ----------
    xy : (n, 2) float array, user units; kind : (n,) int array — the texture (n > K)
    centres : (c,) int array — indices into ``xy``
    exemplar_xy : (m, 2) float array, user units; exemplar_kind : (m,) int array
    spacing : float, user units

    Returns
    -------
    (c,) float array, squared spacings
    """
    xy, kind, centres = (
        np.asarray(xy, float),
        np.asarray(kind, np.int64),
        np.asarray(centres, np.int64),
    )
    nb = cKDTree(xy).query(xy[centres], k=K + 1)[1][:, 1:].astype(np.int64)
    pe, ke = neighbourhoods(exemplar_xy, exemplar_kind, EXEMPLAR_FACTOR * K)
    cost, pair = _tables(
        (xy[nb] - xy[centres][:, None, :]) / spacing, pe / spacing, ke.astype(np.int64), ALPHA
    )
    ce = np.asarray(exemplar_kind, np.int64)
    return np.array([_energy(a, c, kind, nb, cost, pair, ce, ALPHA) for a, c in enumerate(centres)])


def neighbourhood_kinds(xy: np.ndarray, kind: np.ndarray, movable: np.ndarray, exemplar_xy: np.ndarray,
                        exemplar_kind: np.ndarray, spacing: float, *, sweeps: int = SWEEPS,
                        frequency: np.ndarray | None = None) -> np.ndarray:  # fmt: skip
    """The kinds of ``movable`` motifs re-chosen to lower ma2011's neighbourhood energy (§3.2 eq. 1).

    Parameters
    ----------
    xy : (n, 2) float array, user units — the motifs that may change and the fixed ones around
        them (whose kinds count but stay)
    kind : (n,) int array
    movable : (n,) bool array
    exemplar_xy : (m, 2) float array, user units; exemplar_kind : (m,) int array
    spacing : float, user units — the exemplar's mean spacing (positions are compared in spacings)
    sweeps : at most this many sweeps (fewer when one changes nothing)
    frequency : (k,) float array, the exemplar's kind shares (by count): each kind's count over the
        n motifs (the fixed ones count, the movable ones change) is held to them
        (:func:`svgtile.engines.growth.kinds.mix_bounds`); None leaves it free

    Returns
    -------
    (n,) int array: the new kinds (unchanged where not ``movable``)
    """
    kind = np.array(kind, np.int64)
    n = len(kind)
    movable = np.asarray(movable, np.bool_)
    if n <= K or not movable.any() or sweeps <= 0 or len(exemplar_xy) < 2:
        return kind
    xy = np.asarray(xy, float)
    _, nb = cKDTree(xy).query(xy, k=K + 1)
    nb = nb[:, 1:].astype(
        np.int64
    )  # the motif itself first (positions are distinct after the exact check)
    # the centres whose energy a change can touch: the movable motifs and those whose neighbourhood holds one
    need = movable | movable[nb].any(1)
    centre = np.flatnonzero(need).astype(np.int64)
    rows = np.full(n, -1, np.int64)
    rows[centre] = np.arange(len(centre))
    cnb = nb[centre]
    rel = (xy[cnb] - xy[centre][:, None, :]) / spacing
    pe, ke = neighbourhoods(exemplar_xy, exemplar_kind, EXEMPLAR_FACTOR * K)
    cost, pair = _tables(rel, pe / spacing, ke.astype(np.int64), ALPHA)
    owner = np.repeat(np.arange(len(centre)), K)
    order = np.argsort(cnb.ravel(), kind="stable")
    hidx = owner[order].astype(np.int64)
    hptr = np.searchsorted(cnb.ravel()[order], np.arange(n + 1)).astype(np.int64)
    nkind = int(max(np.max(exemplar_kind), kind.max()) + 1)
    if frequency is not None:
        nkind = max(nkind, len(frequency))
    count, lo, hi = mix_bounds(kind, movable, frequency, nkind)
    _sweeps(kind, movable & need, rows, centre, cnb, hptr, hidx, cost, pair, np.asarray(exemplar_kind, np.int64),
            nkind, ALPHA, sweeps, count, lo, hi)  # fmt: skip
    return kind


__all__ = ["ALPHA", "SWEEPS", "K", "energies", "neighbourhood_kinds"]
