"""The repetition figure leaves out the exemplar's own order (issue 12): a faithful texture of a
lattice or of rows does not repeat "too much", a stamped tile of irregular content still does.

Exemplars are built from their construction (exact lattices, jittered lattices, rows with a
random phase per row, every motif its own kind); expected values follow from it.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from conftest import stamp

from svgtile import Region, analyze, metrics
from svgtile.core.arrangement import Arrangement
from svgtile.metrics.order import explained, order_steps
from svgtile.svg.reader import parse_exemplar


def exemplar(points, kinds=None, size: float = 20.0, period: bool = False):
    """Dots (radius 0.8; kind ``k<i>`` a dot of radius 0.5 + 0.02 i) at ``points`` in a
    ``size × size`` region, a repeating tile of that period if ``period``."""
    kinds = [0] * len(points) if kinds is None else kinds
    used = sorted(set(kinds))
    defs = "".join(f'<symbol id="k{k}" overflow="visible"><circle r="{0.5 + 0.02 * k:.2f}"/></symbol>' for k in used)
    body = "".join(f'<use xlink:href="#k{k}" transform="translate({x:.4f} {y:.4f})"/>' for k, (x, y) in zip(kinds, points, strict=True))
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
           f'viewBox="0 0 {size:g} {size:g}"><defs>{defs}</defs>'
           f'<rect id="region" x="0" y="0" width="{size:g}" height="{size:g}" fill="none"/>{body}</svg>')  # fmt: skip
    ex = parse_exemplar(svg)
    return dataclasses.replace(ex, period=(size, size)) if period else ex


def grid(cells: int, cell: float = 5.0, jitter: float = 0.0, seed: int = 0) -> list[tuple[float, float]]:
    rng = np.random.default_rng(seed)
    return [tuple((np.array([a, b]) + 0.5) * cell + rng.uniform(-jitter, jitter, 2)) for b in range(cells)
            for a in range(cells)]  # fmt: skip




def measure(ex, arr, region):
    return metrics.repetition(arr, ex, analyze(ex), metrics.interior(ex, region))


@pytest.mark.parametrize("period", [False, True], ids=["drawn", "tile"])
def test_a_texture_of_an_exact_lattice_is_its_order_not_repetition(period):
    ex = exemplar(grid(4), period=period)
    rep = measure(ex, *stamp(ex, 10))
    assert sorted(tuple(abs(round(c, 6)) for c in v) for v in rep.order_steps) == [(0.0, 5.0), (5.0, 0.0)]
    assert rep.repetition_total > 0.95  # the figure before issue 12: every lattice repeats
    assert rep.repetition < 0.05


def test_a_stamped_jittered_lattice_is_repetition():
    # each dot within ±0.5 (0.1 s) of its site: a lattice to the analysis, but stamping copies
    # the jitter exactly at the tile's period — a near-lattice gravel's period is not excused
    ex = exemplar(grid(4, jitter=0.5, seed=3), period=True)
    assert analyze(ex).count_density > 0
    rep = measure(ex, *stamp(ex, 10))
    assert rep.order_steps == ()
    assert rep.repetition == rep.repetition_total
    assert rep.repetition > 0.95


def test_a_tile_whose_motifs_are_each_their_own_kind_is_not_excused_its_period():
    # exact sites, but every motif a kind of its own: its only same-kind neighbours are its own
    # copies one period (4 spacings) away — the analysis calls that a lattice (FGDC 626, 659, 732)
    ex = exemplar(grid(4), kinds=list(range(16)), period=True)
    rep = measure(ex, *stamp(ex, 10))
    assert rep.order_steps == ()
    assert rep.repetition > 0.95
    cells = np.array(rep.repetition_vector) / 20.0
    assert np.abs(cells - np.round(cells)).max() < 1e-6


def test_a_tile_of_one_icon_is_a_lattice_of_that_icon():
    # osm-carto's one icon per tile: its copies are its nearest neighbours, the period its order
    ex = exemplar([(2.5, 2.5)], size=5.0, period=True)
    rep = measure(ex, *stamp(ex, 24))
    assert len(rep.order_steps) == 2
    assert rep.repetition_total > 0.95
    assert rep.repetition < 0.05


def rows(n_rows: int, per_row: int, rng, step: float = 5.0) -> list[tuple[float, float]]:
    """Rows ``step`` apart of dots ``step`` apart, each row at a random phase along x."""
    phase = rng.uniform(0, step, n_rows)
    return [(float(phase[r] + step * i), step * (r + 0.5)) for r in range(n_rows) for i in range(per_row)]


def test_rows_excuse_the_row_step_only():
    ex = exemplar(rows(4, 4, np.random.default_rng(2)), size=20.0)
    assert [tuple(round(c, 6) for c in v) for v in order_steps(ex, 5.0, 10.0)] == [(5.0, 0.0)]
    # stamped: the tile's period is no multiple of the row step, its rows' phases repeat
    rep = measure(ex, *stamp(ex, 10))
    assert rep.repetition > 0.95
    assert abs(rep.repetition_vector[1]) > 15
    # a faithful texture: rows at the same step, each at a fresh phase.  Its rows' spacing still
    # puts a partner in the 3 × 3-bin box at a row offset for 1.5 of every 5 units of phase
    # (0.3, against the Poisson chance 0.09 the figure corrects for): the known limit of rows
    # (svgtile.metrics.order), far below the stamped tile's 1
    texture = np.array(rows(40, 40, np.random.default_rng(7)))
    arr = Arrangement(np.zeros(len(texture), np.int64), texture, np.zeros(len(texture)), np.ones(len(texture)))
    rep = measure(ex, arr, Region.rectangle(200, 200, -2.5, 0))
    assert rep.repetition_total > 0.95
    assert rep.repetition < 0.4


@pytest.mark.parametrize("steps", [[[5.0, 0.0]], [[5.0, 0.0], [2.0, 5.0]]], ids=["rows", "lattice"])
def test_explained_is_the_lattice_of_the_steps_within_the_box(steps):
    steps = np.array(steps)
    rng = np.random.default_rng(4)
    m = rng.integers(-6, 7, size=(200, len(steps))).astype(np.float64)
    on = m @ steps
    off = rng.uniform(0.15, 0.35, size=(200, 2)) * rng.choice([-1, 1], size=(200, 2))
    assert explained(on, steps, 0.1).all()
    assert explained(on + off / 4, steps, 0.1).all()
    assert not explained(on + off, steps, 0.1).any()  # 0.15–0.35 away on both axes
    assert not explained(on, np.zeros((0, 2)), 0.1).any()


def test_the_score_reports_both_figures_and_the_steps_left_out():
    from svgtile.apps.compare import format_score

    ex = exemplar(grid(4), period=True)
    arr, region = stamp(ex, 8)
    s = metrics.score(ex, analyze(ex), arr, region)
    plain = s.to_dict()
    assert plain["repetition"] < 0.05 and plain["repetition_total"] > 0.95
    assert len(plain["repetition_order_steps"]) == 2
    text = format_score(s).splitlines()
    rows = [line for line in text if line.startswith(("repetition", "  incl. exemplar's lattice"))]
    assert [float(r.split()[-1]) for r in rows] == [round(s.repetition, 3), round(s.repetition_total, 3)]


@pytest.mark.parametrize("jitter", [0.0, 1.2])
def test_with_no_order_left_out_the_total_is_the_mode_of_every_displacement(jitter, monkeypatch):
    """score11e: without exemplar steps the total's figures are read off the first peak (the
    same bin) instead of a second pass over the displacements (``_mode_share``, still run where
    steps are left out): the same figures, bit for bit."""
    from svgtile.metrics import repeats

    ex = exemplar(grid(4, jitter=2.0, seed=3), kinds=[i % 2 for i in range(16)], period=True)
    arr, region = stamp(ex, 8)
    arr = Arrangement(arr.kind, arr.xy + np.random.default_rng(1).uniform(-jitter, jitter, arr.xy.shape), arr.angle,
                      arr.scale)  # fmt: skip
    calls = []
    plain = repeats._mode_share
    monkeypatch.setattr(repeats, "_mode_share", lambda *a: calls.append(1) or plain(*a))
    fast = measure(ex, arr, region)
    assert fast.order_steps == () and calls == [], "an irregular tile: no steps, no second pass"
    # a step far beyond reach explains no displacement: the same displacements, with the second pass
    monkeypatch.setattr(repeats, "order_steps", lambda *a: np.array([[1e9, 0.0]]))
    slow = measure(ex, arr, region)
    assert calls == [1]
    assert (fast.repetition_total, fast.repetition_total_vector) == (slow.repetition_total, slow.repetition_total_vector)
    assert (fast.repetition, fast.repetition_raw) == (slow.repetition, slow.repetition_raw)
    assert fast.repetition_total > 0 and fast.repetition_total_vector is not None
