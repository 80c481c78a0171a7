"""The assignment step (Ma, Wei & Tong 2011 §4.3): positions by least squares, kinds by voting.

Every output element ``s_o`` matched to ``s_i`` predicts where each of its paired neighbours
should stand: ``p(s'_o) − p(s_o) ≈ R(θ)(p(s'_i) − p(s_i))`` (eq. (3), turned by the local
orientation of eq. (7)).  All predictions together are a sparse linear least-squares problem in
the positions (eq. (4)): ``min Σ |p_j − p_i − d_ij|² + λ Σ |p_i − p_i⁰|²`` whose normal
equations ``(λI + BᵀB) p = λp⁰ + Bᵀd`` are assembled with scipy.sparse (``B`` the edge–element
incidence matrix).  The ``λ`` term anchors the solution where the predictions leave it free (a
translation) and makes the step a proximal one.

The system is solved by a few Jacobi sweeps from the current positions, not exactly: the exact
solution moves every element a little for a change anywhere, while ``S`` sweeps move only
elements within ``S`` neighbourhood hops of it, which keeps a texture stable under an edit of its
region far away (the engine contract) and the cost per iteration O(n).  Successive iterations
carry on the descent.

Kinds are voted (eq. (5)): each element's own match and every neighbour's prediction cast a vote;
the most voted kind wins, ties going to the own match.  Angle and scale come with the winning
vote (the own match's, else the lowest-numbered neighbour's), turned by the local orientation.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from svgtile.core.footprint import rotation
from svgtile.engines.optimize.match import descend_kinds, rebalance_kinds
from svgtile.engines.optimize.samples import Samples
from svgtile.engines.optimize.search import Neighbourhoods
from svgtile.engines.windows import square_windows


def predictions(samples: Samples, hoods: Neighbourhoods, match: np.ndarray, slots: np.ndarray):
    """The relative positions every match predicts (eq. (3)).

    Returns
    -------
    src, dst : (e,) int — output element pairs ``(s_o, s'_o)``
    d : (e, 2) float, user units — predicted ``p(s'_o) − p(s_o)``
    sample : (e,) int — the exemplar sample predicted at ``s'_o``
    """
    n, k = slots.shape
    ok = (slots >= 0) & (hoods.index >= 0)
    src = np.repeat(np.arange(n), k)[ok.ravel()]
    slot = slots[ok]
    dst = hoods.index[ok]
    rel = samples.rel[match[src], slot] * samples.spacing
    turn = rotation(hoods.turn[src])
    d = np.einsum("eij,ej->ei", turn, rel)
    return src, dst, d, samples.nindex[match[src], slot]


def solve_positions(xy: np.ndarray, src: np.ndarray, dst: np.ndarray, d: np.ndarray, *,
                    anchor: float, sweeps: int) -> np.ndarray:  # fmt: skip
    """Least squares of eq. (4) by ``sweeps`` Jacobi sweeps from ``xy`` (see the module notes).

    Parameters
    ----------
    xy : (n, 2) float, user units, the current positions (also the anchor ``p⁰``)
    src, dst : (e,) int; d : (e, 2) float, user units — ``p_dst − p_src ≈ d``
    anchor : λ, weight of staying put against one prediction
    sweeps : S

    Returns
    -------
    (n, 2) float, user units
    """
    n, e = len(xy), len(src)
    if e == 0:
        return xy.copy()
    rows = np.arange(e)
    b = sp.csr_matrix((np.r_[-np.ones(e), np.ones(e)], (np.r_[rows, rows], np.r_[src, dst])), shape=(e, n))
    a = (sp.identity(n, format="csr") * anchor + b.T @ b).tocsr()
    rhs = anchor * xy + b.T @ d
    diag = a.diagonal()[:, None]
    p = xy.copy()
    for _ in range(sweeps):
        p = p + (rhs - a @ p) / diag
    return p


#: How far each kind's share in a window may stray from the exemplar's by a kind change, and the
#: side of the world-anchored windows, exemplar spacings (:func:`assign_kinds`).  Windows, not the
#: whole texture: a count over the whole texture would let an edit anywhere change kinds
#: everywhere (the engine contract's edit stability).
MIX = 0.01
WINDOW = 12.0
#: Side of the world-anchored windows whose mix ``assign_kinds(rebalance=True)`` brings back within
#: :data:`MIX` of the exemplar's, exemplar spacings.  A change is made wherever its window's
#: count calls for it, so an edit of the region changes kinds as far as a window reaches from
#: it: on the engine contract's edit (tests/test_engines_contract.py) 0.971 of the far motifs
#: unchanged at 8 spacings, 0.905 / 0.669 at 12 / 24 (bounds floored and ceiled; 0.95 required).  The ten bundled exemplars,
#: seeds 1–3 (omix14; the start thinned by count): runs over kind-mix TV 0.05 at 8 / 24 spacings
#: 0 / 1 of 30, mean L 0.868 / 0.878 (0.911, 15 runs over, without rebalancing); at 8 with the
#: bounds widened by a fair draw's deviation, 8 runs over (L 0.893): the start's drift is a few
#: points in every window, a fair draw's deviation in one of 64 motifs six.
MIX_WINDOW = 8.0


def assign_kinds(samples: Samples, hoods: Neighbourhoods, xy: np.ndarray, kind: np.ndarray, candidates: np.ndarray,
                 match: np.ndarray, cost: np.ndarray, dst: np.ndarray, predicted: np.ndarray,
                 alpha: float, rebalance: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """Kinds by eq. (5) as Pseudocode 1 states it: the vote that minimises the energy.

    Each element's votes are the kind of its own match and of every prediction about it (the
    samples its neighbours' matches put where it stands).  Of those kinds the one kept is the
    one of least energy over every neighbourhood the element belongs to, each neighbourhood
    matched again among its own k-coherence candidates (:func:`.match.descend_kinds`); elements
    are visited in reading order, each seeing the kinds already chosen.  A change may not take a
    kind's share in its world-anchored window (:data:`WINDOW`) further than :data:`MIX` from the
    exemplar's (a kind already past it can only come back).  A majority count (the
    energy with every match held fixed) cannot undo a seam between two exemplar patches: each
    side out-votes the other at its own elements; the energy, with the matches free, sees that
    one side's kinds let the other side's neighbourhoods match the exemplar.

    With ``rebalance``, the mix is then brought back where it strayed: every world-anchored
    window of :data:`MIX_WINDOW` spacings into :data:`MIX` of the exemplar's, by the changes of
    least energy among the voted kinds (:func:`.match.rebalance_kinds`), whatever they cost.

    Parameters
    ----------
    xy : (n, 2) float, user units; kind : (n,) int — the elements' positions and current kinds
    candidates : (n, C) int, the search's candidates; match, cost : (n,) the search's result
    dst, predicted : (e,) int, the predictions (:func:`predictions`)

    Returns
    -------
    kind : (n,) int, the new kinds
    match, cost : (n,) the best candidate of every element under them
    take : (n,) int — the sample whose angle and scale each element takes: its match if that is
        of its kind, else the first prediction of its kind; −1 for an element keeping a kind
        nobody voted for (it keeps its angle and scale)
    """
    n = len(kind)
    nk = max(int(samples.kind.max()), int(kind.max(initial=0))) + 1
    voted = np.zeros((n, nk), dtype=bool)
    voted[np.arange(n), samples.kind[match]] = True
    voted[dst, samples.kind[predicted]] = True
    # the elements that have each element as a neighbour (CSR)
    present = hoods.index >= 0
    owner = np.repeat(np.arange(n), hoods.index.shape[1])[present.ravel()]
    target = hoods.index[present]
    order = np.argsort(target, kind="stable")
    rev_idx = owner[order].astype(np.int64)
    rev_ptr = np.r_[0, np.cumsum(np.bincount(target, minlength=n))].astype(np.int64)
    cand = np.ascontiguousarray(candidates, dtype=np.int64)
    best = (cand == match[:, None]).argmax(axis=1).astype(np.int64)
    new, cost = kind.astype(np.int64), cost.astype(np.float64)
    # the exemplar's kind mix in every world-anchored window, give or take MIX (see descend_kinds)
    share = np.bincount(samples.kind, minlength=nk) / len(samples)
    window, count = _window_counts(xy, new, nk, WINDOW * samples.spacing)
    size = count.sum(axis=1, keepdims=True)
    lo = np.minimum(np.floor((share - MIX) * size), count).astype(np.int64)
    hi = np.maximum(np.ceil((share + MIX) * size), count).astype(np.int64)
    descend_kinds(new, voted, window, count, lo, hi, hoods.index, rev_ptr, rev_idx, hoods.rel, cand, best, cost, samples.rel,
                  samples.nkind, samples.kind, alpha)  # fmt: skip
    if rebalance:
        # bounds to the nearest count, give or take MIX of the window and at least half a motif:
        # floored and ceiled in windows of a few dozen, the mix sat a motif a window low (gravel,
        # the lower bounds summed: 0.376 for 0.403 − MIX); to the nearest count alone, a window of
        # a few motifs at the region's edge was held to the count nearest its share, one motif to
        # the commonest kind
        window, count = _window_counts(xy, new, nk, MIX_WINDOW * samples.spacing)
        size = count.sum(axis=1, keepdims=True)
        slack = np.maximum(MIX * size, 0.5)
        lo, hi = np.rint(share * size - slack).astype(np.int64), np.rint(share * size + slack).astype(np.int64)
        rebalance_kinds(new, voted, window, count, lo, hi, hoods.index, rev_ptr, rev_idx, hoods.rel, cand, best, cost,
                        samples.rel, samples.nkind, samples.kind, alpha)  # fmt: skip
    match = cand[np.arange(n), best]
    take = np.where(samples.kind[match] == new, match, -1)
    lack = np.flatnonzero(take < 0)
    if len(lack):
        # the first prediction (lowest source element) of the element's kind
        hit = samples.kind[predicted] == new[dst]
        sel = np.flatnonzero(hit)
        first = np.full(n, -1)
        order = sel[np.argsort(dst[sel], kind="stable")]
        uniq, at = np.unique(dst[order], return_index=True)
        first[uniq] = predicted[order[at]]
        take[lack] = first[lack]
    return new, match, cost, take


def _window_counts(xy: np.ndarray, kind: np.ndarray, nk: int, side: float) -> tuple[np.ndarray, np.ndarray]:
    """Each element's world-anchored window of side ``side`` (user units), (n,) int64
    (:func:`svgtile.engines.windows.square_windows`), and each window's count of every kind,
    (nw, nk) int64."""
    window = square_windows(xy, side)[1]
    count = np.zeros((int(window.max()) + 1, nk), dtype=np.int64)
    np.add.at(count, (window, kind), 1)
    return window, count
