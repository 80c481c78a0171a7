"""The ``optimize`` engine: a patch-copy start refined by discrete element texture optimisation.

Ma, Wei & Tong 2011 §4.1 initialise by copying exemplar patches of the neighbourhood's size
(:func:`.init.patch_start`, integral motifs, world-anchored cells), and the solver
(:func:`.solver.refine`, Pseudocode 1) then minimises the neighbourhood energy.

The patch engine's output (AlMeraj et al. 2013) is a valid start too — ``--engine patch --refine
N`` — but not this engine's: its density repair decides window by window from what earlier
rounds left, so about 1 % of its motifs change far from an edit of the region, and every
iteration spreads each such change over its neighbourhood; small patches on fixed cells change
only near the edit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.engines.base import Context, EngineParams, param
from svgtile.errors import ParameterError

if TYPE_CHECKING:  # the solver (numba, scipy.sparse) is imported when the engine runs, not when declared
    from svgtile.engines.optimize.solver import Settings


#: Side of the start's patches cut from a repeating tile that the solver refills (:func:`.init.seamless`
#: is false): this share of the tile's shorter period — large, for the tile's content is seamless
#: up to its period and every seam costs L, but well short of the whole of it, which neighbouring
#: patches would repeat side by side (below) — and at most :data:`MAX_CELL` exemplar spacings (FGDC 606, 616, 617 at 5, 8 and 12 spacings: L 0.48 / 0.71 / 0.71 → 0.75 /
#: 0.82 / 0.80 → 0.77 / 0.83 / 0.88; 626 and 641, tiles of 5.6–5.9 spacings, at 12: repetition
#: 0.50 and 0.25, their tile's period inside each patch).  0.8 → 1.0 with the seeded first
#: search (:data:`SEEDED`), overlap 0.25, FGDC's 90 tiles (2 × 2 tiles, seed 1): every bound met
#: 28 → 42, median L 0.82 → 0.84, L ≥ 0.85 31 → 44; but 642 density / ρ 0.93 → 1.16 (3 large
#: motifs carry 85 % of its cover: 19 in the region for its 12) and 629 L 0.87 → 0.84, which
#: :data:`REFILL_OVERLAP` undoes.  1.0 → 0.65 (2026-12-05): two patches cut at independent phases
#: of a tile of period w with side f·w share about f² of their marks, all at one displacement —
#: at f = 1 every pair of neighbouring patches is the whole tile twice, side by side.  On the gate
#: regions of issue 12 (3 × 3 periods, tests/test_wholeset.py, seed 1), the 35 tiles auto sends
#: here, f = 1.0 / 0.8 / 0.72 / 0.65: repetition > 0.2 on 21 / 15 / 15 / 5 (FGDC 684, 686, 715:
#: 0.60, 0.64, 0.66 at 1.0 → 0.17, 0.17, 0.18), every bound met 14 / 19 / 19 / 21, kind-mix TV
#: > 0.05 on 4 / 7 / 6 / 11, mean L 0.85 / 0.82 / 0.82 / 0.80 (benchmarks/README.md).  The
#: 2 × 2-tile figures above saw little of it: that region is scored whole, and its dozen pairs of
#: neighbouring patches, each at its own displacement, dilute the mode that one period of
#: interior, seeing one or two pairs, finds.
TILE_CELL = 0.65
MAX_CELL = 12.0
#: How far the start's patches reach past their cells (σ, a fraction of the cell) where the
#: solver refills: not at all.  The overlap is there so that seams, once culled, are not sparser
#: than the exemplar; insertion refills them here.  With patches of the tile's whole period the
#: overlap strips held a second phase of the tile, whose large motifs culling keeps (the smaller
#: leave first) and whose mismatched neighbourhoods the solver does not undo.  0.25 → 0, FGDC's
#: 90 tiles (2 × 2 tiles, seed 1, with TILE_CELL 1.0 and the seeded search): every bound met 42 →
#: 67, median L 0.84 → 0.91, L ≥ 0.85 44 → 73, density in bounds 88 → 88 (642 1.16 → 0.99, 641
#: 0.87 → 1.02; 606 0.90 → 0.89, 614 0.95 → 0.90 out), repetition ≤ 0.2 87 → 85 (664 0.07 →
#: 0.22, 653 0.15 → 0.22: whole-period patches put more of the tile side by side).
REFILL_OVERLAP = 0.0
#: Patches of at least this many exemplar spacings seed the solver's first search with the
#: exemplar motif each start motif was copied from (:func:`.init.patch_start` ``sources``,
#: :func:`.solver.refine` ``first``; §4.1–4.2: a motif copied with its neighbours has its own
#: source as its best match, which the hashed first candidates, 48 of the tile's motifs, may miss
#: on a tile of hundreds).  Below it (drawn exemplars at the default ``start_cell``, tiles whose
#: :data:`TILE_CELL` share of the period is under 12 spacings — periods under about 18.5
#: spacings) the first search is unchanged, so are their textures.  Seeding keeps copies as
#: copies: at 7.8 spacings (what 12 was of a whole-period patch) on the 35 gate tiles of
#: TILE_CELL's note, 11 → 24 of them seeded, mean L 0.796 → 0.804, repetition > 0.2 on 5 → 9,
#: every bound met 21 → 20 — kept at 12.  A start that is the tile itself (:func:`.init.seamless`)
#: is seeded at any size: each of its motifs is a copy of its site with the site's whole
#: neighbourhood, so its source is its exact match, and the hashed candidates missed it for a rare
#: kind — Equinor 30019's two hollow squares among 126 dots were matched to dots' sites and voted
#: away, 5 of 8 on 2 × 2 tiles (density / ρ 0.83 → 1.00, kind mix 0.010 → 0.000).
SEEDED = 12.0


@dataclass(frozen=True)
class OptimizeParams(EngineParams):
    """Parameters of the optimize engine.

    Attributes
    ----------
    passes : int ≥ 0
        Search-and-assignment iterations of the solver (§4, Pseudocode 1).
    neighbourhood : int in [2, 24]
        k, neighbours per neighbourhood (§3.2; 6 is the first ring of a lattice).
    start_cell : float > 0
        Side of the start's patches, exemplar spacings (§4.1: the neighbourhood's extent); on a
        repeating tile the solver refills, larger up to the tile's size (:func:`start_side`).
    start_overlap : float ≥ 0
        How far each start patch reaches past its cell, a fraction of the cell (on a repeating
        tile the solver refills, :data:`REFILL_OVERLAP` instead).
    renew : float ≥ 0
        On a drawn exemplar (with ``insert``, one sample per motif, ``passes`` ≥ 2), the start is
        renewed before the first assignment: in each of :data:`.solver.RENEW_ROUNDS` rounds the
        motifs whose neighbourhood matches over ``renew`` times as badly as their window's median
        and worst among their neighbours leave, and insertion adds what the neighbourhoods
        predict (:class:`.solver.Settings`; 0: off, the paper's fixed count).
    anchor, sweeps, similar, alpha, domain, elongated, insert : solver settings (:class:`.solver.Settings`)
    """

    passes: int = param(10, "Optimisation iterations (search, then assignment) after the patch-copy start.",
                        interval=(0, 100))
    neighbourhood: int = param(6, "Neighbours each motif's surroundings are compared by (2 to 24; 6 = one ring).",
                               interval=(2, 24))
    start_cell: float = 5.0
    start_overlap: float = 0.25
    anchor: float = 1.0
    sweeps: int = 3
    similar: int = 2
    alpha: float = 1.0
    domain: float = 1.0
    elongated: float = 0.0
    insert: bool = True
    renew: float = 2.0

    def __post_init__(self) -> None:
        if not 0 <= self.passes <= 100:
            raise ParameterError(f"--passes must be between 0 and 100, not {self.passes}")
        if not 2 <= self.neighbourhood <= 24:
            raise ParameterError(f"--neighbourhood must be between 2 and 24, not {self.neighbourhood}")
        if not (self.start_cell > 0 and self.start_overlap >= 0):
            raise ParameterError("start_cell must be positive and start_overlap at least 0")
        if not (self.anchor > 0 and self.sweeps >= 1 and self.similar >= 0 and self.alpha >= 0
                and self.domain >= 0 and self.elongated >= 0 and self.renew >= 0):
            raise ParameterError("anchor must be positive, sweeps at least 1, similar, alpha, domain, elongated and renew "
                                 "at least 0")

    def settings(self) -> Settings:
        from svgtile.engines.optimize.solver import Settings

        return Settings(self.neighbourhood, self.alpha, self.similar, self.anchor, self.sweeps, self.domain,
                        self.elongated, self.insert, renew=self.renew)


def start_side(exemplar: Exemplar, start_cell: float, refill: bool) -> float:
    """Side of the start's patches, user units: ``start_cell`` exemplar spacings (§4.1: the
    neighbourhood's extent), or on a repeating tile that the solver refills (``refill``) the
    larger of that and :data:`TILE_CELL` of the tile's shorter period, at most :data:`MAX_CELL`
    spacings.  Each seam of the start loses motifs to culling and L to mismatched neighbourhoods;
    a tile's own content is seamless up to its period, so large patches have few seams; but two
    patches of the whole period are the whole tile twice, side by side, hence a share of it."""
    spacing = _spacing(exemplar)
    cell = start_cell * spacing
    if refill and exemplar.period is not None:
        cell = max(cell, min(TILE_CELL * min(exemplar.period), MAX_CELL * spacing))
    return cell


#: The refilled texture is filled when the motifs centred in its interior cover less than this
#: share of ρ there (:func:`fill_light`): the whole-set gate's lower bound on density / ρ.
FILL_BELOW = 0.9


def fill_light(arr: Arrangement, ctx: Context) -> Arrangement:
    """The solver's texture, or where it is light as a whole, that texture with the kinds its light
    windows lack by area dropped into their empty places (:func:`svgtile.engines.holes.fill_holes`,
    the patch engine's last step).

    A departure from Ma, Wei & Tong 2011, who keep the element count of the start (§4: every
    element is matched and moved, none added; their §4.1 start has no seams).  A start of patches
    cut from a repeating tile loses motifs where patches meet; insertion (:mod:`.insert`) refills
    what the neighbourhoods predict, but on tiles whose cover is in large marks each drawn once
    (FGDC 606, breccia: 60 of 62 kinds once) the seams keep holes no prediction fills without
    breaking a rule, and the texture stays at 0.88 of ρ.  Here the holes are filled after the last
    iteration, so the motifs added are not pulled towards the exemplar's neighbourhoods (L falls
    where they land); to spend that only where density needs it, the step runs only when the
    texture is light as a whole: the footprint area of the motifs centred in the region's interior
    (shrunk by the exemplar's larger side, where the boundary mode's losses do not reach; the
    whole region if that is empty) is below :data:`FILL_BELOW` ρ of its area — the window and
    estimate :func:`svgtile.metrics.score` reads density by.  A texture within the density bound
    is returned as it is, and so is one the fill would take over (2 − :data:`FILL_BELOW`) ρ there:
    on tiles whose cover is a few large motifs one more a window overshoots (FGDC 641 and 642 with
    ``--engine optimize`` on 2 × 2 tiles: 0.67 → 1.27 and 0.84 → 1.36, L 0.76 → 0.50 and
    0.69 → 0.55).  Measured on the whole-set gate's 35 tile-scatter tiles
    (benchmarks/README.md, "optfill"): with fill_holes' own trigger alone (any whole window below
    0.9 ρ), FGDC 684 and 685 went to kind-mix TV 0.079 / 0.087 and L fell by up to 0.11 on tiles
    already in bounds; gated on the whole windows' mean, 614 (interior 0.95) was filled at L −0.03
    and 606 on issue 14's 2 × 2-tile region (scored 0.905) at L 0.75 → 0.67; the patch engine's
    density repair (pasted discs of the tile, unturned) took L down by up to 0.33 (614) and left
    606 at 0.898.  The trigger depends on the region's extent, as fill_holes' own does.

    Parameters
    ----------
    arr : the refined texture, no conflicts, kept by the boundary mode
    ctx : the engine's context (exemplar, stats, region, boundary, key: every random choice of
        the fill is a hash of ``ctx.key`` and world-anchored integers)

    Returns
    -------
    Arrangement: ``arr`` itself, or its motifs not displaced followed by those added; no overlaps,
    no distance-rule violations, kept by the boundary mode.
    """
    from svgtile.engines.holes import fill_holes

    if _interior_density(arr, ctx) >= FILL_BELOW * ctx.stats.density:
        return arr
    filled = fill_holes(arr, ctx.exemplar, ctx.stats, ctx.region, ctx.boundary, key=ctx.key, tolerance=1 - FILL_BELOW)
    if _interior_density(filled, ctx) > (2 - FILL_BELOW) * ctx.stats.density:
        return arr  # a few large motifs over ρ: the fill overshot the bound's other side
    return filled


def _interior_density(arr: Arrangement, ctx: Context) -> float:
    """The covered fraction of the region's interior (shrunk by the exemplar's larger side; the
    whole region if that is empty): the footprint area of the motifs centred in it over its area,
    as :func:`svgtile.metrics.score` reads density (:func:`svgtile.analysis.window.measured_window`,
    :func:`svgtile.analysis.window.density`)."""
    from svgtile.analysis.window import density, measured_window

    window, _ = measured_window(ctx.exemplar, ctx.region)
    return density(arr, ctx.exemplar, window)


def _spacing(exemplar: Exemplar) -> float:
    """The exemplar's mean spacing ``sqrt(area / motifs)``, user units."""
    return float(np.sqrt(exemplar.region.area / max(len(exemplar.motifs), 1)))


class OptimizeEngine:
    """Discrete element texture optimisation behind the engine protocol (:mod:`svgtile.engines.base`)."""

    name = "optimize"
    #: CPU seconds per motif of ``svgtile synth`` end to end (benchmarks/work_per_motif.py, rounded up)
    seconds_per_motif = 3e-4
    #: … and of each iteration of ``--refine`` on another engine's texture
    refine_seconds_per_motif = 1e-4
    summary = ("copies of the exemplar, then every motif's neighbourhood pulled towards the exemplar's "
               "(Ma, Wei & Tong 2011)")
    Params = OptimizeParams
    controls = frozenset({"flow"})

    def place(self, ctx: Context, p: OptimizeParams) -> Arrangement:
        """Exemplar patches (§4.1), refined by ``p.passes`` iterations (§4); a refilled texture that
        is light as a whole then has its holes filled (:func:`fill_light`, not in the paper)."""
        from svgtile.engines.optimize.init import patch_start, seamless
        from svgtile.engines.optimize.solver import refine

        ex = ctx.exemplar
        # insertion, capped at ρ, refills the seams of patches cut from a repeating tile;
        # elsewhere the start's density holds (patches of a drawn exemplar thinned to ρ, or the
        # tile itself)
        itself = seamless(ex, ctx.controls.flow)  # the start is the tile repeated (a repeating tile only)
        refill = p.insert and ex.period is not None and not itself
        # a drawn exemplar's start is off its kind mix (its windows take its middle more often
        # than its edges, :func:`.init.thin`): thinned by count, its mix brought back as it goes
        drawn = ex.period is None
        # a drawn exemplar's start also renews its worst-matched motifs, insertion refilling them;
        # on a repeating tile the refill copies its neighbours' stretch of the tile, and the
        # repeats that makes outweigh the likeness (benchmarks/README.md, renew14)
        renew = p.renew if drawn and p.insert else 0.0
        settings = replace(p.settings(), insert=refill, rebalance=drawn, renew=renew)
        ctx.progress("patches", 0.0)
        cell = start_side(ex, p.start_cell, refill)
        # the tile itself (which has no cells) is its motifs' sources; MAX_CELL's cap is SEEDED spacings exactly
        seeded = itself or cell >= SEEDED * _spacing(ex) * (1.0 - 1e-9)
        start = patch_start(ex, ctx.stats, ctx.region, ctx.boundary, key=ctx.key, cell=cell,
                            overlap=REFILL_OVERLAP if refill else p.start_overlap,
                            flow=ctx.controls.flow, refill=refill, by_count=drawn, sources=seeded)  # fmt: skip
        arr, first = start if seeded else (start, None)
        arr, _ = refine(arr, ctx.exemplar, ctx.stats, ctx.region, ctx.boundary, iterations=p.passes, key=ctx.key,
                        flow=ctx.controls.flow, settings=settings, progress=ctx.progress, first=first)  # fmt: skip
        if refill and p.passes > 0:
            arr = fill_light(arr, ctx)
        return arr

    def reach(self, exemplar: Exemplar, params: OptimizeParams) -> float:
        """Not exactly tile-exact: culling at the start's seams may chain (in practice a few
        motifs), so it is run whole."""
        return math.inf


OPTIMIZE = OptimizeEngine()
