"""Invariants of the patch engine on every bundled exemplar (almeraj2013 §3.2–3.5).

Every exemplar × two sizes × both grids must give: no overlapping footprints, no distance-rule
violation, every motif where its boundary mode allows, interior density within ±10 % of ρ,
kind mix within 0.05 total variation, orientations inside their kind's exemplar arc.  The checks
use brute-force shapely, independent of the engine's own conflict search.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import arrange

from svgtile import Region, analyze, metrics, read_exemplar
from svgtile.analysis.stats import in_arcs
from svgtile.core.arrangement import Arrangement
from svgtile.core.cellrng import hash64, uniform
from svgtile.core.conflicts import Conflicts, cull, find_conflicts, slack
from svgtile.core.footprint import world_footprints
from svgtile.engines.patch.engine import PatchParams, grid
from svgtile.errors import ParameterError

EXEMPLARS = sorted((Path(__file__).resolve().parents[1] / "exemplars").glob("*.svg"))
SIZES = (400, 900)


@cache
def load(path: Path):
    ex = read_exemplar(path)
    return ex, analyze(ex)


@cache
def run(path: Path, size: float, grid_kind: str, seed: int = 7, **params):
    ex, stats = load(path)
    region = Region.rectangle(size, size * 0.75)
    arr = arrange("patch", ex, region, rng=np.random.default_rng(seed), stats=stats, grid=grid_kind, **params)
    return ex, stats, region, arr


def brute_force_conflicts(arr: Arrangement, ex, stats) -> tuple[int, int]:
    """(overlapping pairs, rule-violating pairs), every pair tested with shapely."""
    geoms = world_footprints(arr, ex.prototypes)
    tree = shapely.STRtree(geoms)
    reach = float(stats.distance.max())
    i, j = tree.query(geoms, predicate="dwithin", distance=reach)
    keep = i < j
    i, j = i[keep], j[keep]
    dist = shapely.distance(geoms[i], geoms[j])
    rule = stats.distance[arr.kind[i], arr.kind[j]] - slack(ex.prototypes)
    share = shapely.area(shapely.intersection(geoms[i], geoms[j])) > 1e-9
    return int(share.sum()), int((dist < rule).sum())


def test_there_are_enough_exemplars():
    assert len(EXEMPLARS) >= 8


@pytest.mark.parametrize("grid_kind", ["square", "hex"])
@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("path", EXEMPLARS, ids=lambda p: p.stem)
def test_invariants(path, size, grid_kind):
    ex, stats, region, arr = run(path, size, grid_kind)
    assert len(arr) > 0
    overlaps, violations = brute_force_conflicts(arr, ex, stats)
    assert overlaps == 0
    assert violations == 0
    geoms = world_footprints(arr, ex.prototypes)
    assert shapely.intersects(region.shape, geoms).all()  # default boundary "clip"
    inner = metrics.interior(ex, region)
    ratio = metrics.density(arr, ex, inner) / stats.density
    assert 0.9 <= ratio <= 1.1, f"interior density {ratio:.3f} of the exemplar's"
    assert metrics.kind_mix_tv(arr, stats, inner) <= 0.05
    assert in_arcs(arr.angle, arr.kind, stats).all()


@pytest.mark.parametrize("path", EXEMPLARS, ids=lambda p: p.stem)
def test_vary_orientation_stays_in_arcs(path):
    ex, stats, _region, arr = run(path, 400, "square", vary_orientation=True)
    assert in_arcs(arr.angle, arr.kind, stats).all()
    assert brute_force_conflicts(arr, ex, stats) == (0, 0)
    wide = stats.arc_width[arr.kind] > 10
    if wide.sum() > 20:  # orientations really vary: not just the exemplar's few angles
        assert len(np.unique(np.round(arr.angle[wide], 4))) > 0.5 * wide.sum()


@pytest.mark.parametrize("mode", ["inside", "centroid", "clip", "none"])
def test_boundary_modes_on_a_circle(mode):
    ex, stats = load(EXEMPLARS[0])
    region = Region(shapely.Point(300, 300).buffer(250))
    arr = arrange("patch", ex, region, rng=np.random.default_rng(3), stats=stats, boundary=mode)
    geoms = world_footprints(arr, ex.prototypes)
    if mode == "inside":
        assert shapely.contains(region.shape, geoms).all()
    elif mode == "centroid":
        assert shapely.contains_xy(region.shape, arr.xy[:, 0], arr.xy[:, 1]).all()
    else:
        assert shapely.intersects(region.shape, geoms).all()
    # each mode keeps what the stricter ones drop along the border
    if mode in ("clip", "none"):
        assert (~shapely.contains(region.shape, geoms)).any()


def test_same_seed_same_texture_other_seed_other_texture():
    path = EXEMPLARS[0]
    a = run(path, 400, "square", seed=1)[3]
    b = arrange("patch", *load(path)[:1], Region.rectangle(400, 300), rng=np.random.default_rng(1), stats=load(path)[1])
    c = run(path, 400, "square", seed=2)[3]
    assert np.array_equal(a.xy, b.xy) and np.array_equal(a.kind, b.kind) and np.array_equal(a.angle, b.angle)
    assert len(a) != len(c) or not np.array_equal(a.xy, c.xy)


def test_texture_is_anchored_in_world_coordinates():
    """The grid's random choices depend on the cell, not on how far the region extends."""
    ex, _stats = load(EXEMPLARS[0])
    small = grid(ex, Region.rectangle(300, 300), key=5, grid_kind="square", overlap=0.3, max_rotation=30)
    large = grid(ex, Region.rectangle(900, 600), key=5, grid_kind="square", overlap=0.3, max_rotation=30)
    index = {tuple(c): xy for c, xy in zip(map(tuple, large[1]), large[0].xy, strict=True)}
    shared = [(xy, index[tuple(c)]) for c, xy in zip(map(tuple, small[1]), small[0].xy, strict=True) if tuple(c) in index]
    assert len(shared) > 0.9 * len(small[1])
    assert all(np.array_equal(p, q) for p, q in shared)


def test_copies_are_rotated_but_motifs_keep_their_orientation():
    ex, _ = load(EXEMPLARS[0])
    arr, cell = grid(ex, Region.rectangle(500, 500), key=9, grid_kind="hex", overlap=0.3, max_rotation=30)
    assert np.allclose(arr.angle, np.round(ex.motifs.angle[cell[:, 2]], 4))
    # positions of one copy relative to its first motif are the exemplar's turned by one angle
    # (the fullest copy: one cut by the region's edge may keep too few motifs to tell)
    cells, counts = np.unique(cell[:, :2], axis=0, return_counts=True)
    a, b = cells[counts.argmax()]
    mine = (cell[:, 0] == a) & (cell[:, 1] == b)
    rel = arr.xy[mine] - arr.xy[mine][0]
    src = ex.motifs.xy[cell[mine, 2]] - ex.motifs.xy[cell[mine, 2]][0]
    angle = np.degrees(np.arctan2(rel[:, 1], rel[:, 0]) - np.arctan2(src[:, 1], src[:, 0]))
    far = np.hypot(*src.T) > 5
    spread = np.ptp(np.mod(angle[far] - angle[far][0] + 180, 360))
    assert spread < 0.1
    assert np.allclose(np.hypot(*rel.T), np.hypot(*src.T), atol=1e-3)


def test_max_rotation_zero_gives_translated_copies():
    ex, _ = load(EXEMPLARS[0])
    arr, cell = grid(ex, Region.rectangle(300, 300), key=9, grid_kind="square", overlap=0.3, max_rotation=0)
    mine = (cell[:, 0] == cell[0, 0]) & (cell[:, 1] == cell[0, 1])
    rel = arr.xy[mine] - arr.xy[mine][0]
    src = ex.motifs.xy[cell[mine, 2]] - ex.motifs.xy[cell[mine, 2]][0]
    assert np.allclose(rel, src, atol=2e-4)


@pytest.mark.parametrize("kind", ["square", "hex"])
def test_grid_step_is_region_times_one_minus_overlap(kind):
    ex, _ = load(EXEMPLARS[0])
    x0, y0, x1, y1 = ex.region.bounds
    arr, cell = grid(ex, Region.rectangle(400, 400), key=1, grid_kind=kind, overlap=0.25, max_rotation=0)
    first = cell[:, 2] == 0
    xy, ab = arr.xy[first], cell[first, :2]
    row = ab[:, 1] == ab[0, 1]
    steps = np.diff(np.sort(xy[row, 0]))
    assert np.allclose(steps, (x1 - x0) * 0.75, atol=1e-3)
    col_step = (y1 - y0) * 0.75 * (np.sqrt(3) / 2 if kind == "hex" else 1)
    ys = np.unique(np.round(xy[:, 1] - ex.motifs.xy[0, 1], 3))
    assert np.allclose(np.diff(ys), col_step, atol=1e-3)


@pytest.mark.parametrize(
    "params",
    [dict(overlap=-0.1), dict(overlap=0.6), dict(max_rotation=-1), dict(max_rotation=181),
     dict(grid="triangle"), dict(junction=1.0)],
)
def test_parameters_out_of_range_are_refused(params):
    with pytest.raises(ParameterError):
        PatchParams(**params)


def test_cull_keeps_a_maximal_independent_set():
    # a path 0-1-2-3-4 and a triangle 5-6-7
    i = np.array([0, 1, 2, 3, 5, 6, 5])
    j = np.array([1, 2, 3, 4, 6, 7, 7])
    c = Conflicts(i, j, np.zeros(7, bool), np.ones(7, bool))
    rng = np.random.default_rng(0)
    for _ in range(50):
        keep = cull(9, c, rng.random(9))
        assert not (keep[i] & keep[j]).any()  # independent
        for m in np.flatnonzero(~keep):  # maximal: every removed motif has a kept neighbour
            assert keep[np.r_[j[i == m], i[j == m]]].any()
        assert keep[8]  # not in any conflict


def test_cull_prefers_removing_preferred_motifs():
    c = Conflicts(np.array([0]), np.array([1]), np.ones(1, bool), np.ones(1, bool))
    assert list(cull(2, c, np.array([0.9, 0.1]), prefer=np.array([0.0, 1.0]))) == [True, False]
    assert list(cull(2, c, np.array([0.9, 0.1]))) == [False, True]


def test_find_conflicts_matches_brute_force_and_bands(monkeypatch):
    ex, stats = load(EXEMPLARS[0])
    arr, _ = grid(ex, Region.rectangle(300, 300), key=3, grid_kind="square", overlap=0.3, max_rotation=30)
    whole = find_conflicts(arr, ex.prototypes, stats.distance)
    monkeypatch.setattr("svgtile.core.conflicts.BAND_MOTIFS", 500)
    banded = find_conflicts(arr, ex.prototypes, stats.distance)
    pairs = lambda c: set(zip(c.i.tolist(), c.j.tolist(), strict=True))  # noqa: E731
    assert pairs(whole) == pairs(banded)
    geoms = world_footprints(arr, ex.prototypes)
    i, j = shapely.STRtree(geoms).query(geoms, predicate="dwithin", distance=float(stats.distance.max()))
    keep = i < j
    i, j = i[keep], j[keep]
    dist = shapely.distance(geoms[i], geoms[j])
    rule = stats.distance[arr.kind[i], arr.kind[j]] - slack(ex.prototypes)
    bad = dist < rule
    assert pairs(whole) == set(zip(i[bad].tolist(), j[bad].tolist(), strict=True))
    # and each pair's flags: sharing area, and closer than a positive rule
    share = shapely.intersects(geoms[i], geoms[j]) & ~shapely.touches(geoms[i], geoms[j])
    flags = {(a, b): (o, v) for a, b, o, v in zip(i.tolist(), j.tolist(), share.tolist(), ((dist < rule) & (rule > 0)).tolist(), strict=True)}
    got = {(a, b): (o, v) for a, b, o, v in zip(whole.i.tolist(), whole.j.tolist(), whole.overlap.tolist(), whole.violation.tolist(), strict=True)}
    assert sum(o for o, _ in got.values()) > 0 and sum(v and not o for o, v in got.values()) > 0  # both kinds occur
    assert all(got[k][0] == flags[k][0] for k in got)
    assert all(got[k][1] == flags[k][1] for k in got if not flags[k][0])


@pytest.mark.parametrize("name", ["gravel", "till", "breccia", "scrub"])
def test_pairs_said_apart_by_their_extents_are_farther_than_the_reach(name):
    """The footprint-free filter of find_conflicts never drops a pair GEOS finds within reach."""
    from svgtile.core.conflicts import _surely_apart

    ex = read_exemplar(Path(__file__).parent.parent / "exemplars" / f"{name}.svg")
    rng = np.random.default_rng(5)
    n = 4000
    r = max(p.radius for p in ex.prototypes)
    arr = Arrangement(rng.integers(0, len(ex.kinds), n), rng.uniform(0, 4 * r, (n, 2)) + 1000.0,
                      rng.uniform(-180, 180, n), rng.uniform(0.5, 1.5, n))  # fmt: skip
    i, j = np.arange(0, n, 2), np.arange(1, n, 2)
    reach = rng.uniform(0, 0.3 * r, len(i))
    apart = _surely_apart(arr, ex.prototypes, i, j, reach)
    geoms = world_footprints(arr, ex.prototypes)
    dist = shapely.distance(geoms[i], geoms[j])
    assert (dist[apart] > reach[apart]).all()
    far = dist > reach * 1.01 + 1e-6
    assert 0.3 < apart.sum() / far.sum() <= 1.0  # the bound is not idle either


def test_counter_based_randomness_is_local_and_uniform():
    a = uniform(11, 0, np.arange(-5000, 5000), 3)
    assert 0.45 < a.mean() < 0.55 and a.min() >= 0 and a.max() < 1
    assert np.array_equal(uniform(11, 0, np.array([7, 8]), 3), a[[5007, 5008]])
    assert not np.array_equal(hash64(11, 0, 1, 2), hash64(11, 1, 1, 2))
    assert not np.array_equal(hash64(11, 0, 1, 2), hash64(12, 0, 1, 2))


@pytest.mark.parametrize("per_kind", [True, False])
def test_near_pairs_finds_exactly_the_pairs_whose_discs_come_within_reach(per_kind):
    from svgtile.core.footprint import near_pairs

    rng = np.random.default_rng(3)
    n = 3000
    xy = rng.uniform(0, 200, (n, 2))
    kind = rng.integers(0, 3, n)
    radius = np.array([0.4, 1.0, 6.0])[kind] * rng.uniform(0.8, 1.2, n)  # very different sizes
    reach = np.array([[0.2, 0.5, 1.0], [0.5, 0.3, 2.0], [1.0, 2.0, 0.1]]) if per_kind else 0.7
    i, j = near_pairs(xy, radius, reach, kind)
    gap = np.hypot(*(xy[:, None] - xy[None]).transpose(2, 0, 1)) - radius[:, None] - radius[None]
    want = gap < (reach[kind[:, None], kind[None]] if per_kind else reach)
    want &= np.triu(np.ones((n, n), dtype=bool), 1)
    assert (i < j).all()
    wi, wj = np.nonzero(want)
    assert sorted(zip(i.tolist(), j.tolist(), strict=True)) == sorted(zip(wi.tolist(), wj.tolist(), strict=True))
