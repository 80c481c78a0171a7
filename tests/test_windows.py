"""The world-anchored square windows the optimize engine measures its start, insertion, kind mix
and renewal in (:func:`svgtile.engines.windows.square_windows`, :func:`~svgtile.engines.windows.square_area`)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from svgtile.core.region import Region
from svgtile.engines.windows import square_area, square_cells, square_windows


def test_points_fall_in_windows_counted_from_the_world_origin():
    xy = np.array([[1.5, 2.5], [-0.1, 0.0], [0.1, 0.0], [0.9, 0.99], [-0.1, -3.0]])
    ids, which = square_windows(xy, 1.0)
    assert ids.tolist() == [[-1, -3], [-1, 0], [0, 0], [1, 2]]  # lexicographic, negative windows too
    assert which.tolist() == [3, 1, 2, 2, 0]
    assert which.dtype == np.int64 and ids.dtype == np.int64


def test_a_window_does_not_depend_on_the_other_points():
    """World-anchored: the same point is in the same window whatever else is measured."""
    rng = np.random.default_rng(1)
    xy = rng.uniform(-20, 20, (200, 2))
    ids, which = square_windows(xy, 3.0)
    sub_ids, sub_which = square_windows(xy[::7], 3.0)
    assert np.array_equal(sub_ids[sub_which], ids[which][::7])
    assert np.array_equal(ids[which], np.floor(xy / 3.0).astype(np.int64))


def test_window_areas_are_their_part_inside_the_region():
    region = Region(shapely.box(0.0, 0.0, 1.5, 3.0))
    ids = np.array([[-1, 0], [0, 0], [1, 2], [0, 2]])
    assert square_area(ids, 1.0, region) == pytest.approx([0.0, 1.0, 0.5, 1.0])
    assert square_area(np.array([[0, 0]]), 2.0, region) == pytest.approx([3.0])


def test_cells_are_the_windows_coordinates():
    xy = np.array([[2.99, -0.01], [3.0, 0.0], [-6.5, 7.2]])
    assert square_cells(xy, 3.0).tolist() == [[0, -1], [1, 0], [-3, 2]]
    ids, which = square_windows(xy, 3.0)
    assert np.array_equal(ids[which], square_cells(xy, 3.0))
