"""The shortcuts that make ``svgtile score`` cheap give what the plain computations give, bit for bit.

Timings are in benchmarks/README.md; these tests only check the answers.
"""

from __future__ import annotations

import click
import numpy as np
import pytest
import shapely
from scipy.ndimage import distance_transform_edt

from svgtile.cli.main import COMMANDS, LazyCommands, cli
from svgtile.metrics.coverage import _contains_grid, _feature_distance


def test_every_command_loads_under_its_name():
    for name in COMMANDS:
        command = cli.commands[name]
        assert isinstance(command, click.Command) and command.name == name
    assert sorted(cli.commands) == sorted(COMMANDS)


def test_lazy_commands_import_only_what_is_looked_up():
    table = LazyCommands({"score": "svgtile.cli.score:score", "broken": "svgtile.no_such_module:x"})
    assert table["score"].name == "score"
    assert list(table) == ["score", "broken"] and len(table) == 2
    with pytest.raises(ImportError):
        table["broken"]
    del table["broken"]
    assert list(table) == ["score"]


@pytest.mark.parametrize(
    "geom",
    [
        shapely.box(1.0, 2.0, 7.5, 6.25),  # the rectangle shortcut
        shapely.Polygon([(7.5, 6.25), (1.0, 6.25), (1.0, 2.0), (7.5, 2.0)]),  # the same, other winding
        shapely.Point(4, 4).buffer(2.6),  # the general test
        shapely.box(0, 0, 9, 9).difference(shapely.box(3, 3, 5, 5)),  # a hole: general
    ],
)
def test_contains_grid_is_contains_xy(geom):
    xs = np.arange(-0.5, 9.5, 0.25)  # grid lines on the rectangle's edges too
    ys = np.arange(0.0, 8.0, 0.25)
    gx, gy = np.meshgrid(xs, ys)
    got = _contains_grid(geom, xs, ys)
    assert got.shape == (len(ys), len(xs)) and got.any() and not got.all()
    assert np.array_equal(got, shapely.contains_xy(geom, gx, gy))


def test_feature_distance_is_the_distance_transform():
    rng = np.random.default_rng(5)
    free = rng.random((61, 47)) > 0.02
    iy, ix = np.nonzero(rng.random(free.shape) > 0.3)
    got = _feature_distance(free, iy, ix)
    want = distance_transform_edt(free)[iy, ix]
    assert got.max() > 2 and np.array_equal(got, want)
