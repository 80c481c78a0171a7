"""World-anchored windows, where engines measure cover, counts and mix against the exemplar's
(so decisions at a place do not depend on how far the region extends).

Windows the size of the exemplar's region: where the patch engine's density repair (almeraj2013
§3.4, :mod:`svgtile.engines.patch.density`) and the hole filling that follows patch and optimize
(:mod:`svgtile.engines.holes`) measure the covered area against ρ.  A window is the exemplar
region's bounding box, tiled from the world origin shifted by one of :data:`WINDOW_OFFSETS`.

Square windows of a given side, tiled from the world origin (:func:`square_cells`,
:func:`square_windows`, :func:`square_area`): the optimize engine's, of 8–12 exemplar spacings,
where its start is thinned (:func:`.optimize.init.thin`), its insertion capped and its vote
kept from shrinking a short window's cover (:mod:`.optimize.insert`), its kinds held to the
exemplar's mix (:mod:`.optimize.assign`) and its renewal's costs compared
(:func:`.optimize.solver.renewed`); and its insertion's bins of half a spacing, where
predictions are counted.
"""

from __future__ import annotations

import math

import numpy as np
import shapely

from svgtile.analysis.stats import footprint_areas
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region

#: The windows' offsets, in window sizes: rounds take them in turn, so that what one round's
#: window edges cut, the next round's windows hold whole.
WINDOW_OFFSETS = np.array([[0.0, 0.0], [0.5, 0.5], [0.5, 0.0], [0.0, 0.5]])


def window_size(exemplar: Exemplar) -> np.ndarray:
    """(2,) float array, user units: the windows' width and height, the exemplar region's."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return np.array([x1 - x0, y1 - y0])


def window_cover(
    arr: Arrangement,
    protos,
    origin: np.ndarray,
    size: np.ndarray,
    ids: np.ndarray,
    areas: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The (n,) window of each motif (index into ``ids``, -1: none of them) and the (w,)
    footprint area the motifs of each window cover, square user units; ``areas`` the (n,)
    :func:`~svgtile.analysis.stats.footprint_areas` of ``arr``, if known."""
    win = window_of(arr.xy, origin, size, ids)
    if areas is None:
        areas = footprint_areas(arr, protos)
    return win, np.bincount(win[win >= 0], weights=areas[win >= 0], minlength=len(ids))


def region_windows(region: Region, size: np.ndarray, offset: np.ndarray):
    """Windows meeting the region: (origin, (w, 2) integer ids, (w,) area inside the region)."""
    X0, Y0, X1, Y1 = region.bounds
    ia = np.arange(math.floor((X0 - offset[0]) / size[0]), math.ceil((X1 - offset[0]) / size[0]))
    ib = np.arange(math.floor((Y0 - offset[1]) / size[1]), math.ceil((Y1 - offset[1]) / size[1]))
    IA, IB = (v.ravel() for v in np.meshgrid(ia, ib))
    lo = offset + np.stack([IA, IB], -1) * size
    boxes = shapely.box(lo[:, 0], lo[:, 1], lo[:, 0] + size[0], lo[:, 1] + size[1])
    area = shapely.area(shapely.intersection(boxes, region.shape))
    # a window mostly outside the region measures its border, not its density
    full = area >= 0.5 * size[0] * size[1]
    if not full.any():
        return None
    return offset, np.stack([IA, IB], -1)[full], area[full]


def square_cells(xy: np.ndarray, side: float) -> np.ndarray:
    """(n, 2) int64: the integer coordinates of the world-anchored square window of side ``side``
    (user units) that holds each point ``xy`` (n, 2)."""
    return np.floor(xy / side).astype(np.int64)


def square_windows(xy: np.ndarray, side: float) -> tuple[np.ndarray, np.ndarray]:
    """The world-anchored square windows of side ``side`` (user units) that hold the points ``xy``
    (n, 2): their integer coordinates (:func:`square_cells`), (w, 2) int64 in lexicographic
    order, and each point's window, (n,) int64, an index into them."""
    ids, which = np.unique(square_cells(xy, side), axis=0, return_inverse=True)
    return ids, which.ravel().astype(np.int64)


def square_area(ids: np.ndarray, side: float, region: Region) -> np.ndarray:
    """(w,) float, square user units: the area inside ``region`` of each square window ``ids``
    (w, 2) of side ``side`` (:func:`square_windows`)."""
    boxes = shapely.box(ids[:, 0] * side, ids[:, 1] * side, (ids[:, 0] + 1) * side, (ids[:, 1] + 1) * side)
    return shapely.area(shapely.intersection(boxes, region.shape))


def window_of(xy: np.ndarray, origin: np.ndarray, size: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """(n,) index into ``ids`` of the window holding each point, or -1."""
    cell = np.floor((xy - origin) / size).astype(np.int64)
    lo = ids.min(axis=0)
    span = ids.max(axis=0) - lo + 1
    table = np.full(span[0] * span[1], -1, dtype=np.int64)
    table[(ids[:, 0] - lo[0]) * span[1] + (ids[:, 1] - lo[1])] = np.arange(len(ids))
    rel = cell - lo
    ok = (rel >= 0).all(axis=1) & (rel < span).all(axis=1)
    out = np.full(len(xy), -1, dtype=np.int64)
    out[ok] = table[rel[ok, 0] * span[1] + rel[ok, 1]]
    return out
