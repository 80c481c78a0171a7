"""Is an exemplar an arrangement at all?  The check made before the analysis (issue 16 item 3).

The analysis of almeraj2013 §3.1 (minimum distances ``d_ij``, density ρ) and every engine assume
motifs that lie apart, as in a drawn arrangement.  A raw pattern tile (FGDC 661: 3,137 motifs,
12,321 overlapping pairs) or a drawing of strokes that cross breaks that assumption: its distances
are all zero, and measuring and synthesising it costs minutes and gigabytes.  Such an input is
recognised here, in well under a second, by counting pairs of motifs whose footprints share area,
and refused with what to do instead (``svgtile import`` rebuilds the motifs of a tile).
"""

from __future__ import annotations

import numpy as np
import shapely

from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import (
    MAX_NEAR_PAIRS,
    motif_radius,
    near_pair_bound,
    near_pairs,
    world_footprints,
)
from svgtile.errors import ExemplarError

#: Overlapping pairs per motif above which an exemplar is not an arrangement: a few touching or
#: overlapping motifs are drawn by hand (svgtile warns and goes on); more pairs than motifs means
#: motifs are drawn over each other throughout.
MAX_OVERLAPS_PER_MOTIF = 1.0


def check_crowding(exemplar: Exemplar, *, imported: bool = False) -> None:
    """Refuse an exemplar whose motifs overlap heavily (a few overlaps pass: the analysis counts them).

    Parameters
    ----------
    exemplar : the exemplar as read
    imported : it was made by ``svgtile import`` already (the message then does not suggest it)

    Raises
    ------
    ExemplarError
        More than :data:`MAX_OVERLAPS_PER_MOTIF` overlapping pairs per motif, or more than
        :data:`MAX_NEAR_PAIRS` pairs of motifs near enough to be measured.
    """
    arr, protos = exemplar.motifs, exemplar.prototypes
    n = len(arr)
    if n < 2:  # nothing to crowd: a cellular exemplar (svgtile import of a bedded tile) may have no motif
        return
    radius = motif_radius(arr, protos)
    what = ("its motifs are drawn over each other; it is not an arrangement svgtile can measure" if imported else
            "is it a pattern tile or a drawing? Import it first: 'svgtile import FILE -o exemplar.svg', "
            "or 'svgtile synth FILE --import'")  # fmt: skip
    stacked = near_pair_bound(arr.xy, float(np.median(radius)))
    if stacked > MAX_NEAR_PAIRS:
        raise ExemplarError(f"over {MAX_NEAR_PAIRS:,} pairs of its {n:,} motifs lie on each other; {what}",
                            source=exemplar.source)  # fmt: skip
    i, j = near_pairs(arr.xy, radius, 0.0)
    if len(i) > MAX_NEAR_PAIRS:
        raise ExemplarError(f"{len(i):,} pairs of its {n:,} motifs come within a motif of each other; {what}",
                            source=exemplar.source)  # fmt: skip
    if len(i) <= MAX_OVERLAPS_PER_MOTIF * n:
        return  # too few to matter
    geoms = world_footprints(arr, protos)
    share = shapely.intersects(geoms[i], geoms[j]) & ~shapely.touches(geoms[i], geoms[j])
    overlaps = int(share.sum())
    if overlaps > MAX_OVERLAPS_PER_MOTIF * n:
        raise ExemplarError(f"{overlaps:,} pairs of its {n:,} motifs overlap; {what}", source=exemplar.source)
