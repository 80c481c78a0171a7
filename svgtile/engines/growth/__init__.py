"""The local-growth engine of Ijiri, Měch, Igarashi & Miller 2008 (``--engine growth``).

Read in pipeline order: :mod:`.connectivity` (§4, the exemplar's ring shapes),
:mod:`.matching` (§5.2–5.3, the best-matching reference), :mod:`.grow` (§5.1, §5.4, growth from
seeds), :mod:`.relax` (§5.5, relaxation), :mod:`.rows` (a drawn exemplar's row lines, held by
growth and relaxation), :mod:`.kinds` (the final kind pass on such rows, §5.2 over each motif's
complete ring) and :mod:`.neighbourkinds` (after it, kinds against the exemplar's k-nearest
neighbourhoods, Ma, Wei & Tong 2011 §3.2), :mod:`.gapfill` and :mod:`.phases` (a repeating tile's sites: its gaps filled, its
hand-phased rows at wandering world phases), :mod:`.engine` (world cells, the tools).

This module is the engine's declaration — its parameters (:class:`GrowthParams`, from which the
CLI options, styles keys and dialogs are made) and its protocol object (:data:`GROWTH`) — and
imports none of the modules above: they (numba's compiled kernel, scipy's sparse solver) are
imported when the engine runs, so a command that does not grow (``svgtile score``, ``analyze``,
``--help``) does not pay for them.
"""

from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass

import numpy as np

from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.engines.base import Context, EngineParams, param
from svgtile.errors import ExemplarError, ParameterError

ROTATIONS = ("auto", "none", "fit", "flow")
_PRIORITY_ITEM = re.compile(r"^\s*([^=,\s][^=,]*?)\s*=\s*(-?\d+)\s*$")


@dataclass(frozen=True)
class Weights:
    """Weights of eq. (2) (:mod:`.matching`).

    The paper uses w1 = w2 = 1, w3 = 100 on hand-made irregular references.  On a repeating tile
    each element's ring is the only faithful continuation, and the sub-id term (1 when a target
    neighbour and the reference neighbour it is matched with are the same exemplar motif) would
    forbid exactly that; so w3 defaults to 0 and is a library setting.
    """

    distance: float = 1.0
    kind: float = 1.0
    subid: float = 0.0


@dataclass(frozen=True)
class GrowthParams(EngineParams):
    """Parameters of the growth engine.

    Attributes
    ----------
    rotation : ``auto`` (``flow`` with ``--flow``, else ``none``), ``none``, ``fit``, ``flow`` (§5.3)
    priority : ``KIND=N,KIND=N …`` — kinds with a higher N grow first (§5.1); unnamed kinds keep
        their default, which is by size: kinds within a factor 4 in footprint area share a level,
        larger kinds higher (the paper grows its large stones before the fillers)
    relax_every : relax each cell every this many growth steps (§5.5); 0 = once per cell, after
        its growth (the final pass is always made)
    relaxation : run relaxation at all (library only)
    gap_fill : on a repeating tile, fill the gaps growth leaves with the motifs placed ones
        predict (library only, see :mod:`.gapfill`)
    snap : on a repeating tile grown with rotation ``none``, move each grown motif to the
        nearest site of its kind in the tile's pattern (library only, see :meth:`.engine.Growth.on_sites`)
    row_phases : on a tile of rows exact along x whose phases repeat only at its height, give each
        world row its own phase, a Markov chain of the tile's row-to-row phase steps, instead of
        the tile's sites (library only, see :mod:`.phases`)
    rows : on a drawn exemplar of rows grown with rotation ``none``, grow on world row lines and
        hold the motifs on them in relaxation (library only, see :mod:`.rows`)
    cell_widths : a cell is at least this many exemplar widths wide (library only)
    kind_sweeps : on a drawn exemplar of rows grown with rotation ``none``, sweeps of the final
        kind pass that re-chooses kinds against each motif's complete ring, holding the
        exemplar's kind mix (library only, see :mod:`.kinds`); 0 = none
    neighbourhood_sweeps : with the kind pass, at most this many sweeps of the pass after it that
        re-chooses kinds against the exemplar's k-nearest neighbourhoods (ma2011 §3.2; library
        only, see :mod:`.neighbourkinds`); 0 = none
    weights : eq. (2)'s w1, w2, w3 (library only, see :class:`Weights`)
    """

    rotation: str = param("auto", "How motifs turn (growth engine): none = as in the exemplar; fit = the best "
                          "rotation of each neighbourhood; flow = along --flow; auto = flow with --flow, else none.",
                          choices=ROTATIONS)  # fmt: skip
    priority: str = param("", "Growth order of kinds (growth engine), e.g. 'stone=2,dot=0': higher grows first; "
                          "default: larger motifs first.", metavar="KIND=N,…")  # fmt: skip
    relax_every: int = param(0, "Relax the growing texture every N motifs (growth engine); 0 = once per cell.",
                             interval=(0, 1_000_000), metavar="N")  # fmt: skip
    relaxation: bool = True
    gap_fill: bool = True
    snap: bool = True
    row_phases: bool = True
    rows: bool = True
    cell_widths: float = 1.0
    kind_sweeps: int = 4  # growth.kinds.SWEEPS (not imported: this module imports no engine module)
    neighbourhood_sweeps: int = 8  # growth.neighbourkinds.SWEEPS
    weights: Weights = dataclasses.field(default_factory=Weights)

    def __post_init__(self) -> None:
        if self.rotation not in ROTATIONS:
            raise ParameterError(f"rotation must be one of {', '.join(ROTATIONS)}, not {self.rotation!r}")
        if not 0 <= self.relax_every <= 1_000_000:
            raise ParameterError(f"relax_every must be at least 0, not {self.relax_every}")
        if self.kind_sweeps < 0:
            raise ParameterError(f"kind_sweeps must be at least 0, not {self.kind_sweeps}")
        if self.neighbourhood_sweeps < 0:
            raise ParameterError(f"neighbourhood_sweeps must be at least 0, not {self.neighbourhood_sweeps}")
        if not self.cell_widths > 0:
            raise ParameterError(f"cell_widths must be positive, not {self.cell_widths:g}")
        self.priorities()

    def priorities(self) -> dict[str, int]:
        """``--priority`` parsed: kind name → priority."""
        out: dict[str, int] = {}
        for item in filter(str.strip, self.priority.split(",")):
            m = _PRIORITY_ITEM.match(item)
            if not m:
                raise ParameterError(f"priority: {item.strip()!r} is not KIND=N (a kind name, '=', a whole number)")
            out[m.group(1)] = int(m.group(2))
        return out


class GrowthEngine:
    """Local growth (ijiri2008) behind the engine protocol (:mod:`svgtile.engines.base`)."""

    name = "growth"
    #: CPU seconds per motif of ``svgtile synth`` end to end (benchmarks/work_per_motif.py, rounded up)
    seconds_per_motif = 3e-4
    summary = ("motifs grown one by one from the exemplar's neighbourhoods (Ijiri et al. 2008): keeps rows, "
               "lattices and bricks; honours --flow, --barrier and --grow-within")
    Params = GrowthParams
    controls = frozenset({"flow", "barriers", "grow_within"})

    def place(self, ctx: Context, p: GrowthParams) -> Arrangement:
        """Grow the texture over the cells that ``ctx.region`` needs (:mod:`.engine`).

        Raises
        ------
        ExemplarError
            when the exemplar has no rings to grow from (:func:`grows_from`).
        """
        from svgtile.engines.growth.engine import Growth

        if not grows_from(ctx.exemplar):
            raise ExemplarError(f"engine 'growth' grows each motif's ring of neighbours (Ijiri et al. 2008, §4), and "
                                f"this exemplar's {len(ctx.exemplar.motifs)} motif centres lie on one line, which has "
                                "no rings: use --engine patch (or auto)", source=ctx.exemplar.source)  # fmt: skip
        return Growth(ctx, p).run()

    def reach(self, exemplar: Exemplar, params: GrowthParams) -> float:
        """Tile-exact with no halo: a cell's motifs are a function of the key and the cell alone."""
        return 0.0


GROWTH = GrowthEngine()


def grows_from(exemplar: Exemplar) -> bool:
    """Whether growth can read rings from ``exemplar`` (§4: the Delaunay triangulation of the
    motif centres, skewed triangles left out): a repeating tile always can (its copies fill the
    plane), a drawn exemplar when some triangle of its centres is not skewed — not when they lie
    on one line (FGDC 624, 625 and nine of the map-pattern symbols drawn as one column of marks),
    nor when they lie near one (a slanted row whose coordinates are rounded to the file's digits,
    a hand-drawn row: every triangle skewed, no edge, no ring), nor with fewer than three."""
    from svgtile.engines.growth.connectivity import triangles

    xy = exemplar.motifs.xy
    if exemplar.period is not None:
        return len(xy) > 0
    return len(triangles(xy)) > 0


#: Share of the (row, phase step) pairs of a tile of wandering rows that must keep the distance
#: rule for growth to be auto's choice there (:func:`rows_wander`).
ROWS_FIT = 0.9


def rows_wander(exemplar: Exemplar, distance: np.ndarray) -> bool:
    """Whether growth's row phases (:mod:`svgtile.engines.growth.phases`) free this tile from its
    period: it is rows exact along x at hand-drawn phases (:func:`.phases.row_phases` reads it),
    and at least :data:`ROWS_FIT` of the tile's row-to-row phase steps fit after every row
    (the distance rule, :func:`.phases.fitting_steps`), so any row may follow any row as the
    tile's rows do.  FGDC 619 0.975, 620 1.000: growth keeps L 0.98 / 0.92 at repetition 0; 621
    0.46 (rows of three kinds a 26.8-unit step apart, most steps bring a row's motifs too near
    the next's): growth there is L 0.28, repetition 0.31 (benchmarks/README.md, auto13).

    ``distance`` : (k, k) user units, the exemplar's distance rule (:attr:`Stats.distance`).
    """
    from svgtile.engines.growth.phases import row_phases

    read = row_phases(exemplar, 0, distance)
    return read is not None and float(read.count.sum()) >= ROWS_FIT * len(read.count) ** 2


__all__ = ["GROWTH", "ROTATIONS", "ROWS_FIT", "GrowthEngine", "GrowthParams", "Weights", "grows_from", "rows_wander"]
