"""Issue 13's done-when on every regular FGDC lithology / osm-carto area-fill tile.

Which tiles are regular is decided by a documented rule, not by hand: a tile is *regular* (rows
or a lattice) when its imported exemplar's ring shapes (Ijiri et al. 2008 §4, periodic across the
tile's edges) fall into few classes — :func:`svgtile.engines.growth.connectivity.regularity`
≥ :data:`~svgtile.engines.growth.connectivity.REGULAR` (0.75: at most about one ring shape per
four motifs).  :data:`REGULAR_TILES` is that rule applied to every tile of
``shared/data/fgdc-geologic-patterns/lithology`` and ``shared/data/osm-carto/patterns`` that
``svgtile import`` accepts as a texture of motifs — not a pattern of cells (FGDC 660 and 668,
bedded rows of marks, pass the ring rule but are the cellular engine's: issue 15) —
(``benchmarks/growth_likeness.py --select`` re-derives it; the first test below re-checks the
rule on each listed tile).

On each: likeness L ≥ 0.8 against the tile and random engines, 0 overlaps and 0 violators, density
ratio in 0.9–1.1, repetition ≤ 0.2 — figures that are not met are marked ``xfail(strict=True)``
with the measured value, never loosened.  Figures measured on 2026-12-02 (benchmarks/README.md).
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from growth_measure import SHARED, baselines, distance, measure
from row_probes import markov_rows, row_phases, row_step, shuffled_rows, successive_modes, tile_rows
from scipy.spatial import cKDTree
from test_growth_gaps import jittered_tile

from svgtile import analyze
from svgtile.analysis.neighbourhood import likeness
from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.connectivity import REGULAR, reference_rings, regularity
from svgtile.metrics import score
from svgtile.metrics.window import spacing
from svgtile.svg.reader import parse_exemplar

FGDC = SHARED / "fgdc-geologic-patterns" / "lithology"
OSM = SHARED / "osm-carto" / "patterns"
#: The regular tiles by the module docstring's rule.
REGULAR_TILES = {name: FGDC / f"{name}.svg" for name in ("619", "620", "670", "710", "711", "712", "713", "716", "721", "728", "731")} | {
    name: OSM / f"{name}.svg" for name in ("allotments", "dog_park", "grave_yard_christian", "grave_yard_generic",
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
#: out, so 17 of the 20 pass).  On 619, 620 and 670 no texture that keeps the tile's rows can pass:
#: each row repeats its content at exact along-row steps (8.94 units in 619 and 620, the dots'
#: 1.8 in 670), which the figure does not leave out — the order reading's two steps are the
#: jittered diagonals between rows (619, 620) or a lattice the dots' step is not on (670) — so
#: even the tile's rows with every row at its own random phase score 1.000
#: (:func:`test_the_tiles_own_rows_repeat_by_the_figure`); and with those steps left out, the
#: tile's own row-to-row relations, kept at a likeness ≥ 0.8, still repeat > 0.2
#: (:func:`test_the_tiles_row_relations_repeat_beyond_a_fifth`; benchmarks/README.md,
#: "Why growth on FGDC 619, 620 and 670 cannot meet the repetition gate").
#: (FGDC 660 and 668, bedded rows of marks imported as cells, measured 1.000 the same way when grown.)
#: Issue 13's figure excuses what the exemplar shows inside itself (a row's exact step, and m
#: steps of it to within 1/m of the box): 619 and 620 pass since (0.000).  670 passes since
#: rep13f (1.000 → 0.000): on a tile each kind is read at its own step, and its dashes, jittered
#: along their rows by less than the figure's square, show the tile's width to the square at every
#: multiple (tests/test_repetition_resolved.py).
REPEATS: dict[str, float] = {}


@cache
def figures(name: str):
    return measure(REGULAR_TILES[name])


@needs_data
@pytest.mark.parametrize("name", sorted(REGULAR_TILES))
def test_the_tile_is_regular_by_the_rule(name):
    ex, _ = load_exemplar(str(REGULAR_TILES[name]), as_tile=True, warn=lambda m: None)
    assert ex.cellular is None and regularity(reference_rings(ex)) >= REGULAR


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
    strict=True, reason=f"repetition {REPEATS[n]:.3f}: the tile's rows repeat at steps the figure "
                        "does not leave out (test_the_tiles_own_rows_repeat_by_the_figure)")) if n in REPEATS else n for n in sorted(REGULAR_TILES)])  # fmt: skip
def test_growth_repeats_at_most_a_fifth(name):
    assert figures(name).repetition <= 0.2



def at_step(arr, g, tol: float) -> float:
    """Share of the motifs with a same-kind motif within ``tol`` of ``x + g`` or ``x − g``."""
    has = np.zeros(len(arr), bool)
    for c in np.unique(arr.kind):
        mine = np.flatnonzero(arr.kind == c)
        tree = cKDTree(arr.xy[mine])
        for sign in (1.0, -1.0):
            d, _ = tree.query(arr.xy[mine] + sign * np.asarray(g), distance_upper_bound=tol)
            has[mine] |= np.isfinite(d)
    return float(has.mean())


@pytest.mark.parametrize("probe", [shuffled_rows, markov_rows])
def test_row_probes_keep_each_row_and_break_the_period(probe):
    ex = parse_exemplar(jittered_tile(5, 8, 3.0, 5.0, 0.3))  # rows 5 apart, dots jittered by ≤ 0.3
    st = analyze(ex)
    rows = tile_rows(ex, 1.0)
    assert np.array_equal(np.bincount(rows), np.full(5, 8))
    y = ex.motifs.xy[:, 1]
    assert all(np.ptp(y[rows == r]) <= 0.6 for r in range(5))
    region = Region.rectangle(96, 100)
    tiled = synthesize(ex, region, "tile", seed=1, boundary="centroid").arrangement
    arr = probe(ex, st, region, rng=np.random.default_rng(3))
    assert abs(len(arr) - len(tiled)) <= 0.1 * len(tiled)
    w, h = ex.period
    # each row still repeats at the tile's width along x, exactly; across rows the period is gone
    assert at_step(arr, (w, 0.0), 1e-6) > 0.95 and at_step(tiled, (0.0, h), 1e-6) > 0.95
    assert at_step(arr, (0.0, h), 0.05) < 0.3
    assert successive_modes(tiled, ex, st, region, 1)[0][0] == score(ex, st, tiled, region).repetition


#: The rows of the REPEATS tiles (:func:`row_probes.tile_rows`).
ROWS = {"619": 18, "620": 18, "670": 16}


def region_of(name: str):
    ex, st = load_exemplar(str(REGULAR_TILES[name]), as_tile=True, warn=lambda m: None)
    w, h = ex.period
    return ex, st, Region.rectangle(4 * w, 4 * h)


@needs_data
@pytest.mark.parametrize("name", sorted(ROWS))
def test_the_tiles_own_rows_repeat_by_the_figure(name):
    """Why :data:`REPEATS` are xfails whatever growth does: the tile's rows, each row copy moved
    along x by its own random shift (nothing repeats across rows at the period), still repeat
    ≥ 0.8 by the figure, at a displacement along a row.  When the figure learns to leave a
    row's exact step out this fails: measure the three again.  Issue 13's figure does (it
    excuses what the exemplar shows): 619 and 620's shuffled rows score ≤ 0.2 by it, and the
    figure before (``repetition_order``) is kept here; 670's since rep13f, which reads its dashes
    (jittered along their rows by less than the figure's square) at their own step."""
    ex, st, region = region_of(name)
    per_row = np.bincount(tile_rows(ex, 0.5 * spacing(st)))
    assert len(per_row) == ROWS[name] and per_row.min() >= 5
    arr = shuffled_rows(ex, st, region, rng=np.random.default_rng(1))
    assert at_step(arr, (0.0, ex.period[1]), 0.01 * spacing(st)) < 0.3  # the probe broke the period
    s = score(ex, st, arr, region)
    assert s.repetition_order >= 0.8, s.repetition_order
    vx, vy = s.repetition_order_vector
    assert abs(vy) < 0.1 * spacing(st) < abs(vx), s.repetition_order_vector  # along a row
    assert (s.repetition >= 0.8) if name in REPEATS else (s.repetition <= 0.2), s.repetition


@needs_data
@pytest.mark.parametrize("name", ["619", "620"])
def test_the_tiles_row_relations_repeat_beyond_a_fifth(name):
    """Rows in the tile's order, each row's phase the previous row's plus one of the tile's own
    row-to-row phase steps (its period broken, its look kept: likeness ≥ 0.8), scored by the
    figure with the along-row displacements it finds first left out as well: the first mode
    across rows is still over 0.2 — the brick relation between neighbouring rows (phase steps
    spread over ~3 units, the figure's box of 3 bins 1.1–1.5 units) is itself what it counts."""
    ex, st, region = region_of(name)
    step = row_step(ex, st)
    assert step == pytest.approx(ex.period[0] / 6, abs=0.02)
    phase_steps = row_phases(ex, st)[1]
    # the tile's rows close over its height: the phase steps add up to whole row steps
    assert np.ptp(phase_steps) > 2.5 and phase_steps.sum() / step == pytest.approx(round(phase_steps.sum() / step), abs=0.01)
    arr = markov_rows(ex, st, region, rng=np.random.default_rng(1))
    assert likeness(distance(arr, ex, st, region), *baselines(ex, st, region)) >= 0.8
    modes = successive_modes(arr, ex, st, region, 6)
    assert modes[0][0] >= 0.8 and abs(modes[0][1][1]) < 0.1 * spacing(st)  # the figure's own: along a row
    across = [(v, vec) for v, vec in modes if vec is not None and abs(vec[1]) > 0.5 * spacing(st)]
    assert across and across[0][0] > 0.2, modes
