"""The optimize engine's controls (Ma, Wei & Tong 2011 §4.3 eq. (5), §5 eq. (6)), issue 14.

* eq. (6), the domain-shape term: unit test of the count of shifted samples outside, and the
  energy of the neighbourhoods at the region's edge, measured by an exhaustive search with the
  term, drops when the solver uses it;
* eq. (5), kinds by the vote of least energy: a seam between two patches of a two-kind exemplar
  is repaired where a majority count leaves it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from svgtile import analyze, read_exemplar
from svgtile.core.region import Region
from svgtile.engines.optimize.controls import DomainTerm
from svgtile.engines.optimize.init import patch_start
from svgtile.engines.optimize.match import candidate_costs
from svgtile.engines.optimize.samples import exemplar_samples
from svgtile.engines.optimize.search import output_neighbourhoods
from svgtile.engines.optimize.solver import Settings, refine

REPO = Path(__file__).resolve().parents[1]


def test_domain_term_counts_the_shifted_samples_outside():
    ex = read_exemplar(REPO / "exemplars" / "gravel.svg")
    samples = exemplar_samples(ex, 6)
    region = Region.rectangle(100, 100)
    term = DomainTerm(region, samples, 6)
    reach = float(np.nanmax(np.hypot(*samples.rel[:, :6].reshape(-1, 2).T))) * samples.spacing
    xy = np.array([[50.0, 50.0], [0.5, 50.0], [reach + 1.0, 50.0]])
    assert list(term.near_edge(xy)) == [1]
    cand = np.broadcast_to(np.arange(len(samples)), (3, len(samples)))
    c = term.costs(xy, np.zeros(3), cand)
    rel = samples.rel[:, :6] * samples.spacing
    # by hand: a shifted sample is outside where x < 0 (the left edge) — none in the middle
    expected = ((0.5 + rel[..., 0]) < 0).sum(axis=1)
    assert (c[0] == 0).all() and (c[2] == 0).all()
    np.testing.assert_array_equal(c[1], expected)
    assert c[1].max() >= 2  # some candidates do stick out: the test can tell
    # turned by 180°, the neighbourhood reaches the other way
    flipped = term.costs(xy[1:2], np.array([180.0]), cand[:1])
    np.testing.assert_array_equal(flipped[0], ((0.5 - rel[..., 0]) < 0).sum(axis=1))


def _edge_energy(arr, ex, samples, region, k=6) -> float:
    """Mean of min over every exemplar sample of eq. (1) + eq. (6) at the elements near the edge."""
    term = DomainTerm(region, samples, k)
    hoods = output_neighbourhoods(arr.xy, arr.kind, k, samples.spacing, np.zeros(len(arr)))
    edge = term.near_edge(arr.xy)
    cand = np.ascontiguousarray(np.broadcast_to(np.arange(len(samples)), (len(edge), len(samples))))
    eq1 = candidate_costs(hoods.rel[edge], hoods.kind[edge], arr.kind[edge], cand, samples.rel, samples.nkind,
                          samples.kind, 1.0)  # fmt: skip
    return float((eq1 + term.costs(arr.xy[edge], np.zeros(len(edge)), cand)).min(axis=1).mean())


def test_the_domain_term_lowers_the_energy_at_the_region_edge():
    ex = read_exemplar(REPO / "exemplars" / "scrub.svg")
    stats = analyze(ex)
    region = Region.rectangle(150, 150)
    samples = exemplar_samples(ex, 6)
    spacing = samples.spacing
    got = {}
    for domain in (0.0, 1.0):
        runs = []
        for key in (1, 2, 3):
            start = patch_start(ex, stats, region, "clip", key=key, cell=5 * spacing, overlap=0.25)
            arr, _ = refine(start, ex, stats, region, "clip", iterations=6, key=key, samples=samples,
                            settings=Settings(domain=domain))  # fmt: skip
            runs.append(_edge_energy(arr, ex, samples, region))
        got[domain] = float(np.mean(runs))
    assert got[1.0] < got[0.0], got


def _kind_case():
    """A breccia texture from the optimize start, its neighbourhoods, candidates and search."""
    from svgtile.engines.optimize.assign import predictions
    from svgtile.engines.optimize.search import coherent_candidates, first_candidates, search

    ex = read_exemplar(REPO / "exemplars" / "breccia.svg")
    stats = analyze(ex)
    region = Region.rectangle(120, 120)
    samples = exemplar_samples(ex, 6)
    arr = patch_start(ex, stats, region, "clip", key=3, cell=5 * samples.spacing, overlap=0.25)
    hoods = output_neighbourhoods(arr.xy, arr.kind, 6, samples.spacing, np.zeros(len(arr)))
    match, _, _ = search(samples, hoods, arr.kind, first_candidates(samples, arr.xy, arr.kind, key=3), 1.0)
    cand = np.ascontiguousarray(coherent_candidates(samples, hoods, match, lambda q: q))
    match, cost, slots = search(samples, hoods, arr.kind, cand, 1.0)
    _, dst, _, predicted = predictions(samples, hoods, match, slots)
    return samples, hoods, arr, cand, match, cost, dst, predicted


def test_kinds_are_the_vote_of_least_energy(monkeypatch):
    """The first element whose kind changes takes the voted kind of least energy over the
    neighbourhoods it is in (each matched again among its candidates), by brute force (with the
    kind mix left free: the next test holds it)."""
    from svgtile.engines.optimize import assign
    from svgtile.engines.optimize.assign import assign_kinds

    monkeypatch.setattr(assign, "MIX", 1.0)
    samples, hoods, arr, cand, match, cost, dst, predicted = _kind_case()
    kind, _, _, take = assign_kinds(samples, hoods, arr.xy, arr.kind, cand, match, cost, dst, predicted, 1.0)
    changed = np.flatnonzero(kind != arr.kind)
    assert len(changed) > 0
    o = changed[0]
    rows = np.r_[o, np.flatnonzero((hoods.index == o).any(axis=1))]
    voted = set(samples.kind[match[o : o + 1]]) | set(samples.kind[predicted[dst == o]])

    def energy(q):
        k = arr.kind.copy()
        k[o] = q
        nk = np.where(hoods.index[rows] >= 0, k[np.maximum(hoods.index[rows], 0)], -1)
        c = candidate_costs(hoods.rel[rows], nk, k[rows], cand[rows], samples.rel, samples.nkind, samples.kind, 1.0)
        return c.min(axis=1).sum()

    totals = {int(q): energy(q) for q in voted | {int(arr.kind[o])}}
    assert kind[o] in voted
    assert totals[int(kind[o])] == min(totals.values()) < totals[int(arr.kind[o])]
    # every element takes angle and scale from a sample of its new kind
    got = take >= 0
    assert (samples.kind[take[got]] == kind[got]).all()


def test_kind_changes_keep_the_exemplar_mix_in_every_window():
    from svgtile.engines.optimize.assign import MIX, WINDOW, assign_kinds

    samples, hoods, arr, cand, match, cost, dst, predicted = _kind_case()
    nk = int(samples.kind.max()) + 1
    share = np.bincount(samples.kind, minlength=nk) / len(samples)
    kind, *_ = assign_kinds(samples, hoods, arr.xy, arr.kind, cand, match, cost, dst, predicted, 1.0)
    assert (kind != arr.kind).sum() > 0
    cells = np.floor(arr.xy / (WINDOW * samples.spacing)).astype(np.int64)
    _, window = np.unique(cells, axis=0, return_inverse=True)
    for w in np.unique(window):
        at = window.ravel() == w
        before, after = np.bincount(arr.kind[at], minlength=nk), np.bincount(kind[at], minlength=nk)
        lo = np.minimum(np.floor((share - MIX) * at.sum()), before)
        hi = np.maximum(np.ceil((share + MIX) * at.sum()), before)
        # no kind's count leaves the exemplar's share ± MIX (or goes further than it already was)
        assert ((lo <= after) & (after <= hi)).all(), (w, share * at.sum(), before, after)


@pytest.mark.parametrize("k", [6, 14, 20])
def test_tied_neighbours_do_not_depend_on_points_elsewhere(k):
    """On a square lattice the 5th to 8th neighbours are tied (the diagonals); which of them
    make the k = 6 must not depend on points far away (the tree's shape), or an edit of the
    region changes neighbourhoods, matches and positions far from it (FGDC 601's edit
    stability was 0.68).  At k = 14 the tie group at the 15th distance (√5) has 8 points, more
    than a fixed margin of neighbours past the k + 1 held (the reviewer's case)."""
    g = np.arange(30, dtype=float)
    lattice = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
    rng = np.random.default_rng(4)
    far = rng.uniform(0, 30, (400, 2)) + np.array([100.0, 0.0])
    inner = ((lattice > 2) & (lattice < 27)).all(axis=1)

    def sets(xy):
        h = output_neighbourhoods(xy, np.zeros(len(xy), int), k, 1.0, np.zeros(len(xy)))
        return np.sort((xy[h.index[: len(lattice)]] @ [1000.0, 1.0]), axis=1)[inner]

    alone = sets(lattice)
    centre = (lattice @ [1000.0, 1.0])[inner][:, None]
    axial = centre + np.array([-1000.0, -1.0, 1.0, 1000.0])  # the four nearest, untied, are always in
    assert all(np.isin(axial[i], alone[i]).all() for i in range(len(alone)))
    for extra in (far[:1], far[:50], far):
        assert np.array_equal(sets(np.r_[lattice, extra]), alone)
