"""Row lines: the row structure of a drawn exemplar, held by growth and relaxation.

Ijiri et al. 2008 grow an arrangement from ring shapes alone (§5.4) and relax it towards them
(§5.5, eq. 5).  A ring knows its neighbours' positions but not where its row runs: on a hand-drawn
exemplar of rows (marsh's tufts) every ring is a little different, so the best match for a seed
is a ring whose row neighbours sit a little higher or lower and whose next row lies a little
nearer or farther.  Those errors add up along a growth front — rows climb and bunch — and
fronts grown from two seeds (two world cells) meet with their rows out of step, so the seams
crowd and tear.  The exemplar itself says what is kept there: its motifs lie on evenly spaced
lines (:func:`svgtile.analysis.order.read_order` finds the step along them), each motif a little
off its line.

This module reads those lines and makes them world lines: line ``k`` is at the across
coordinate ``offset + k · pitch`` everywhere (the exemplar's own lines, continued), so every
cell grows onto the same lines and the seams join.  The growth engine (:mod:`.engine`) puts a
cell's first seed on a line, and relaxation (:func:`svgtile.engines.growth.relax.relax`) holds
each grown motif at its nearest line plus its exemplar motif's own offset from its line — a term
added to eq. (5) alongside the ring terms, like the paper's constraints of eq. (6) but soft.

Only a drawn exemplar (not a repeating tile, whose motifs the engine moves to the tile's sites)
with rows, grown unturned (``--rotation none``), has row lines: turned rings (fit, flow) have no
fixed across direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.order import read_order
from svgtile.core.arrangement import Arrangement
from svgtile.core.conflicts import find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import Prototype, motif_radius, world_footprints

#: Fewest rows an exemplar must show for its lines to be trusted (a pitch from two rows is one gap).
MIN_ROWS = 3
#: Rounds of :func:`slide_apart`; each moves the motifs of the conflicting pairs found in it (a motif
#: pressed from both sides is pushed both ways, so a crowded run needs several).
SLIDE_ROUNDS = 8
#: Share of a pair's lack each of two new motifs gives way by: more than half, so that a crowded
#: run opens in fewer rounds (marsh at 300 × 300: 0.5 took 5.7 rounds a cell and 2.2 s, 0.75
#: 4.9 and 1.7 s, L alike within the seeds' spread; benchmarks/README.md, "Row lines").
SLIDE_SHARE = 0.75
#: :func:`slide_apart` opens a gap this much wider than the distance rule asks (user units), so
#: that rounding to the written digits does not close it again.
SLIDE_MARGIN = 0.02
#: Weight of the row term against one ring term of eq. (5): a motif one unit off its line costs
#: as much as a neighbour ``√ROW_WEIGHT`` units off its ring position.
ROW_WEIGHT = 4.0


@dataclass(frozen=True, eq=False)
class RowLines:
    """Evenly spaced lines the rows of an exemplar run along, in world coordinates.

    Attributes
    ----------
    along : (2,) float array — unit vector along the rows
    across : (2,) float array — unit vector across them (``along`` turned by +90°)
    pitch : float, user units — distance between successive lines
    offset : float, user units — the across coordinate ``xy · across`` of line 0
    residual : (m,) float array, user units — each exemplar motif's across offset from its row's
        mean (the hand's jitter, kept; the rows' own uneven spacing is not)
    """

    along: np.ndarray
    across: np.ndarray
    pitch: float
    offset: float
    residual: np.ndarray

    def coordinate(self, xy: np.ndarray) -> np.ndarray:
        """(n,) float: the across coordinate of points ``xy`` ((n, 2), user units)."""
        return np.asarray(xy, float).reshape(-1, 2) @ self.across

    def target(self, xy: np.ndarray, sub: np.ndarray) -> np.ndarray:
        """(n,) float: where motifs at ``xy`` ((n, 2)) copying exemplar motifs ``sub`` ((n,) int)
        belong across the rows: the nearest line to their position less their offset, plus it."""
        res = self.residual[sub]
        u = self.coordinate(xy) - res
        return self.offset + np.round((u - self.offset) / self.pitch) * self.pitch + res

    def onto(self, xy: np.ndarray, sub: np.ndarray) -> np.ndarray:
        """(n, 2) float: points ``xy`` moved across the rows to their :meth:`target`."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        return xy + (self.target(xy, sub) - self.coordinate(xy))[:, None] * self.across


def row_lines(exemplar: Exemplar) -> RowLines | None:
    """The row lines of a drawn exemplar whose order is rows (:func:`lines_of` along the order's
    step), or None (no rows, too few of them, or a repeating tile)."""
    if exemplar.period is not None:
        return None
    order = read_order(exemplar)
    if order.kind != "rows":
        return None
    return lines_of(exemplar.motifs.xy, np.asarray(order.steps[0].vector, float))


def lines_of(xy: np.ndarray, step: np.ndarray) -> RowLines | None:
    """Evenly spaced lines through rows of points, or None when fewer than :data:`MIN_ROWS`.

    The across coordinates (across ``step``) are cut into rows where successive ones, sorted, lie
    more than half the step apart; each row is numbered by its mean over a first pitch (the
    median gap between row means), and the pitch and the offset of line 0 are the least-squares
    line through the row means by number, each row weighted by the square root of its count.

    Parameters
    ----------
    xy : (m, 2) float array, user units — the exemplar's motif centres
    step : (2,) float array, user units — the step along a row
    """
    step_length = float(np.hypot(*step))
    along = np.asarray(step, float) / step_length
    across = np.array([-along[1], along[0]])
    u = np.asarray(xy, float).reshape(-1, 2) @ across
    by = np.argsort(u, kind="stable")
    row = np.zeros(len(u), np.int64)
    row[by] = np.cumsum(np.r_[0, np.diff(u[by]) > step_length / 2])
    count = np.bincount(row)
    mean = np.bincount(row, weights=u) / count
    if len(mean) < MIN_ROWS:
        return None
    number = np.round((mean - mean[0]) / float(np.median(np.diff(mean))))
    if len(np.unique(number)) < MIN_ROWS:
        return None
    pitch, offset = np.polyfit(number, mean, 1, w=np.sqrt(count))
    if not (math.isfinite(pitch) and pitch > step_length / 2):
        return None
    # line 0 is the one nearest the world origin, so the numbers stay small
    offset = float(offset - math.floor(offset / pitch + 0.5) * pitch)
    return RowLines(along, across, float(pitch), offset, u - mean[row])


def slide_apart(new: Arrangement, before: Arrangement, protos: list[Prototype], distance: np.ndarray,
                rows: RowLines) -> Arrangement:  # fmt: skip
    """``new`` with the motifs of conflicting pairs on one row slid apart along it.

    On an exemplar of rows a motif's neighbours along its row nearly touch it (marsh's tufts
    keep 0.8 units between footprints 4 units wide), so a position a few tenths off its ring's
    makes an overlap or breaks the distance rule, and the exact check of :mod:`.engine` removes
    one of the pair — a hole, whose regrowth seldom fits (at 300 × 300, 17 % of marsh's grown
    motifs were removed so; 1.6 % after sliding).  A row has room to give: each such pair (both on one row, at least
    one of ``new``) is pushed apart along the row by what its footprints lack of the distance
    rule — :data:`SLIDE_SHARE` of it each for two motifs of ``new``, all of it for one of ``new``
    against one of ``before`` (which stay) — for :data:`SLIDE_ROUNDS` rounds.  What is still in
    conflict is left to the exact check.

    Parameters
    ----------
    new : the motifs just grown (n)
    before : the motifs placed before, which do not move
    protos : the kinds' prototypes
    distance : (k, k) float array, user units — the distance rule d_ij
    rows : the exemplar's row lines

    Returns
    -------
    Arrangement: ``new`` with moved positions (kinds, angles, scales as they were)
    """
    if not len(new):
        return new
    # two motifs farther apart than ``reach`` cannot conflict; a motif slides less than a reach
    largest = max(float(motif_radius(new, protos).max()), float(motif_radius(before, protos).max(initial=0.0)))
    reach = 2 * largest + float(distance.max())
    near = before
    if len(before):
        near = before.take(np.flatnonzero(np.isfinite(cKDTree(new.xy).query(before.xy, distance_upper_bound=2 * reach)[0])))
    f, n = len(near), len(new)
    xy = new.xy.copy()
    look = np.arange(f + n)  # the motifs checked: all at first, then those near the last moves
    for _ in range(SLIDE_ROUNDS):
        both = Arrangement.concat([near, Arrangement(new.kind, xy, new.angle, new.scale)])
        found = find_conflicts(both.take(look), protos, distance)
        i, j = look[found.i], look[found.j]
        d = both.xy[j] - both.xy[i]
        keep = ((i >= f) | (j >= f)) & (np.abs(d @ rows.across) < rows.pitch / 2)
        i, j, d = i[keep], j[keep], d[keep]
        if not len(i):
            break
        geoms = world_footprints(both.take(np.r_[i, j]), protos)
        gap = shapely.distance(geoms[: len(i)], geoms[len(i) :])
        lack = distance[both.kind[i], both.kind[j]] - gap + SLIDE_MARGIN
        sign = np.where(d @ rows.along >= 0, 1.0, -1.0)
        share = np.where((i >= f) & (j >= f), SLIDE_SHARE, 1.0) * lack * sign
        move = np.zeros(f + n)
        np.add.at(move, i, -share)
        np.add.at(move, j, share)
        xy += move[f:, None] * rows.along
        moved = both.xy[move != 0]
        close = cKDTree(moved).query(np.r_[near.xy, xy], distance_upper_bound=1.2 * reach)[0]
        look = np.flatnonzero(np.isfinite(close))
    return Arrangement(new.kind, xy, new.angle, new.scale)


__all__ = ["MIN_ROWS", "ROW_WEIGHT", "SLIDE_MARGIN", "SLIDE_ROUNDS", "SLIDE_SHARE", "RowLines", "lines_of", "row_lines",
           "slide_apart"]
