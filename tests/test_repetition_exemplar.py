"""The repetition figure counts only what the exemplar does not show inside itself (issue 13).

Known answers: an exemplar scored against itself ≈ 0; a tile of irregular content stamped ≈ 1;
random placement ≈ 0; a drawn exemplar of rows at hand-drawn phases, stamped at its period, is
still caught; growth on FGDC 619 / 620 (rows exact along x, grown at fresh phases) passes the
gate; and ``P_ex`` follows its definition on hand-made exemplars.
"""

from __future__ import annotations

import dataclasses
from functools import cache

import numpy as np
import pytest
from conftest import stamp
from scipy.spatial import cKDTree
from test_growth_phases import phased_tile
from test_growth_regular import FGDC, SHARED, needs_data
from test_repetition_order import exemplar, grid
from test_wholeset import gate_region

from svgtile import Region, analyze, metrics, read_exemplar
from svgtile.apps.load import load_exemplar
from svgtile.engines import synthesize
from svgtile.metrics.repeats import _exemplar_shares, _kind_shares
from svgtile.svg.reader import parse_exemplar
from svgtile.tiles.importer import import_tile

BUNDLED = ("sand", "marsh", "boulders", "till", "gravel")
IRREGULAR = ("603", "605", "607", "626")


@cache
def fgdc(name: str):
    return load_exemplar(str(FGDC / f"{name}.svg"), as_tile=True, warn=lambda m: None)


def on_tiles(ex, st, engine: str, tiles: int = 5):
    """repetition of ``engine`` on ``tiles × tiles`` of the exemplar's period, in the interior."""
    w, h = ex.period
    region = Region.rectangle(tiles * w, tiles * h)
    arr = synthesize(ex, region, engine, seed=1, stats=st, boundary="centroid").arrangement
    return metrics.repetition(arr, ex, st, metrics.interior(ex, region))


@pytest.mark.parametrize("name", BUNDLED)
def test_a_bundled_exemplar_against_itself_is_not_repetition(name):
    ex = read_exemplar(f"exemplars/{name}.svg")
    rep = metrics.repetition(ex.motifs, ex, analyze(ex), ex.region)
    assert rep.repetition <= 0.05
    assert rep.repetition_exemplar >= rep.repetition_raw  # what it shows is what excuses it


def test_sand_against_itself_was_repetition_before():
    # the figure this replaces (kept as repetition_order) charged sand's own rows to it
    ex = read_exemplar("exemplars/sand.svg")
    rep = metrics.repetition(ex.motifs, ex, analyze(ex), ex.region)
    assert rep.repetition_order > 0.2 and rep.repetition <= 0.05


@needs_data
@pytest.mark.parametrize("name", ["603", "605", "607", "611", "619", "620", "670"])
def test_an_fgdc_tile_against_itself_is_not_repetition(name):
    ex, st = fgdc(name)
    assert metrics.repetition(ex.motifs, ex, st, ex.region).repetition <= 0.05


@needs_data
@pytest.mark.parametrize("name", IRREGULAR)
def test_stamping_an_irregular_tile_is_repetition(name):
    ex, st = fgdc(name)
    rep = on_tiles(ex, st, "tile")
    assert rep.repetition >= 0.8
    # a displacement of a whole period: the tile cannot show it (only its divisors, by chance)
    assert rep.repetition_exemplar <= 0.1


@needs_data
def test_random_placement_is_not_repetition_on_average():
    figures = [on_tiles(*fgdc(name), "random").repetition for name in (*IRREGULAR, "619", "620")]
    assert np.mean(figures) <= 0.05
    assert max(figures) <= 0.1


def test_a_drawn_tile_of_rows_at_hand_drawn_phases_stamped_is_still_caught():
    ex = parse_exemplar(phased_tile())  # rows exact along x; the phases repeat at the height only
    st = analyze(ex)
    assert metrics.repetition(ex.motifs, ex, st, ex.region).repetition <= 0.05
    arr, region = stamp(ex, 8)
    rep = metrics.repetition(arr, ex, st, metrics.interior(ex, region))
    assert rep.repetition >= 0.8
    assert abs(rep.repetition_vector[1]) > 1.0  # across the rows, where the phases repeat


@needs_data
@pytest.mark.parametrize("name", ["619", "620"])
def test_growth_on_rows_at_fresh_phases_passes_the_gate(name):
    ex, st = fgdc(name)
    rep = on_tiles(ex, st, "growth")
    assert rep.repetition <= 0.2
    assert rep.repetition_order > 0.9  # the figure before: the exact along-row step, charged


def test_exact_rows_show_their_multiples_and_a_jittered_tile_does_not_show_its_period():
    rows = [
        (x + 0.5 * (r % 2), y)
        for r, y in enumerate(np.arange(2.5, 20, 5.0))
        for x in np.arange(0.5, 20, 2.0)
    ]
    ex = exemplar(rows)
    # 2, 3 and 5 steps along a row; 10 steps (20 units) is the region's width: shown by the step
    shifts = np.array([[4.0, 0.0], [6.0, 0.0], [10.0, 0.0], [20.0, 0.0], [0.0, 5.0]])
    share = _exemplar_shares(ex, shifts, 0.15, 1.0)
    assert np.all(share[:4] == 1.0)
    assert share[4] == 0.0  # the rows' half-step offset: no partner straight above
    jit = exemplar(grid(4, jitter=0.6, seed=3))
    assert _exemplar_shares(jit, np.array([[20.0, 0.0], [5.0, 0.0]]), 0.15, 1.0)[0] == 0.0


@cache
def equinor_50090():
    """Equinor lithology 50090, imported as tests/test_wholeset.py does: (exemplar, box)."""
    t = import_tile(SHARED / "equinor-lithology" / "svg" / "50090.svg")
    return parse_exemplar(t.text, source="50090"), t.box


def stamped(ex, box):
    """repetition of the tile engine on ``ex`` on the whole-set gate's region (seed 1)."""
    st = analyze(ex)
    region = gate_region(box, len(ex.motifs))
    arr = synthesize(ex, region, "tile", seed=1, stats=st).arrangement
    return metrics.repetition(arr, ex, st, metrics.interior(ex, region))


@needs_data
def test_equinor_50090_is_a_4_by_4_stamp_of_an_exact_tile_so_stamping_it_is_faithful():
    # its 64 motifs repeat at (16, 0) and (0, 16) to 5e-4 (the bin is 0.8): the divisor rule
    # excuses its period (0, 64) = 4 · (0, 16) because the exemplar shows it, not by a loose
    # tolerance
    ex, box = equinor_50090()
    xy, kind = ex.motifs.xy, ex.motifs.kind
    for step in ((16.0, 0.0), (0.0, 16.0)):
        for c in np.unique(kind):
            mine = xy[kind == c]
            moved = mine + step
            moved = moved[(moved[:, 0] < box[0] + box[2]) & (moved[:, 1] < box[1] + box[3])]
            assert cKDTree(mine).query(moved)[0].max() < 1e-3
    rep = stamped(ex, box)
    assert rep.repetition <= 0.05
    assert rep.repetition_exemplar >= 0.95


def jittered_50090(jitter: float):
    """Equinor 50090 with every motif moved by up to ± ``jitter`` per axis (fixed draws): (exemplar, box)."""
    ex, box = equinor_50090()
    rng = np.random.default_rng(0)
    xy = ex.motifs.xy + rng.uniform(-jitter, jitter, ex.motifs.xy.shape)
    return dataclasses.replace(ex, motifs=dataclasses.replace(ex.motifs, xy=xy)), box


@needs_data
@pytest.mark.parametrize("jitter", [0.8, 1.6])
def test_equinor_50090_jittered_by_a_bin_or_more_and_stamped_is_repetition(jitter):
    # the same tile with every motif moved by up to ± jitter (the bin is 0.8, the figure's square
    # ± 1.2): two motifs' jitters differ by more than the square, so the tile does not show its
    # steps to the square at every multiple, and its period stamped is not excused
    rep = stamped(*jittered_50090(jitter))
    assert rep.repetition >= 0.8
    assert rep.repetition_exemplar < 0.95


@needs_data
def test_equinor_50090_jittered_by_half_a_bin_is_below_the_figures_square_and_not_charged():
    # ± 0.4: any two motifs' jitters differ by at most 0.8 < 1.2, so the tile shows its steps to
    # the square at every multiple it can — a texture that keeps its lattice, stamped or grown
    # anew, meets a partner in the square at the period as the tile does one step on (rep13f;
    # it was charged 1.000 before, when a step had to hold to the square ÷ m at m steps)
    ex, box = jittered_50090(0.4)
    rep = stamped(ex, box)
    assert rep.repetition_raw == 1.0 and rep.repetition_exemplar == 1.0
    assert rep.repetition <= 0.05
    w = ex.region.bounds[2] - ex.region.bounds[0]
    assert _kind_shares(ex, np.array([[w, 0.0]]), 1.2, 4.0)[0] == 1.0
    assert _exemplar_shares(ex, np.array([[w, 0.0]]), 1.2, 4.0)[0] < 1.0  # the reading before rep13f


def test_a_reference_whose_partners_all_lie_behind_it_scores_zero_not_an_error():
    """Peaks are taken in the half-plane dx > 0 (or dx = 0, dy ≥ 0): a texture whose only same-kind
    displacements from motifs in the window point the other way has no peak, and scores 0 (the
    reviewer's case: `svgtile score` ended in an internal TypeError; 0.000 before issue 13's figure)."""
    from svgtile.core.arrangement import Arrangement

    ex = read_exemplar("exemplars/gravel.svg")
    stats = analyze(ex)
    kind = ex.motifs.kind[:1].repeat(2)
    arr = Arrangement(kind, np.array([[100.0, 100.0], [40.0, 100.0]]), np.zeros(2), np.ones(2))
    window = Region.rectangle(40, 40, 80, 80).shape
    got = metrics.repetition(arr, ex, stats, window)
    assert got.repetition == 0.0 and got.repetition_vector is None
