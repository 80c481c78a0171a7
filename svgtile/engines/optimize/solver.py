"""The solver of Ma, Wei & Tong 2011 §4, Pseudocode 1: search and assignment, alternated.

::

    for each iteration:
        search      — each output element's best exemplar sample (§4.2, k-coherence)
        assignment  — positions by sparse least squares, kinds by voting (§4.3)
        settle      — the interleaved non-penetration step (:func:`.controls.settle`)

The energy ``E = Σ_o min_i |n(s_o) − n(s_i)|²`` (§3.2–§4), reported per iteration as its mean
per element (squared exemplar spacings), is that of the search of each iteration, i.e. of the
positions the previous iteration left (the first: of the start, after renewal if it renews).  The
element count is kept (as in the paper), unless ``Settings.insert``: then elements the
neighbourhoods predict where none stands are added (:mod:`.insert`); or ``Settings.renew``: then
the start's worst-matched elements are first removed and what the neighbourhoods predict inserted.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.flow import FlowField
from svgtile.core.region import Region
from svgtile.engines.optimize.assign import assign_kinds, predictions, solve_positions
from svgtile.engines.optimize.controls import DomainTerm, conflict_codes, flawed, local_turn, settle
from svgtile.engines.optimize.elements import Layout, layout
from svgtile.engines.optimize.insert import WINDOW, insert, shrinking
from svgtile.engines.optimize.match import candidate_costs, pairings
from svgtile.engines.optimize.samples import Samples, exemplar_samples, wrap
from svgtile.engines.optimize.search import (
    coherent_candidates,
    first_candidates,
    output_neighbourhoods,
    search,
)
from svgtile.engines.windows import square_windows

#: Rounds of renewal (``Settings.renew``) on the start, before the first assignment.  Each
#: round's removals and insertions depend on the neighbourhoods the round before left, so the
#: reach of an edit of the region grows with the rounds; and renewing in every iteration (its
#: insertions then follow the moves of each assignment) spread an edit over six exemplar widths
#: (the engine contract's edit stability on gravel: 0.54 of the far motifs unchanged, 0.95 asked).
#: On the start only, 2 rounds (insertion capped by area): 0.98 (0.97 without renewal); the ten
#: bundled exemplars, seeds 1–3, mean L 0.867 → 0.906 (every iteration: 0.923; 1 round 0.893, 3
#: and 5 rounds 0.906 and 0.909, the edit's reach growing with them: benchmarks/README.md,
#: renew14).  Renewal's insertion is capped by count, as a drawn exemplar's start is thinned
#: (:func:`.init.thin`): capped by area it put back 16 for scrub's 136 removals in the first round
#: and 120 for 151 in the second (the start's kinds, before the assignments bring the mix back,
#: cover more than ρ), and the texture ended at 0.90 of ρ; by count 172 for 136 and 158 for 161,
#: density / ρ 1.04, the bundled exemplars' mean L 0.911, issue 14's bounds on 24 of 30 runs, and
#: the contract's edit case 0.967 (renew14c).
RENEW_ROUNDS = 2


@dataclass(frozen=True)
class Settings:
    """How the solver runs.

    Attributes
    ----------
    neighbours : k, output neighbourhood size (6: the first ring of a lattice; the paper's 1–3 rings)
    alpha : kind mismatch cost, squared spacings (eq. (1))
    similar : K, the k-coherence similarity set size (§4.2)
    anchor : λ of the least squares, against one prediction (:mod:`.assign`)
    sweeps : Jacobi sweeps per assignment (:mod:`.assign`)
    domain : λ of eq. (6), the cost of each exemplar neighbour that a candidate would put outside
        the output region, squared spacings (:class:`.controls.DomainTerm`; 0: no domain term;
        none on a repeating tile, whose samples all have whole neighbourhoods)
    elongated : length over width from which a motif is two samples (§3.1, :mod:`.elements`;
        0, the default: one sample per motif; :data:`.elements.ELONGATED` is the value measured)
    insert : whether elements are added where the neighbourhoods predict one and none stands,
        up to the exemplar's density (:mod:`.insert`; iterations 2 to N − 1, one sample per
        motif only).  The paper keeps the
        count of its start; the engine inserts, ``--refine`` keeps the count.
    rebalance : whether each assignment brings the kind mix back to the exemplar's where the
        start strayed from it (:func:`.assign.assign_kinds`; the engine's start from a drawn
        exemplar, :func:`.init.patch_start`); ``--refine`` holds the mix where it is.  The
        energy is then the energy under the exemplar's mix: the first assignments raise it as
        they bring the mix back, later ones lower it (gravel's start: 1.16, 1.176, 1.147, 1.118).
    renew : the first search is followed by :data:`RENEW_ROUNDS` rounds of renewal: the elements
        whose cost (eq. (1), their best match's) is over ``renew`` times the median cost of
        their world-anchored window (:data:`.insert.WINDOW` spacings) and the highest of their
        neighbourhood (:func:`renewed`) are removed, and insertion (:mod:`.insert`, capped by
        count) puts back what the remaining neighbourhoods predict (0: off; one sample per
        motif only).  Not in
        the paper, whose element count is its start's: search and assignment move an element
        but never re-seat it, and at the seams of the start's patches the descent stops in
        configurations no exemplar neighbourhood has (benchmarks/README.md, seams14, renew14).
    """

    neighbours: int = 6
    alpha: float = 1.0
    similar: int = 2
    anchor: float = 1.0
    sweeps: int = 3
    domain: float = 1.0
    elongated: float = 0.0
    insert: bool = False
    rebalance: bool = False
    renew: float = 0.0


def refine(arr: Arrangement, exemplar: Exemplar, stats: Stats, region: Region, boundary: str, *,
           iterations: int, key: int, flow: FlowField | None = None, settings: Settings = Settings(),
           progress: Callable[[str, float], None] | None = None, samples: Samples | None = None,
           first: np.ndarray | None = None) -> tuple[Arrangement, list[float]]:  # fmt: skip
    """``iterations`` of Pseudocode 1 starting from ``arr``.

    Parameters
    ----------
    arr : the start, with no conflicts and kept by ``boundary`` in ``region``
    exemplar, stats : the exemplar and its analysis
    region, boundary : where the texture lies and how its edge is treated
    iterations : how many search/assignment iterations
    key : the run's key (only the first search draws from it)
    flow : the local orientation field (§5, eq. (7)), or None
    settings : solver settings
    progress : called as ``progress(stage, fraction)`` each iteration, the stage naming the energy
    first : (n,) int or None — the first search's matches, one exemplar sample per element of
        ``arr`` (in its order): the exemplar motif each was copied from
        (:func:`.init.patch_start` with ``sources``).  A motif copied with its neighbours has its
        source as its best match (§4.1–4.2: its neighbourhood is the source's, but at the patch's
        seams), so the first pass takes them instead of searching ``FIRST_CANDIDATES`` samples
        by hash, and later passes propagate them by k-coherence as usual.  Used with one sample
        per motif only (ignored with elongated samples, whose indices are not the motifs').

    Returns
    -------
    the refined arrangement (the start's motif count unless it inserts or renews, rounded to the
    output precision, no conflicts),
    and the mean energy per element at each iteration's search (squared spacings)
    """
    energies: list[float] = []
    # one motif has a neighbourhood only as a repeating tile (its copies are its neighbours)
    lone = len(exemplar.motifs) < 2 and getattr(exemplar, "period", None) is None
    if iterations <= 0 or len(arr) < 2 or len(exemplar.motifs) == 0 or lone:
        return arr, energies
    s = settings
    # reading order: ties (equal costs, equal votes) go by position, not by where an engine put a motif
    order = np.lexsort((arr.xy[:, 0], arr.xy[:, 1]))
    arr = arr.take(order)
    lay = layout(exemplar.prototypes, s.elongated)
    seeds = None if first is None or lay is not None else np.asarray(first, dtype=np.int64)[order]
    if samples is None:
        ex_samples = None
        if lay is not None:
            exy, eattr, eowner = lay.samples(exemplar.motifs)
            ex_samples = Arrangement(eattr, exy, exemplar.motifs.angle[eowner], exemplar.motifs.scale[eowner])
        samples = exemplar_samples(exemplar, s.neighbours, alpha=s.alpha, similar=s.similar, motifs=ex_samples)
    match = None
    start = conflict_codes(arr, exemplar, stats)
    known = start[0]  # none for an engine's output
    lax = flawed(arr, exemplar, stats, start)
    # a repeating tile has no edge: every sample's neighbourhood is whole, none is like an edge's
    domain = DomainTerm(region, samples, s.neighbours) if s.domain > 0 and samples.period is None else None
    report = progress or (lambda stage, fraction: None)
    for it in range(iterations):
        if lay is None:
            sarr, owner = arr, None
        else:
            sxy, sattr, owner = lay.samples(arr)
            sarr = Arrangement(sattr, sxy, arr.angle[owner], arr.scale[owner])
        turn = local_turn(flow, sarr.xy)
        hoods = output_neighbourhoods(sarr.xy, sarr.kind, s.neighbours, samples.spacing, turn)
        if match is None and seeds is not None:
            # the seeds as the one candidate each: the search keeps them, pairs and costs them;
            # the kind vote then weighs the k-coherence candidates they propose, as later passes'
            match, cost, slots = search(samples, hoods, sarr.kind, seeds[:, None], s.alpha)
            cand = coherent_candidates(samples, hoods, match, lambda q: wrap(q, exemplar))
        else:
            if match is None:
                cand = first_candidates(samples, sarr.xy, sarr.kind, key=key)
            else:
                cand = coherent_candidates(samples, hoods, match, lambda q: wrap(q, exemplar))
            match, cost, slots = search(samples, hoods, sarr.kind, cand, s.alpha)
        # renewal (the start only, before the first assignment; with one iteration there is no
        # later one to settle what it inserts), then insertion: each searched again
        renewing = s.renew > 0 and lay is None and it == 0 and iterations > 1
        for _ in range(RENEW_ROUNDS if renewing else 1):
            if renewing:
                drop = renewed(cost, hoods.index, sarr.xy, s.renew, WINDOW * samples.spacing)
                if drop.any():
                    arr, known, lax, match = _kept(arr, ~drop, known, lax, match)
                    sarr = arr
                    turn, hoods, cand, match, cost, slots = _searched(arr, match, samples, exemplar, flow, s)
            if renewing or (s.insert and lay is None and 0 < it < iterations - 1):
                grown, chosen = insert(arr, samples, hoods, match, slots, exemplar, stats, region, boundary, key=key,
                                       by_count=renewing)  # fmt: skip
                if len(chosen):  # the new elements searched from their predicted samples
                    arr, known, lax, grown_match = _reading_order(grown, len(arr), known, lax, np.r_[match, chosen])
                    sarr = arr
                    turn, hoods, cand, match, cost, slots = _searched(arr, grown_match, samples, exemplar, flow, s)
        extra = np.zeros(len(sarr))
        if domain is not None:
            match, cost, slots, extra = _domain_search(domain, s, samples, hoods, sarr, cand, match, cost, slots)
        energies.append(float((cost + extra).mean()))
        report(f"optimize: iteration {it + 1}/{iterations}, energy {energies[-1]:.4f}", it / iterations)
        src, dst, d, predicted = predictions(samples, hoods, match, slots)
        kind, match, cost, take = assign_kinds(samples, hoods, sarr.xy, sarr.kind, cand, match, cost, dst, predicted, s.alpha,
                                              rebalance=s.rebalance)  # fmt: skip
        if s.insert and lay is None:  # inserting up to ρ: no vote shrinks a window already short of it
            back = shrinking(sarr, kind, exemplar, stats, region, window=WINDOW * samples.spacing)
            kind, take = np.where(back, sarr.kind, kind), np.where(back, -1, take)
        if (kind != sarr.kind).any():
            # the predictions of the matches the new kinds brought
            hoods = replace(hoods, kind=np.where(hoods.index >= 0, kind[np.maximum(hoods.index, 0)], -1))
            slots = pairings(hoods.rel, hoods.kind, match, samples.rel, samples.nkind, s.alpha)
            src, dst, d, predicted = predictions(samples, hoods, match, slots)
        xy = solve_positions(sarr.xy, src, dst, d, anchor=s.anchor, sweeps=s.sweeps)
        got = take >= 0
        t = np.maximum(take, 0)
        angle = np.where(got, samples.angle[t] if flow is None else (samples.angle[t] + turn + 180.0) % 360.0 - 180.0,
                         sarr.angle)  # fmt: skip
        new = Arrangement(kind, xy, angle, np.where(got, samples.scale[t], sarr.scale))
        if lay is not None:
            new = _motifs(lay, arr, new, owner)
        arr, known = settle(arr, new.quantized(DECIMALS), exemplar, stats, region, boundary, known, lax)
    return arr, energies


def _searched(arr: Arrangement, match: np.ndarray, samples: Samples, exemplar: Exemplar, flow: FlowField | None,
              s: Settings):  # fmt: skip
    """The search of §4.2 on ``arr`` (one sample per motif) from the k-coherence candidates of
    ``match`` (n,): its local turn, neighbourhoods, candidates, and the search's match, cost and
    slots."""
    turn = local_turn(flow, arr.xy)
    hoods = output_neighbourhoods(arr.xy, arr.kind, s.neighbours, samples.spacing, turn)
    cand = coherent_candidates(samples, hoods, match, lambda q: wrap(q, exemplar))
    match, cost, slots = search(samples, hoods, arr.kind, cand, s.alpha)
    return turn, hoods, cand, match, cost, slots


def renewed(cost: np.ndarray, index: np.ndarray, xy: np.ndarray, factor: float, side: float) -> np.ndarray:
    """The elements the renewal step removes (``Settings.renew``).

    Parameters
    ----------
    cost : (n,) float, each element's eq. (1) cost, squared spacings
    index : (n, k) int, each element's neighbours (−1 absent)
    xy : (n, 2) float, positions, user units
    factor : how many times its window's median cost an element's must exceed
    side : side of the world-anchored windows, user units (a median over the whole texture would
        let an edit anywhere change the removals everywhere: the engine contract's edit stability)

    Returns
    -------
    (n,) bool: over ``factor`` times its window's median (floored at 10⁻⁶ squared spacings) and
    above every one of its neighbours by ``(cost, index)``, so that of two elements in each
    other's neighbourhood at most one leaves (the other's neighbourhood still predicts where it
    stood).  Neighbourhoods are not symmetric: a pair where only one is the other's neighbour may
    both leave (2–5 pairs a round on gravel, renew14).
    """
    window = square_windows(xy, side)[1]
    order = np.lexsort((cost, window))
    w = window[order]
    start = np.r_[0, np.flatnonzero(np.diff(w)) + 1]
    size = np.diff(np.r_[start, len(w)])
    lo, hi = cost[order[start + (size - 1) // 2]], cost[order[start + size // 2]]
    median = np.maximum(0.5 * (lo + hi), 1e-6)
    j = np.maximum(index, 0)
    i = np.arange(len(cost))[:, None]
    above = (index < 0) | (cost[:, None] > cost[j]) | ((cost[:, None] == cost[j]) & (i > j))
    return (cost > factor * median[window]) & above.all(axis=1)


def _kept(arr: Arrangement, keep: np.ndarray, known: np.ndarray, lax: np.ndarray, match: np.ndarray):
    """``arr``'s elements in ``keep`` (n,) bool, in their order (reading order stays), with the
    conflict codes ``known`` among them renumbered and ``lax`` (n,) and ``match`` (n,) carried along."""
    n = len(arr)
    where = np.cumsum(keep) - 1
    i, j = known // n, known % n
    ok = keep[i] & keep[j]
    m = int(keep.sum())
    codes = np.sort(where[i[ok]] * m + where[j[ok]])
    return arr.take(np.flatnonzero(keep)), codes, lax[keep], match[keep]


def _reading_order(grown: Arrangement, n: int, known: np.ndarray, lax: np.ndarray, match: np.ndarray):
    """``grown`` (``n`` elements, then the inserted ones) in reading order, as :func:`refine`
    keeps its elements (ties go by position, so by index only in reading order), with the
    conflict codes ``known`` of the first ``n``, ``lax`` (n,) and ``match`` (all) carried along."""
    order = np.lexsort((grown.xy[:, 0], grown.xy[:, 1]))
    where = np.empty(len(grown), dtype=np.int64)
    where[order] = np.arange(len(grown))
    i, j = where[known // n], where[known % n]
    codes = np.sort(np.minimum(i, j) * len(grown) + np.maximum(i, j))
    lax = np.r_[lax, np.zeros(len(grown) - n, dtype=bool)][order]
    return grown.take(order), codes, lax, match[order]


def _domain_search(domain: DomainTerm, s: Settings, samples: Samples, hoods, arr: Arrangement, cand: np.ndarray,
                   match: np.ndarray, cost: np.ndarray, slots: np.ndarray):  # fmt: skip
    """The search of the elements near the region's edge again, with eq. (6) added (§5).

    Returns match, the eq. (1) cost and slots (all (n, …), changed near the edge only), and the
    eq. (6) term of each element's match, λ-weighted, (n,) squared spacings.
    """
    extra = np.zeros(len(arr))
    edge = domain.near_edge(arr.xy)
    if len(edge) == 0:
        return match, cost, slots, extra
    c = np.ascontiguousarray(cand[edge], dtype=np.int64)
    eq1 = candidate_costs(hoods.rel[edge], hoods.kind[edge], arr.kind[edge], c, samples.rel, samples.nkind,
                          samples.kind, s.alpha)  # fmt: skip
    eq6 = s.domain * domain.costs(arr.xy[edge], hoods.turn[edge], c)
    best = np.argmin(eq1 + eq6, axis=1)
    rows = np.arange(len(edge))
    match, cost, slots = match.copy(), cost.copy(), slots.copy()
    match[edge] = c[rows, best]
    cost[edge] = eq1[rows, best]
    extra[edge] = eq6[rows, best]
    slots[edge] = pairings(hoods.rel[edge], hoods.kind[edge], match[edge], samples.rel, samples.nkind, s.alpha)
    return match, cost, slots, extra


def _motifs(lay: Layout, arr: Arrangement, new: Arrangement, owner: np.ndarray) -> Arrangement:
    """The motifs of the assigned samples ``new`` (§3.1): each at the middle of its samples; a
    two-sample motif turned along them, a one-sample motif with its sample's angle; the kind and
    scale of its first sample — unless that kind has another number of samples (the layout of
    the samples is kept from one iteration to the next, and with it the matches)."""
    centre, axis, two = lay.poses(arr, new.xy, owner)
    first = np.r_[0, np.cumsum(np.bincount(owner, minlength=len(arr)))[:-1]]
    kind = new.kind[first] // 3
    same = lay.elongated[kind] == lay.elongated[arr.kind]
    kind = np.where(same, kind, arr.kind)
    angle = np.where(two & (kind == arr.kind), axis, np.where(same, new.angle[first], arr.angle))
    return Arrangement(kind, centre, angle, np.where(same, new.scale[first], arr.scale))
