"""Figures that say how well a texture reproduces its exemplar.

Measured on the texture's *interior* — the output region shrunk by one exemplar width — so that
border effects (motifs cut or dropped at the edge) do not dominate.
"""

from __future__ import annotations

import numpy as np
import shapely

from .analysis import Stats, footprint_areas
from .arrangement import Arrangement
from .exemplar import Exemplar
from .region import Region


def interior(exemplar: Exemplar, region: Region) -> shapely.Geometry:
    """The output region shrunk by the larger side of the input region's bounding box."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return region.interior(max(x1 - x0, y1 - y0))


def density(arr: Arrangement, exemplar: Exemplar, window: shapely.Geometry) -> float:
    """Footprint area of the motifs whose centroid lies in ``window``, over its area.

    Counting by centroid is an unbiased estimate of the covered fraction (motifs cut by the
    window's edge are counted in full as often as they are missed).
    """
    inside = shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1])
    return float(footprint_areas(arr, exemplar.prototypes)[inside].sum() / window.area)


def kind_mix_tv(arr: Arrangement, stats: Stats, window: shapely.Geometry | None = None) -> float:
    """Total variation distance between the kind frequencies of ``arr`` and the exemplar's."""
    kind = arr.kind
    if window is not None:
        kind = kind[shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1])]
    if len(kind) == 0:
        return 1.0
    freq = np.bincount(kind, minlength=len(stats.frequency)) / len(kind)
    return float(0.5 * np.abs(freq - stats.frequency).sum())
