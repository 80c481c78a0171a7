"""The likeness figures of svgtile/metrics/ on constructed textures with known answers.

Exemplars are built here as ``<symbol>``/``<use>`` SVG text; textures are built from them by
stamping the exemplar's motifs on a grid (a perfect tiling, whose answers follow from the
construction), by uniform random placement, or by editing a tiling (a hole, a denser half, turned
motifs, a missing kind).  Expected values come from the construction, never from the code under
test.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import stamp

from svgtile import Region, analyze, metrics, read_exemplar
from svgtile.analysis.stats import nearest_gaps
from svgtile.apps.compare import format_score
from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import world_footprints
from svgtile.metrics import pattern
from svgtile.svg.reader import parse_exemplar

EXEMPLARS = sorted((Path(__file__).resolve().parents[1] / "exemplars").glob("*.svg"))

SYMBOLS = {
    "dot": '<symbol id="dot" overflow="visible"><circle r="1"/></symbol>',
    "sq": '<symbol id="sq" overflow="visible"><rect x="-1" y="-1" width="2" height="2"/></symbol>',
    "bar": '<symbol id="bar" overflow="visible"><rect x="-1.5" y="-0.4" width="3" height="0.8"/></symbol>',
    # discs of like size, each drawn once below: one shape class (issue 12.3)
    "d1": '<symbol id="d1" overflow="visible"><circle r="1"/></symbol>',
    "d2": '<symbol id="d2" overflow="visible"><circle r="1.15"/></symbol>',
    "d3": '<symbol id="d3" overflow="visible"><circle r="1.3"/></symbol>',
}


def make_exemplar(uses: list[tuple[str, float, float, float]], size: float = 20.0, height: float | None = None):
    """An exemplar of ``(symbol, x, y, angle)`` instances in a ``size × size`` input region
    (``size × height`` if ``height`` is given)."""
    height = size if height is None else height
    used = sorted({u[0] for u in uses})
    body = "".join(
        f'<use xlink:href="#{k}" transform="translate({x:.4f} {y:.4f}) rotate({a:.4f})"/>' for k, x, y, a in uses
    )
    svg = (
        '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
        f'viewBox="0 0 {size:g} {height:g}"><defs>{"".join(SYMBOLS[k] for k in used)}</defs>'
        f'<rect id="region" x="0" y="0" width="{size:g}" height="{height:g}" fill="none"/>{body}</svg>'
    )
    return parse_exemplar(svg)


def grid_uses(cells: int, kinds: list[str], seed: int, cell: float = 5.0) -> list[tuple[str, float, float, float]]:
    """One motif per cell of a ``cells × cells`` grid, jittered by up to ±0.5, kinds in turn.

    Bars turn by 0–20°, the others not at all.  Motifs stay 0.4 inside the region and 1.4 apart,
    so stamped copies of the exemplar never overlap.
    """
    rng = np.random.default_rng(seed)
    uses = []
    for n, (a, b) in enumerate((a, b) for b in range(cells) for a in range(cells)):
        kind = kinds[n % len(kinds)]
        x, y = (np.array([a, b]) + 0.5) * cell + rng.uniform(-0.5, 0.5, 2)
        uses.append((kind, float(x), float(y), float(rng.uniform(0, 20)) if kind == "bar" else 0.0))
    return uses


def name_index(ex, name: str) -> int:
    return [k.name for k in ex.kinds].index(name)




def scatter(stats, region: Region, rng: np.random.Generator) -> Arrangement:
    """Uniform random placement at the exemplar's motif density, kind mix and orientation arcs."""
    n = round(stats.count_density * region.area)
    x0, y0, x1, y1 = region.bounds
    kind = rng.choice(len(stats.frequency), n, p=stats.frequency)
    angle = stats.arc_start[kind] + rng.uniform(0, 1, n) * stats.arc_width[kind]
    return Arrangement(kind, rng.uniform([x0, y0], [x1, y1], (n, 2)), angle, np.ones(n))


@pytest.fixture(scope="module")
def grid16():
    """16 motifs of three kinds in a 20 × 20 region (6 dots, 5 squares, 5 bars)."""
    ex = make_exemplar(grid_uses(4, ["dot", "sq", "bar"], seed=3))
    return ex, analyze(ex)


@pytest.fixture(scope="module")
def grid36():
    """36 motifs of two kinds in a 30 × 30 region: enough pairs for every structure figure."""
    ex = make_exemplar(grid_uses(6, ["dot", "bar"], seed=5), size=30.0)
    return ex, analyze(ex)


# ----------------------------------------------------------------------------- the whole score


def test_a_perfect_tiling_scores_as_the_exemplar(grid16):
    ex, stats = grid16
    arr, region = stamp(ex, 10, 10)
    s = metrics.score(ex, stats, arr, region)
    assert s.window == "interior"
    assert s.motifs == 8 * 8 * len(ex.motifs)  # interior = the inner 8 × 8 copies
    assert s.overlaps == s.overlaps_total == 0  # (seams may break the distance rule)
    assert s.density_ratio == pytest.approx(1.0, rel=1e-9)
    assert s.density_windows == 64
    assert s.density_cv == pytest.approx(0.0, abs=1e-9)
    assert s.density_min_ratio == pytest.approx(1.0, rel=1e-9)
    assert s.kind_mix_tv == pytest.approx(0.0, abs=1e-12)
    assert s.orientation_outside == 0.0
    assert s.repetition > 0.95


def test_score_is_plain_json(grid16):
    ex, stats = grid16
    arr, region = stamp(ex, 6, 6)
    s = metrics.score(ex, stats, arr, region)
    plain = s.to_dict()
    assert json.loads(json.dumps(plain, allow_nan=False)) == plain
    assert s.sample is None  # a small texture is measured whole, and its JSON does not say "sampled"
    assert list(plain) == [f.name for f in dataclasses.fields(metrics.Score) if f.name != "sample"]
    assert plain["kind_pairs"][0] == dataclasses.asdict(s.kind_pairs[0]) | {"kinds": list(s.kind_pairs[0].kinds),
        "names": list(s.kind_pairs[0].names), "gap_samples": list(s.kind_pairs[0].gap_samples)}  # fmt: skip
    documented = metrics.Score.__doc__
    for field in dataclasses.fields(metrics.Score):
        assert re.search(rf"^    {field.name} : \S", documented, re.M), f"{field.name} is not documented in Score"
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.motifs = 0


def test_a_region_without_interior_is_measured_whole(grid16):
    ex, stats = grid16
    arr, region = stamp(ex, 2, 2)  # 40 × 40: shrunk by 20 there is nothing left
    s = metrics.score(ex, stats, arr, region)
    assert s.window == "region"
    assert s.motifs == len(arr)
    assert json.dumps(s.to_dict(), allow_nan=False)


def test_an_empty_texture_scores_without_failing(grid16):
    ex, stats = grid16
    region = Region.rectangle(100, 100)
    s = metrics.score(ex, stats, Arrangement.empty(), region)
    assert s.motifs == 0
    assert s.density_ratio == 0.0
    assert s.kind_mix_tv == 1.0
    assert s.orientation_outside is None
    assert s.repetition is None
    assert s.gap_distance is None
    # the disc is bounded only by the region: its centre lies in the interior [20, 80]²
    assert s.empty_disc_radius == pytest.approx(50.0, abs=0.1)
    assert json.dumps(s.to_dict(), allow_nan=False)


def test_bundled_exemplar_smoke():
    ex = read_exemplar(EXEMPLARS[0])
    stats = analyze(ex)
    arr, region = stamp(ex, 6, 6)
    s = metrics.score(ex, stats, arr, region)
    assert s.overlaps == 0
    assert s.density_ratio == pytest.approx(1.0, rel=1e-6)
    assert s.repetition > 0.95
    assert json.dumps(s.to_dict(), allow_nan=False)


# ----------------------------------------------------------------------------- conflicts


@pytest.fixture(scope="module")
def squares():
    """16 axis-aligned 2 × 2 squares on a 5-unit grid."""
    ex = make_exemplar([("sq", 2.5 + 5 * a, 2.5 + 5 * b, 0.0) for a in range(4) for b in range(4)])
    return ex, analyze(ex)


@pytest.mark.parametrize(
    ("centre", "gap", "overlaps", "violators", "total"),
    [
        ((50, 50), -0.5, 1, 2, 1),  # overlapping
        ((50, 50), "half", 0, 2, 0),  # closer than d_ij
        ((50, 50), 1e-6, 0, 2, 0),  # all but touching
        ((50, 50), "beyond", 0, 0, 0),  # farther than d_ij
        ((5, 50), -0.5, 0, 0, 1),  # overlapping in the border, outside the interior
    ],
)
def test_two_overlapping_squares_are_one_overlap(squares, centre, gap, overlaps, violators, total):
    ex, stats = squares
    half = float(np.abs(ex.kinds[0].prototype.rings[0][:, 0]).max())  # the footprint's half width
    d = float(stats.distance[0, 0])
    assert d > 1.0
    gap = {"half": d / 2, "beyond": d + 0.5}.get(gap, gap)
    x, y = centre
    xy = [(x, y), (x + 2 * half + gap, y), (30, 30), (70, 70), (30, 75)]  # three far from all
    arr = Arrangement(np.zeros(len(xy), np.int64), xy, np.zeros(len(xy)), np.ones(len(xy)))
    s = metrics.score(ex, stats, arr, Region.rectangle(100, 100))
    assert s.overlaps == overlaps
    assert s.violators == violators
    assert s.overlaps_total == total
    assert s.violator_fraction == pytest.approx(violators / s.motifs)


def test_a_motif_with_two_close_neighbours_is_one_violator(squares):
    ex, stats = squares
    half = float(np.abs(ex.kinds[0].prototype.rings[0][:, 0]).max())
    step = 2 * half + float(stats.distance[0, 0]) / 2
    xy = [(40 + step * i, 50) for i in range(3)]
    arr = Arrangement(np.zeros(3, np.int64), xy, np.zeros(3), np.ones(3))
    s = metrics.score(ex, stats, arr, Region.rectangle(100, 100))
    assert (s.overlaps, s.violators, s.violator_fraction) == (0, 3, 1.0)


# ----------------------------------------------------------------------------- density, kind mix, orientation


def test_a_denser_half_has_a_large_density_cv(grid16):
    ex, stats = grid16
    base, region = stamp(ex, 8, 4)  # 160 × 80; interior [20, 140] × [20, 60] = 6 × 2 windows
    more, _ = stamp(ex, 10, 6)
    more = Arrangement(more.kind, more.xy - 30.0, more.angle, more.scale)  # shifted by half a copy
    left = (more.xy[:, 0] < 80) & (more.xy[:, 0] > 0) & (more.xy[:, 1] > 0) & (more.xy[:, 1] < 80)
    arr = Arrangement.concat([base, more.take(left)])
    s = metrics.score(ex, stats, arr, region)
    # every 20 × 20 window holds one copy's worth of motifs, those left of x = 80 two
    assert s.density_windows == 12
    assert s.density_min_ratio == pytest.approx(1.0, rel=1e-9)
    assert s.density_max_ratio == pytest.approx(2.0, rel=1e-9)
    assert s.density_cv == pytest.approx(0.5 / 1.5, rel=1e-9)  # six windows at 1, six at 2
    assert s.density_ratio == pytest.approx(1.5, rel=1e-9)


def test_window_densities_skip_windows_outside_the_window(grid16):
    ex, stats = grid16
    arr, _ = stamp(ex, 8, 8)
    ell = shapely.Polygon([(0, 0), (160, 0), (160, 60), (60, 60), (60, 160), (0, 160)])
    dens = metrics.window_densities(arr, ex, ell)
    # an 8 × 8 grid of 20-unit windows; the L holds 8·3 + 3·5 of them
    assert len(dens) == 39
    assert dens == pytest.approx(np.full(39, stats.density), rel=1e-9)


def test_kind_mix_counts_a_missing_kind(grid16):
    ex, stats = grid16
    arr, region = stamp(ex, 6, 6)
    bar = name_index(ex, "bar")
    s = metrics.score(ex, stats, arr.take(arr.kind != bar), region)
    assert s.kind_mix_tv == pytest.approx(5 / 16)  # all of the bars' share is missing


@pytest.fixture(scope="module")
def one_offs():
    """22 squares and three discs of like size drawn once each (d1, d2, d3) on a 5 × 5 grid of
    6-unit cells in a 30 × 30 region: the discs are rare kinds of one shape class."""
    uses = [("sq", (a + 0.5) * 6, (b + 0.5) * 6, 0.0) for b in range(5) for a in range(5)]
    for n, name in zip((6, 12, 18), ("d1", "d2", "d3"), strict=True):
        uses[n] = (name, *uses[n][1:])
    ex = make_exemplar(uses, size=30.0)
    return ex, analyze(ex)


def test_kind_mix_pools_rare_kinds_of_like_shape(one_offs):
    ex, stats = one_offs
    d1, d2, d3, sq = (name_index(ex, n) for n in ("d1", "d2", "d3", "sq"))
    assert stats.classes[d1] == stats.classes[d2] == stats.classes[d3] != stats.classes[sq]
    arr, region = stamp(ex, 6, 6)
    s = metrics.score(ex, stats, arr, region)
    assert s.kind_mix_tv == pytest.approx(0.0, abs=1e-12) and s.kind_mix_tv_kinds == pytest.approx(0.0, abs=1e-12)
    # every one-off disc drawn as d1: the class mix is the exemplar's, each kind's is not
    kind = np.where(np.isin(arr.kind, [d2, d3]), d1, arr.kind)
    s = metrics.score(ex, stats, Arrangement(kind, arr.xy, arr.angle, arr.scale), region)
    assert s.kind_mix_tv == pytest.approx(0.0, abs=1e-12)
    assert s.kind_mix_tv_kinds == pytest.approx(2 / 25)  # d1 holds 3/25 for 1/25; d2, d3 lack 1/25 each
    assert s.kind_mix_noise == pytest.approx(metrics.kind_mix_noise(s.motifs, stats.frequency))
    # svgtile score prints both readings where kinds pool, the per-kind one under the other
    lines = format_score(s).splitlines()
    at = next(i for i, line in enumerate(lines) if line.startswith("kind mix TV"))
    assert lines[at].split()[-1] == "0.000" and lines[at + 1].split() == ["per", "kind", f"{2 / 25:.3f}"]
    assert lines[at + 2].split()[:3] == ["its", "sampling", "noise"]
    # the discs gone: both readings miss their whole share
    s = metrics.score(ex, stats, arr.take(arr.kind == sq), region)
    assert s.kind_mix_tv == pytest.approx(3 / 25) and s.kind_mix_tv_kinds == pytest.approx(3 / 25)


def test_kind_mix_per_kind_is_left_out_where_no_kind_is_pooled(grid16):
    ex, stats = grid16
    assert len(np.unique(stats.classes)) == len(ex.kinds)
    arr, region = stamp(ex, 6, 6)
    bar = name_index(ex, "bar")
    s = metrics.score(ex, stats, arr.take(arr.kind != bar), region)
    assert s.kind_mix_tv_kinds is None and s.kind_mix_noise is None
    assert metrics.kind_mix_tv(arr, stats, classes=False) == metrics.kind_mix_tv(arr, stats)


def test_kind_mix_noise_is_the_mean_tv_of_a_fair_draw():
    rng = np.random.default_rng(7)
    for n, f in ((214, np.r_[np.full(61, 1.0), np.full(3, 51.0)]), (50, np.array([5.0, 3, 2])), (7, np.array([9.0, 1]))):
        f = f / f.sum()
        draws = rng.multinomial(n, f, size=40_000) / n
        chance = float((0.5 * np.abs(draws - f).sum(axis=1)).mean())
        assert metrics.kind_mix_noise(n, f) == pytest.approx(chance, rel=0.02)
    assert metrics.kind_mix_noise(1, np.array([0.5, 0.5])) == pytest.approx(0.5)  # one coin: always half off
    assert metrics.kind_mix_noise(100, np.array([1.0])) == 0.0 == metrics.kind_mix_noise(0, np.array([0.5, 0.5]))


def test_wrong_orientations_are_counted(grid16):
    ex, stats = grid16
    arr, region = stamp(ex, 6, 6)
    bar = name_index(ex, "bar")
    assert stats.arc_width[bar] < 25.0
    inner = (arr.xy > 20).all(axis=1) & (arr.xy < 100).all(axis=1)
    turned = np.flatnonzero(inner & (arr.kind == bar))[::3]
    angle = arr.angle.copy()
    angle[turned] = 90.0
    # turned motifs outside the interior do not count
    outer = np.flatnonzero(~inner & (arr.kind == bar))
    angle[outer] = -90.0
    s = metrics.score(ex, stats, arr.with_angle(angle), region)
    assert s.orientation_outside == pytest.approx(len(turned) / inner.sum())
    assert metrics.score(ex, stats, arr, region).orientation_outside == 0.0


# ----------------------------------------------------------------------------- structure


def test_a_translated_copy_has_no_structure_distance(grid36):
    ex, stats = grid36
    shift = np.array([123.25, -56.5])
    moved = Arrangement(ex.motifs.kind, ex.motifs.xy + shift, ex.motifs.angle, ex.motifs.scale)
    window = shapely.transform(ex.region, lambda c: c + shift)
    found = metrics.structure(ex, stats, moved, window)
    assert found.gap_distance == pytest.approx(0.0, abs=1e-9)
    assert found.pair_correlation_distance == pytest.approx(0.0, abs=1e-9)
    counted = [p for p in found.kind_pairs if p.gap_distance is not None]
    assert len(counted) == 4  # every ordered pair of the two kinds has enough samples
    assert any(p.pair_correlation_distance is not None for p in found.kind_pairs)


def test_random_placement_loses_the_structure_a_tiling_keeps(grid36):
    ex, stats = grid36
    tiled, region = stamp(ex, 8, 8)
    tile = metrics.score(ex, stats, tiled, region)
    rand = metrics.score(ex, stats, scatter(stats, region, np.random.default_rng(4)), region)
    assert tile.gap_distance < 0.5 * rand.gap_distance
    assert tile.pair_correlation_distance < 0.5 * rand.pair_correlation_distance


def test_tiled_pairs_keep_their_gaps_exactly():
    # dots in pairs 3 apart (gap 1), pairs 10 apart: in a tiling every dot's nearest dot is its
    # partner, as in the exemplar, so the gap distributions are the same point mass
    uses = [("dot", x + dx, y, 0.0) for x in (3.0, 13.0) for y in (2.5, 7.5, 12.5, 17.5) for dx in (0.0, 3.0)]
    ex = make_exemplar(uses)
    stats = analyze(ex)
    arr, region = stamp(ex, 8, 8)
    assert metrics.score(ex, stats, arr, region).gap_distance == pytest.approx(0.0, abs=1e-9)
    rand = metrics.score(ex, stats, scatter(stats, region, np.random.default_rng(2)), region)
    assert rand.gap_distance > 0.5


@pytest.mark.parametrize(
    "values, n, expected",
    [
        (np.array([0.0, 1.0] * 50), 1, 0.5),  # one draw is 0 or 1, always ½ from the fair coin
        (np.full(40, 3.0), 7, 0.0),  # a constant: every sample is exact
        (np.array([0.0, 2.0, 4.0]), 1, 16 / 9),  # see below
    ],
)
def test_sampling_noise_known_answers(values, n, expected):
    # for {0, 2, 4}: W1(δ_0) = (0 + 2 + 4)/3 = 2, W1(δ_2) = (2 + 0 + 2)/3 = 4/3, W1(δ_4) = 2; their
    # mean 16/9 is what many draws approach (64 draws: within a few percent)
    got = metrics.sampling_noise(values, n)
    assert got == pytest.approx(expected, rel=0.08, abs=1e-12)


def test_sampling_noise_shrinks_like_one_over_root_n():
    values = np.random.default_rng(5).random(4000)
    small, large = metrics.sampling_noise(values, 16), metrics.sampling_noise(values, 256)
    assert small / large == pytest.approx(4.0, rel=0.25)


def test_gap_noise_separates_a_tiling_from_a_sample(grid36):
    # a tiling repeats the exemplar's very sample: its distance is below the noise of a fresh
    # sample; random placement is far above it
    ex, stats = grid36
    tiled, region = stamp(ex, 8, 8)
    tile = metrics.score(ex, stats, tiled, region)
    rand = metrics.score(ex, stats, scatter(stats, region, np.random.default_rng(4)), region)
    assert tile.gap_noise > 0 and rand.gap_noise > 0
    assert tile.gap_distance < tile.gap_noise
    assert rand.gap_distance > 2 * rand.gap_noise
    noise = [p.gap_noise for p in tile.kind_pairs if p.gap_distance is not None]
    assert len(noise) == 4 and all(v is not None and v >= 0 for v in noise)


def test_nearest_gaps_match_brute_force(grid16):
    ex, _ = grid16
    rng = np.random.default_rng(11)
    n = 60
    kind = rng.integers(0, 2, n)
    kind[0] = 2  # kind 2 has a single motif: it has no other motif of its kind
    arr = Arrangement(kind, rng.uniform(0, 40, (n, 2)), rng.uniform(0, 360, n), np.ones(n))
    geoms = world_footprints(arr, ex.prototypes)
    dist = shapely.distance(geoms[:, None], geoms[None, :])
    np.fill_diagonal(dist, np.inf)
    sources = np.arange(n)
    for k in range(3):
        expected = np.where(kind[None, :] == k, dist, np.inf).min(axis=1)
        got = nearest_gaps(arr, ex.prototypes, sources, k)
        assert got == pytest.approx(expected, abs=1e-9)
    assert nearest_gaps(arr, ex.prototypes, np.array([0]), 2)[0] == np.inf


def test_wasserstein_of_a_shift_is_the_shift():
    u = np.random.default_rng(0).normal(size=50)
    assert metrics.wasserstein(u, u + 3.0) == pytest.approx(3.0)
    assert metrics.wasserstein(u, u[::-1]) == 0.0
    assert metrics.wasserstein(np.array([0.0]), np.array([0.0, 2.0])) == pytest.approx(1.0)


@pytest.mark.parametrize(
    "window",
    [shapely.box(0, 0, 100, 100), shapely.Point(50, 50).buffer(55, 64)],
    ids=["rectangle", "disc"],
)
def test_pair_correlation_of_poisson_points_is_one(window):
    rng = np.random.default_rng(8)
    xy = rng.uniform(-5, 105, (6000, 2))
    kind = rng.integers(0, 2, len(xy))
    g, pairs = metrics.pair_correlation(xy, kind, 2, window, reach=10.0, bins=10)
    assert pairs.min() > 1000
    assert g.mean() == pytest.approx(1.0, abs=0.03)
    assert np.abs(g - 1).max() < 0.25  # the first bins hold fewer pairs


def test_pair_correlation_sees_a_hard_core():
    # a square lattice of step 2: no pair closer than 2, a peak at 2
    a, b = np.meshgrid(np.arange(50), np.arange(50))
    xy = np.stack([a.ravel(), b.ravel()], axis=1) * 2.0
    g, _ = metrics.pair_correlation(xy, np.zeros(len(xy), np.int64), 1, shapely.box(0, 0, 98, 98), 4.0, bins=8)
    assert (g[0, 0, :3] == 0).all()  # [0, 1.5)
    assert g[0, 0, 4] > 1.8  # [2, 2.5) holds the 4 nearest neighbours: 1.77 expected at random


# ----------------------------------------------------------------------------- repetition


def test_a_perfect_tiling_repeats(grid16):
    ex, stats = grid16
    arr, region = stamp(ex, 10, 10)
    rep = metrics.repetition(arr, ex, stats, metrics.interior(ex, region))
    assert rep.repetition_raw == 1.0
    assert rep.repetition == pytest.approx(1.0)
    cells = np.array(rep.repetition_vector) / 20.0  # a period of the tiling
    assert np.abs(cells - np.round(cells)).max() < 1e-6
    assert np.abs(np.round(cells)).max() >= 1


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_placement_does_not_repeat(grid16, seed):
    ex, stats = grid16
    region = Region.rectangle(200, 200)
    arr = scatter(stats, region, np.random.default_rng(seed))
    assert metrics.repetition(arr, ex, stats, metrics.interior(ex, region)).repetition < 0.1


def test_repetition_at_random_is_chance_and_corrected_away():
    # one kind: a reference has a partner in the 3q × 3q square of any given displacement with
    # the Poisson probability 1 − exp(−λ·9q²), about 0.086 — the raw figure; the corrected ≈ 0
    ex = make_exemplar(grid_uses(4, ["dot"], seed=7))
    stats = analyze(ex)
    region = Region.rectangle(300, 300)
    arr = scatter(stats, region, np.random.default_rng(12))
    window = metrics.interior(ex, region)
    lam = shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1]).sum() / window.area
    q = pattern.REPEAT_BIN / math.sqrt(stats.count_density)
    chance = 1 - math.exp(-lam * 9 * q * q)
    rep = metrics.repetition(arr, ex, stats, window)
    assert rep.repetition_raw == pytest.approx(chance, abs=0.025)
    assert rep.repetition < 0.03


def test_repetition_is_graded(grid16):
    # keep 70 % of a tiling's motifs in place and move the rest by 1–3 spacings: a reference
    # and its partner one period away are both in place with probability 0.7² = 0.49
    ex, stats = grid16
    arr, region = stamp(ex, 10, 10)
    rng = np.random.default_rng(6)
    moved = rng.random(len(arr)) >= 0.7
    turn = rng.uniform(0, 2 * np.pi, moved.sum())
    xy = arr.xy.copy()
    xy[moved] += rng.uniform(5, 15, moved.sum())[:, None] * np.stack([np.cos(turn), np.sin(turn)], axis=1)
    rep = metrics.repetition(Arrangement(arr.kind, xy, arr.angle, arr.scale), ex, stats, metrics.interior(ex, region))
    assert rep.repetition == pytest.approx(0.49, abs=0.06)


def test_figures_do_not_depend_on_motif_order(grid36, monkeypatch):
    ex, stats = grid36
    for name in ("GAP_SAMPLES", "PAIR_SAMPLES", "REPEAT_SAMPLES"):
        monkeypatch.setattr(pattern, name, 200)  # so that the texture is sampled
    arr, region = stamp(ex, 6, 6)
    rng = np.random.default_rng(9)
    arr = Arrangement(arr.kind, arr.xy + rng.normal(0, 0.3, arr.xy.shape), arr.angle, arr.scale)
    a = metrics.score(ex, stats, arr, region)
    b = metrics.score(ex, stats, arr.take(rng.permutation(len(arr))), region)
    for key in ("gap_distance", "repetition", "repetition_raw", "overlaps", "density_cv", "coverage"):
        assert getattr(a, key) == pytest.approx(getattr(b, key), rel=1e-9, abs=1e-12), key
    assert a.pair_correlation_distance is not None
    assert a.pair_correlation_distance == pytest.approx(b.pair_correlation_distance, rel=1e-6)


# ----------------------------------------------------------------------------- coverage


def test_a_big_hole_has_coverage_far_above_one(grid16):
    ex, stats = grid16
    arr, region = stamp(ex, 10, 10)
    hole, centre = 40.0, np.array([100.0, 100.0])
    reach = max(p.radius for p in ex.prototypes)
    keep = np.hypot(*(arr.xy - centre).T) > hole + reach  # no footprint reaches into the disc
    full = metrics.score(ex, stats, arr, region)
    holed = metrics.score(ex, stats, arr.take(keep), region)
    assert hole * 0.99 <= holed.empty_disc_radius <= hole + reach + 5.0
    assert holed.coverage > 5
    assert holed.coverage > 5 * full.coverage
    assert full.coverage < 2


def _one_dot_tile(w: float, h: float, x: float, y: float):
    """A ``w × h`` repeating tile of one dot at (x, y): a rectangular lattice of dots."""
    return dataclasses.replace(make_exemplar([("dot", x, y, 0.0)], w, h), period=(w, h))


@pytest.mark.parametrize(("w", "h"), [(20.0, 20.0), (60.0, 10.0)])
def test_a_repeating_tile_has_its_holes_measured_across_its_edges(w, h):
    """A tile's holes run on into the next copy.  One dot at (3, 4) in a ``w × h`` tile of that
    period is a rectangular lattice of dots: its largest hole is the lattice's, centred half a
    period from the dot both ways, of radius half the period's diagonal less the dot's radius
    (20 × 20: the disc the tile's own sides cut is about 9.2; 60 × 10: a 3 × 3 block of copies
    cuts it at 15).  A stamp of the tile — the same holes — scores coverage 1 (it scored
    1.47–1.71 on osm-carto's stamped tiles while the exemplar's disc was cut at the tile's sides)."""
    ex = _one_dot_tile(w, h, 3.0, 4.0)
    proto = ex.prototypes[0]
    r_out = proto.radius
    r_in = float(shapely.distance(shapely.Point(0, 0), shapely.polygons(proto.rings[0]).exterior))
    half = math.hypot(w, h) / 2
    radius = metrics.exemplar_empty_disc(ex, step=1.0)
    assert half - r_out - 0.05 <= radius <= half - r_in + 1e-9
    # a drawn exemplar (no period) keeps the disc inside its region
    drawn = metrics.exemplar_empty_disc(dataclasses.replace(ex, period=None), step=1.0)
    assert drawn == metrics.largest_empty_disc(ex.motifs, ex.prototypes, ex.region, ex.region, step=1.0)[0]
    assert drawn < 0.75 * radius
    arr, region = stamp(ex, 6, 6 * max(1, round(w / h)))
    s = metrics.score(ex, analyze(ex), arr, region)
    assert s.coverage == pytest.approx(1.0, abs=0.03)


def test_a_tiles_hole_is_found_at_its_edge_off_the_raster():
    """The tile's largest hole may be centred on its side, where the raster (of a step the period
    is no multiple of) has no point; the disc is searched a step beyond the tile too (the same
    hole one period on), so the figure keeps its precision there: one dot at the tile's centre of
    a 20 × 20 tile has its hole at the corners, √200 − r, found at a step of 2.7."""
    ex = _one_dot_tile(20.0, 20.0, 10.0, 10.0)
    proto = ex.prototypes[0]
    r_in = float(shapely.distance(shapely.Point(0, 0), shapely.polygons(proto.rings[0]).exterior))
    radius = metrics.exemplar_empty_disc(ex, step=2.7)
    bound = 2.7 / 4**2 / math.sqrt(2)  # largest_empty_disc's: the last grid's step over √2
    assert math.sqrt(200) - proto.radius - bound - 1e-9 <= radius <= math.sqrt(200) - r_in + 1e-9


@pytest.mark.parametrize(
    ("dots", "expected"),
    [
        # four dots at (5, 5) … (15, 15): the centre is √50 from each
        ([(5, 5), (15, 5), (5, 15), (15, 15)], lambda r: math.sqrt(50) - r),
        # one dot in the middle: a disc in a corner, touching two sides and the dot
        ([(10, 10)], lambda r: (10 * math.sqrt(2) - r) / (1 + math.sqrt(2))),
    ],
)
def test_largest_empty_disc_known_answers(dots, expected):
    ex = make_exemplar([("dot", x, y, 0.0) for x, y in dots])
    proto = ex.prototypes[0]
    r_out = proto.radius  # the footprint is a polygon between these two radii
    r_in = float(shapely.distance(shapely.Point(0, 0), shapely.polygons(proto.rings[0]).exterior))
    radius, centre = metrics.largest_empty_disc(ex.motifs, ex.prototypes, ex.region, ex.region, step=1.0)
    assert expected(r_out) - 0.05 <= radius <= expected(r_in) + 1e-9  # grid step 1/16 at the end
    assert shapely.contains(ex.region, shapely.Point(centre).buffer(radius * 0.999))
