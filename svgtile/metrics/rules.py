"""Whether the texture keeps the exemplar's rules: no overlaps, the distance rule ``d_ij``
(almeraj2013 §3.1) and the orientation arcs (§3.5)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.analysis.stats import Stats, in_arcs
from svgtile.core.arrangement import Arrangement
from svgtile.core.conflicts import find_conflicts
from svgtile.core.footprint import Prototype
from svgtile.metrics.window import in_window


@dataclass(frozen=True)
class Conflicts:
    """Overlaps and distance-rule violators of a texture, in a window and in total.

    Attributes
    ----------
    overlaps : int
        Pairs of motifs whose footprints share area (touching does not count), at least one of
        them in the window; 0 is right.
    violators : int
        Motifs in the window with a neighbour (anywhere) closer than ``d_ij``; 0 is right.
    violator_fraction : float or None
        ``violators`` over the motifs in the window (None if there are none); 0 is right.
    overlaps_total, violators_total : int
        The same over the whole texture.
    """

    overlaps: int
    violators: int
    violator_fraction: float | None
    overlaps_total: int
    violators_total: int


def conflict_counts(
    arr: Arrangement, protos: list[Prototype], stats: Stats, inside: np.ndarray, geoms: np.ndarray | None = None
) -> Conflicts:
    """Overlaps and distance-rule violators, in a window and in total.

    A violator has a neighbour whose footprint is closer than ``d_ij`` (an overlapping neighbour
    is closer unless ``d_ij = 0``), less the rounding slack of
    :func:`svgtile.core.conflicts.slack`.

    Parameters
    ----------
    arr : Arrangement of n motifs
    protos : kind prototypes
    stats : the exemplar's analysis (its ``d_ij``)
    inside : (n,) bool, the motifs in the window
    geoms : (n,) world footprints, if built (or a :class:`~svgtile.metrics.coverage.Footprints`)

    Returns
    -------
    Conflicts
    """
    found = find_conflicts(arr, protos, stats.distance, geoms)
    touch = inside[found.i] | inside[found.j]
    violator = np.zeros(len(arr), dtype=bool)
    violator[found.i[found.violation]] = violator[found.j[found.violation]] = True
    n_in = int(inside.sum())
    return Conflicts(
        overlaps=int((found.overlap & touch).sum()),
        violators=int((violator & inside).sum()),
        violator_fraction=float((violator & inside).sum() / n_in) if n_in else None,
        overlaps_total=int(found.overlap.sum()),
        violators_total=int(violator.sum()),
    )


def orientation_outside(
    arr: Arrangement, stats: Stats, window: shapely.Geometry, *, inside: np.ndarray | None = None
) -> float | None:
    """Fraction of the motifs in ``window`` outside their kind's orientation arc (almeraj2013 §3.5).

    Uses :func:`svgtile.analysis.stats.in_arcs` (with its rounding tolerance); None if no motif is in
    ``window``; 0 is right.  ``inside`` : (n,) bool, the motifs in ``window``, if already known.
    """
    if inside is None:
        inside = in_window(arr, window)
    if not inside.any():
        return None
    return float((~in_arcs(arr.angle[inside], arr.kind[inside], stats)).mean())
