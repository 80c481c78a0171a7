"""Patch-based geometric texture synthesis (AlMeraj, Kaplan & Asente 2013).

Start from a Tiling of the exemplar and remove the order that betrays it:

1. :func:`grid` — copies of the exemplar on a square or hexagonal grid of step ``r(1 − σ)``, each
   rotated by θ ~ U[−M, M] about its centre while every motif is turned back by −θ (§3.2);
2. :func:`vary_orientations` — optionally, new orientations drawn from each kind's arc (§3.5);
3. :func:`svgtile.core.conflicts.resolve` — overlapping pairs lose one motif, preferring distance-rule
   violators (§3.3), and the distance rule of §3.1 is then enforced;
4. :func:`adjust_density` — windows the size of the input region are brought to the exemplar's
   density ρ by random removal or by pasting discs of the exemplar into the largest empty disc
   (§3.4);
5. :func:`~svgtile.engines.holes.fill_holes` — where a window wholly inside the region is
   still below ρ(1 − tolerance), the kinds each light window lacks *by area* are dropped into its
   empty places, largest first, displacing a few motifs of surplus kinds (not in the paper).

The structure of the texture is the exemplar's inside each copy and is made where copies meet
and where discs are pasted.  Three choices keep those junctions like the exemplar (issue 3,
measured by the nearest-gap distance of :func:`svgtile.metrics.structure`; README, "Likeness"):

* the *junction rule* (:func:`svgtile.analysis.stats.junction_distance`): motifs of different copies,
  and pasted motifs and the texture, keep the q-quantile of the exemplar's nearest gaps rather
  than its smallest gap ``d_ij``, which packed seams tighter than the exemplar ever is; density
  repair relaxes it to ``d_ij`` step by step for the holes it leaves;
* a motif whose turned orientation stays in its kind's arc turns with its copy (:func:`turn`), so
  a copy of motifs drawn at all angles is rigid and keeps its gaps;
* σ = 0.05 by default: less overlap, fewer motifs at seams (the paper suggests 0.3).

Every random choice is a hash of the run's key and world-anchored integer coordinates (grid cell,
motif, density window; see :mod:`svgtile.core.cellrng`), so the texture at a place does not depend on
how far the output region extends.

Deviations from the paper, each to make the result hold for any region and exemplar:

* orientations are varied *before* overlap resolution, so motifs turned by §3.5 cannot overlap;
* when none of the tried exemplar discs can be pasted whole (§3.4), the largest subset of the best
  one that keeps the rule is pasted, so density repair always makes progress;
* windows alternate between four half-window offsets, so the seams of one window grid are the
  centres of the next;
* every other disc try is centred on a motif of the kind the window lacks most and pasted where
  that kind has the most room under the rule (:func:`_roomiest`), not at the largest empty disc
  — which suits small motifs — and a round adds no kind beyond its share of the window
  (:data:`KIND_CAP`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from svgtile.analysis.order import read_order
from svgtile.analysis.stats import (
    Stats,
    exemplar_gaps,
    junction_distance,
)
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import resolve
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius, rotation
from svgtile.core.region import Region
from svgtile.engines.base import Context, EngineParams, param
from svgtile.engines.holes import fill_holes
from svgtile.engines.patch.density import _ORIENT, _PRIORITY, _ROTATE, adjust_density, uniform_at
from svgtile.engines.patch.lattice import lattice_pivot, lattice_steps, lattice_variation
from svgtile.engines.patch.orientation import turn, vary_orientations
from svgtile.errors import ParameterError

#: Steps from the junction rule to the distance rule over the density rounds (§3.4).
JUNCTION_STEPS = 4



@dataclass(frozen=True)
class PatchParams(EngineParams):
    """Parameters of the patch engine.

    Attributes
    ----------
    grid : "square", "hex" or "lattice"
        Layout of the exemplar copies (§3.2); "lattice" steps copies by the exemplar's own
        lattice or row step, or its tile period (:func:`lattice_steps`), so that the rows and
        lattices of one copy continue into the next.
    overlap : float in [0, 0.5]
        σ, the fraction by which neighbouring copies overlap (§3.2).
    max_rotation : float in [0, 180], degrees
        M, copies are rotated by θ ~ U[−M, M] (§3.2).
    junction : float in [0, 1)
        q, motifs of different copies, and pasted motifs and the texture, keep the q-quantile of
        the exemplar's nearest gaps apart (:func:`svgtile.analysis.stats.junction_distance`) rather
        than the smallest gap ``d_ij``; 0 is the paper's distance rule alone.  Density repair
        relaxes it to ``d_ij`` in :data:`JUNCTION_STEPS` steps, for holes too small for it.
    vary_orientation : bool
        Draw each motif's orientation from its kind's exemplar arc (§3.5).
    coherence : float in [0, 1]
        Weight, against chance, of removing the motif farther from its own copy's centre when
        two conflict (§3.3): copies stay whole near their centres and meet along seams.
    density_tolerance : float
        Windows whose density is within ρ(1 ± tolerance) are left alone (§3.4).
    density_rounds : int
        At most this many density-adjustment rounds.
    disc_tries : int
        Exemplar placements tried per sparse window and round (§3.4).
    """

    grid: str = param("square", "Layout of the exemplar copies; hex suits round exemplars; lattice steps "
                                "copies by the exemplar's own rows, lattice or tile period, so rows run on "
                                "across copies.",
                      choices=("square", "hex", "lattice"))
    overlap: float = param(0.05, "How much neighbouring exemplar copies overlap, 0 to 0.5. More overlap "
                                 "hides seams but removes more motifs.",
                           interval=(0.0, 0.5))
    max_rotation: float = param(30.0, "Each exemplar copy is turned by a random angle up to this many degrees "
                                      "(0 to 180); motifs keep their own orientation. 0 keeps copies square "
                                      "to the page.", interval=(0.0, 180.0))
    junction: float = param(0.6, "Where copies meet, motifs keep this quantile (0 to <1) of the exemplar's "
                                 "nearest gaps apart; 0 = only its smallest gap (the paper's rule).",
                            interval=(0.0, 1.0))
    vary_orientation: bool = param(False, "Give every motif a new orientation, drawn from the range its kind "
                                          "shows in the exemplar.")
    coherence: float = 0.5
    density_tolerance: float = 0.1
    density_rounds: int = 12
    disc_tries: int = 6

    def __post_init__(self) -> None:
        if self.grid not in ("square", "hex", "lattice"):
            raise ParameterError(f"--grid must be square, hex or lattice, not {self.grid!r}")
        if not 0.0 <= self.overlap <= 0.5:
            raise ParameterError(f"--overlap must be between 0 and 0.5, not {self.overlap:g}")
        if not 0.0 <= self.max_rotation <= 180.0:
            raise ParameterError(f"--max-rotation must be between 0 and 180 degrees, not {self.max_rotation:g}")
        if not 0.0 <= self.coherence <= 1.0:
            raise ParameterError(f"coherence must be between 0 and 1, not {self.coherence:g}")
        if not 0.0 <= self.junction < 1.0:
            raise ParameterError(f"--junction must be at least 0 and below 1, not {self.junction:g}")
        if not 0.0 < self.density_tolerance < 1.0:
            raise ParameterError("density tolerance must be between 0 and 1")
        if not (self.density_rounds >= 0 and self.disc_tries >= 1):
            raise ParameterError("density_rounds must be at least 0 and disc_tries at least 1")


class PatchEngine:
    """The patch engine behind the engine protocol (:mod:`svgtile.engines.base`)."""

    name = "patch"
    #: CPU seconds per motif of ``svgtile synth`` end to end (benchmarks/work_per_motif.py, rounded up)
    seconds_per_motif = 2.5e-5
    summary = "copies of the exemplar blended without seams (AlMeraj et al. 2013)"
    Params = PatchParams

    def place(self, ctx: Context, p: PatchParams) -> Arrangement:
        """Fill ``ctx.region`` with a texture like ``ctx.exemplar`` (almeraj2013 §3).

        Returns
        -------
        Arrangement with no overlaps and no distance-rule violations, already filtered by the
        boundary mode (copies and pasted discs are filtered as they are made).
        """
        exemplar, stats, region, key, report = ctx.exemplar, ctx.stats, ctx.region, ctx.key, ctx.progress
        protos = exemplar.prototypes

        report("grid", 0.0)
        arr, cell = grid(
            exemplar, region, key=key, grid_kind=p.grid, overlap=p.overlap, max_rotation=p.max_rotation, stats=stats
        )
        if p.vary_orientation:
            arr = vary_orientations(arr, stats, uniform_at(key, _ORIENT, cell))
        inside = region.keep(arr, protos, ctx.boundary)
        arr, cell = arr.take(inside), cell[inside]

        report("overlaps", 0.2)
        # the junction rule, relaxed in equal steps to the distance rule over the density rounds
        steps = p.junction * (1 - np.arange(JUNCTION_STEPS) / (JUNCTION_STEPS - 1))
        gaps = exemplar_gaps(exemplar)
        rules = [junction_distance(exemplar, stats, q, gaps) for q in steps]
        priority = p.coherence * _from_centre(exemplar)[cell[:, 2]] + (1 - p.coherence) * uniform_at(key, _PRIORITY, cell)
        copy = np.unique(cell[:, :2], axis=0, return_inverse=True)[1].ravel()
        # copies of a tile on its own period, unturned, are the pattern itself: its pairs across
        # the seams are the pattern's own, which the junction rule (a gap quantile) would thin,
        # and its density holds everywhere, which window-by-window repair would only disturb
        exact = p.grid == "lattice" and exemplar.period is not None and p.max_rotation == 0 and not p.vary_orientation
        keep = resolve(arr, protos, stats.distance, priority, frequency=stats.frequency, group=copy,
                       junction=stats.distance if exact else rules[0])  # fmt: skip
        arr = arr.take(keep)
        if exact:
            return arr
        arr = adjust_density(arr, exemplar, stats, region, p, ctx.boundary, key=key, progress=report, rules=rules)
        if p.density_rounds == 0:  # no density adjustment at all (§3.4), hole filling included
            return arr
        return fill_holes(arr, exemplar, stats, region, ctx.boundary, key=key, tolerance=p.density_tolerance)

    def reach(self, exemplar: Exemplar, params: PatchParams) -> float:
        """Not tile-exact: density repair decides window by window from what earlier rounds left,
        so a change can travel a window per round; run it whole."""
        return math.inf


PATCH = PatchEngine()


# ----------------------------------------------------------------------------- §3.2


def grid(
    exemplar: Exemplar, region: Region, *, key: int, grid_kind: str, overlap: float, max_rotation: float,
    stats: Stats | None = None,
) -> tuple[Arrangement, np.ndarray]:  # fmt: skip
    """Overlapping, rotated copies of the exemplar covering the region (almeraj2013 §3.2).

    Copies sit at ``(a·sx, b·sy)`` in world coordinates, ``sx = w(1 − σ)``, ``sy = h(1 − σ)`` for
    an input region of bounding size ``w × h``; the hexagonal layout shifts odd rows by ``sx/2``
    and packs rows ``√3/2`` closer.  The ``lattice`` layout steps copies by the exemplar's own
    lattice vectors (:func:`~svgtile.engines.patch.lattice.lattice_steps`) and turns each by 0°
    or 180° about a motif and shifts it by a lattice step
    (:func:`~svgtile.engines.patch.lattice.lattice_variation`, drawn exemplars only), on top of θ.  Copy ``(a, b)`` is rotated by θ = M(2u − 1), u a hash of the
    cell, about its centre; each motif keeps its exemplar orientation (it is turned by −θ), as in
    the paper, unless ``stats`` is given: then a motif whose orientation turned by θ is still
    in its kind's exemplar arc turns with its copy (:func:`turn`).

    Returns
    -------
    arrangement : Arrangement of every copied motif near the region.
    cell : (n, 3) int array, (a, b, index of the motif in the exemplar) for each motif.
    """
    x0, y0, x1, y1 = exemplar.region.bounds
    w, h = x1 - x0, y1 - y0
    centre = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    sx = w * (1.0 - overlap)
    sy = h * (1.0 - overlap) * (math.sqrt(3.0) / 2.0 if grid_kind == "hex" else 1.0)
    motifs = exemplar.motifs
    local = motifs.xy - centre
    reach = float(np.hypot(local[:, 0], local[:, 1]).max() + motif_radius(motifs, exemplar.prototypes).max())

    X0, Y0, X1, Y1 = region.bounds
    pivot, flip = np.zeros(2), 0.0
    if grid_kind == "lattice":
        order = read_order(exemplar)
        A, B, cx, cy = _lattice_centres(lattice_steps(order, (w, h), overlap),
                                        (X0 - reach, Y0 - reach, X1 + reach, Y1 + reach))  # fmt: skip
        flip, shift = lattice_variation(order, key, A, B)
        cx, cy = cx + shift[:, 0], cy + shift[:, 1]
        pivot = lattice_pivot(exemplar)
        sx = 0.0  # the box above already bounds the centres
    else:
        b = np.arange(math.floor((Y0 - reach) / sy), math.ceil((Y1 + reach) / sy) + 1)
        a = np.arange(math.floor((X0 - reach) / sx) - 1, math.ceil((X1 + reach) / sx) + 2)
        A, B = np.meshgrid(a, b)
        A, B = A.ravel(), B.ravel()
        shift = (B % 2) * 0.5 if grid_kind == "hex" else 0.0
        cx, cy = (A + shift) * sx, B * sy
    near = (cx > X0 - reach - sx) & (cx < X1 + reach + sx) & (cy > Y0 - reach) & (cy < Y1 + reach)
    A, B, cx, cy = A[near], B[near], cx[near], cy[near]
    flip = flip[near] if grid_kind == "lattice" else flip

    theta = max_rotation * (2.0 * cellrng.uniform(key, _ROTATE, A, B) - 1.0) + flip
    rot = rotation(theta)  # (c, 2, 2)
    turned = np.matmul(rot, (local - pivot).T).transpose(0, 2, 1) + pivot  # (c, m, 2)
    xy = turned + np.stack([cx, cy], -1)[:, None, :]
    c, m = len(A), len(motifs)
    kind = np.tile(motifs.kind, c)
    angle = turn(kind, np.tile(motifs.angle, c), np.repeat(theta, m), stats)
    arr = Arrangement(kind, xy.reshape(-1, 2), angle, np.tile(motifs.scale, c)).quantized(DECIMALS)
    cell = np.stack([np.repeat(A, m), np.repeat(B, m), np.tile(np.arange(m), c)], -1)
    radius = motif_radius(arr, exemplar.prototypes)
    touch = (
        (arr.xy[:, 0] + radius > X0) & (arr.xy[:, 0] - radius < X1)
        & (arr.xy[:, 1] + radius > Y0) & (arr.xy[:, 1] - radius < Y1)
    )  # fmt: skip
    return arr.take(touch), cell[touch]


# ----------------------------------------------------------------------------- helpers


def _lattice_centres(steps: np.ndarray, box: tuple[float, float, float, float]
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """Copy indices (A, B) and centres ``A·X + B·Y`` of the copies whose centre lies in ``box``.

    ``steps`` is (2, 2), rows X and Y (:func:`svgtile.engines.patch.lattice.lattice_steps`); the
    index ranges come from the box's corners in lattice coordinates.
    """
    x0, y0, x1, y1 = box
    corners = np.array([[x0, y0], [x1, y0], [x0, y1], [x1, y1]])
    ab = np.linalg.solve(steps.T, corners.T).T  # (4, 2) lattice coordinates
    lo, hi = np.floor(ab.min(axis=0)) - 1, np.ceil(ab.max(axis=0)) + 1
    A, B = np.meshgrid(np.arange(lo[0], hi[0] + 1), np.arange(lo[1], hi[1] + 1))
    A, B = A.ravel().astype(np.int64), B.ravel().astype(np.int64)
    cx = A * steps[0, 0] + B * steps[1, 0]
    cy = A * steps[0, 1] + B * steps[1, 1]
    inside = (cx >= x0) & (cx <= x1) & (cy >= y0) & (cy <= y1)
    return A[inside], B[inside], cx[inside], cy[inside]


def _from_centre(exemplar: Exemplar) -> np.ndarray:
    """(m,) distance of each exemplar motif from the input region's centre, scaled to [0, 1]."""
    x0, y0, x1, y1 = exemplar.region.bounds
    d = np.hypot(exemplar.motifs.xy[:, 0] - (x0 + x1) / 2, exemplar.motifs.xy[:, 1] - (y0 + y1) / 2)
    return d / max(float(d.max()), 1e-12)


