"""Probes of the repetition figure on hand-jittered row tiles (FGDC 619, 620, 670; issue 13).

Growth on these tiles scores repetition 1.000, as stamping the tile does.  These probes are the
textures a better engine could at best make from the tile's rows, and show what the figure
(:func:`svgtile.metrics.repetition`) reads in them (tests/test_growth_regular.py,
benchmarks/repetition_rows.py):

* :func:`shuffled_rows` — every row copy at its own random phase: nothing repeats across rows;
* :func:`markov_rows` — each row's phase the previous row's plus a step drawn from the tile's own
  row-to-row phase steps: the tile's local relations, its period broken;
* :func:`successive_modes` — the figure's mode, then the mode with it left out, and so on: what
  the figure would find if it also excused what it found first.

They are probes of the figure, not textures: motifs are not checked for conflicts.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.order import symmetry_steps
from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.metrics import interior
from svgtile.metrics.order import BOX, EXACT, explained, order_steps
from svgtile.metrics.pattern import (
    REPEAT_BIN,
    REPEAT_MIN,
    REPEAT_REACH,
    REPEAT_SAMPLES,
    _mode_share,
)
from svgtile.metrics.window import exemplar_size, in_window, motif_sample, spacing


def tile_rows(exemplar: Exemplar, gap: float) -> np.ndarray:
    """(m,) int: the row of each of a repeating tile's motifs, numbered by y — motifs whose y lie
    within ``gap`` user units of the next form one row (the FGDC tiles' rows run along x)."""
    y = exemplar.motifs.xy[:, 1]
    order = np.argsort(y, kind="stable")
    row = np.empty(len(y), np.int64)
    row[order] = np.r_[0, np.cumsum(np.diff(y[order]) > gap)]
    return row


def row_step(exemplar: Exemplar, stats: Stats) -> float:
    """The tile's exact along-row step, user units: its first exact symmetry step (x component),
    or the tile's width when it has none (a row's content always repeats by the width)."""
    tol = EXACT * spacing(stats)
    steps = symmetry_steps(exemplar.motifs.xy, exemplar.motifs.kind, exemplar.period, tol)
    along = [abs(s.vector[0]) for s in steps if abs(s.vector[1]) <= tol and abs(s.vector[0]) > tol]
    return float(along[0]) if along else float(exemplar.period[0])


def _rows_over(exemplar: Exemplar, region: Region, row: np.ndarray, shift: np.ndarray) -> Arrangement:
    """The tile over ``region`` with row ``r`` of tile copy ``b`` (counted in y) moved along x by
    ``shift[b, r]``; the copies run from below ``region``'s bounds."""
    ex = exemplar.motifs
    w, h = exemplar.period
    x0, y0, x1, _ = region.shape.bounds
    ia = np.arange(math.floor((x0 - w) / w), math.ceil(x1 / w) + 1)
    ib = np.arange(math.floor((y0 - h) / h), math.floor((y0 - h) / h) + len(shift))
    B, A, S = np.meshgrid(np.arange(len(ib)), ia, np.arange(len(ex)), indexing="ij")
    xy = np.c_[(ex.xy[S, 0] + A * w + shift[B, row[S]]).ravel(), (ex.xy[S, 1] + ib[B] * h).ravel()]
    keep = shapely.contains_xy(region.shape, xy[:, 0], xy[:, 1])
    s = S.ravel()[keep]
    return Arrangement(ex.kind[s], xy[keep], ex.angle[s], ex.scale[s])


def _copies(exemplar: Exemplar, region: Region) -> int:
    y0, y1 = region.shape.bounds[1], region.shape.bounds[3]
    h = exemplar.period[1]
    return math.ceil(y1 / h) + 1 - math.floor((y0 - h) / h)


def shuffled_rows(exemplar: Exemplar, stats: Stats, region: Region, *, rng: np.random.Generator) -> Arrangement:
    """The tile's rows over ``region``, every row copy moved along x by its own uniform shift in
    [0, row step): each row keeps the tile's exact content, no two rows their tile relation."""
    row = tile_rows(exemplar, 0.5 * spacing(stats))
    shift = rng.uniform(0, row_step(exemplar, stats), (_copies(exemplar, region), row.max() + 1))
    return _rows_over(exemplar, region, row, shift)


def row_phases(exemplar: Exemplar, stats: Stats) -> tuple[np.ndarray, np.ndarray]:
    """((n,), (n,)) float: each tile row's phase (its first motif of its lowest kind, x modulo the
    row step) and the phase step from it to the next row (the last to the first row's copy
    above), both in [0, row step), user units."""
    m = exemplar.motifs
    row = tile_rows(exemplar, 0.5 * spacing(stats))
    step = row_step(exemplar, stats)
    phase = np.array([np.min(m.xy[(row == r) & (m.kind == m.kind[row == r].min()), 0] % step)
                      for r in range(row.max() + 1)])  # fmt: skip
    return phase, np.diff(np.r_[phase, phase[0]]) % step


def markov_rows(exemplar: Exemplar, stats: Stats, region: Region, *, rng: np.random.Generator) -> Arrangement:
    """The tile's rows over ``region``, in their tile order, each row's phase the previous row's
    plus a phase step drawn from the tile's own (:func:`row_phases`): neighbouring rows relate
    as in the tile, and the phase wanders, so the tile's period is gone."""
    row = tile_rows(exemplar, 0.5 * spacing(stats))
    n = row.max() + 1
    step = row_step(exemplar, stats)
    phase, steps = row_phases(exemplar, stats)
    copies = _copies(exemplar, region)
    walk = phase[0] + np.r_[0.0, np.cumsum(steps[rng.integers(0, n, copies * n - 1)])]
    shift = (walk.reshape(copies, n) - phase[None]) % step
    return _rows_over(exemplar, region, row, shift)


def successive_modes(arr: Arrangement, exemplar: Exemplar, stats: Stats, region: Region, rounds: int,
                     ) -> list[tuple[float, tuple[float, float] | None]]:  # fmt: skip
    """The repetition figure's (value, vector) ``rounds`` times, each round with the displacements
    near the vectors found before (and their multiples: a row) left out, as the figure leaves out
    the exemplar's order (:func:`svgtile.metrics.order.explained`).  The first is the figure's own
    (steps 1–2 of :func:`svgtile.metrics.repetition` written again here, steps 3–5 its own code)."""
    window = interior(exemplar, region)
    inside = in_window(arr, window)
    s = spacing(stats)
    q = REPEAT_BIN * s
    r0 = min(REPEAT_MIN * s, max(exemplar_size(exemplar)) / 2)
    reach = max(REPEAT_REACH * max(exemplar_size(exemplar)), 2 * r0)
    ref = motif_sample(arr, np.flatnonzero(inside), REPEAT_SAMPLES)
    lam = np.bincount(arr.kind[inside], minlength=len(stats.frequency)) / window.area
    chance = float(np.mean(-np.expm1(-lam[arr.kind[ref]] * 9 * q * q)))
    who, disp = [], []
    for c in np.unique(arr.kind[ref]):
        mine, peers = ref[arr.kind[ref] == c], np.flatnonzero(arr.kind == c)
        found = cKDTree(arr.xy[mine]).sparse_distance_matrix(cKDTree(arr.xy[peers]), reach, output_type="ndarray")
        near = (found["v"] >= r0) & (found["v"] < reach)
        who.append(mine[found["i"][near]])
        disp.append(arr.xy[peers[found["j"][near]]] - arr.xy[mine[found["i"][near]]])
    who, disp = np.concatenate(who), np.concatenate(disp)
    keep = ~explained(disp, order_steps(exemplar, s, REPEAT_MIN * s), BOX * q)
    out = []
    for _ in range(rounds):
        value, _raw, vector = _mode_share(who[keep], disp[keep], ref, len(arr), q, reach, chance)
        out.append((value, vector))
        if vector is None:
            break
        keep &= ~explained(disp, np.array([vector]), BOX * q)
    return out
