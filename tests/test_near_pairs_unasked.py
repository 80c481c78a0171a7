"""near_pairs with a per-kind reach: class pairs with no kind pair asked are not searched
(a k-d tree given r = −inf returns every pair; the result was right but O(n²))."""

import numpy as np
from scipy.spatial import cKDTree

import svgtile.core.footprint as footprint
from svgtile.core.footprint import near_pairs


class _PositiveReach(cKDTree):
    """A k-d tree that refuses the searches near_pairs must not ask: r ≤ 0 (r = −inf is every pair)."""

    def query_pairs(self, r, *args, **kwargs):
        assert r > 0, f"query_pairs asked with r = {r}"
        return super().query_pairs(r, *args, **kwargs)

    def sparse_distance_matrix(self, other, max_distance, *args, **kwargs):
        assert max_distance > 0, f"sparse_distance_matrix asked with r = {max_distance}"
        return super().sparse_distance_matrix(other, max_distance, *args, **kwargs)


def test_unasked_class_pairs_are_not_searched(monkeypatch):
    monkeypatch.setattr(footprint, "cKDTree", _PositiveReach)
    rng = np.random.default_rng(3)
    xy = rng.random((3000, 2)) * 100.0
    kind = (np.arange(3000) % 2).astype(np.int64)
    radius = np.where(kind == 0, 1.0, 0.3)  # two size classes, one per kind
    reach = np.full((2, 2), -np.inf)
    reach[0, 1] = reach[1, 0] = 2.0
    i, j = near_pairs(xy, radius, reach, kind)
    gap = np.hypot(*(xy[i] - xy[j]).T) - radius[i] - radius[j]
    assert len(i) > 0 and (kind[i] != kind[j]).all() and (gap < 2.0).all()
    # every cross pair within the reach is found
    d = np.hypot(*(xy[kind == 0][:, None] - xy[kind == 1][None]).transpose(2, 0, 1)) - 1.3
    assert len(i) == int((d < 2.0).sum())
