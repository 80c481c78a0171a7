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
#: is false): this share of the tile's shorter period, so that a window with its overlap (σ = 0.25)
#: stays within one period and holds no repeat of it, and at most :data:`MAX_CELL` exemplar
#: spacings (FGDC 606, 616, 617 at 5, 8 and 12 spacings: L 0.48 / 0.71 / 0.71 → 0.75 / 0.82 / 0.80
#: → 0.77 / 0.83 / 0.88, density / ρ 0.87 / 0.85 / 0.83 → 0.91–0.95; 626 and 641, tiles of
#: 5.6–5.9 spacings, at 12: repetition 0.50 and 0.25, their tile's period inside each patch).
TILE_CELL = 0.8
MAX_CELL = 12.0


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
        How far each start patch reaches past its cell, a fraction of the cell.
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

    def __post_init__(self) -> None:
        if not 0 <= self.passes <= 100:
            raise ParameterError(f"--passes must be between 0 and 100, not {self.passes}")
        if not 2 <= self.neighbourhood <= 24:
            raise ParameterError(f"--neighbourhood must be between 2 and 24, not {self.neighbourhood}")
        if not (self.start_cell > 0 and self.start_overlap >= 0):
            raise ParameterError("start_cell must be positive and start_overlap at least 0")
        if not (self.anchor > 0 and self.sweeps >= 1 and self.similar >= 0 and self.alpha >= 0
                and self.domain >= 0 and self.elongated >= 0):
            raise ParameterError("anchor must be positive, sweeps at least 1, similar, alpha, domain and elongated at least 0")

    def settings(self) -> Settings:
        from svgtile.engines.optimize.solver import Settings

        return Settings(self.neighbourhood, self.alpha, self.similar, self.anchor, self.sweeps, self.domain,
                        self.elongated, self.insert)


def start_side(exemplar: Exemplar, start_cell: float, refill: bool) -> float:
    """Side of the start's patches, user units: ``start_cell`` exemplar spacings (§4.1: the
    neighbourhood's extent), or on a repeating tile that the solver refills (``refill``) the
    larger of that and :data:`TILE_CELL` of the tile's shorter period, at most :data:`MAX_CELL`
    spacings.  Each seam of the start loses motifs to culling and L to mismatched neighbourhoods;
    a tile's own content is seamless up to its period, so patches as large as it allows have the
    fewest seams without repeating it."""
    spacing = float(np.sqrt(exemplar.region.area / max(len(exemplar.motifs), 1)))
    cell = start_cell * spacing
    if refill and exemplar.period is not None:
        cell = max(cell, min(TILE_CELL * min(exemplar.period), MAX_CELL * spacing))
    return cell


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
        """Exemplar patches (§4.1), refined by ``p.passes`` iterations (§4)."""
        from svgtile.engines.optimize.init import patch_start, seamless
        from svgtile.engines.optimize.solver import refine

        ex = ctx.exemplar
        # insertion, capped at ρ, refills the seams of patches cut from a repeating tile;
        # elsewhere the start's density holds (patches of a drawn exemplar thinned to ρ, or the
        # tile itself)
        refill = p.insert and ex.period is not None and not seamless(ex, ctx.controls.flow)
        settings = replace(p.settings(), insert=refill)
        ctx.progress("patches", 0.0)
        arr = patch_start(ex, ctx.stats, ctx.region, ctx.boundary, key=ctx.key, cell=start_side(ex, p.start_cell, refill),
                          overlap=p.start_overlap, flow=ctx.controls.flow, refill=refill)  # fmt: skip
        arr, _ = refine(arr, ctx.exemplar, ctx.stats, ctx.region, ctx.boundary, iterations=p.passes, key=ctx.key,
                        flow=ctx.controls.flow, settings=settings, progress=ctx.progress)  # fmt: skip
        return arr

    def reach(self, exemplar: Exemplar, params: OptimizeParams) -> float:
        """Not exactly tile-exact: culling at the start's seams may chain (in practice a few
        motifs), so it is run whole."""
        return math.inf


OPTIMIZE = OptimizeEngine()
