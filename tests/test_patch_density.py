"""Density repair of the patch engine (almeraj2013 §3.4): its shortcuts give what the plain
computation gives.

The speed-ups of :mod:`svgtile.engines.patch.density` (issue 12's speed target) must not change a
texture: the best sample per window without a sort, the empty-disc search handing its neighbour
query to the roomiest-spot search, and the nearest-centroid clash test that searches only as far
as a clash can reach.  Each is checked here against the computation it replaces; the golden
snapshots (tests/test_output.py) check whole textures.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely
from scipy.spatial import cKDTree

from svgtile import Region, analyze, read_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import Prototype
from svgtile.engines import synthesize
from svgtile.engines.patch.density import _best_per_owner, _largest_empty_discs, _roomiest
from svgtile.engines.patch.engine import PatchParams

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"


def _by_sort(value: np.ndarray, owner: np.ndarray) -> np.ndarray:
    """The reference: a lexicographic sort, the last of each owner's run."""
    order = np.lexsort((value, owner))
    return order[np.r_[np.flatnonzero(np.diff(owner[order])), len(order) - 1]]


@pytest.mark.parametrize("seed", range(6))
def test_best_per_owner_is_the_last_of_the_largest(seed):
    rng = np.random.default_rng(seed)
    n = 3000
    owner = rng.integers(0, 40, n)  # not contiguous, some owners absent
    value = np.round(rng.normal(size=n), 1)  # many ties
    value[rng.random(n) < 0.2] = -np.inf
    value[owner == 7] = -np.inf  # an owner with nothing inside the region
    assert np.array_equal(_best_per_owner(value, owner), _by_sort(value, owner))


def test_best_per_owner_takes_the_last_of_ties():
    value = np.array([1.0, 3.0, 3.0, -np.inf, -np.inf, 2.0])
    owner = np.array([0, 0, 0, 1, 1, 2])
    assert _best_per_owner(value, owner).tolist() == [2, 4, 5]


def _scatter(seed: int) -> tuple[Arrangement, list[Prototype]]:
    rng = np.random.default_rng(seed)
    protos = [Prototype.from_geometry(shapely.Point(0, 0).buffer(r, 32), tolerance=0.0) for r in (4.0, 1.0, 0.5)]
    xy = rng.uniform(0, 200, (400, 2))
    return Arrangement(rng.integers(0, 3, 400), xy, np.zeros(400), np.ones(400)), protos


@pytest.mark.parametrize("seed", range(3))
def test_roomiest_spot_is_the_same_with_the_empty_disc_search_s_neighbours(seed):
    arr, protos = _scatter(seed)
    tree = cKDTree(arr.xy)
    region = Region(shapely.box(0, 0, 190, 170))  # windows partly outside
    size, ids = np.array([50.0, 50.0]), np.array([[a, b] for a in range(4) for b in range(4)])
    origin = np.array([0.0, 0.0])
    kind = np.arange(len(ids)) % 3
    rule = np.array([[12.0, 3.0, 2.0], [3.0, 1.0, 0.5], [2.0, 0.5, 0.0]])
    centre, radius, nearest = _largest_empty_discs(arr, tree, protos, region, origin, size, ids)
    alone = _roomiest(arr, tree, protos, region, origin, size, ids, kind, rule, arr)
    shared = _roomiest(arr, tree, protos, region, origin, size, ids, kind, rule, arr, nearest=nearest)
    assert np.array_equal(alone[0], shared[0]) and np.array_equal(alone[1], shared[1])
    # the empty discs are empty: no footprint reaches into them
    d = np.hypot(*(centre[:, None, :] - arr.xy[None, :, :]).transpose(2, 0, 1)) - np.array([4.0, 1.0, 0.5])[arr.kind]
    assert (d.min(axis=1) >= radius - 1e-9).all() and (radius > 0).any()


@pytest.mark.parametrize("seed", range(4))
def test_roomiest_spot_measured_lazily_is_the_one_measured_everywhere(seed):
    """_roomiest measures the room (a k-d tree query per kind) only where the nearest motif's
    term can still reach the best kept: the same spots and clearances as measuring every sample."""
    arr, protos = _scatter(seed)
    if seed % 2:  # a cleared hole: few samples can win
        arr = arr.take(np.hypot(*(arr.xy - 90).T) > 20)
    tree = cKDTree(arr.xy)
    region = Region(shapely.box(0, 0, 190, 170))
    size, ids = np.array([50.0, 40.0]), np.array([[a, b] for a in range(-1, 4) for b in range(5)])
    kind = np.arange(len(ids)) % 3
    rule = np.array([[12.0, 3.0, 2.0], [3.0, 1.0, 0.5], [2.0, 0.5, 0.0]])
    lazy = _roomiest(arr, tree, protos, region, np.zeros(2), size, ids, kind, rule, arr)
    plain = _roomiest(arr, tree, protos, region, np.zeros(2), size, ids, kind, rule, arr, lazy=False)
    assert np.array_equal(lazy[0], plain[0]) and np.array_equal(lazy[1], plain[1])
    assert (plain[1] > 0).any()


def test_patch_texture_is_full_and_clean_after_density_repair():
    """End to end on a bundled exemplar with kinds of very different sizes (till): density repair
    brings the texture near ρ without an overlap; with no repair rounds it stays light."""
    from svgtile.metrics import score

    ex = read_exemplar(EXEMPLARS / "till.svg")
    stats = analyze(ex)
    region = Region.rectangle(600, 600)
    full = synthesize(ex, region, "patch", seed=3, stats=stats).arrangement
    none = synthesize(ex, region, "patch", seed=3, stats=stats, params=PatchParams(density_rounds=0)).arrangement
    s_full, s_none = score(ex, stats, full, region), score(ex, stats, none, region)
    assert s_full.overlaps_total == s_full.violators_total == 0
    assert 0.9 <= s_full.density_ratio <= 1.1
    assert s_none.density_ratio < s_full.density_ratio - 0.03


def _plain_empty_discs(arr, tree, protos, region, origin, size, ids, samples=12):
    """The reference: the k-neighbour clearance bound at every sample (the search before its
    shortcut)."""
    g = (np.arange(samples) + 0.5) / samples
    gx, gy = (v.ravel() for v in np.meshgrid(g, g))
    lo = origin + ids * size
    pts = (lo[:, None, :] + np.stack([gx, gy], -1)[None, :, :] * size).reshape(-1, 2)
    owner = np.repeat(np.arange(len(ids)), len(gx))
    edge = np.minimum(np.minimum(pts[:, 0] - lo[owner, 0], lo[owner, 0] + size[0] - pts[:, 0]),
                      np.minimum(pts[:, 1] - lo[owner, 1], lo[owner, 1] + size[1] - pts[:, 1]))  # fmt: skip
    radius = np.array([p.radius for p in protos])[arr.kind] * arr.scale
    dist, idx = tree.query(pts, k=6)
    clear = np.minimum(edge, np.minimum((dist - radius[idx]).min(axis=1), dist[:, -1] - radius.max()))
    clear[~shapely.contains_xy(region.shape, pts[:, 0], pts[:, 1])] = -np.inf
    best = _by_sort(clear, owner)
    return pts[best], np.maximum(clear[best], 0.0)


@pytest.mark.parametrize("seed", range(4))
def test_empty_discs_are_those_of_the_plain_search(seed):
    arr, protos = _scatter(seed)
    if seed % 2:  # a denser texture with a cleared hole: the best sample is one of few
        arr = arr.take(np.hypot(*(arr.xy - 120).T) > 25)
    tree = cKDTree(arr.xy)
    region = Region(shapely.box(0, 0, 190, 170))
    size, ids, origin = np.array([50.0, 40.0]), np.array([[a, b] for a in range(-1, 4) for b in range(5)]), np.zeros(2)
    centre, radius, _ = _largest_empty_discs(arr, tree, protos, region, origin, size, ids)
    plain_centre, plain_radius = _plain_empty_discs(arr, tree, protos, region, origin, size, ids)
    assert np.array_equal(centre, plain_centre) and np.array_equal(radius, plain_radius)


@pytest.mark.parametrize("seed", range(4))
def test_cross_conflicts_staged_tests_find_what_every_pair_finds(seed):
    """cross_conflicts tests each new motif's nearest pair first and skips the rest of a motif
    found in conflict: the same motifs conflict as when every pair is tested."""
    from svgtile.core.conflicts import cross_conflicts, cross_pairs

    rng = np.random.default_rng(seed)
    bar = Prototype.from_geometry(shapely.box(-3, -0.3, 3, 0.3), tolerance=0.0)  # thin: inscribed discs decide little
    dot = Prototype.from_geometry(shapely.Point(0, 0).buffer(0.8, 16), tolerance=0.0)
    protos = [bar, dot]

    def scatter(n):
        return Arrangement(rng.integers(0, 2, n), rng.uniform(0, 60, (n, 2)), rng.uniform(-90, 90, n), np.ones(n))

    old, new = scatter(150), scatter(200)
    rule = np.array([[1.0, 0.5], [0.5, 0.3]])
    a, _ = cross_pairs(new, old, protos, rule, complete=True)
    every = np.zeros(len(new), dtype=bool)
    every[a] = True
    staged = cross_conflicts(new, old, protos, rule)
    assert 0 < every.sum() < len(new)
    assert np.array_equal(staged, every)
