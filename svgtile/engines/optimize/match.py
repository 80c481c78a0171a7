"""Eq. (1) of Ma, Wei & Tong 2011 with the greedy pairing of §3.2, returning the pairing.

:func:`svgtile.analysis.neighbourhood.neighbourhood_distance` computes the same distance for the
likeness figure, in bulk numpy over every exemplar neighbourhood; the solver needs something
else: the cost of a handful of *candidate* exemplar samples per output element (k-coherence,
§4.2) and, for the chosen one, which exemplar neighbour each output neighbour was paired with
(the predictions of §4.3).  The pairing is sequential — take the closest pair, strike its row and
column, repeat — so it is a tight numba loop over (element, candidate), compiled once and cached.

The cost is exactly :func:`svgtile.analysis.neighbourhood._greedy_costs` plus the centre's kind
term: ``α·[q(s_o) ≠ q(s_i)] + Σ |p̂(s'_o) − p̂(s'_i)|² + α·[q(s'_o) ≠ q(s'_i)]``, a texture
neighbour left without partner costing ``|p̂|² + α`` (tested against the shared implementation).
"""

from __future__ import annotations

import numba
import numpy as np


@numba.njit(cache=True)
def _pair(po, ko, pe, kee, alpha, slots):  # pragma: no cover - compiled
    """Greedy eq. (1) of one output neighbourhood ``po`` (k, 2) against one exemplar ``pe``
    (ke, 2); ``slots`` (k,) receives the exemplar slot paired with each output neighbour (−1)."""
    k = po.shape[0]
    ke = pe.shape[0]
    d = np.empty((k, ke))
    for a in range(k):
        slots[a] = -1
        for b in range(ke):
            dx = po[a, 0] - pe[b, 0]
            dy = po[a, 1] - pe[b, 1]
            v = dx * dx + dy * dy
            d[a, b] = v if v == v else np.inf  # NaN (an absent neighbour) never pairs
    used = np.zeros(ke, dtype=np.bool_)
    cost = 0.0
    for _ in range(k):
        best = np.inf
        ba = -1
        bb = -1
        for a in range(k):
            if slots[a] >= 0:
                continue
            for b in range(ke):
                if not used[b] and d[a, b] < best:
                    best = d[a, b]
                    ba = a
                    bb = b
        if ba < 0:
            break
        slots[ba] = bb
        used[bb] = True
        cost += best + (alpha if ko[ba] != kee[bb] else 0.0)
    for a in range(k):
        if slots[a] < 0 and po[a, 0] == po[a, 0]:
            cost += po[a, 0] * po[a, 0] + po[a, 1] * po[a, 1] + alpha
    return cost


@numba.njit(cache=True)
def candidate_costs(rel_o, kind_o, centre_o, cand, rel_e, kind_e, centre_e, alpha):  # pragma: no cover
    """(n, C) float: eq. (1) between each output neighbourhood and each of its candidates.

    Parameters
    ----------
    rel_o : (n, k, 2) float, spacings, in the exemplar's frame; NaN rows are absent neighbours
    kind_o : (n, k) int
    centre_o : (n,) int, each output element's kind
    cand : (n, C) int, candidate exemplar samples
    rel_e : (m, ke, 2) float, spacings; kind_e : (m, ke) int; centre_e : (m,) int
    alpha : kind mismatch cost, squared spacings
    """
    n, c = cand.shape
    out = np.empty((n, c))
    slots = np.empty(rel_o.shape[1], dtype=np.int64)
    for i in range(n):
        for j in range(c):
            e = cand[i, j]
            cost = _pair(rel_o[i], kind_o[i], rel_e[e], kind_e[e], alpha, slots)
            out[i, j] = cost + (alpha if centre_o[i] != centre_e[e] else 0.0)
    return out


@numba.njit(cache=True)
def pairings(rel_o, kind_o, chosen, rel_e, kind_e, alpha):  # pragma: no cover - compiled
    """(n, k) int: the exemplar slot each output neighbour is paired with by the greedy pairing
    against the chosen sample ``chosen`` (n,), −1 where unpaired."""
    n, k = kind_o.shape
    out = np.empty((n, k), dtype=np.int64)
    slots = np.empty(k, dtype=np.int64)
    for i in range(n):
        _pair(rel_o[i], kind_o[i], rel_e[chosen[i]], kind_e[chosen[i]], alpha, slots)
        out[i] = slots
    return out
