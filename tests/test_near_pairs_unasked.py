"""near_pairs with a per-kind reach: class pairs with no kind pair asked are not searched
(a k-d tree given r = −inf returns every pair; the result was right but O(n²))."""

import numpy as np

from svgtile.core.footprint import near_pairs


def test_unasked_class_pairs_are_not_searched():
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
