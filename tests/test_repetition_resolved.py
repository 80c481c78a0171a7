"""What the repetition figure cannot resolve it does not charge (rep13f, issues 12 and 13).

On a repeating tile ``P_ex`` reads each kind at its own divisor of a shift, and a row or lattice
jittered by less than the figure's square as shown at every multiple
(:func:`svgtile.metrics.shown._kind_shares`).  Known answers on a hand-made tile of rows — dots
exact every 2 units, dashes every 5 jittered along their row — and on FGDC 670, the tile that
made the case: rows of dots 26 to the width between rows of dashes 5 to the width, each dash
jittered by up to 0.17 along its row.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import stamp
from test_growth_regular import FGDC, needs_data
from test_repetition_order import exemplar, measure

from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import score
from svgtile.metrics.repeats import _exemplar_shares, _kind_shares
from svgtile.metrics.window import spacing

#: The hand-made tile's figure: its spacing is ≈ 2.67, so the bin is 0.267 and the square ± 0.4.
HALF, SHORTEST = 0.4, 1.0
#: The tile's width stamped, its height, and both.
SHIFTS = np.array([[20.0, 0.0], [0.0, 20.0], [20.0, -20.0]])


def rows_tile(dash_jitter: float, seed: int = 0):
    """A 20 × 20 repeating tile of four rows: dots (kind 0) exact every 2 units, and 2.5 above
    each row of dots a row of dashes (kind 1) every 5 units, each moved along its row by up to
    ± ``dash_jitter``."""
    rng = np.random.default_rng(seed)
    pts, kinds = [], []
    for r in range(4):
        y = 2.5 + 5 * r
        pts += [(x, y) for x in np.arange(0.5, 20, 2.0)]
        kinds += [0] * 10
        pts += [(x + rng.uniform(-dash_jitter, dash_jitter), y + 2.5) for x in np.arange(1.5, 20, 5.0)]
        kinds += [1] * 4
    return exemplar(pts, kinds, period=True)


@pytest.mark.parametrize("jitter", [0.15, 0.2])
def test_rows_jittered_within_the_square_show_the_tiles_period(jitter):
    # two dashes' jitters differ by at most 2 · jitter ≤ 0.4: each step holds to the square at
    # every multiple the tile shows, and each kind is read at its own step (dots 10, dashes 4 to
    # the width), so the period — along x, along y and both — is shown by every motif
    ex = rows_tile(jitter)
    assert np.all(_kind_shares(ex, SHIFTS, HALF, SHORTEST) == 1.0)
    # read as before (and as a drawn exemplar is): one divisor for every kind, to the square ÷ m
    assert np.all(_exemplar_shares(ex, SHIFTS[[0, 2]], HALF, SHORTEST) < 1.0)


def test_rows_jittered_beyond_the_square_do_not():
    # up to ± 0.4: dashes' jitters differ by up to 0.8, twice the square's half: some dash misses
    # its partner at some multiple, so the tile does not show its width for every dash …
    ex = rows_tile(0.4)
    shares = _kind_shares(ex, SHIFTS, HALF, SHORTEST)
    assert shares[0] < 1.0 and shares[2] < 1.0
    # … and its stamp, which repeats every dash at the width, is charged
    rep = measure(ex, *stamp(ex, 10))
    assert rep.repetition >= 0.8


@needs_data
@pytest.mark.parametrize("engine", ["tile", "growth"])
def test_fgdc_670_kept_is_not_charged_its_period(engine):
    """FGDC 670 stamped, and grown (on the tile's sites: the same motifs), scored 1.000 at the
    tile's period before rep13f; its dashes' jitter is below the figure's square, its dots exact."""
    ex, st = load_exemplar(str(FGDC / "670.svg"), as_tile=True, warn=lambda m: None)
    w, h = ex.period
    region = Region.rectangle(4 * w, 4 * h)
    arr = synthesize(ex, region, engine, seed=1, stats=st, boundary="centroid").arrangement
    s = score(ex, st, arr, region)
    assert s.repetition <= 0.2, (s.repetition, s.repetition_vector)
    assert s.repetition_total >= 0.95  # it does repeat, every motif, at the period
    s = spacing(st)
    assert _kind_shares(ex, np.array([[w, 0.0]]), 1.5 * 0.1 * s, 0.5 * s)[0] == 1.0


@pytest.mark.parametrize(("name", "rows"), [("lattice", 1.92), ("rows", 2.0)])
def test_a_step_that_drifts_off_the_tile_is_a_seam_and_its_stamp_is_charged(name, rows):
    # dots every 1.92 along x (and across, or in rows exactly 2 apart) in a tile of 20: each step
    # holds to the square for the first multiples, but ten of them make 19.2, not 20 — a seam of
    # 2.72 at every period, which a texture keeping the step does not repeat (the reviewer's case:
    # 0.000 when only the first three multiples were asked)
    pts = [(0.5 + 1.92 * i, 0.5 + rows * r) for r in range(10) for i in range(10)]
    ex = exemplar(pts, period=True)
    # only the multiples the tile can show are asked: the motifs of its right half see fewer
    # than the five steps it takes the drift to leave the square, and pass
    assert _kind_shares(ex, np.array([[20.0, 0.0]]), HALF, SHORTEST)[0] < 0.8
    rep = measure(ex, *stamp(ex, 8))
    assert rep.repetition >= 0.8, rep


def test_a_shift_along_both_axes_is_shown_as_far_as_both_parts_surely_are():
    # the hand-made rows (dashes within the square): the width and the height each shown by
    # every motif, so the diagonal is; and its bound is the two parts' shares less one
    ex = rows_tile(0.15)
    along, up, both = _kind_shares(ex, SHIFTS, HALF, SHORTEST)
    assert along == up == both == 1.0
