"""The Random strategy: dart throwing to the exemplar's statistics (almeraj2013 §1).

AlMeraj et al. (2011) saw people synthesize textures in three ways; the Random strategy places
motifs "randomly so that they capture high-level statistical features of the exemplar, such as
density and relative frequencies of distinct shapes" — no repetition, but none of the exemplar's
local structure either.  This engine is that strategy, the baseline against which the patch
engine's structure is measured.  It reproduces, from :class:`~svgtile.analysis.stats.Stats`:

* the kind frequencies and the density ρ — every cell of a world grid receives the exemplar's
  number of motifs of each kind per unit area (so ρ follows on average);
* the orientation arcs — angles are uniform in each kind's arc (almeraj2013 §3.5);
* the scales — each dart copies the scale of a random exemplar instance of its kind;
* the distance rule d_ij (almeraj2013 §3.1) and no overlaps.

Dart throwing (random sequential addition) runs kind by kind, in vectorised rounds
(:func:`throw`).  Each round proposes many darts of one kind at once, rejects those that conflict
with the motifs already placed (:func:`svgtile.core.conflicts.cross_conflicts`), breaks conflicts among
the round's darts (:func:`svgtile.core.conflicts.find_conflicts`, :func:`svgtile.core.conflicts.cull`), and
keeps, per cell, as many survivors as the cell still lacks.  A cell stops receiving darts of the
kind when it has enough or when its acceptance rate collapses (a jammed neighbourhood).

Two choices make the counts come out right, where plain dart throwing drifts:

* per-cell targets (stratification by exemplar-sized cells) instead of one global count, so the
  density is even across the texture and the loop knows where to throw;
* the kinds hardest to place go first (:func:`hardness_rank`).  Random sequential addition jams
  the kinds placed last: on ``till.svg``, placing the large, widely spaced clasts last leaves
  almost none of them (density 0.36 ρ); in the order chosen every kind of every bundled
  exemplar reaches at least 0.88 of its count, the density at least 0.95 ρ.

Randomness is world-anchored: cells are the input region's bounding box tiled from the world
origin, and dart ``i`` of kind ``k`` thrown into cell ``(a, b)`` in round ``r`` is a hash of
``(key, a, b, r, k, i)``; darts fall anywhere in their cell, also in cells the boundary cuts.
What this guarantees:

* the first round of the first kind throws the same darts into a cell lying wholly inside two
  output regions, whatever their extent, so textures of overlapping regions start alike there;
* every later decision depends on what was placed nearby, so a difference at the border of the
  smaller region (where its darts stop) spreads inwards, by at most about one cell per round.
  Measured on the bundled exemplars (a 600 × 500 region inside a 1000 × 900 one, off the cell
  grid): the textures agree on every motif more than two exemplar widths inside the smaller
  region, on 99–100 % of those one width inside, and on 92–98 % of all its motifs.  The tests
  hold the engine to the first figure; nothing stronger is promised.

The patch engine's parameters are not this engine's (there are no exemplar copies; orientations
are always drawn from the arcs, which is what ``vary_orientation`` asks of the patch engine): one
given to it is an error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import Stats
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import cross_conflicts, cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.engines.base import Context, EngineParams, Progress
from svgtile.errors import ParameterError

# hash streams: one per independent random choice
_DART, _X, _Y, _ANGLE, _SCALE, _PRIORITY, _TARGET = range(7)


@dataclass(frozen=True)
class RandomParams(EngineParams):
    """Parameters of the random engine (library only: the CLI offers none).

    Attributes
    ----------
    oversample : float ≥ 1
        Darts thrown into a cell per missing motif in a round, before dividing by the acceptance
        rate its darts had in the previous round (at most :data:`MAX_BOOST` per missing motif).
    max_rounds : int ≥ 1
        At most this many rounds of dart throwing per kind.
    min_acceptance : float in [0, 1)
        A cell whose darts of the kind being placed were accepted less often than this in a
        round receives no more darts of that kind: its neighbourhood is jammed.
    """

    oversample: float = 1.5
    max_rounds: int = 16
    min_acceptance: float = 0.01

    def __post_init__(self) -> None:
        if not self.oversample >= 1.0:
            raise ParameterError(f"oversample must be at least 1, not {self.oversample:g}")
        if not self.max_rounds >= 1:
            raise ParameterError(f"max_rounds must be at least 1, not {self.max_rounds}")
        if not 0.0 <= self.min_acceptance < 1.0:
            raise ParameterError(f"min_acceptance must be in [0, 1), not {self.min_acceptance:g}")


#: Darts thrown into one cell and kind in one round, at most, per missing motif.
MAX_BOOST = 40.0

#: A cell whose part of the domain is smaller than this fraction of it is thrown at as if it
#: were this large (a thin sliver of a cell must not receive thousands of darts).
MIN_FRACTION = 0.05


class RandomEngine:
    """The Random strategy behind the engine protocol (:mod:`svgtile.engines.base`)."""

    name = "random"
    #: CPU seconds per motif of ``svgtile synth`` end to end (benchmarks/work_per_motif.py, rounded up)
    seconds_per_motif = 2.5e-5
    summary = ("motifs scattered by dart throwing to the exemplar's statistics, a baseline for svgtile score "
               "and compare: no repetition and only the structure the distance rule imposes")
    Params = RandomParams

    def place(self, ctx: Context, p: RandomParams) -> Arrangement:
        """Fill ``ctx.region`` by dart throwing to the exemplar's statistics (the Random strategy)."""
        return throw(ctx.exemplar, ctx.stats, ctx.region, p, ctx.boundary, key=ctx.key, progress=ctx.progress)

    def reach(self, exemplar: Exemplar, params: RandomParams) -> float:
        """Not tile-exact: a dart's fate depends on what was placed nearby, kind after kind and round
        after round, so a difference travels about a cell per round; run it whole."""
        return math.inf


RANDOM = RandomEngine()


def throw(
    exemplar: Exemplar, stats: Stats, region: Region, p: RandomParams, boundary: str, *, key: int,
    progress: Progress | None = None,
) -> Arrangement:  # fmt: skip
    """Dart throwing in rounds until every cell holds the exemplar's count of each kind.

    Centroids are placed in the *domain*: the region for the ``inside`` and ``centroid`` modes,
    the region grown by the largest motif radius for ``clip`` and ``none`` (motifs centred just
    outside may reach in; the caller's :meth:`Region.keep` drops those that do not).  With
    ``inside``, darts that would cross the boundary are rejected at once, so border cells fill
    with whole motifs.  Cell ``(a, b)`` spans ``[a·w, (a+1)·w) × [b·h, (b+1)·h)`` for an input
    region whose bounding box is ``w × h``; its target for kind ``k`` is the exemplar's count of
    kind ``k`` per unit area times the area of the cell in the domain, rounded up or down at
    random so that the expected count is exact.

    Returns
    -------
    Arrangement of the motifs placed (not yet filtered by the boundary mode, not sorted).
    """
    report = progress or (lambda stage, fraction: None)
    motifs, protos = exemplar.motifs, exemplar.prototypes
    k = len(protos)
    x0, y0, x1, y1 = exemplar.region.bounds
    size = np.array([x1 - x0, y1 - y0])
    reach = float(np.max([pr.radius for pr in protos]) * motifs.scale.max())
    domain = region.shape if boundary in ("inside", "centroid") else shapely.buffer(region.shape, reach)
    shapely.prepare(domain)

    # cells meeting the domain, and the area of each inside it
    X0, Y0, X1, Y1 = domain.bounds
    ia = np.arange(math.floor(X0 / size[0]), math.ceil(X1 / size[0]))
    ib = np.arange(math.floor(Y0 / size[1]), math.ceil(Y1 / size[1]))
    cell = np.stack([v.ravel() for v in np.meshgrid(ia, ib)], -1)
    lo = cell * size
    boxes = shapely.box(lo[:, 0], lo[:, 1], lo[:, 0] + size[0], lo[:, 1] + size[1])
    area = shapely.area(shapely.intersection(boxes, domain))
    cell, lo, area = cell[area > 0], lo[area > 0], area[area > 0]
    # darts fall anywhere in their cell, also in cells the boundary cuts: the darts of a cell,
    # and their order, are then the same in every region that meets it
    fraction = np.maximum(area / (size[0] * size[1]), MIN_FRACTION)
    c = len(cell)

    per_area = np.bincount(motifs.kind, minlength=k) / exemplar.region.area  # (k,) motifs per unit²
    u = cellrng.uniform(key, _TARGET, cell[:, 0, None], cell[:, 1, None], np.arange(k)[None, :])
    deficit = np.floor(per_area[None, :] * area[:, None] + u).astype(np.int64)  # (c, k)

    placed: list[Arrangement] = []
    tree, old = None, Arrangement.empty()
    order = np.argsort(hardness_rank(exemplar, stats))
    for step, kk in enumerate(order):
        rate = np.ones(c)
        for rnd in range(p.max_rounds):
            active = (deficit[:, kk] > 0) & (rate >= p.min_acceptance)
            if not active.any():
                break
            report("darts", (step + rnd / p.max_rounds) / k)
            boost = np.minimum(p.oversample / np.maximum(rate, 1e-9), MAX_BOOST)
            count = np.where(active, np.ceil(deficit[:, kk] * boost / fraction), 0).astype(np.int64)
            gc = np.repeat(np.arange(c), count)  # (n,) the cell of each dart
            index = np.arange(len(gc)) - np.repeat(np.cumsum(count) - count, count)
            dart = cellrng.hash64(key, _DART, cell[gc, 0], cell[gc, 1], rnd, kk, index).view(np.int64)
            new, priority = _darts(exemplar, stats, kk, lo[gc], size, dart, key=key)

            ok = shapely.contains_xy(domain, new.xy[:, 0], new.xy[:, 1])
            if boundary == "inside":
                ok[ok] = region.keep(new.take(ok), protos, "inside")
            offered = np.bincount(gc[ok], minlength=c)
            if tree is not None:
                ok[ok] = ~cross_conflicts(new.take(ok), old, protos, stats.distance, tree)
            sel = np.flatnonzero(ok)
            sel = sel[cull(len(sel), find_conflicts(new.take(sel), protos, stats.distance), priority[sel])]
            survived = np.bincount(gc[sel], minlength=c)

            # per cell, the best-ranked survivors up to the deficit
            sel = sel[np.lexsort((priority[sel], gc[sel]))]
            g = gc[sel]
            starts = np.r_[0, np.flatnonzero(np.diff(g)) + 1] if len(g) else np.zeros(0, np.int64)
            nth = np.arange(len(g)) - np.repeat(starts, np.diff(np.r_[starts, len(g)]))
            sel = sel[nth < deficit[g, kk]]
            deficit[:, kk] -= np.bincount(gc[sel], minlength=c)
            # a cell none of whose darts landed in the domain gets rate 0 and stops
            rate = np.where(active, survived / np.maximum(offered, 1), rate)
            if len(sel):
                placed.append(new.take(sel))
                old = Arrangement.concat(placed)
                tree = cKDTree(old.xy)
    return Arrangement.concat(placed)


def _darts(
    exemplar: Exemplar, stats: Stats, kind: int, lo: np.ndarray, size: np.ndarray, dart: np.ndarray, *, key: int
) -> tuple[Arrangement, np.ndarray]:
    """Darts of one kind: uniform in their cells, angles uniform in the kind's arc (§3.5).

    Parameters
    ----------
    kind : the kind thrown
    lo : (n, 2) float array, the lower corner of each dart's cell, user units
    size : (2,) float array, the cell size, user units
    dart : (n,) int array, each dart's identity (a world-anchored hash)

    Returns
    -------
    darts : Arrangement of n motifs, each with the scale of a random exemplar instance of ``kind``
    priority : (n,) floats in [0, 1): which of two conflicting darts is removed (the higher)
    """
    motifs = exemplar.motifs
    u = np.stack([cellrng.uniform(key, s, dart) for s in (_X, _Y, _ANGLE, _SCALE, _PRIORITY)])
    xy = lo + u[:2].T * size
    angle = stats.arc_start[kind] + u[2] * stats.arc_width[kind]
    instances = np.flatnonzero(motifs.kind == kind)
    scale = motifs.scale[instances[np.minimum((u[3] * len(instances)).astype(np.int64), len(instances) - 1)]]
    darts = Arrangement(np.full(len(dart), kind), xy, (angle + 180.0) % 360.0 - 180.0, scale)
    return darts.quantized(DECIMALS), u[4]


def hardness_rank(exemplar: Exemplar, stats: Stats) -> np.ndarray:
    """(k,) int: 0 for the kind hardest to place among the others, 1 for the next, and so on.

    Random sequential addition jams the kinds placed last, so :func:`throw` places the kinds in
    this order.  A kind's hardness is the number of exemplar motifs that would keep a dart of
    that kind out if they were scattered at random: ``Σ_j n_j E_kj / area``, where ``E_kj`` is
    the mean area, over a uniform random rotation, of the positions where a motif of kind j
    comes closer than ``d_kj`` to one of kind k.  For convex footprints (their hulls are used)
    Blaschke's principal kinematic formula gives it exactly:
    ``E_kj = a_k + a_j + p_k p_j / 2π + d_kj (p_k + p_j) + π d_kj²`` (areas a, perimeters p).
    """
    motifs, protos = exemplar.motifs, exemplar.prototypes
    k = len(protos)
    hull = shapely.convex_hull(np.array([pr.geometry() for pr in protos], dtype=object))
    scale = np.bincount(motifs.kind, motifs.scale, minlength=k) / np.maximum(np.bincount(motifs.kind, minlength=k), 1)
    a, per = shapely.area(hull) * scale**2, shapely.length(hull) * scale
    d = stats.distance
    mean = a[:, None] + a[None, :] + np.outer(per, per) / (2 * np.pi) + d * (per[:, None] + per[None, :]) + np.pi * d**2
    hardness = mean @ np.bincount(motifs.kind, minlength=k) / exemplar.region.area
    rank = np.empty(k, dtype=np.int64)
    rank[np.argsort(-hardness, kind="stable")] = np.arange(k)
    return rank
