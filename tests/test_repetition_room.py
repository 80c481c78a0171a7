"""The repetition figure asks each reference for room (step 4 of
:func:`svgtile.metrics.repeats.repetition`): ``P_tex(v)`` is the share of the references whose
square at ``v`` lies inside the texture's region, as ``P_ex`` is the share of the exemplar's motifs
whose square stays inside the exemplar.  Counting every reference read a texture two periods wide,
where half the references have no room one period on, as half as repetitive as it is (FGDC 654's
stamped tile scored 0.00 at 2 × 2 tiles and 1.00 at 3 × 3).
"""

from __future__ import annotations

import pytest
from conftest import stamp
from test_repetition_order import exemplar, grid

from svgtile import analyze, metrics, read_exemplar
from svgtile.analysis.window import measured_window

BUNDLED = ["boulders", "breccia", "breccia-plain", "chert-nodules", "gravel", "marsh", "sand", "scrub", "shale", "till"]


@pytest.mark.parametrize("tiles", [2, 3])
def test_a_stamp_of_irregular_content_two_periods_wide_is_repetition(tiles):
    # dots jittered off their sites (no exact order: nothing is excused), stamped 2 × 2 and 3 × 3
    ex = exemplar(grid(4, jitter=0.5, seed=3), period=True)
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


@pytest.mark.parametrize("name", BUNDLED)
def test_an_exemplar_against_itself_is_not_repetition_under_the_room_rule(name):
    # the same rule on both sides: P_tex = P_ex at every peak
    ex = read_exemplar(f"exemplars/{name}.svg")
    rep = metrics.repetition(ex.motifs, ex, analyze(ex), ex.region, room=ex.region)
    assert rep.repetition == 0.0, rep
    assert rep.repetition_raw == pytest.approx(rep.repetition_exemplar), rep
