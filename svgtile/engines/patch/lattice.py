"""Copy steps on the exemplar's own lattice, for ``--grid lattice`` (issue 12).

AlMeraj et al. 2013 §3.2 step copies by ``w(1 − σ)``, a length that has nothing to do with the
pattern: where the exemplar is ordered (rows, a lattice, a repeating tile), copies laid at that
step break the rows at every seam.  Here the steps are the lattice vectors of the exemplar
(:func:`svgtile.analysis.order.read_order`) nearest to ``(w(1 − σ), 0)`` and ``(0, h(1 − σ))``,
so that a row of one copy continues into the next and seams fall between motifs.
"""

from __future__ import annotations

import itertools

import numpy as np

from svgtile.analysis.order import Order
from svgtile.core import cellrng
from svgtile.core.exemplar import Exemplar

#: Hash streams of the lattice layout's turns and shifts (the patch engine's own are 0–5, in ``density``).
_FLIP, _SHIFT = 6, 7

#: Largest multiple of a lattice step tried when composing a copy step.
MULTIPLES = 40


def lattice_steps(order: Order, size: tuple[float, float], overlap: float) -> np.ndarray:
    """(2, 2) float array, user units: the two copy steps, rows ``X`` then ``Y``.

    Candidates are the integer combinations of the exemplar's lattice steps (one step for rows),
    or, for a pattern tile, of its period, which is exact where steps read from the motifs are
    not (a copy step made of 10 steps each 1 % off leaves a seam); ``X`` is the one nearest to ``(w(1 − σ), 0)`` and
    ``Y`` the one nearest to ``(0, h(1 − σ))`` among those not parallel to ``X`` (the copies must
    cover the plane).  Without a lattice step or a period this is the square grid.

    Parameters
    ----------
    order : the exemplar's order
    size : (w, h), the input region's bounding size, user units
    overlap : σ (almeraj2013 §3.2)
    """
    w, h = size
    targets = np.array([[w * (1.0 - overlap), 0.0], [0.0, h * (1.0 - overlap)]])
    basis = [np.asarray(s.vector, dtype=np.float64) for s in order.steps[:2]]
    if order.period is not None:
        basis_p = [np.array([order.period[0], 0.0]), np.array([0.0, order.period[1]])]
    else:
        basis_p = []
    candidates = [np.zeros((0, 2))]
    if basis_p:  # a tile's period is exact; steps read from hand-placed motifs are not
        basis = []
    if basis:
        m = np.arange(-MULTIPLES, MULTIPLES + 1, dtype=np.float64)
        combos = itertools.product(m, repeat=len(basis))
        coef = np.array(list(combos))
        candidates.append(coef @ np.array(basis))
    if basis_p:
        m = np.arange(-3, 4, dtype=np.float64)
        coef = np.array(list(itertools.product(m, repeat=2)))
        candidates.append(coef @ np.array(basis_p))
    cand = np.vstack(candidates)
    cand = cand[np.hypot(cand[:, 0], cand[:, 1]) > 0.5 * min(targets[0, 0], targets[1, 1])]
    if len(cand) == 0:
        return targets
    out = targets.copy()
    x = cand[np.argmin(np.hypot(*(cand - targets[0]).T))]
    if abs(x[0]) >= 0.5 * targets[0, 0] and abs(x[1]) <= 0.5 * targets[1, 1]:
        out[0] = x
    cross = np.abs(out[0, 0] * cand[:, 1] - out[0, 1] * cand[:, 0])
    ok = cross >= 0.5 * targets[0, 0] * targets[1, 1]
    if ok.any():
        c = cand[ok]
        y = c[np.argmin(np.hypot(*(c - targets[1]).T))]
        if abs(y[1]) >= 0.5 * targets[1, 1] and abs(y[0]) <= 0.5 * targets[0, 0]:
            out[1] = y
    return out


def lattice_pivot(exemplar: Exemplar) -> np.ndarray:
    """(2,) float array, user units, relative to the input region's centre: the motif nearest
    the centre, about which a copy is turned by 180° (a lattice point, so the turned lattice is
    the same lattice)."""
    x0, y0, x1, y1 = exemplar.region.bounds
    local = exemplar.motifs.xy - np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    return local[np.argmin(np.hypot(local[:, 0], local[:, 1]))]


def lattice_variation(order: Order, key: int, A: np.ndarray, B: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each copy's turn (0° or 180°) and shift by a lattice step, hashed from its cell ``(A, B)``.

    For a drawn exemplar: a half turn about a lattice point (:func:`lattice_pivot`) and a shift by
    a lattice step both map a lattice onto itself, so rows run on across copies while the copies
    stop repeating the exemplar's own jitter at one period (the bundled marsh: repetition 0.42
    with turns alone, 0.10 with both; the gaps they open where copies meet are filled by
    density repair).  A pattern tile gets neither: its copies meet edge to edge on its period,
    without seams, and a turned tile's motifs (centroids of dashes of different lengths, off the
    lattice by a little) would no longer meet its neighbours' rows.

    Returns
    -------
    theta : (c,) float array, degrees, 0 or 180
    shift : (c, 2) float array, user units, ``i·v1 + j·v2`` with ``i, j ∈ {−1, 0, 1}``
    """
    theta = np.zeros(len(A))
    shift = np.zeros((len(A), 2))
    if order.period is not None:
        return theta, shift
    theta = np.where(cellrng.uniform(key, _FLIP, A, B) < 0.5, 0.0, 180.0)
    for n, step in enumerate(order.steps[:2]):
        i = np.floor(3.0 * cellrng.uniform(key, _SHIFT, A, B, n)) - 1.0
        shift += i[:, None] * np.asarray(step.vector)[None, :]
    return theta, shift
