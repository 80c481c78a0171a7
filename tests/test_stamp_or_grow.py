"""Auto stamps a repeating tile only where the stamp is the tile's own order; a tile of rows
exact along x at hand-drawn phases is grown (issues 12 and 13, rule ``tile-rows`` of
:data:`svgtile.engines.choose.RULES`; figures in benchmarks/README.md, "auto13")."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from test_order import exemplar, grid_points

from svgtile.analysis.order import read_order, stamp_repeats
from svgtile.analysis.stats import analyze
from svgtile.engines import ENGINES, choose
from svgtile.engines.growth import rows_wander


def test_an_exact_lattice_tile_is_its_own_stamp():
    ex = exemplar(grid_points(), size=(40.0, 40.0), period=True)  # 10 × 10 dots, 4 apart
    assert not stamp_repeats(ex)


def test_offset_rows_two_to_the_tile_are_their_own_stamp():
    # rows 4 apart, every other one shifted by 2: the period (0, 8) is (2, 4) + (-2, 4), no divisor
    ex = exemplar(grid_points(a=4.0, b=4.0, size=(40.0, 8.0), offset=2.0), size=(40.0, 8.0), period=True)
    assert read_order(ex).kind == "lattice" and not stamp_repeats(ex)


def test_a_jittered_lattice_tile_repeats_when_stamped():
    ex = exemplar(grid_points(jitter=0.3, seed=2), size=(40.0, 40.0), period=True)
    assert read_order(ex).kind != "scatter" and stamp_repeats(ex)


def test_rows_exact_along_x_at_free_phases_repeat_when_stamped():
    rng = np.random.default_rng(4)
    pts = [(x + ph, y + 1.0) for y, ph in zip(np.arange(0, 40, 4.0), rng.uniform(0, 4, 10), strict=True)
           for x in np.arange(0, 40, 4.0)]  # fmt: skip
    ex = exemplar([(x % 40.0, y) for x, y in pts], size=(40.0, 40.0), period=True)
    assert stamp_repeats(ex)


def test_a_drawn_exemplar_is_never_a_stamp():
    assert not stamp_repeats(exemplar(grid_points(jitter=0.3)))


FGDC = Path(__file__).resolve().parents[2] / "shared" / "data" / "fgdc-geologic-patterns" / "lithology"


@pytest.mark.skipif(not FGDC.is_dir(), reason="../shared/data (real symbol sets) is not beside the checkout")
@pytest.mark.parametrize(("name", "rule"), [("619", "tile-rows"), ("620", "tile-rows"), ("621", "tile-order"),
                                            ("610", "tile-order"), ("711", "tile-order"), ("618", "tile-jitter"),
                                            ("669", "tile-jitter"), ("670", "tile-order")])  # fmt: skip
def test_auto_grows_the_tiles_whose_rows_wander_and_stamps_the_others(name, rule):
    from svgtile.svg.reader import parse_exemplar
    from svgtile.tiles.importer import import_tile

    ex = parse_exemplar(import_tile(FGDC / f"{name}.svg").text, source=name)
    st = analyze(ex)
    c = choose(ex, st, available=ENGINES)
    assert c.rule == rule
    assert stamp_repeats(ex) == (name != "711")  # 711: an exact lattice, its stamp is the tile
    if rule == "tile-rows":
        assert c.engine == "growth" and "hand-drawn phases" in c.why
    elif name == "621":  # rows read, but most of its row-to-row phase steps break the distance rule
        assert not rows_wander(ex, st.distance)
