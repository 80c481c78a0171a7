"""What every engine's output has in common: precision, order, and the shared parameters.

Every engine returns an :class:`~svgtile.core.arrangement.Arrangement` that

* has no overlapping footprints and no distance-rule violations (:mod:`svgtile.core.conflicts`),
* is filtered by the boundary mode (:meth:`svgtile.core.region.Region.keep`),
* has positions, angles and scales rounded to :data:`DECIMALS` when they are created, so every
  check runs on exactly what is written,
* lists its motifs in reading order (:func:`reading_order`),
* draws one key from the caller's ``rng`` and derives every random choice from it with
  world-anchored hashes (:mod:`svgtile.core.cellrng`): the same seed gives the same texture.

The CLI passes ``grid``, ``overlap``, ``max_rotation``, ``vary_orientation``, ``junction`` and
``boundary`` to every engine; :class:`CommonParams` accepts them all, and each engine documents
which it uses.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from svgtile.core.arrangement import DECIMALS, Arrangement  # noqa: F401  (DECIMALS: engines import it from here)
from svgtile.core.region import BOUNDARY_MODES
from svgtile.errors import ParameterError


@dataclass(frozen=True)
class CommonParams:
    """The parameters the CLI passes to every engine.

    Attributes
    ----------
    grid, overlap, max_rotation, vary_orientation, junction
        Parameters of the patch engine (:class:`svgtile.engines.patch.engine.PatchParams`).  Engines
        that have no use for them accept and ignore them, so one command line works with every
        engine; their values are not checked here (the CLI checks their ranges).
    boundary : one of ``inside``, ``centroid``, ``clip``, ``none``
        How motifs meet the output region's boundary (see :mod:`svgtile.core.region`).
    """

    grid: str = "square"
    overlap: float = 0.05
    max_rotation: float = 30.0
    vary_orientation: bool = False
    boundary: str = "clip"
    junction: float = 0.6

    def __post_init__(self) -> None:
        if self.boundary not in BOUNDARY_MODES:
            raise ParameterError(f"--boundary must be one of {', '.join(BOUNDARY_MODES)}, not {self.boundary!r}")


def reading_order(arr: Arrangement) -> Arrangement:
    """Motifs in reading order (rows, then columns): a stable, diff-friendly output."""
    return arr.take(np.lexsort((arr.xy[:, 0], arr.xy[:, 1])))
