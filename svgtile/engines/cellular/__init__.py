"""Feature-based cellular textures (Legakis, Dorsey & Gortler 2001), ``--engine cellular``.

Read in pipeline order: :mod:`.mesh` (the base mesh, §3.1), :mod:`.frame` (parameterisation,
§3.2), :mod:`.tree` (the tree of pattern generators, §4.1), :mod:`.generators` (the generators
and their tools, §5.1–5.4), :mod:`.engine` (ordering and occupancy, §3.3 and §4.2).

This module is the engine's declaration — its parameters (:class:`CellularParams`, from which the
CLI options, styles keys and dialogs are made) and its protocol object (:data:`CELLULAR`) — and
imports none of the modules above: they (scipy's interpolators and sparse least squares) are
imported when the engine runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from svgtile.core.arrangement import Arrangement
from svgtile.core.cells import Cellwork
from svgtile.core.exemplar import Exemplar
from svgtile.engines.base import Context, EngineParams, param
from svgtile.errors import ParameterError


@dataclass(frozen=True)
class CellularParams(EngineParams):
    """Parameters of the cellular engine.

    Attributes
    ----------
    tree : path of a TOML/JSON pattern description (:mod:`.tree`); "" = the exemplar's own (as
        ``svgtile import`` writes it), else the paper's "Bricks" tree sized to the exemplar
    courses : ``strike`` (courses along ``strike``) or ``long-axis`` (along the unit's long
        axis); the ``--flow`` control, when given, overrides both
    strike : degrees, the courses' bearing in user space (0 = along +x)
    course_height, cell_length, mortar : user units; 0 = the description's
    label : ``NAME=MAP.svg#ID`` pairs, comma-separated: edges running along that map element are
        labelled NAME (for the tree's ``label`` tests)
    corner_angle : degrees; the boundary turning by more than this makes a corner (library only)
    label_unit : units of the ``label`` files per user unit (library only: ``svgtile map`` sets a
        class's ``unit``, its map lines then label edges of the unit in the exemplar's units)
    """

    tree: str = param("", "Cellular pattern description, a TOML or JSON file (default: the exemplar's own, or running-bond bricks).", metavar="FILE")
    courses: str = param("strike", "Cellular courses run along the --strike angle or along the unit's long axis (a --flow overrides both).", choices=("strike", "long-axis"))
    strike: float = param(0.0, "Bearing of the cellular courses, degrees from +x.", interval=(-360.0, 360.0))
    course_height: float = param(0.0, "Cellular course height, user units (0 = the description's).", interval=(0.0, math.inf))
    cell_length: float = param(0.0, "Cellular cell length along a course, user units (0 = the description's).", interval=(0.0, math.inf))
    mortar: float = param(0.0, "Gap between cellular cells, user units (0 = the description's).", interval=(0.0, math.inf))
    label: str = param("", "Label the unit's edges that run along map lines, NAME=MAP.svg#ID[,NAME=MAP.svg#ID…] (cellular trees route labelled edges).", metavar="NAME=MAP.svg#ID")
    halves: str = param("fewest", "Cellular bricks: the bond with the fewest cut bricks in each unit (legakis2001 §5.2), or anchored to the world (an edit then changes only the cells near it).", choices=("fewest", "anchored"))
    corner_angle: float = 30.0
    label_unit: float = 1.0

    def __post_init__(self) -> None:
        for name in ("course_height", "cell_length", "mortar"):
            value = getattr(self, name)
            if not (value >= 0 and math.isfinite(value)):
                raise ParameterError(f"{name} must be a finite number ≥ 0, not {value:g}")
        if not (math.isfinite(self.strike) and -360.0 <= self.strike <= 360.0):
            raise ParameterError(f"strike must be in [-360, 360], not {self.strike:g}")
        if not (self.label_unit > 0 and math.isfinite(self.label_unit)):
            raise ParameterError(f"label_unit must be a positive number, not {self.label_unit:g}")
        if not 0.0 < self.corner_angle < 180.0:
            raise ParameterError(f"corner_angle must be in (0, 180), not {self.corner_angle:g}")


class CellularEngine:
    """Cellular textures behind the engine protocol (:mod:`svgtile.engines.base`)."""

    name = "cellular"
    #: CPU seconds per motif of ``svgtile synth`` end to end (benchmarks/work_per_motif.py, rounded up)
    seconds_per_motif = 1.5e-3
    summary = ("cells in courses — bricks, blocks, random ashlar, rhombs, bedding lines, motifs set in cells — "
               "turning the unit's corners and following its edges (Legakis et al. 2001)")
    Params = CellularParams
    controls = frozenset({"flow"})

    def place(self, ctx: Context, p: CellularParams) -> Arrangement:
        """The motifs set in cells (the cells themselves: :meth:`place_cells`)."""
        return self.place_cells(ctx, p)[0]

    def place_cells(self, ctx: Context, p: CellularParams) -> tuple[Arrangement, Cellwork]:
        """Texture ``ctx.region``: corners, edges, then the face (§4.2); lines; motifs in cells."""
        from .engine import description, read_labels, texture

        d = description(ctx.exemplar, p)
        labels = read_labels(p.label, d.course, unit=p.label_unit)
        return texture(ctx, d, p, labels)

    def reach(self, exemplar: Exemplar, params: CellularParams) -> float:
        """Not tile-exact: edge and corner cells follow the whole unit's boundary, and a tile's
        boundary is not the unit's; run it whole."""
        return math.inf


CELLULAR = CellularEngine()


__all__ = ["CELLULAR", "CellularEngine", "CellularParams"]
