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
