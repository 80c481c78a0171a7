"""How much the texture holds: the covered fraction, globally and per window, and the kind mix.

almeraj2013 §3.4 keeps the density ρ (the covered fraction) and the kind frequencies ``f_i`` of
the exemplar; these figures say how close a texture comes.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from svgtile.analysis.stats import Stats, footprint_areas
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.metrics.window import exemplar_size, in_window


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
    inside : (n,) bool, :func:`~svgtile.metrics.window.in_window` of ``window`` if already known

    Returns
    -------
    float, the covered fraction (dimensionless)
    """
    if inside is None:
        inside = in_window(arr, window)
    return float(footprint_areas(arr, exemplar.prototypes)[inside].sum() / window.area)


def kind_mix_tv(
    arr: Arrangement, stats: Stats, window: shapely.Geometry | None = None, *, inside: np.ndarray | None = None
) -> float:
    """Total variation distance between the kind frequencies of ``arr`` and the exemplar's.

    ``½ Σ_i |f'_i − f_i|`` over the motifs in ``window`` (all of them if None; ``inside``, (n,)
    bool, if already known): 0 is the exemplar's mix, 1 if no motif is counted.
    """
    kind = arr.kind
    if inside is not None:
        kind = kind[inside]
    elif window is not None:
        kind = kind[in_window(arr, window)]
    if len(kind) == 0:
        return 1.0
    freq = np.bincount(kind, minlength=len(stats.frequency)) / len(kind)
    return float(0.5 * np.abs(freq - stats.frequency).sum())


def window_densities(arr: Arrangement, exemplar: Exemplar, window: shapely.Geometry) -> np.ndarray:
    """Covered fraction ``D_w`` of each window the size of the input region tiling ``window``.

    The windows are the cells of a grid of the input region's bounding-box size ``w × h``,
    centred on ``window``'s bounding box, that lie wholly inside ``window`` (``⌊W/w⌋ × ⌊H/h⌋``
    of them for a ``W × H`` rectangle).  ``D_w`` is the footprint area of the motifs whose
    centroid lies in cell ``w`` (cells are half-open), over ``w·h`` — as in :func:`density`.

    Returns
    -------
    (m,) float array, in row-major order of the grid; empty if no cell fits.
    """
    w, h = exemplar_size(exemplar)
    x0, y0, x1, y1 = window.bounds
    nx, ny = math.floor((x1 - x0) / w + 1e-9), math.floor((y1 - y0) / h + 1e-9)
    if nx < 1 or ny < 1:
        return np.zeros(0)
    ox, oy = x0 + ((x1 - x0) - nx * w) / 2, y0 + ((y1 - y0) - ny * h) / 2
    cx, cy = np.meshgrid(np.arange(nx), np.arange(ny))
    cx, cy = cx.ravel(), cy.ravel()
    cells = shapely.box(ox + cx * w, oy + cy * h, ox + (cx + 1) * w, oy + (cy + 1) * h)
    fits = shapely.contains(shapely.buffer(window, 1e-9 * max(w, h)), cells)
    ix = np.floor((arr.xy[:, 0] - ox) / w).astype(np.int64)
    iy = np.floor((arr.xy[:, 1] - oy) / h).astype(np.int64)
    ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
    area = np.bincount(iy[ok] * nx + ix[ok], footprint_areas(arr, exemplar.prototypes)[ok], minlength=nx * ny)
    return area[fits] / (w * h)
