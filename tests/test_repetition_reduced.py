"""What a viewer does not see as repetition (rep13e, issues 12 and 13).

1. **A tile that is its exact lattice, kinds and all** (Equinor 40100, 60100–60700, 65100,
   80100, 80200): dots on an exact lattice ``(16, 16) / (−16, 16)`` and on a second site lattice
   offset by ``(8, 8)``, half of whose sites hold the other kind.  Stamped, a dot's same-kind
   partner at ``(8, −56)`` is its ``(8, 8)`` neighbour one period down: the exemplar shows it,
   modulo its exact lattice.  The figure reads ``P_ex`` modulo that lattice; the same tile with
   its second lattice jittered has no exact order and stays caught.
2. **Rows**: on a drawn exemplar of rows (marsh), partners at a whole row offset meet as often
   as motifs thrown at random along a line, not over the plane.  Motifs at random along
   marsh's row lines score ≈ 0; a block of them copied to another place still scores high.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from conftest import stamp
from test_repetition_order import exemplar, measure

from svgtile import Region, analyze, metrics, read_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.engines.growth.rows import row_lines
from svgtile.metrics.order import EXACT, order_steps
from svgtile.metrics.repeats import (
    BOX,
    REPEAT_BIN,
    REPEAT_DIVIDE,
    REPEAT_MIN,
    _exemplar_shares,
    _reduced_shares,
    _rows_floor,
)
from svgtile.metrics.window import spacing


def two_site_lattices(jitter: float = 0.0, seed: int = 0):
    """A 64-unit tile like Equinor 40100: kind 0 on every site of the lattice (16, 16) / (−16, 16)
    through (2.5, 4.5); the offset lattice through (10.5, 12.5) holds kind 0 and kind 1 on
    alternate sites.  ``jitter``: the offset lattice's motifs moved by up to ± that per axis."""
    rng = np.random.default_rng(seed)
    points, kinds = [], []
    for j in range(4):
        for i in range(4):
            points.append((2.5 + 16 * i, 4.5 + 16 * j))
            kinds.append(0)
            points.append(tuple(np.array([10.5 + 16 * i, 12.5 + 16 * j]) + rng.uniform(-jitter, jitter, 2)))
            kinds.append((i + j) % 2)
    return exemplar(points, kinds, size=64.0, period=True)


def test_a_tile_that_is_its_exact_lattice_kinds_and_all_stamped_is_not_repetition():
    ex = two_site_lattices()
    s = spacing(analyze(ex))
    assert len(order_steps(ex, s, REPEAT_MIN * s)) == 2  # the exact lattice (16, 16) / (−16, 16)
    arr, region = stamp(ex, 5)
    rep = measure(ex, arr, region)
    assert rep.repetition <= 0.05, rep
    # the figure without the reduction charged it: the peak's own displacement is one the
    # 64-unit exemplar cannot show unwrapped, its reduction is its (8, 8) neighbour
    v = np.array([[8.0, -56.0]])
    q = REPEAT_BIN * s
    assert _exemplar_shares(ex, v, BOX * q, REPEAT_DIVIDE * s)[0] == 0.0
    steps = np.array([[16.0, 16.0], [-16.0, 16.0]])
    assert _reduced_shares(ex, v, steps, BOX * q, REPEAT_DIVIDE * s, EXACT * s)[0] >= 0.4


def test_the_same_tile_with_its_offset_lattice_jittered_stamped_is_still_repetition():
    # seed 4: no exact step left (with seed 0 the jittered half still leaves 62 % of the motifs
    # on the steps: the lattice, the period with it, is left out — order.py's known limit)
    ex = two_site_lattices(jitter=1.5, seed=4)
    s = spacing(analyze(ex))
    assert len(order_steps(ex, s, REPEAT_MIN * s)) == 0
    arr, region = stamp(ex, 5)
    assert measure(ex, arr, region).repetition >= 0.8


@pytest.mark.parametrize("jitter", [1.0, 1.5])
def test_a_reduction_counts_only_partners_on_the_lattice(jitter):
    """Seed 0: the jittered offset lattice leaves 62 % of the motifs on the exact steps, so the
    lattice is found.  At (8, −56) the exact tile shows its (8, 8) neighbours modulo the lattice
    (0.52); jittered, those neighbours are off the lattice, which does not repeat them, so the
    reduction must not count them (reviewer, 2026-12-04: it read 0.52 for the jittered tile too).
    The stamp's own period stays left out with the lattice: order.py's known limit."""
    v = np.array([[8.0, -56.0]])
    shares = []
    for j in (0.0, jitter):
        ex = two_site_lattices(jitter=j, seed=0)
        s = spacing(analyze(ex))
        steps = order_steps(ex, s, REPEAT_MIN * s)
        assert len(steps) == 2
        q = REPEAT_BIN * s
        shares.append(_reduced_shares(ex, v, steps, BOX * q, REPEAT_DIVIDE * s, EXACT * s)[0])
        everyone = _reduced_shares(ex, v, steps, BOX * q, REPEAT_DIVIDE * s, math.inf)[0]
    assert shares[0] >= 0.5
    assert shares[1] < 0.4 < everyone  # every partner counted: the jittered ones excused


def test_a_reduction_never_counts_a_motif_as_its_own_partner():
    # a shift next to a lattice point reduces to a short vector: no motif of an exact grid has a
    # partner there, so the share stays 0 although each motif lies within the box of itself + t
    pts = [((a + 0.5) * 5.0, (b + 0.5) * 5.0) for b in range(4) for a in range(4)]
    ex = exemplar(pts, period=True)
    steps = np.array([[5.0, 0.0], [0.0, 5.0]])
    assert _reduced_shares(ex, np.array([[15.3, 0.2]]), steps, 0.2, 1.0, 0.05)[0] == 0.0
    assert _reduced_shares(ex, np.array([[15.1, 0.0]]), steps, 0.2, 1.0, 0.05)[0] == 1.0  # the whole of (15, 0)


def marsh():
    ex = read_exemplar("exemplars/marsh.svg")
    return ex, analyze(ex), row_lines(ex)


def along_rows(ex, lines, size: float, seed: int) -> Arrangement:
    """Marsh's motif count for a ``size``² square, each on one of its row lines (plus an exemplar
    motif's residual) at a uniform random place along it: rows, and nothing between them."""
    rng = np.random.default_rng(seed)
    n = round(len(ex.motifs) * size * size / ex.region.area)
    pick = rng.integers(0, len(ex.motifs), n)
    xy = lines.onto(rng.uniform(0, size, (n, 2)), pick)  # onto the nearest line, plus the residual
    m = ex.motifs
    return Arrangement(m.kind[pick], xy, m.angle[pick], m.scale[pick])


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_motifs_at_random_along_marshs_rows_are_not_repetition(seed):
    ex, st, lines = marsh()
    assert abs(lines.along[1]) < 0.01  # marsh's rows run along x
    arr = along_rows(ex, lines, 300.0, seed)
    region = Region.rectangle(300, 300)
    rep = metrics.repetition(arr, ex, st, metrics.interior(ex, region))
    # seeds 1–12 read 0.004–0.061 (mean 0.038; random placement on marsh 0.01–0.02): the
    # maximum over the figure's 4 peaks of noise.  Against the plane's chance alone (the figure
    # before rep13e) they read 0.11–0.17 at the single mode, and more at the other peaks
    assert rep.repetition <= 0.07, rep
    assert rep.repetition_order >= 0.1, rep


def test_a_block_of_marsh_rows_copied_at_a_whole_row_offset_is_still_repetition():
    ex, st, lines = marsh()
    arr = along_rows(ex, lines, 300.0, 1)
    # the strip x < 70 stamped three more times along x, each copy 70 units on and 4 pitches down
    # (a run copied: within the figure's reach of 1.5 exemplar widths, 90 units)
    left = np.flatnonzero(arr.xy[:, 0] < 70)
    shift = np.array([70.0, 0.0]) + 4 * lines.pitch * lines.across
    xy = np.concatenate([arr.xy[left] + i * shift for i in range(4)])
    pick = np.tile(left, 4)
    keep = (xy[:, 1] >= 0) & (xy[:, 1] < 300)
    copied = Arrangement(arr.kind[pick][keep], xy[keep], arr.angle[pick][keep], arr.scale[pick][keep])
    region = Region.rectangle(300, 300)
    rep = metrics.repetition(copied, ex, st, metrics.interior(ex, region))
    assert rep.repetition >= 0.5, rep


def test_the_rows_floor_is_the_chance_along_a_line_at_whole_row_offsets_only():
    ex, _, lines = marsh()
    q = 0.7
    lam = np.array([0.01, 0.02])
    shifts = np.array([[50.0, 3 * lines.pitch], [50.0, 3.5 * lines.pitch], [80.0, 0.0]])
    floor = _rows_floor(ex, shifts, lam, q)
    res = lines.residual
    i, j = np.triu_indices(len(res), 1)
    meet = np.mean(np.abs(res[i] - res[j]) <= BOX * q)
    assert floor[0] == pytest.approx(np.mean(1 - np.exp(-lam * lines.pitch * 3 * q * meet)))
    assert floor[1] == 0.0 and floor[2] == floor[0]
    # a repeating tile has no row lines: no floor
    tile = dataclasses.replace(ex, period=(60.0, 60.0))
    assert not _rows_floor(tile, shifts, lam, q).any()
