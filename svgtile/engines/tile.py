"""The Tiling strategy: stamped copies of the exemplar (almeraj2013 §1, §3).

AlMeraj et al. (2011) saw people synthesize textures in three ways — Tiling, Structured and
Random — and found Tiling the most faithful to the exemplar but visibly repetitive; almeraj2013
§3 calls a pure Tiling "trivial to implement: we need only stamp out regularly spaced copies of
the exemplar" and builds the patch engine by removing its order.  This engine is that trivial
Tiling, the baseline against which the patch engine's repetition is measured: σ = 0, no rotation.

Copy ``(a, b)`` is the exemplar translated so that the corner ``(x0, y0)`` of its input region's
bounding box lands on ``(a·w, b·h)``, ``w × h`` being that box's size: the grid is anchored at
the world origin, so an output region of exactly ``k × l`` boxes from the origin holds ``k × l``
whole copies, and a texture at a place does not depend on the output region's extent.  Copies
step by the bounding box whatever the input region's shape, so a round exemplar leaves the
corners between its copies empty (``chert-nodules.svg`` tiles at π/4 ≈ 0.79 of its density).

Copies keep the exemplar's motifs exactly.  Where the exemplar's padding is too small, motifs of
neighbouring copies overlap or break the distance rule across the seams; those conflicts are
resolved once, on the exemplar itself with periodic boundaries (:func:`periodic_keep`), and the
same motifs are left out of every copy.  The texture thus stays exactly periodic — resolving the
stamped texture instead would make copies differ at their seams — and the cost of resolving is
that of one exemplar, whatever the output size.  Which motif of a conflicting pair leaves is the
only random choice, a hash of the run's key and the motif's index in the exemplar.

The Tiling strategy is defined by a square grid, σ = 0, no rotation and the exemplar's own
orientations (a patch parameter given to it is an error).  Its one parameter, ``redraw_jitter``
(auto's rule ``tile-jitter``), keeps a repeating tile's rows but draws each copy's row phases and
jitter anew (:mod:`svgtile.engines.jitter`); the baseline is the plain Tiling.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from svgtile.analysis.stats import Stats
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import RULE_SLACK, Conflicts, cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius
from svgtile.core.region import Region
from svgtile.engines.base import Context, EngineParams, param
from svgtile.errors import ParameterError

_PRIORITY = 0  # hash stream: which motif of a conflicting pair leaves the tiling

#: Extra distance, user units, by which motifs of *different* copies must clear the distance rule
#: when the tile's size or corner is not a multiple of the output precision: copies are then
#: rounded differently, a pair's distance varies by up to ~1.5e-4 from copy to copy, and this
#: margin makes the decision taken on one copy hold for all of them.  (On the usual tile whose
#: numbers have at most four decimals every copy is the same rounded pattern, and a seam exactly
#: as wide as the distance rule is kept.)
SEAM_MARGIN = 2 * RULE_SLACK


@dataclass(frozen=True)
class TileParams(EngineParams):
    """The Tiling strategy: a square grid, σ = 0, no rotation; ``redraw_jitter`` keeps the tile's
    lattice or rows and draws each copy's jitter anew (:mod:`svgtile.engines.jitter`)."""

    redraw_jitter: bool = param(False, "Keep a repeating tile's rows and lattice but draw each copy's row "
                                       "phases and jitter anew from the tile's own, so a hand-jittered tile "
                                       "does not repeat at its period.")


class TileEngine:
    """The Tiling strategy behind the engine protocol (:mod:`svgtile.engines.base`)."""

    name = "tile"
    #: CPU seconds per motif of ``svgtile synth`` end to end (benchmarks/work_per_motif.py, rounded up)
    seconds_per_motif = 5e-6
    summary = ("plain repeated copies of the exemplar's bounding box, a baseline for svgtile score and "
               "compare: the most faithful structure and obvious repetition (a round exemplar leaves holes "
               "between its copies)")
    Params = TileParams

    def place(self, ctx: Context, p: TileParams) -> Arrangement:
        """Translated copies of the exemplar over ``ctx.region`` (the Tiling strategy).

        ``ctx.key`` only decides which motif of a pair conflicting across a seam leaves the tiling
        (an exemplar with enough padding gives the same texture for every seed).
        """
        ctx.progress("seams", 0.0)
        keep = periodic_keep(ctx.exemplar, ctx.stats, key=ctx.key)
        ctx.progress("tiles", 0.3)
        if p.redraw_jitter and ctx.exemplar.period is None:
            raise ParameterError(f"{ctx.exemplar.source}: --redraw-jitter redraws a repeating tile's jitter, and this "
                                 "exemplar is no repeating tile (no svgtile:period; `svgtile import` makes one)")  # fmt: skip
        if p.redraw_jitter:
            from svgtile.analysis.order import read_order
            from svgtile.engines.jitter import redraw

            return redraw(ctx.exemplar, ctx.stats, read_order(ctx.exemplar), ctx.region, keep, key=ctx.key)
        return stamp(ctx.exemplar, ctx.region, keep)

    def reach(self, exemplar: Exemplar, params: TileParams) -> float:
        """Tile-exact with no halo: a copy is a function of its grid cell alone.  Redrawn jitter
        (``redraw_jitter``) settles conflicts by rounds of redraws and a cull, whose chains have no
        bound: run whole."""
        return math.inf if params.redraw_jitter and exemplar.period is not None else 0.0


TILE = TileEngine()


def tile_size(exemplar: Exemplar) -> tuple[float, float, float, float]:
    """``(x0, y0, w, h)``: corner and size of the input region's bounding box, user units."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return x0, y0, x1 - x0, y1 - y0


def periodic_keep(exemplar: Exemplar, stats: Stats, *, key: int) -> np.ndarray:
    """(m,) bool: the exemplar motifs every copy keeps, so that the tiling has no conflicts.

    The exemplar is surrounded by as many rings of translated copies as a conflict can reach
    across; every conflicting pair found in this block, mapped back to exemplar indices, is an
    edge of the periodic conflict graph (a motif in conflict with its own translate is an edge to
    itself and always leaves).  The graph is then culled as :func:`svgtile.core.conflicts.resolve`
    culls a texture (almeraj2013 §3.3, §3.1): overlapping pairs first, preferring to remove
    motifs that break the distance rule, then the remaining violations.  Pairs within one copy
    are the exemplar's own and conflict only if the exemplar overlaps itself.
    """
    motifs, protos = exemplar.motifs, exemplar.prototypes
    m = len(motifs)
    x0, y0, w, h = tile_size(exemplar)
    scaled = np.array([x0, y0, w, h]) * 10**DECIMALS
    margin = 0.0 if np.allclose(scaled, np.round(scaled), rtol=0, atol=1e-6) else SEAM_MARGIN
    radius = motif_radius(motifs, protos)
    reach = 2 * float(radius.max()) + float(stats.distance.max()) + margin + 2 * RULE_SLACK
    na = math.ceil((np.ptp(motifs.xy[:, 0]) + reach) / w)
    nb = math.ceil((np.ptp(motifs.xy[:, 1]) + reach) / h)
    da, db = (v.ravel() for v in np.meshgrid(np.arange(-na, na + 1), np.arange(-nb, nb + 1)))
    block = copies(exemplar, motifs, da, db)
    copy = np.repeat(np.arange(len(da)), m)
    index = np.tile(np.arange(m), len(da))

    own = find_conflicts(block, protos, stats.distance)
    seam = find_conflicts(block, protos, stats.distance + margin) if margin else own
    same, across = copy[own.i] == copy[own.j], copy[seam.i] != copy[seam.j]
    i = index[np.r_[own.i[same], seam.i[across]]]
    j = index[np.r_[own.j[same], seam.j[across]]]
    overlap = np.r_[own.overlap[same], seam.overlap[across]]
    violation = np.r_[own.violation[same], seam.violation[across]]

    keep = np.ones(m, dtype=bool)
    keep[i[i == j]] = False  # a motif that conflicts with its own translate cannot be tiled
    edge = (i != j) & keep[i] & keep[j]
    code = np.minimum(i, j)[edge] * m + np.maximum(i, j)[edge]
    # one edge per motif pair: it may overlap across one seam and only violate across another
    pair, which = np.unique(code, return_inverse=True)
    lo, hi = pair // m, pair % m
    over = np.zeros(len(pair), dtype=bool)
    bad = np.zeros(len(pair), dtype=bool)
    np.logical_or.at(over, which, overlap[edge])
    np.logical_or.at(bad, which, violation[edge])

    priority = cellrng.uniform(key, _PRIORITY, np.arange(m))
    violator = np.zeros(m)
    side = bad & ~over
    violator[lo[side]] = violator[hi[side]] = 1.0
    keep &= cull(m, Conflicts(lo[over], hi[over], over[over], bad[over]), priority, violator)
    rest = (bad | over) & keep[lo] & keep[hi]
    keep &= cull(m, Conflicts(lo[rest], hi[rest], over[rest], bad[rest]), priority)
    return keep


def stamp(exemplar: Exemplar, region: Region, keep: np.ndarray | None = None) -> Arrangement:
    """Every copy of the (kept) exemplar motifs whose bounding disc meets the region's box.

    Copy ``(a, b)`` translates the exemplar by ``(a·w − x0, b·h − y0)`` (see :func:`copies`).

    Parameters
    ----------
    keep : (m,) bool array, the exemplar motifs to copy (all by default)

    Returns
    -------
    Arrangement of the copies, copy by copy (not yet filtered by a boundary mode).
    """
    motifs = exemplar.motifs if keep is None else exemplar.motifs.take(keep)
    if len(motifs) == 0:
        return Arrangement.empty()
    x0, y0, w, h = tile_size(exemplar)
    r = motif_radius(motifs, exemplar.prototypes)
    X0, Y0, X1, Y1 = region.bounds
    # copy a reaches [a·w − x0 + min(x − r), a·w − x0 + max(x + r)]
    a = np.arange(
        math.ceil((X0 + x0 - float((motifs.xy[:, 0] + r).max())) / w),
        math.floor((X1 + x0 - float((motifs.xy[:, 0] - r).min())) / w) + 1,
    )
    b = np.arange(
        math.ceil((Y0 + y0 - float((motifs.xy[:, 1] + r).max())) / h),
        math.floor((Y1 + y0 - float((motifs.xy[:, 1] - r).min())) / h) + 1,
    )
    A, B = (v.ravel() for v in np.meshgrid(a, b))
    arr = copies(exemplar, motifs, A, B)
    rr = np.tile(r, len(A))
    xy = arr.xy
    return arr.take((xy[:, 0] + rr > X0) & (xy[:, 0] - rr < X1) & (xy[:, 1] + rr > Y0) & (xy[:, 1] - rr < Y1))


def copies(exemplar: Exemplar, motifs: Arrangement, a: np.ndarray, b: np.ndarray) -> Arrangement:
    """Copies ``(a[t], b[t])`` of ``motifs``, copy by copy, at the output precision.

    Copy ``(a, b)`` translates by ``(a·w − x0, b·h − y0)``.  Positions are rounded before and after
    the translation, so every copy is the same rounded pattern whenever the translation itself
    has at most :data:`~svgtile.core.arrangement.DECIMALS` decimals.

    Parameters
    ----------
    motifs : Arrangement of m exemplar motifs
    a, b : (c,) int arrays

    Returns
    -------
    Arrangement of ``c·m`` motifs.
    """
    x0, y0, w, h = tile_size(exemplar)
    shift = np.stack([a * w - x0, b * h - y0], -1)
    base = motifs.quantized(DECIMALS)
    c = len(shift)
    return Arrangement(
        np.tile(base.kind, c),
        (base.xy[None, :, :] + shift[:, None, :]).reshape(-1, 2),
        np.tile(base.angle, c),
        np.tile(base.scale, c),
    ).quantized(DECIMALS)
