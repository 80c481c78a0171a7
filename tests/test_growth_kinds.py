"""The final kind passes: kinds re-chosen against each motif's complete ring (Ijiri et al. 2008,
§5.2 eq. 1–3, :mod:`svgtile.engines.growth.kinds`), then against the exemplar's k-nearest
neighbourhoods (Ma, Wei & Tong 2011, §3.2 eq. 1, :mod:`svgtile.engines.growth.neighbourkinds`), per
cell, on a drawn exemplar of rows."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile import analyze, read_exemplar
from svgtile.analysis.neighbourhood import neighbourhood_distance
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth import GrowthParams, Weights
from svgtile.engines.growth.connectivity import reference_rings
from svgtile.engines.growth.kinds import MIX, mix_bounds, repick
from svgtile.engines.growth.neighbourkinds import energies, neighbourhood_kinds
from svgtile.engines.growth.rows import row_lines
from svgtile.errors import ParameterError
from svgtile.metrics import score
from svgtile.metrics.window import spacing

REPO = Path(__file__).resolve().parents[1]


@cache
def loaded(name: str):
    ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
    return ex, analyze(ex)


@cache
def grown(name: str, sweeps: int, box: tuple[float, float, float, float] = (0, 0, 180, 180), seed: int = 1):
    ex, st = loaded(name)
    return synthesize(ex, Region(shapely.box(*box)), "growth", seed=seed, stats=st, boundary="centroid",
                      params={"kind_sweeps": sweeps}).arrangement  # fmt: skip


def test_a_wrong_kind_in_a_copy_of_the_exemplar_is_put_right_and_held_motifs_keep_theirs():
    """On the exemplar itself every whole ring matches a reference exactly; one interior motif
    given the other kind is given its own back, and the motifs not allowed to change keep theirs."""
    ex, _ = loaded("marsh")
    rings = reference_rings(ex)
    m = ex.motifs
    centre = np.array([30.0, 30.0])
    i = rings.element[np.argmin(np.hypot(*(m.xy[rings.element] - centre).T))]  # an interior motif with a ring
    kind = m.kind.copy()
    kind[i] = 1 - kind[i]
    movable = np.zeros(len(m), bool)
    movable[i] = True
    new, ring = repick(rings, m.xy, kind, np.arange(len(m)), movable, weights=Weights())
    assert new[i] == m.kind[i]
    assert ring[i] >= 0 and rings.kind[ring[i]] == m.kind[i]
    assert np.array_equal(new[~movable], kind[~movable]) and np.all(ring[~movable] == -1)
    # nothing may change: nothing does
    same, none = repick(rings, m.xy, kind, np.arange(len(m)), np.zeros(len(m), bool), weights=Weights())
    assert np.array_equal(same, kind) and np.all(none == -1)


def test_the_pass_brings_the_seams_kinds_nearer_the_exemplars():
    """At the cells' seams (within 6 units of a cell edge: most of what growth loses on marsh) the
    part of E that kinds make (E less E with kinds ignored) falls (measured 0.83 → 0.76, seed 1,
    with the kind mix held, :func:`svgtile.engines.growth.kinds.mix_bounds`; 0.83 → 0.64 when the
    passes moved the mix), and the cells' insides do not get worse."""
    ex, st = loaded("marsh")
    s = spacing(st)
    before, after = grown("marsh", 0), grown("marsh", GrowthParams().kind_sweeps)
    parts = []
    for arr in (before, after):
        m = arr.xy % 60.0  # marsh's cells are one exemplar width wide
        edge = np.minimum(m, 60.0 - m).min(1)
        inside = (arr.xy.min(1) > 15) & (arr.xy.max(1) < 165)
        e = [[neighbourhood_distance(arr.xy, arr.kind, ex.motifs.xy, ex.motifs.kind, spacing=s, k=6, alpha=a,
                                     centres=np.flatnonzero(inside & sel), sample=None) for a in (1.0, 0.0)]
             for sel in (edge < 6, edge >= 6)]  # fmt: skip
        parts.append([e[0][0] - e[0][1], e[1][0]])
    (seam0, inner0), (seam1, inner1) = parts
    assert seam1 < 0.95 * seam0, (seam0, seam1)
    assert inner1 <= inner0 + 0.02, (inner0, inner1)


def test_marsh_with_the_pass_is_deterministic_and_tile_exact():
    """Same seed, same motifs; and a small region's motifs are the large region's inside it (a
    cell's kinds are re-chosen with only its earlier-phase neighbours held, never a later cell's)."""
    small = grown("marsh", 4, (30, 20, 130, 100))
    again = synthesize(*loaded("marsh")[:1], Region(shapely.box(30, 20, 130, 100)), "growth", seed=1,
                       stats=loaded("marsh")[1], boundary="centroid").arrangement  # fmt: skip
    assert all(np.array_equal(getattr(small, f), getattr(again, f)) for f in ("kind", "xy", "angle", "scale"))
    large = grown("marsh", 4, (-40, -50, 200, 170))
    inside = shapely.contains_xy(shapely.box(30, 20, 130, 100), *large.xy.T)
    a = np.lexsort((small.xy[:, 1], small.xy[:, 0]))
    b = np.flatnonzero(inside)[np.lexsort((large.xy[inside, 1], large.xy[inside, 0]))]
    assert len(a) == len(b) > 100
    assert np.array_equal(small.xy[a], large.xy[b]) and np.array_equal(small.kind[a], large.kind[b])
    assert np.array_equal(small.angle[a], large.angle[b]) and np.array_equal(small.scale[a], large.scale[b])


@pytest.mark.parametrize("name", ["sand", "gravel"])
def test_the_pass_leaves_textures_without_row_lines_alone(name):
    """Only a drawn exemplar of rows grown unturned has the pass (the goldens, tiles, sand and
    gravel are grown as before)."""
    a, b = grown(name, 0, (0, 0, 120, 90)), grown(name, 4, (0, 0, 120, 90))
    assert all(np.array_equal(getattr(a, f), getattr(b, f)) for f in ("kind", "xy", "angle", "scale"))


def test_a_negative_number_of_sweeps_is_a_clear_error():
    with pytest.raises(ParameterError, match="kind_sweeps must be at least 0"):
        GrowthParams(kind_sweeps=-1)
    with pytest.raises(ParameterError, match="neighbourhood_sweeps must be at least 0"):
        GrowthParams(neighbourhood_sweeps=-1)


def test_the_neighbourhood_pass_puts_wrong_kinds_in_a_copy_of_the_exemplar_right():
    """On the exemplar itself every neighbourhood has an exact copy (E = 0): interior motifs
    given the other kind, apart from each other, are given their own back; held motifs keep
    theirs, and with nothing movable nothing changes."""
    ex, st = loaded("marsh")
    m, s = ex.motifs, spacing(st)
    inner = np.flatnonzero((m.xy.min(1) > 12) & (m.xy.max(1) < 48))
    wrong = inner[::5]
    kind = m.kind.copy()
    kind[wrong] = 1 - kind[wrong]
    movable = np.zeros(len(m), bool)
    movable[wrong] = True
    new = neighbourhood_kinds(m.xy, kind, movable, m.xy, m.kind, s)
    assert len(wrong) >= 3 and np.array_equal(new, m.kind), np.flatnonzero(new != m.kind)
    assert np.array_equal(
        neighbourhood_kinds(m.xy, kind, np.zeros(len(m), bool), m.xy, m.kind, s), kind
    )


def test_the_neighbourhood_pass_lowers_the_likeness_scores_own_distance():
    """The energy the pass lowers is, centre by centre, the term the likeness score averages
    (ma2011 eq. 1 with greedy pairing, analysis.neighbourhood); and on a grown piece of marsh with
    the pass off the pass lowers its mean."""
    ex, st = loaded("marsh")
    s, m = spacing(st), ex.motifs
    arr = grown("marsh", 0, (0, 0, 120, 90))
    inside = np.flatnonzero((arr.xy.min(1) > 15) & (arr.xy[:, 0] < 105) & (arr.xy[:, 1] < 75))
    e = energies(arr.xy, arr.kind, inside, m.xy, m.kind, s)
    ref = neighbourhood_distance(arr.xy, arr.kind, m.xy, m.kind, spacing=s, k=6, alpha=1.0, centres=inside,
                                 sample=None)  # fmt: skip
    assert len(inside) > 100 and e.mean() == pytest.approx(ref, rel=1e-9, abs=1e-12)
    movable = np.zeros(len(arr.xy), bool)
    movable[inside] = True
    new = neighbourhood_kinds(arr.xy, arr.kind, movable, m.xy, m.kind, s)
    after = energies(arr.xy, new, inside, m.xy, m.kind, s).mean()
    assert after < 0.9 * e.mean(), (e.mean(), after)
    assert np.array_equal(new[~movable], arr.kind[~movable])


def test_mix_bounds_are_the_exemplars_share_widened_to_the_count_now():
    """(f ± MIX) × n rounded outwards, widened to hold the count a kind has; no bound without a
    frequency or without a movable motif."""
    kind = np.array([0] * 30 + [1] * 70)
    movable = np.ones(100, bool)
    count, lo, hi = mix_bounds(kind, movable, np.array([0.4, 0.6]), 2)
    assert count.tolist() == [30, 70]
    assert lo.tolist() == [30, int(np.floor((0.6 - MIX) * 100))]  # kind 0 under its band: it may only gain
    assert hi.tolist() == [int(np.ceil((0.4 + MIX) * 100)), 70]
    for free in (mix_bounds(kind, movable, None, 2), mix_bounds(kind, np.zeros(100, bool), np.array([0.4, 0.6]), 2)):
        assert free[1].tolist() == [0, 0] and (free[2] > 10**9).all()


def _drifting_piece():
    """A grown piece of marsh with its passes off, its interior movable, and the exemplar's mix: on
    it the free passes drift the mix (kind 0: 0.40 of the motifs → 0.33 and 0.31 in the first
    version of the passes, which held no mix)."""
    ex, st = loaded("marsh")
    arr = grown("marsh", 0, (0, 0, 180, 180))
    movable = (arr.xy.min(1) > 15) & (arr.xy.max(1) < 165)
    return ex, st, arr, movable


def test_the_ring_pass_holds_the_kind_mix_it_drifts_when_free():
    ex, st, arr, movable = _drifting_piece()
    rings = reference_rings(ex)
    sub = np.zeros(len(arr), np.int64)  # the ring pass reads sub-ids only through the weights' sub-id term
    free, _ = repick(rings, arr.xy, arr.kind, sub, movable, weights=Weights())
    held, _ = repick(rings, arr.xy, arr.kind, sub, movable, weights=Weights(), frequency=st.frequency)
    _, lo, hi = mix_bounds(arr.kind, movable, st.frequency, 2)
    got = np.bincount(held, minlength=2)
    assert (lo <= got).all() and (got <= hi).all(), (lo, got, hi)
    assert np.bincount(free, minlength=2)[0] < lo[0], (np.bincount(free, minlength=2), lo)  # free, it drifts
    assert (held != arr.kind).any()  # held, it still changes kinds
    assert np.array_equal(held[~movable], arr.kind[~movable])


def test_the_neighbourhood_pass_holds_the_kind_mix_it_drifts_when_free():
    ex, st, arr, movable = _drifting_piece()
    m, s = ex.motifs, spacing(st)
    free = neighbourhood_kinds(arr.xy, arr.kind, movable, m.xy, m.kind, s)
    held = neighbourhood_kinds(arr.xy, arr.kind, movable, m.xy, m.kind, s, frequency=st.frequency)
    _, lo, hi = mix_bounds(arr.kind, movable, st.frequency, 2)
    got = np.bincount(held, minlength=2)
    assert (lo <= got).all() and (got <= hi).all(), (lo, got, hi)
    assert np.bincount(free, minlength=2)[0] < lo[0], (np.bincount(free, minlength=2), lo)
    assert (held != arr.kind).any()
    assert np.array_equal(held[~movable], arr.kind[~movable])


@cache
def marsh_figures(seed: int, sweeps: int | None = None):
    ex, st = loaded("marsh")
    region = Region.rectangle(300, 300)
    params = None if sweeps is None else {"neighbourhood_sweeps": sweeps}
    arr = synthesize(
        ex, region, "growth", seed=seed, stats=st, boundary="centroid", params=params
    ).arrangement
    return score(ex, st, arr, region)


#: Issue 13's repetition gate not met on marsh (300 × 300, default growth): none since rep13e.
#: Before it seeds 2, 3 and 5 read 0.216, 0.212 and 0.201 (the others 0.177–0.198), at whole row
#: offsets longer than the exemplar shows: marsh's rows put every partner on a row line, and
#: the figure took the plane's Poisson chance (≈ 0.05) for what rows at random along their lines
#: meet (≈ 0.16).  With the rows' own chance at whole row offsets
#: (:func:`svgtile.metrics.repeats._rows_floor`) seeds 1–7 read 0.062–0.114 (benchmarks/README.md,
#: "rep13e"); a run copied along the rows is still caught (tests/test_repetition_reduced.py).
REPETITION_NOT_MET: dict[int, float] = {}
SEEDS = (1, 2, 3, 4, 5, 6, 7)
#: Issue 13's likeness gate not met on marsh since the kind passes hold the exemplar's kind mix
#: (2026-12-07, benchmarks/README.md "growth's kind mix"): the passes had reached L 0.828–0.881 on
#: seeds 1–7 by moving the mix (kind 0: 0.41 of the exemplar's tufts, 0.31 of the texture's;
#: kind-mix TV 0.12–0.15), and with it held they add 0.008 to the 0.770 of no passes at all.
LIKENESS_NOT_MET: dict[int, float] = {1: 0.765, 2: 0.770, 3: 0.756, 4: 0.749, 6: 0.773}
#: The kind-mix bound not met: none (seed 4 reads 0.045; 0.063 with both passes off).
MIX_NOT_MET: dict[int, float] = {}


def _seeds(known: dict[int, float], figure: str) -> list:
    return [pytest.param(seed, marks=pytest.mark.xfail(strict=True, reason=f"{figure} {known[seed]:.3f}"))
            if seed in known else seed for seed in SEEDS]  # fmt: skip


@pytest.mark.parametrize("seed", _seeds(LIKENESS_NOT_MET, "likeness"))
def test_marsh_meets_issue_13s_likeness_on_seeds_1_to_7(seed):
    """L ≥ 0.8 with 0 overlaps, 0 violators and density ratio in 0.9–1.1 at 300 × 300, scored as
    tests/test_growth_auto.py scores it (with the kind mix held: 0.765 / 0.770 / 0.756 / 0.749 /
    0.812 / 0.773 / 0.824 on seeds 1–7)."""
    s = marsh_figures(seed)
    assert s.overlaps_total == s.violators_total == 0
    assert 0.9 <= s.density_ratio <= 1.1, s.density_ratio
    assert s.likeness >= 0.8, s.likeness


@pytest.mark.parametrize("seed", _seeds(MIX_NOT_MET, "kind mix"))
def test_marsh_keeps_the_exemplars_kind_mix_on_seeds_1_to_7(seed):
    """Kind-mix TV ≤ 0.05 (the whole-set gates' bound) at 300 × 300: the kind passes may not trade
    the exemplar's mix for likeness (before they held it: 0.116 / 0.142 / 0.151 on seeds 1–3)."""
    assert marsh_figures(seed).kind_mix_tv <= 0.05, marsh_figures(seed).kind_mix_tv


@pytest.mark.parametrize("seed", [
    pytest.param(seed, marks=pytest.mark.xfail(strict=True, reason=f"repetition {REPETITION_NOT_MET[seed]:.3f}"))
    if seed in REPETITION_NOT_MET else seed for seed in SEEDS])  # fmt: skip
def test_marsh_repetition_on_seeds_1_to_7(seed):
    assert marsh_figures(seed).repetition <= 0.2, marsh_figures(seed).repetition


def test_marsh_rows_at_random_phases_repeat_less_but_lose_likeness():
    """What is left over the rows' own chance is the relation between neighbouring rows, and it is
    what L is made of: seed 2's texture with every row moved along itself by its own random shift
    (each row's own spacing kept, the relations between rows gone) repeats less (0.062 → 0.040;
    0.216 → 0.06–0.16 by three draws before rep13e, when the figure took the plane's chance at
    whole row offsets) but falls far below it in likeness (0.58 against 0.77; 0.64 against 0.86
    when the kind passes moved the mix)."""
    ex, st = loaded("marsh")
    region = Region.rectangle(300, 300)
    arr = synthesize(ex, region, "growth", seed=2, stats=st, boundary="centroid").arrangement
    rows = row_lines(ex)
    row = np.round((arr.xy @ rows.across - rows.offset) / rows.pitch).astype(np.int64)
    assert abs(rows.along[1]) < 0.01  # marsh's rows run along x
    rng = np.random.default_rng(2)
    xy = arr.xy.copy()
    for r in np.unique(row):
        xy[row == r, 0] = (xy[row == r, 0] + rng.uniform(0, 300)) % 300
    shifted = score(ex, st, Arrangement(arr.kind, xy, arr.angle, arr.scale), region)
    grown2 = marsh_figures(2)
    assert shifted.repetition < grown2.repetition, (shifted.repetition, grown2.repetition)
    assert shifted.likeness < grown2.likeness - 0.15, (shifted.likeness, grown2.likeness)


def test_the_neighbourhood_pass_does_not_lower_marshs_likeness():
    """Seed 3, the pass off (ring pass alone) against on: L does not fall (0.741 → 0.753 with the
    kind mix held; 0.772 → 0.848 when the passes moved the mix), and the mix stays in bounds."""
    off, on = marsh_figures(3, 0), marsh_figures(3)
    assert on.likeness >= off.likeness, (off.likeness, on.likeness)
    assert on.kind_mix_tv <= 0.05, on.kind_mix_tv
