"""Which displacements the exemplar's own order explains (for :func:`svgtile.metrics.repetition`).

A texture of a lattice repeats at every lattice vector, however it was made: a faithful
texture of dots on a square grid, or of dashes in rows, has a same-kind partner one, two, …
steps away for every motif, as the exemplar has.  That repetition is the exemplar's *order*,
not a flaw of the engine.  What the eye objects to is repetition at a displacement the order
does not explain: the tile's period stamped over irregular content, a patch copied.  This
module finds the translations the exemplar itself is built on, so that the repetition figure
can leave them out.

**The rule.**  The candidates are the exemplar's dominant same-kind neighbour steps
(:func:`svgtile.analysis.order.read_order`, at most two, across the edges of a repeating tile).
A step ``g`` is part of the order when

1. it is **exact**: at least :data:`~svgtile.analysis.order.SUPPORT` of the exemplar's motifs
   have a same-kind motif within :data:`EXACT` mean spacings of ``x + g`` or ``x − g``.  The
   analysis finds steps with a tolerance of 0.2 s (a hand-jittered lattice has rows too); the
   repetition figure bins displacements at 0.1 s, so a step excuses repetition only where the
   exemplar repeats to that precision.  A near-lattice gravel (each pebble jittered by ~0.1 s
   about its site) is a lattice to the analysis but not here: stamping its tile copies its
   jitter exactly, which is repetition of irregular content, and it is not excused;
2. it is **not the tile's own period** (a non-zero integer combination ``(i w, j h)`` of the
   period), unless it is shorter than ``REPEAT_MIN`` mean spacings.  Every motif of a tile
   meets its own copy one period away, so the period always looks like an exact step with
   full support (FGDC 626, 659, 732: every fragment its own kind, a "lattice" of period 6–7 s).
   Only a tile of a handful of motifs (osm-carto's one icon per tile) has its copies as its
   nearest neighbours, and then the period *is* the pattern's lattice.

The steps kept generate the explained set: every integer combination ``m₁ g₁ + m₂ g₂`` (one
step: ``m g``, rows), each with a square of ± :data:`BOX` bins (the figure's own 3 × 3-bin
box) around it.  A true lattice tile's period is such a combination and is excused; an
irregular tile's is not, whatever its size.

Known limits: kinds placed irregularly on a lattice of sites (a kind's same-kind neighbours
at no common step) give no exact same-kind step; their lattice is not excused.  The other way
round, when most motifs do share the steps (support ≥ 0.6), the whole lattice is excused, and a
minority kind's irregular placement repeated at the tile's period goes with it (and, since
rep13e, its repeats at the period plus a displacement the exemplar shows: ``P_ex`` is read
modulo the lattice, :func:`svgtile.metrics.shown._reduced_shares`).  Equinor 41000 and 61000
(70 % support), once read as such a case, are not: their minority kind is triplets on an exact
lattice of its own, and the tile engine scores 0.000 there since rep13e (0.157 before).  Rows (one
step) excuse the multiples of the row step only: rows at a fixed spacing but a free phase put
same-kind partners at a row offset ~3 times as often as the Poisson chance; since issue 13 the
figure compares that with the exemplar's own share at the same displacement
(:mod:`svgtile.metrics.repeats`), which such rows show, so it is excused there instead.
"""

from __future__ import annotations

import numpy as np

from svgtile.analysis.order import EXACT_STEP, SUPPORT, exact_support, is_period, read_order
from svgtile.core.exemplar import Exemplar

#: A step is exact when its partners lie within this many mean spacings of it (half a bin of
#: the repetition figure, whose bins are 0.1 s): the analysis's own tolerance, one value for both.
EXACT = EXACT_STEP
#: A displacement within this many bins (per axis) of a lattice point is explained: the
#: figure counts partners in the 3 × 3 bins around its mode, ± 1.5 bins of its centre.
BOX = 1.5


def order_steps(exemplar: Exemplar, spacing: float, shortest_period: float) -> np.ndarray:
    """The exemplar's exact neighbour steps that are its order (the module docstring's rule).

    Parameters
    ----------
    exemplar : the exemplar (its motifs, and ``period`` if it is a repeating tile)
    spacing : float, user units, the mean spacing ``s`` the figure is expressed in
    shortest_period : float, user units; a step that is the tile's own period counts only
        when shorter than this (``REPEAT_MIN · s``)

    Returns
    -------
    (m, 2) float array, user units, m ∈ {0, 1, 2}: the generators, most supported first
    """
    order = read_order(exemplar)
    if not order.steps or not spacing > 0:
        return np.zeros((0, 2))
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    period = getattr(exemplar, "period", None)
    tol = EXACT * spacing
    kept = []
    for step in order.steps:
        g = np.asarray(step.vector, dtype=np.float64)
        if period is not None and is_period(g, period, tol) and not np.hypot(*g) < shortest_period:
            continue
        if exact_support(xy, kind, period, g, tol) >= SUPPORT:
            kept.append(g)
    return np.array(kept, dtype=np.float64).reshape(-1, 2)


def explained(disp: np.ndarray, steps: np.ndarray, half: float) -> np.ndarray:
    """(p,) bool: the displacements within ``half`` (per axis) of a point of the lattice of ``steps``.

    Parameters
    ----------
    disp : (p, 2) float array, user units
    steps : (m, 2) float array, the generators (:func:`order_steps`); none explains nothing,
        one generates the multiples ``m g`` (rows), two the lattice ``m₁ g₁ + m₂ g₂``
    half : float, user units, half the side of the square around each lattice point
    """
    if len(steps) == 0 or len(disp) == 0:
        return np.zeros(len(disp), dtype=bool)
    dx, dy = disp[:, 0], disp[:, 1]
    if len(steps) == 1:
        gx, gy = steps[0]
        m = np.round((dx * gx + dy * gy) / (gx * gx + gy * gy))
        return (np.abs(dx - m * gx) <= half) & (np.abs(dy - m * gy) <= half)
    (ax, ay), (bx, by) = steps[:2]
    det = ax * by - ay * bx
    # lattice coordinates c = B⁻¹ d, B = [g₁ g₂]; written out per axis (a (p, 2) @ (2, 2) product
    # of millions of rows is many times slower)
    c1 = np.floor((by * dx - bx * dy) / det)
    c2 = np.floor((ax * dy - ay * dx) / det)
    # the nearest lattice point is among the four around the real coordinates for any basis
    # the analysis reports (its steps are the two shortest well-supported, ≥ 20° apart)
    hit = np.zeros(len(disp), dtype=bool)
    for i in (0.0, 1.0):
        for j in (0.0, 1.0):
            rx = dx - (c1 + i) * ax - (c2 + j) * bx
            ry = dy - (c1 + i) * ay - (c2 + j) * by
            hit |= (np.abs(rx) <= half) & (np.abs(ry) <= half)
    return hit


__all__ = ["BOX", "EXACT", "explained", "order_steps"]
