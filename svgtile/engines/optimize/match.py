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
def _pair(po, ko, pe, kee, alpha, slots, d, used, rowmin, rowarg, start=0.0, bound=np.inf):  # pragma: no cover
    """Greedy eq. (1) of one output neighbourhood ``po`` (k, 2) against one exemplar ``pe``
    (ke, 2); ``slots`` (k,) receives the exemplar slot paired with each output neighbour (−1).

    The cost starts at ``start`` and only grows, so the pairing stops, returning infinity, as
    soon as it reaches ``bound`` (the best candidate's so far: branch and bound).  ``d``
    (k, ke), ``used`` (ke,), ``rowmin`` (k,), ``rowarg`` (k,) are work buffers (no allocation
    in the inner loop)."""
    k = po.shape[0]
    ke = pe.shape[0]
    # each row's smallest distance to a free exemplar neighbour: a pass picks the smallest row
    # minimum (ties: lowest row, then lowest column, as a scan of the whole matrix would) and
    # only rows whose minimum was the taken column look again.  Every present output neighbour
    # costs at least its row minimum or, unpaired, |p̂|² + α: their sum bounds the cost from
    # below, so a candidate whose bound passes ``bound`` is dropped before any pairing (the
    # margin keeps a candidate the rounding of the two sums could wrongly drop)
    lower = start
    limit = bound + 1e-9 * (1.0 + abs(bound))
    for a in range(k):
        slots[a] = -1
        m = np.inf
        arg = -1
        for b in range(ke):
            dx = po[a, 0] - pe[b, 0]
            dy = po[a, 1] - pe[b, 1]
            v = dx * dx + dy * dy
            v = v if v == v else np.inf  # NaN (an absent neighbour) never pairs
            d[a, b] = v
            if v < m:
                m = v
                arg = b
        rowmin[a] = m
        rowarg[a] = arg
        if po[a, 0] == po[a, 0]:
            lower += min(m, po[a, 0] * po[a, 0] + po[a, 1] * po[a, 1] + alpha)
            if lower > limit:
                return np.inf
    used[:] = False
    cost = start
    for _ in range(k):
        best = np.inf
        ba = -1
        for a in range(k):
            if slots[a] < 0 and rowmin[a] < best:
                best = rowmin[a]
                ba = a
        if ba < 0:
            break
        bb = rowarg[ba]
        slots[ba] = bb
        used[bb] = True
        cost += best + (alpha if ko[ba] != kee[bb] else 0.0)
        if cost >= bound:
            return np.inf
        for a in range(k):
            if slots[a] < 0 and rowarg[a] == bb:
                m = np.inf
                arg = -1
                for b in range(ke):
                    if not used[b] and d[a, b] < m:
                        m = d[a, b]
                        arg = b
                rowmin[a] = m
                rowarg[a] = arg
    for a in range(k):
        if slots[a] < 0 and po[a, 0] == po[a, 0]:
            cost += po[a, 0] * po[a, 0] + po[a, 1] * po[a, 1] + alpha
    return cost if cost < bound else np.inf


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
    k, ke = rel_o.shape[1], rel_e.shape[1]
    slots, d, used = np.empty(k, dtype=np.int64), np.empty((k, ke)), np.empty(ke, dtype=np.bool_)
    rowmin, rowarg = np.empty(k), np.empty(k, dtype=np.int64)
    for i in range(n):
        for j in range(c):
            e = cand[i, j]
            cost = _pair(rel_o[i], kind_o[i], rel_e[e], kind_e[e], alpha, slots, d, used, rowmin, rowarg)
            out[i, j] = cost + (alpha if centre_o[i] != centre_e[e] else 0.0)
    return out


@numba.njit(cache=True)
def pairings(rel_o, kind_o, chosen, rel_e, kind_e, alpha):  # pragma: no cover - compiled
    """(n, k) int: the exemplar slot each output neighbour is paired with by the greedy pairing
    against the chosen sample ``chosen`` (n,), −1 where unpaired."""
    n, k = kind_o.shape
    ke = rel_e.shape[1]
    out = np.empty((n, k), dtype=np.int64)
    slots, d, used = np.empty(k, dtype=np.int64), np.empty((k, ke)), np.empty(ke, dtype=np.bool_)
    rowmin, rowarg = np.empty(k), np.empty(k, dtype=np.int64)
    for i in range(n):
        _pair(rel_o[i], kind_o[i], rel_e[chosen[i]], kind_e[chosen[i]], alpha, slots, d, used, rowmin, rowarg)
        out[i] = slots
    return out


@numba.njit(cache=True)
def best_candidates(rel_o, kind_o, centre_o, cand, rel_e, kind_e, centre_e, alpha):  # pragma: no cover
    """The best of each element's candidates by eq. (1): (n,) index into ``cand``'s row (the first
    of equal costs) and (n,) its cost.  Arguments as :func:`candidate_costs`; a candidate met
    again in a row is skipped, and one whose partial cost reaches the best so far is abandoned
    (branch and bound: :func:`_pair`).

    A sequential loop (the greedy pairing is), so numba; the elements are independent, but a
    ``prange`` over them measured no faster on the shared 2-core machine."""
    n = cand.shape[0]
    best = np.empty(n, dtype=np.int64)
    cost = np.empty(n)
    k, ke = rel_o.shape[1], rel_e.shape[1]
    slots, d, used = np.empty(k, dtype=np.int64), np.empty((k, ke)), np.empty(ke, dtype=np.bool_)
    rowmin, rowarg = np.empty(k), np.empty(k, dtype=np.int64)
    for i in range(n):
        best[i], cost[i] = _best_in_row(cand[i], rel_o[i], kind_o[i], centre_o[i], rel_e, kind_e, centre_e, alpha,
                                        slots, d, used, rowmin, rowarg)  # fmt: skip
    return best, cost


@numba.njit(cache=True)
def _best_in_row(row, po, ko, centre, rel_e, kind_e, centre_e, alpha, slots, d, used, rowmin, rowarg):  # pragma: no cover
    """The best of one element's candidates ``row`` (c,) by eq. (1), the element's neighbours
    ``po`` (k, 2) of kinds ``ko`` (k,) and its own attribute ``centre``: (index into ``row``, the
    first of equal costs; cost).  A candidate met again in the row is skipped; one whose partial
    cost reaches the best so far is abandoned (:func:`_pair`)."""
    bi = 0
    bc = np.inf
    for j in range(row.shape[0]):
        e = row[j]
        seen = False
        for t in range(j):
            if row[t] == e:
                seen = True
                break
        if seen:
            continue
        start = alpha if centre != centre_e[e] else 0.0
        v = _pair(po, ko, rel_e[e], kind_e[e], alpha, slots, d, used, rowmin, rowarg, start, bc)
        if v < bc:
            bc = v
            bi = j
    return bi, bc


@numba.njit(cache=True)
def _row_best(r, index, kind, rel_o, cand, rel_e, kind_e, centre_e, alpha, ko, slots, d, used, rowmin, rowarg):  # pragma: no cover
    """The best candidate of output row ``r`` under the current ``kind`` (n,): (index into
    ``cand[r]``, cost); ``ko`` (k,) receives the row's neighbour kinds."""
    k = index.shape[1]
    for a in range(k):
        ko[a] = kind[index[r, a]] if index[r, a] >= 0 else -1
    return _best_in_row(cand[r], rel_o[r], ko, kind[r], rel_e, kind_e, centre_e, alpha, slots, d, used, rowmin, rowarg)


@numba.njit(cache=True)
def _work(k, ke, m):  # pragma: no cover
    """Work buffers of the kind kernels: the pairing's (:func:`_row_best`: ``ko``, ``slots``, ``d``,
    ``used``, ``rowmin``, ``rowarg`` for ``k`` output and ``ke`` exemplar neighbours) and the
    rows a change moves (``nb``, with their best candidates ``tb`` and costs ``tc``), ``m + 1``
    long: ``m``, every element's count of elements that have it as a neighbour summed, bounds any
    one's."""
    return (np.empty(k, dtype=np.int64), np.empty(k, dtype=np.int64), np.empty((k, ke)), np.empty(ke, dtype=np.bool_),
            np.empty(k), np.empty(k, dtype=np.int64), np.empty(m + 1, dtype=np.int64), np.empty(m + 1, dtype=np.int64),
            np.empty(m + 1))  # fmt: skip


@numba.njit(cache=True)
def _neighbourhoods_of(o, rev_ptr, rev_idx, nb):  # pragma: no cover
    """Fill ``nb`` with element ``o`` and the elements that have it as a neighbour (``rev_idx[rev_ptr[o]:
    rev_ptr[o + 1]]``), the rows whose energy a change of ``o`` moves; returns how many."""
    nb[0] = o
    for t in range(rev_ptr[o], rev_ptr[o + 1]):
        nb[1 + t - rev_ptr[o]] = rev_idx[t]
    return 1 + rev_ptr[o + 1] - rev_ptr[o]


@numba.njit(cache=True)
def descend_kinds(kind, voted, window, count, lo, hi, index, rev_ptr, rev_idx, rel_o, cand, best, cost, rel_e, kind_e,
                  centre_e, alpha):  # pragma: no cover  # fmt: skip
    """Each element's kind chosen among its votes as the one of least energy (eq. (5), Pseudocode 1).

    Elements are visited in order; for each kind ``q`` voted for element ``o`` (``voted[o, q]``)
    other than its own, the energy of every neighbourhood ``o`` belongs to — its own and those
    of the elements that have it as a neighbour (``rev_idx[rev_ptr[o]:rev_ptr[o + 1]]``) — is
    found again by the best of their candidates with ``o`` of kind ``q``; the kind of least
    total is kept (the current one on a tie) and the rows' best candidates and costs with it.
    Sequential (a change is seen by the next element's evaluation), so a numba loop.

    The kind mix is held to the exemplar's window by window: a change of an element of window
    ``w = window[o]`` from kind ``a`` to ``q`` is tried only while ``count[w, a] > lo[w, a]`` and
    ``count[w, q] < hi[w, q]`` (``count`` (nw, nk) updated in place).  Without
    it the mix drifts towards the smaller motifs: the non-penetration step undoes a change to a
    larger footprint more often than one to a smaller, and each iteration ratchets.

    ``kind`` (n,), ``best`` (n,) index into ``cand``'s rows and ``cost`` (n,) are updated in
    place; returns how many kinds changed.
    """
    n = index.shape[0]
    nk = voted.shape[1]
    ko, slots, d, used, rowmin, rowarg, nb, tb, tc = _work(index.shape[1], rel_e.shape[1], rev_ptr[n] - rev_ptr[0])
    keep_b, keep_c = np.empty_like(tb), np.empty_like(tc)
    changed = 0
    for o in range(n):
        own = kind[o]
        rows = _neighbourhoods_of(o, rev_ptr, rev_idx, nb)
        now = 0.0
        for t in range(rows):
            now += cost[nb[t]]
        lowest = now - 1e-9 * (1.0 + abs(now))
        won = own
        for q in range(nk):
            w = window[o]
            if q == own or not voted[o, q] or count[w, own] <= lo[w, own] or count[w, q] >= hi[w, q]:
                continue
            kind[o] = q
            total = 0.0
            for t in range(rows):
                bi, bc = _row_best(nb[t], index, kind, rel_o, cand, rel_e, kind_e, centre_e, alpha, ko, slots, d,
                                   used, rowmin, rowarg)  # fmt: skip
                tb[t] = bi
                tc[t] = bc
                total += bc
                if total >= lowest:
                    break
            if total < lowest:
                lowest = total
                won = q
                for t in range(rows):
                    keep_b[t] = tb[t]
                    keep_c[t] = tc[t]
        kind[o] = won
        if won != own:
            changed += 1
            count[window[o], own] -= 1
            count[window[o], won] += 1
            for t in range(rows):
                best[nb[t]] = keep_b[t]
                cost[nb[t]] = keep_c[t]
    return changed


@numba.njit(cache=True)
def _improves(count, lo, hi, w, a, q):  # pragma: no cover
    """Whether a change of an element of window ``w`` from kind ``a`` to ``q`` brings the window's mix
    towards ``[lo, hi]`` without taking either kind past its other bound: ``a`` above its upper
    bound and ``q`` below its own, or ``q`` below its lower bound and ``a`` above its own."""
    return (count[w, a] > hi[w, a] and count[w, q] < hi[w, q]) or (count[w, q] < lo[w, q] and count[w, a] > lo[w, a])


@numba.njit(cache=True)
def rebalance_kinds(kind, voted, window, count, lo, hi, index, rev_ptr, rev_idx, rel_o, cand, best, cost, rel_e, kind_e,
                    centre_e, alpha):  # pragma: no cover  # fmt: skip
    """The changes of kind that bring every window's mix towards ``[lo, hi]``, the cheapest first.

    :func:`descend_kinds` holds a window's mix where it is; this brings it back where it strayed
    (a start drawn off the exemplar's mix, :mod:`.init`).  Each element of a window whose mix a
    change of it would mend (:func:`_improves`) has the cost of that change — the energy of every
    neighbourhood it belongs to, found again as in :func:`descend_kinds`, less their energy now —
    for the cheapest of its voted kinds; then, in order of that cost, each change is made while
    its window still needs it, its neighbourhoods' energies found again then (an earlier change
    may have moved them).  A change is made whatever it costs: the mix is a bound, the energy
    what is minimised within it.  Each element is tried once, with the kind chosen first: a
    window may be left outside its bounds where no voted change mends it (or a change needs two
    steps); the next iteration's call takes it up again.

    Arguments as :func:`descend_kinds` (``lo``, ``hi`` the bounds to bring the counts into);
    returns how many kinds changed.
    """
    n = index.shape[0]
    nk = voted.shape[1]
    ko, slots, d, used, rowmin, rowarg, nb, tb, tc = _work(index.shape[1], rel_e.shape[1], rev_ptr[n] - rev_ptr[0])
    delta = np.full(n, np.inf)
    target = np.full(n, -1, dtype=np.int64)
    for o in range(n):
        own, w = kind[o], window[o]
        rows = _neighbourhoods_of(o, rev_ptr, rev_idx, nb)
        now = 0.0
        for t in range(rows):
            now += cost[nb[t]]
        for q in range(nk):
            if q == own or not voted[o, q] or not _improves(count, lo, hi, w, own, q):
                continue
            kind[o] = q
            total = 0.0
            for t in range(rows):
                total += _row_best(nb[t], index, kind, rel_o, cand, rel_e, kind_e, centre_e, alpha, ko, slots, d, used,
                                   rowmin, rowarg)[1]  # fmt: skip
            kind[o] = own
            if total - now < delta[o]:
                delta[o] = total - now
                target[o] = q
    changed = 0
    for o in np.argsort(delta, kind="mergesort"):
        q, own, w = target[o], kind[o], window[o]
        if q < 0:
            break
        if not _improves(count, lo, hi, w, own, q):
            continue
        rows = _neighbourhoods_of(o, rev_ptr, rev_idx, nb)
        kind[o] = q
        for t in range(rows):
            tb[t], tc[t] = _row_best(nb[t], index, kind, rel_o, cand, rel_e, kind_e, centre_e, alpha, ko, slots, d, used,
                                     rowmin, rowarg)  # fmt: skip
        for t in range(rows):
            best[nb[t]] = tb[t]
            cost[nb[t]] = tc[t]
        count[w, own] -= 1
        count[w, q] += 1
        changed += 1
    return changed
