"""Where and at what scale the figures are measured: the interior, the mean spacing, the sample.

Figures are measured on the texture's *interior* — the output region shrunk by one exemplar
width — so that border effects (motifs cut or dropped at the edge) do not dominate.  A motif is
*in* a window when its centroid is.  Lengths a figure is measured with (ranges, bins, grid steps)
are multiples of the exemplar's *mean spacing* ``s = 1 / sqrt(λ)``, λ its motifs per unit area,
so the figures do not depend on the drawing's scale.  Large textures are measured on a sample of
their motifs where a figure is a distribution (:func:`motif_sample`).
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.cellrng import hash64
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region


def interior(exemplar: Exemplar, region: Region) -> shapely.Geometry:
    """The output region shrunk by the larger side of the input region's bounding box."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return region.interior(max(x1 - x0, y1 - y0))


def spacing(stats: Stats) -> float:
    """The exemplar's mean spacing ``s = 1 / sqrt(λ)``, λ its motifs per unit area (user units)."""
    return 1.0 / math.sqrt(stats.count_density) if stats.count_density > 0 else math.inf


def exemplar_size(exemplar: Exemplar) -> tuple[float, float]:
    """Width and height of the input region's bounding box, user units."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return x1 - x0, y1 - y0


def in_window(arr: Arrangement, window: shapely.Geometry) -> np.ndarray:
    """(n,) bool: the motifs whose centroid lies in ``window``."""
    return shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1])


def motif_sample(arr: Arrangement, index: np.ndarray, most: int) -> np.ndarray:
    """At most ``most`` of the motifs ``index``: those with the smallest hash of kind and position.

    Deterministic and independent of the motifs' order; a hash does not alias with a periodic
    layout the way a stride through reading order would.

    Parameters
    ----------
    arr : Arrangement of n motifs
    index : (m,) int array, indices into ``arr``
    most : largest size of the sample

    Returns
    -------
    (min(m, most),) int array, sorted (``index`` itself if it is small enough)
    """
    if len(index) <= most:
        return index
    q = np.round(arr.xy[index] * 1e4).astype(np.int64)
    h = hash64(0x5C0E, 0, arr.kind[index], q[:, 0], q[:, 1])
    return np.sort(index[np.argsort(h, kind="stable")[:most]])


def finite_or_none(value: float | None) -> float | None:
    """A JSON-able float: None for a missing or non-finite value."""
    return None if value is None or not math.isfinite(value) else float(value)
