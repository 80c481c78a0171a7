"""Filling the gaps growth leaves on a repeating tile (Ijiri et al. 2008, §5.4, Fig. 6b/6d).

Growth fronts that start from different seeds — two cells, two refill rounds, the two sides of a
hole the exact conflict check cut — can meet out of step, and the motifs that would close the
seam collide and are removed.  The refill rounds of :mod:`.engine` regrow such a hole from *one*
predicted slot per place (a seed within r_short of another is merged into it, Fig. 6b), so when
that slot collides (Fig. 6d) the hole stays.  And a tile's motifs that no whole ring places (§4:
FGDC 670 has 65 of 248) are never grown at all, only matched against.

The gap fill keeps every prediction instead: each placed motif predicts the motifs the tile has
around its exemplar motif — every motif of the periodic block within the ring radius, the
ring-less ones included — turned by the motif's own rotation.  The exact footprint check (no
overlap, the distance rule, no barrier) decides which fit, preferring a position more placed
motifs agree on.  Rounds repeat while they add motifs: a filled motif predicts the next ones.

Tiles only: on a drawn exemplar the ring slots of every placed motif fill whatever room the
distance rule leaves, denser than the exemplar (gravel at 300 × 300, seed 1: density ratio
1.12 → 1.31 and likeness 0.50 → 0.39; shale 0.98 → 1.11 and 0.75 → 0.66), while on a tile the
predictions are the tile's own sites (:meth:`.engine.Growth.on_sites`) and cannot over-fill.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from svgtile.analysis.stats import periodic_block
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.engines.growth.connectivity import Rings

#: Rounds of gap filling per piece; each round's motifs predict the next round's.
ROUNDS = 3


@dataclass(frozen=True, eq=False)
class Predictions:
    """What each exemplar motif predicts around itself, as a compressed table (p predictions).

    Attributes
    ----------
    start : (m + 1,) int array — exemplar motif ``s`` predicts rows ``start[s]:start[s + 1]``
    offset : (p, 2) float array, user units — the predicted motif relative to ``s``, unrotated
    sub : (p,) int array — which exemplar motif is predicted (its kind, angle and scale are copied)
    """

    start: np.ndarray
    offset: np.ndarray
    sub: np.ndarray


def predictions(exemplar: Exemplar, rings: Rings, radius: float | None = None) -> Predictions:
    """The prediction table of a repeating tile ``exemplar``: around each of its motifs, every
    motif of the periodic block (3 × 3 tiles) within the ring radius × 1.05 (or ``radius``, user
    units), itself excepted."""
    if exemplar.period is None:
        raise ValueError("predictions are made for a repeating tile only (see the module docstring)")
    m = len(exemplar.motifs)
    block = periodic_block(exemplar.motifs, exemplar.period)
    pairs = cKDTree(exemplar.motifs.xy).sparse_distance_matrix(cKDTree(block.xy), radius or rings.radius * 1.05,
                                                               output_type="ndarray")  # fmt: skip
    i, j = pairs["i"].astype(np.int64), pairs["j"].astype(np.int64)
    keep = j != i  # block motif i is tile motif i itself
    i, j = i[keep], j[keep]
    order = np.lexsort((j, i))
    i, j = i[order], j[order]
    start = np.searchsorted(i, np.arange(m + 1)).astype(np.int64)
    return Predictions(start, block.xy[j] - exemplar.motifs.xy[i], j % m)


def candidates(pred: Predictions, exemplar: Exemplar, placed: Arrangement, sub: np.ndarray,
               ) -> tuple[Arrangement, np.ndarray, np.ndarray]:  # fmt: skip
    """The motifs ``placed`` predict, merged where predictions coincide (to the written digit).

    Parameters
    ----------
    pred : the exemplar's :func:`predictions`
    exemplar : the exemplar (the predicted motifs' kinds, angles and scales)
    placed : the predicting motifs (n)
    sub : (n,) int array — the exemplar motif each copies

    Returns
    -------
    arrangement : the c distinct predicted motifs, quantized
    sub : (c,) int array — the exemplar motif each copies
    support : (c,) int array — how many placed motifs predict it
    """
    count = pred.start[sub + 1] - pred.start[sub]
    src = np.repeat(np.arange(len(placed)), count)
    if not len(src):
        return Arrangement.empty(), np.zeros(0, np.int64), np.zeros(0, np.int64)
    row = pred.start[sub][src] + (np.arange(len(src)) - np.repeat(np.cumsum(count) - count, count))
    ex = exemplar.motifs
    theta = np.radians(placed.angle[src] - ex.angle[sub[src]])
    c, s = np.cos(theta), np.sin(theta)
    v = pred.offset[row]
    xy = placed.xy[src] + np.c_[c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]]
    psub = pred.sub[row]
    angle = (ex.angle[psub] + np.degrees(theta) + 180.0) % 360.0 - 180.0
    arr = Arrangement(ex.kind[psub], xy, angle, ex.scale[psub]).quantized(DECIMALS)
    key = np.c_[psub, np.round(arr.xy * 10**DECIMALS).astype(np.int64), np.round(arr.angle * 10**DECIMALS)]
    _, first, support = np.unique(key, axis=0, return_index=True, return_counts=True)
    return arr.take(first), psub[first], support.astype(np.int64)
