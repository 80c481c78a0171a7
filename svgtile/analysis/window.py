"""Where density is read, and how: the interior window and the covered fraction counted by centroid.

The texture's *interior* is the output region shrunk by one exemplar width (the larger side of
the input region's bounding box), so that border effects (motifs cut or dropped at the edge) do
not dominate; a motif is *in* a window when its centroid is.  The likeness figures are measured
there (:mod:`svgtile.metrics.window`, :func:`svgtile.metrics.amounts.density`), and an engine that
decides by the texture's density as :func:`svgtile.metrics.score` reads it
(:func:`svgtile.engines.optimize.engine.fill_light`) reads it here, before the metrics stage.
"""

from __future__ import annotations

import numpy as np
import shapely

from svgtile.analysis.stats import footprint_areas
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region


def exemplar_size(exemplar: Exemplar) -> tuple[float, float]:
    """Width and height of the input region's bounding box, user units."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return x1 - x0, y1 - y0


def interior(exemplar: Exemplar, region: Region) -> shapely.Geometry:
    """The output region shrunk by the larger side of the input region's bounding box."""
    return region.interior(max(exemplar_size(exemplar)))


def measured_window(exemplar: Exemplar, region: Region) -> tuple[shapely.Geometry, str]:
    """The window density is read on: the :func:`interior`, or the whole region if that is empty.

    Parameters
    ----------
    exemplar : gives the input region (its bounding box's larger side is the margin)
    region : the output region, user units

    Returns
    -------
    (window, kind) — the shapely geometry, user units, and ``"interior"`` or ``"region"``, which
    of the two it is
    """
    window = interior(exemplar, region)
    if window.is_empty or window.area <= 0:
        return region.shape, "region"
    return window, "interior"


def in_window(arr: Arrangement, window: shapely.Geometry) -> np.ndarray:
    """(n,) bool: the motifs whose centroid lies in ``window``."""
    return shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1])


def density(
    arr: Arrangement, exemplar: Exemplar, window: shapely.Geometry, *, inside: np.ndarray | None = None
) -> float:
    """Footprint area of the motifs whose centroid lies in ``window``, over its area.

    Counting by centroid is an unbiased estimate of the covered fraction (motifs cut by the
    window's edge are counted in full as often as they are missed).

    Parameters
    ----------
    arr : Arrangement of n motifs
    exemplar : gives the prototypes
    window : shapely geometry, user units
    inside : (n,) bool, :func:`in_window` of ``window`` if already known

    Returns
    -------
    float, the covered fraction (dimensionless)
    """
    if inside is None:
        inside = in_window(arr, window)
    return float(footprint_areas(arr, exemplar.prototypes)[inside].sum() / window.area)
