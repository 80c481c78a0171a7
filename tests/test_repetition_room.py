"""The repetition figure asks each reference for room (step 4 of
:func:`svgtile.metrics.repeats.repetition`): ``P_tex(v)`` is the share of the references whose
point at ``v`` lies 1.5 bins inside the texture's region, as ``P_ex`` is the share of the
exemplar's motifs whose square stays inside the exemplar; over at least ``REPEAT_ROOM_MIN``
references (all, if fewer), and 0 with fewer than ``REPEAT_EX_MIN`` with room, as ``P_ex``.
Counting every reference read a texture two periods wide, where half the references have no room
one period on, as half as repetitive as it is (FGDC 654's stamped tile scored 0.00 at 2 × 2 tiles
and 1.00 at 3 × 3).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import stamp
from test_repetition_order import exemplar, grid

from svgtile import analyze, metrics, read_exemplar
from svgtile.analysis.window import measured_window
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import repeats

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
BUNDLED = sorted(p.stem for p in EXEMPLARS.glob("*.svg"))


def jittered():
    """64 dots jittered off their sites: no exact order, so nothing of a stamp is excused."""
    return exemplar(grid(8, jitter=0.5, seed=3), size=40.0, period=True)


@pytest.mark.parametrize("tiles", [2, 3])
def test_a_stamp_of_irregular_content_is_repetition_two_periods_wide_as_three(tiles):
    ex = jittered()
    stats = analyze(ex)
    arr, region = stamp(ex, tiles)
    s = metrics.score(ex, stats, arr, region)
    assert s.repetition > 0.95, s
    # the reading without the room rule: on 2 × 2 tiles only the references in the first tile
    # have a partner one period on, and the share halves
    window, _ = measured_window(ex, region)
    blind = metrics.repetition(arr, ex, stats, window).repetition_raw
    with_room = metrics.repetition(arr, ex, stats, window, room=region.shape).repetition_raw
    assert with_room > 0.95
    if tiles == 2:
        assert blind < 0.6, blind


def test_a_stamp_of_few_motifs_is_read_over_all_of_them():
    # 16 motifs a tile: on 3 × 3 tiles the 16 in the interior all have room one period on and
    # the share is 16 / 16; on 2 × 2 tiles 32 of 64 have room, short of the 50 the share is
    # taken over: 32 / 50 (a share over 32 would be 1, over every reference 0.5)
    ex = exemplar(grid(4, jitter=0.5, seed=3), period=True)
    stats = analyze(ex)
    for tiles, share in ((3, 1.0), (2, 32 / 50)):
        arr, region = stamp(ex, tiles)
        window, _ = measured_window(ex, region)
        rep = metrics.repetition(arr, ex, stats, window, room=region.shape)
        assert rep.repetition_raw == pytest.approx(share), (tiles, rep)


def test_a_region_with_a_hole_asks_for_room_around_the_hole():
    # 4 × 4 tiles with the middle 2 × 2 cut out: no motif stands in the hole, and references whose
    # partner would stand there have no room
    ex = jittered()
    arr, box = stamp(ex, 4)
    hole = shapely.box(40, 40, 120, 120)
    region = Region.from_geometry(shapely.difference(box.shape, hole))
    keep = ~shapely.contains_xy(hole, arr.xy[:, 0], arr.xy[:, 1])
    arr = arr.take(np.flatnonzero(keep))
    stats = analyze(ex)
    window, _ = measured_window(ex, region)
    assert metrics.repetition(arr, ex, stats, window, room=region.shape).repetition > 0.95
    assert metrics.repetition(arr, ex, stats, window, room=box.shape).repetition < 0.95  # the hole read as room


@pytest.mark.parametrize("name", ["boulders", "gravel", "sand"])
def test_random_placement_on_a_small_square_is_not_repetition(name):
    # a square one exemplar wide: at most peaks few references have room, and a share over a
    # handful of them is the largest of several draws of noise (with 10 references as the
    # minimum, 2–4 of these 30 seeds read over 0.2: benchmarks/README.md "room07")
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    stats = analyze(ex)
    x0, y0, x1, y1 = ex.region.bounds
    region = Region.rectangle(max(x1 - x0, y1 - y0), max(x1 - x0, y1 - y0))
    window, _ = measured_window(ex, region)
    worst = max(
        metrics.repetition(arr, ex, stats, window, room=region.shape).repetition
        for arr in (synthesize(ex, region, "random", seed=seed, stats=stats).arrangement for seed in range(1, 31))
    )
    assert worst <= 0.2, worst


@pytest.mark.parametrize("dots", [12, 20, 30])
def test_a_small_exemplar_against_itself_is_not_repetition(dots):
    # where fewer than REPEAT_EX_MIN references have room the exemplar cannot show v (P_ex = 0)
    # and neither can the texture: a share of partners over min(n, 50) read up to 0.18 here
    rng = np.random.default_rng(dots)
    for _ in range(15):
        ex = exemplar([tuple(p) for p in rng.uniform(1.0, 19.0, (dots, 2))])
        rep = metrics.repetition(ex.motifs, ex, analyze(ex), ex.region, room=ex.region)
        assert rep.repetition == 0.0, rep


@pytest.mark.parametrize("name", BUNDLED)
def test_an_exemplar_against_itself_is_not_repetition_under_the_room_rule(name, monkeypatch):
    # the same rule on both sides: the reported peak's P_tex is the exemplar's own share there
    # (a drawn exemplar's region, not its box: chert-nodules is a disc) — read over however few
    # references have room; over at least REPEAT_ROOM_MIN, no more than it
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    stats = analyze(ex)
    rep = metrics.repetition(ex.motifs, ex, stats, ex.region, room=ex.region)
    assert rep.repetition == 0.0, rep
    assert rep.repetition_raw <= rep.repetition_exemplar + 1e-12, rep
    monkeypatch.setattr(repeats, "REPEAT_ROOM_MIN", 0)
    rep = metrics.repetition(ex.motifs, ex, stats, ex.region, room=ex.region)
    assert rep.repetition_raw == pytest.approx(rep.repetition_exemplar), rep
