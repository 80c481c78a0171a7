"""Hole filling after the patch engine's density repair (:mod:`svgtile.engines.holes`):
windows left light get the kinds they lack by area, largest first, without a conflict."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from svgtile import Region, analyze, read_exemplar
from svgtile.analysis.stats import footprint_areas
from svgtile.core.conflicts import cross_conflicts, find_conflicts
from svgtile.engines import synthesize
from svgtile.engines.holes import _cumsum_within, fill_holes, kind_targets, sparse_windows

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"


def _same(a, b) -> bool:
    return all(np.array_equal(getattr(a, f), getattr(b, f)) for f in ("kind", "xy", "angle", "scale"))


def test_cumsum_within_restarts_at_each_label():
    got = _cumsum_within(np.array([1.0, 2.0, 3.0, 4.0, 5.0]), np.array([0, 0, 2, 2, 7]))
    assert got.tolist() == [1.0, 3.0, 3.0, 7.0, 5.0]


def test_kind_targets_sum_to_the_exemplar_density():
    ex = read_exemplar(EXEMPLARS / "till.svg")
    stats = analyze(ex)
    t = kind_targets(ex)
    assert t.shape == (len(ex.prototypes),) and (t > 0).all()
    assert t.sum() == pytest.approx(stats.density, rel=1e-9)


@pytest.fixture(scope="module")
def holed():
    """Till (kinds of very different sizes) tiled on a 3 × 3 window grid, with the motifs of two
    whole windows taken out: 7/9 of ρ, below the engine's tolerance."""
    ex = read_exemplar(EXEMPLARS / "till.svg")
    stats = analyze(ex)
    x0, y0, x1, y1 = ex.region.bounds
    w, h = x1 - x0, y1 - y0
    region = Region.rectangle(3 * w, 3 * h)
    full = synthesize(ex, region, "tile", seed=1, stats=stats).arrangement
    cell = np.floor(full.xy / [w, h]).astype(int)
    hole = ((cell[:, 0] == 1) & (cell[:, 1] == 1)) | ((cell[:, 0] == 2) & (cell[:, 1] == 0))
    return ex, stats, region, full.take(~hole), (w, h)


def test_holes_are_filled_towards_rho_with_the_kinds_lacking_by_area(holed):
    ex, stats, region, arr, (w, h) = holed
    out = fill_holes(arr, ex, stats, region, "clip", key=7, tolerance=0.1)
    # the texture is kept but for the few motifs displaced (the fill is appended after them)
    kept = (out.xy[:, None, :] == arr.xy[None, :, :]).all(axis=2) & (out.kind[:, None] == arr.kind[None, :])
    old = kept.any(axis=1)
    n = int(old.sum())
    assert old[:n].all() and not old[n:].any() and n >= 0.9 * len(arr)
    new = out.take(np.arange(n, len(out)))
    assert len(new) > 0
    assert len(find_conflicts(out, ex.prototypes, stats.distance).i) == 0
    # no overlap or rule violation, among the new motifs or against the texture
    assert len(find_conflicts(new, ex.prototypes, stats.distance).i) == 0
    assert not cross_conflicts(new, out.take(np.arange(n)), ex.prototypes, stats.distance).any()
    # the holes, not the full windows, receive them, and no window goes past ρ(1 + 0.1)
    _, ids, area, covered, _ = sparse_windows(out, ex, stats, region, np.zeros(2))
    ratio = covered / area / stats.density
    cell = np.floor(new.xy / [w, h]).astype(int)
    in_holes = ((cell[:, 0] == 1) & (cell[:, 1] == 1)) | ((cell[:, 0] == 2) & (cell[:, 1] == 0))
    assert in_holes.mean() > 0.75  # the holes are 2/9 of the region; shifted windows straddle them
    assert ratio.max() <= 1.1
    holes = [(ids[:, 0] == a) & (ids[:, 1] == b) for a, b in ((1, 1), (2, 0))]
    assert min(float(ratio[m][0]) for m in holes) > 0.5  # from 0
    # the added area's kind mix follows the exemplar's area mix, not its counts
    a_new = np.bincount(new.kind, weights=footprint_areas(new, ex.prototypes), minlength=len(ex.prototypes))
    share_new, share_ex = a_new / a_new.sum(), kind_targets(ex) / stats.density
    tv = 0.5 * np.abs(share_new - share_ex).sum()
    assert tv < 0.25, (share_new, share_ex)
    largest = int(np.argmax([p.area for p in ex.prototypes]))
    assert a_new[largest] > 0  # the largest kind is placed, not only what fits anywhere


def test_holes_fill_the_same_way_for_the_same_key_and_otherwise_for_another(holed):
    ex, stats, region, arr, _ = holed
    a = fill_holes(arr, ex, stats, region, "clip", key=7, tolerance=0.1)
    b = fill_holes(arr, ex, stats, region, "clip", key=7, tolerance=0.1)
    c = fill_holes(arr, ex, stats, region, "clip", key=8, tolerance=0.1)
    assert _same(a, b) and not _same(a, c)


def test_a_texture_within_tolerance_is_left_as_it_is(holed):
    ex, stats, region, _, _ = holed
    full = synthesize(ex, region, "tile", seed=1, stats=stats).arrangement
    assert fill_holes(full, ex, stats, region, "clip", key=7, tolerance=0.1) is full


def test_a_lacking_large_kind_displaces_a_few_surplus_small_ones(holed):
    """Holes packed with the smallest kind at its own distance rule: no empty place is left for a
    larger motif, so the large kinds come only by displacing a few of the small (whose window
    holds more than its area share of them)."""
    from svgtile.core.arrangement import Arrangement

    ex, stats, region, arr, (w, h) = holed
    areas = np.array([p.area for p in ex.prototypes])
    small = int(np.argmin(areas))
    r = ex.prototypes[small].radius
    g = 2 * r + float(stats.distance[small, small]) + 0.05
    gx, gy = np.meshgrid(np.arange(g / 2, w, g), np.arange(g / 2, h, g))
    cell = np.stack([gx.ravel(), gy.ravel()], -1)
    dots = np.concatenate([cell + np.array([w, h]), cell + np.array([2 * w, 0.0])])
    # keep only the dots clear of the texture (the holes' edges meet copies of the tile)
    packed = Arrangement(np.full(len(dots), small), dots, np.zeros(len(dots)), np.ones(len(dots)))
    packed = packed.take(~cross_conflicts(packed, arr, ex.prototypes, stats.distance))
    start = Arrangement.concat([arr, packed])
    assert len(find_conflicts(start, ex.prototypes, stats.distance).i) == 0
    out = fill_holes(start, ex, stats, region, "clip", key=7, tolerance=0.1)
    kept = (start.xy[:, None, :] == out.xy[None, :, :]).all(axis=2).any(axis=1)
    assert 0 < (~kept).sum() <= 0.5 * len(packed)  # some dots went, not most
    assert (~kept[len(arr):]).sum() > (~kept[: len(arr)]).sum()  # mostly the packed dots go
    new = out.take(np.arange(int(kept.sum()), len(out)))
    assert (areas[new.kind] > areas[small]).any()
    assert len(find_conflicts(out, ex.prototypes, stats.distance).i) == 0


def test_a_region_with_no_window_at_the_first_offset_is_left_as_it_is():
    """The gate is measured at the first offset: a region one exemplar wide placed half a window
    off the world grid has no window there (each holds a quarter of it), so it is left alone —
    the later rounds' shifted offsets, whose window fits it, must not fill it ungated."""
    import shapely

    ex = read_exemplar(EXEMPLARS / "till.svg")
    stats = analyze(ex)
    x0, y0, x1, y1 = ex.region.bounds
    w, h = x1 - x0, y1 - y0
    region = Region(shapely.box(0.5 * w, 0.5 * h, 1.5 * w, 1.5 * h))
    full = synthesize(ex, region, "tile", seed=1, stats=stats).arrangement
    light = full.take(np.arange(len(full)) % 2 == 0)  # half of ρ
    assert sparse_windows(light, ex, stats, region, np.zeros(2)) is None
    assert sparse_windows(light, ex, stats, region, 0.5 * np.array([w, h])) is not None
    assert fill_holes(light, ex, stats, region, "clip", key=7, tolerance=0.1) is light
