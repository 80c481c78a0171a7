"""Issue 13's done-when on every regular FGDC lithology / osm-carto area-fill tile.

Which tiles are regular is decided by a documented rule, not by hand: a tile is *regular* (rows
or a lattice) when its imported exemplar's ring shapes (Ijiri et al. 2008 §4, periodic across the
tile's edges) fall into few classes — :func:`svgtile.engines.growth.connectivity.regularity`
≥ :data:`~svgtile.engines.growth.connectivity.REGULAR` (0.75: at most about one ring shape per
four motifs).  :data:`REGULAR_TILES` is that rule applied to every tile of
``shared/data/fgdc-geologic-patterns/lithology`` and ``shared/data/osm-carto/patterns`` that
``svgtile import`` accepts (``benchmarks/growth_likeness.py --select`` re-derives it; the first
test below re-checks the rule on each listed tile).

On each: likeness L ≥ 0.8 against the tile and random engines, 0 overlaps and 0 violators, density
ratio in 0.9–1.1, repetition ≤ 0.2 — figures that are not met are marked ``xfail(strict=True)``
with the measured value, never loosened.  Figures measured on 2026-12-02 (benchmarks/README.md).
"""

from __future__ import annotations

from functools import cache

import pytest
from growth_measure import SHARED, measure

from svgtile.apps.load import load_exemplar
from svgtile.engines.growth.connectivity import REGULAR, reference_rings, regularity

FGDC = SHARED / "fgdc-geologic-patterns" / "lithology"
OSM = SHARED / "osm-carto" / "patterns"
#: The regular tiles by the module docstring's rule.
REGULAR_TILES = {name: FGDC / f"{name}.svg" for name in ("619", "620", "670", "710", "711", "712", "713", "716", "721", "728", "731")} | {
    name: OSM / f"{name}.svg" for name in ("allotments", "grave_yard_christian", "grave_yard_generic",
                                           "grave_yard_jewish", "grave_yard_muslim", "orchard", "plant_nursery", "vineyard")}  # fmt: skip

needs_data = pytest.mark.skipif(not FGDC.is_dir(), reason="../shared/data (real symbol sets) is not beside the checkout")

#: Known failures, with the figure measured (4 periods, at least 200 units a side, seed 1).
#: (grave_yard_muslim was one too — its crescent and star imported as two motifs of two kinds,
#: one whole ring, growth stalled: density 0.059, L −23 — until import kept an icon whole; and
#: FGDC 619 and 670 grew at density 0.770 and 0.665 — fronts drifting off the lattice met out of
#: step — until growth on a tile kept to the tile's sites and filled its gaps, tests/test_growth_gaps.py.)
LOW_DENSITY: dict[str, float] = {}
LOW_LIKENESS: dict[str, float] = {}
#: Repetition beyond the exemplar's own order (issue 12: the lattice of an exact tile is left
#: out, so 16 of the 19 pass); these three are hand-jittered, so no exact lattice explains them.
REPEATS = {"619": 1.000, "620": 1.000, "670": 1.000}


@cache
def figures(name: str):
    return measure(REGULAR_TILES[name])


@needs_data
@pytest.mark.parametrize("name", sorted(REGULAR_TILES))
def test_the_tile_is_regular_by_the_rule(name):
    ex, _ = load_exemplar(str(REGULAR_TILES[name]), as_tile=True, warn=lambda m: None)
    assert regularity(reference_rings(ex)) >= REGULAR


@needs_data
@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.xfail(
    strict=True, reason=f"likeness {LOW_LIKENESS[n]:.1f}: the tile's two motifs give one whole ring, growth stalls"))
    if n in LOW_LIKENESS else n for n in sorted(REGULAR_TILES)])  # fmt: skip
def test_growth_keeps_rows_and_lattices(name):
    f = figures(name)
    assert f.overlaps == 0 and f.violators == 0
    assert f.likeness >= 0.8, f


@needs_data
@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.xfail(
    strict=True, reason=f"density ratio {LOW_DENSITY[n]:.3f}: growth fronts of two cells leave gaps where their "
                        "lattices meet out of step")) if n in LOW_DENSITY else n for n in sorted(REGULAR_TILES)])  # fmt: skip
def test_growth_density_is_within_ten_percent(name):
    assert 0.9 <= figures(name).density_ratio <= 1.1


@needs_data
@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.xfail(
    strict=True, reason=f"repetition {REPEATS[n]:.3f}: growth on a tile keeps to the tile's own sites, so it repeats "
                        "the tile as patch on the period does; the tile's hand-drawn jitter is no exact lattice that "
                        "repetition leaves out")) if n in REPEATS else n for n in sorted(REGULAR_TILES)])  # fmt: skip
def test_growth_repeats_at_most_a_fifth(name):
    assert figures(name).repetition <= 0.2
