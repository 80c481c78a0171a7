"""Coverage: the largest hole of a texture, against the exemplar's.

A texture may keep the density ρ on average and still leave holes (almeraj2013 §3.4 fills them
window by window); the largest disc that meets no footprint finds the worst one.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import nearest_distances, periodic_block
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import Prototype, motif_radius, world_footprints

#: Largest empty disc: the first grid of candidate centres has this many mean spacings …
COVER_STEP = 0.25
#: … and is refined this many times, 4× finer each time …
COVER_LEVELS = 2
#: … around at most this many of the best centres.
COVER_KEEP = 2048
#: At most this many centres of the first grid are measured exactly (see largest_empty_disc).
COVER_EXACT = 16_384


def largest_empty_disc(
    arr: Arrangement, protos: list[Prototype], centres: shapely.Geometry, within: shapely.Geometry,
    *, step: float | None = None, geoms: np.ndarray | None = None, levels: int = COVER_LEVELS,
) -> tuple[float, np.ndarray]:  # fmt: skip
    """The largest disc centred in ``centres``, inside ``within``, that meets no footprint.

    The clearance of a point p is ``c(p) = min(dist(p, footprints), dist(p, ∂within))``; the
    radius returned is ``max c`` over a grid of candidate centres in ``centres`` of ``step``,
    refined ``levels`` times by a grid 4× finer (``±step/2`` about a point) around the
    :data:`COVER_KEEP` best points within ``step/√2`` of the best.  ``c`` is 1-Lipschitz, so the
    radius is a lower bound within ``step / 4**levels / √2`` of the true one, unless more
    than :data:`COVER_KEEP` points compete for the best.

    Exact GEOS distances (:func:`~svgtile.analysis.stats.nearest_distances`) are taken on few points of
    the first grid: a distance transform of a raster of pixel ``step`` (pixels holding a point of
    a footprint's outline, or outside ``within``, are features;
    :func:`scipy.ndimage.distance_transform_edt`) gives each grid point an estimate
    ``e ≥ c − step/√2``; points are measured exactly in decreasing order of
    ``e`` until no point left can be within ``step/√2`` of the best clearance found, or
    :data:`COVER_EXACT` points were measured (a texture as regular as a tiling has as many
    holes as large as the largest: one of them is enough).

    Parameters
    ----------
    arr : the motifs
    protos : kind prototypes
    centres : shapely geometry where a centre may lie
    within : shapely geometry the disc must lie in (contains ``centres``)
    step : first grid step, user units (default: a 40th of the larger side of ``centres``)
    geoms : world footprints of ``arr``, if built: an (n,) object array, or :class:`Footprints`
        to build only those of the motifs near the centres measured exactly
    levels : how many times the grid is refined (default :data:`COVER_LEVELS`)

    Returns
    -------
    radius : float, user units (0 if ``centres`` is empty)
    centre : (2,) float array
    """
    if centres.is_empty:
        return 0.0, np.full(2, np.nan)
    x0, y0, x1, y1 = centres.bounds
    size = max(x1 - x0, y1 - y0)
    step = max(first_step(step, centres), size / 2000)  # at most ~4M pixels
    edge = within.boundary
    if len(arr):
        if geoms is None:
            geoms = world_footprints(arr, protos)
        tree = cKDTree(arr.xy)
        radius = motif_radius(arr, protos)

    def clearance(p: np.ndarray) -> np.ndarray:
        pts = shapely.points(p)
        c = shapely.distance(edge, pts)
        if len(arr):
            c = np.minimum(c, nearest_distances(p, np.zeros(len(p)), pts, tree, radius, geoms))
        return c

    p, e = _raster_clearance(arr, protos, centres, within, step)
    if len(p) == 0:
        p = np.array(shapely.get_coordinates(shapely.point_on_surface(centres)))
        e = np.full(1, np.inf)
    order = _best_first(e, min(len(e), COVER_EXACT))
    p, e = p[order], e[order]
    c = np.full(len(p), -np.inf)
    done, batch = 0, 256
    while done < min(len(p), COVER_EXACT) and (done == 0 or e[done] >= c[:done].max() - math.sqrt(2) * step):
        end = min(done + batch, len(p), COVER_EXACT)
        c[done:end] = clearance(p[done:end])
        done, batch = end, 2 * batch
    p, c = p[:done], c[:done]
    fine = np.arange(-2, 3) / 4
    for _ in range(levels):
        good = np.flatnonzero(c >= c.max() - step / math.sqrt(2))
        good = good[np.argsort(-c[good], kind="stable")[:COVER_KEEP]]
        ox, oy = np.meshgrid(fine * step, fine * step)
        q = (p[good, None, :] + np.stack([ox.ravel(), oy.ravel()], axis=1)[None]).reshape(-1, 2)
        q = q[shapely.contains_xy(centres, q[:, 0], q[:, 1])]
        p, c = np.concatenate([p[good], q]), np.concatenate([c[good], clearance(q)])
        step /= 4
    best = int(np.argmax(c))
    return float(max(c[best], 0.0)), p[best].copy()


def first_step(step: float | None, centres: shapely.Geometry) -> float:
    """The first raster step of :func:`largest_empty_disc`: ``step`` if it is a positive number,
    else a 40th of the larger side of ``centres``' bounding box, user units."""
    if step is not None and step > 0 and math.isfinite(step):
        return step
    x0, y0, x1, y1 = centres.bounds
    return max(x1 - x0, y1 - y0) / 40


def exemplar_empty_disc(exemplar: Exemplar, *, step: float | None = None) -> float:
    """The exemplar's largest empty disc, the hole a texture's is held against (``coverage``).

    A drawn exemplar's disc lies in its input region, as :func:`largest_empty_disc` measures it.
    A repeating tile (``exemplar.period``, its input region one period, as ``svgtile import``
    writes it) has no edge: its holes run across the tile's sides into the next copy, and a copy's
    footprint may reach in across them.  Its disc is centred in the tile (or within one raster
    step of it: the same hole one period on) and measured among the copies around it, as many
    rings of them as a disc so centred can reach — its radius is at most half the period's
    diagonal plus the largest motif radius (every point of the pattern is that close to a copy of
    any motif's centroid), and copies up to a motif radius beyond it can bound it.  Measured
    inside the tile alone, a hole the tile's side cuts counted only its part inside, and a stamp
    of the tile itself — the same holes — scored coverage 1.47–1.71 (osm-carto allotments, grave
    yards, orchard).  A tile without motifs is measured as a drawn exemplar.

    Parameters
    ----------
    exemplar : the exemplar (its motifs, prototypes, region and period)
    step : first raster step, user units (:func:`largest_empty_disc`; default a 40th of the
        region's larger side)

    Returns
    -------
    float, the radius, user units
    """
    motifs, protos, region = exemplar.motifs, exemplar.prototypes, exemplar.region
    if exemplar.period is None or len(motifs) == 0:
        return largest_empty_disc(motifs, protos, region, region, step=step)[0]
    px, py = exemplar.period
    x0, y0, x1, y1 = region.bounds
    step = first_step(step, region)
    r_max = float(motif_radius(motifs, protos).max())
    reach = math.hypot(px, py) / 2 + 2 * r_max + step  # the disc's radius bound, a motif beyond it, the pad
    a, b = math.ceil(reach / px), math.ceil(reach / py)
    copies = periodic_block(motifs, (px, py), (a, b))
    centres = shapely.box(x0 - step, y0 - step, x1 + step, y1 + step)
    within = shapely.box(x0 - a * px, y0 - b * py, x1 + a * px, y1 + b * py)
    return largest_empty_disc(copies, protos, centres, within, step=step)[0]


class Footprints:
    """World footprints of an arrangement's motifs, built in bulk when first indexed.

    ``footprints[index]`` ((m,) int array) is ``world_footprints(arr, protos)[index]``: the
    motifs not built yet among ``index`` are built together
    (:func:`~svgtile.core.footprint.world_footprints` of them), so a search that touches the
    footprints of a few thousand motifs of a large texture builds only those.
    """

    def __init__(self, arr: Arrangement, protos: list[Prototype]) -> None:
        self._arr, self._protos = arr, protos
        self._geoms = np.empty(len(arr), dtype=object)
        self._built = np.zeros(len(arr), dtype=bool)

    def __len__(self) -> int:
        return len(self._geoms)

    def __getitem__(self, index: np.ndarray) -> np.ndarray:
        index = np.asarray(index)
        new = np.unique(index[~self._built[index]])
        if len(new):
            self._geoms[new] = world_footprints(self._arr.take(new), self._protos)
            self._built[new] = True
        return self._geoms[index]


#: Most outline points :func:`_raster_clearance` transforms at once: its few arrays of that many
#: floats then stay in the processor's cache (a chunk of 4M points took a tenth longer).
_OUTLINE_CHUNK = 1 << 16


def _raster_clearance(
    arr: Arrangement, protos: list[Prototype], centres: shapely.Geometry, within: shapely.Geometry, step: float
) -> tuple[np.ndarray, np.ndarray]:
    """Pixel centres in ``centres`` of a raster of pixel ``step``, and a clearance estimate of each.

    Features are the pixels holding a point of a footprint outline (outlines sampled at most
    ``step`` apart) and the pixels whose centre is outside ``within``; the estimate is the
    distance to the nearest feature pixel's centre.  Every footprint and the outside of
    ``within`` have a feature pixel centre within ``step/√2`` of them, so the estimate is at
    least the clearance minus ``step/√2`` (inside a footprint it may be much more: only the
    exact clearance says 0).

    Returns
    -------
    xy : (m, 2) float array, pixel centres in ``centres``
    estimate : (m,) float array, user units
    """
    x0, y0, x1, y1 = centres.bounds
    pad = 2 * step
    ox, oy = x0 - pad, y0 - pad
    nx, ny = math.ceil((x1 - x0 + 2 * pad) / step), math.ceil((y1 - y0 + 2 * pad) / step)
    xs, ys = ox + (np.arange(nx) + 0.5) * step, oy + (np.arange(ny) + 0.5) * step
    feature = np.ascontiguousarray(~_contains_grid(within, xs, ys))
    flat = feature.reshape(-1)  # a view of the contiguous raster
    if len(arr):
        reach = float(motif_radius(arr, protos).max())
        near = (
            (arr.xy[:, 0] > ox - reach) & (arr.xy[:, 0] < ox + nx * step + reach)
            & (arr.xy[:, 1] > oy - reach) & (arr.xy[:, 1] < oy + ny * step + reach)
        )  # fmt: skip
        scale = float(arr.scale.max())
        for k, proto in enumerate(protos):
            idx = np.flatnonzero(near & (arr.kind == k))
            if len(idx) == 0:
                continue
            rings = [shapely.segmentize(shapely.linearrings(r), step / max(scale, 1e-12)) for r in proto.rings]
            local = np.concatenate([shapely.get_coordinates(r) for r in rings])
            turn = np.radians(arr.angle[idx])
            cos, sin = np.cos(turn) * arr.scale[idx], np.sin(turn) * arr.scale[idx]
            rows = max(1, _OUTLINE_CHUNK // len(local))
            for a in range(0, len(idx), rows):
                sl = slice(a, a + rows)
                ix = _pixel(cos[sl, None] * local[:, 0] - sin[sl, None] * local[:, 1], arr.xy[idx[sl], 0, None], ox, step)
                iy = _pixel(sin[sl, None] * local[:, 0] + cos[sl, None] * local[:, 1], arr.xy[idx[sl], 1, None], oy, step)
                ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
                flat[iy[ok] * nx + ix[ok]] = True
    keep = _contains_grid(centres, xs, ys)
    iy, ix = np.nonzero(keep)
    if feature.all():
        estimate = np.zeros(len(iy))
    elif feature.any():
        estimate = _feature_distance(~feature, iy, ix) * step
    else:
        estimate = np.full(len(iy), np.inf)
    return np.stack([xs[ix], ys[iy]], axis=1), estimate


def _pixel(turned: np.ndarray, centre: np.ndarray, origin: float, step: float) -> np.ndarray:
    """Raster column (or row) of outline points, (rows, v) int: ``⌊(turned + centre − origin) / step⌋``
    with ``turned`` the rotated, scaled outline coordinates and ``centre`` (rows, 1) the motifs'
    centroids — the same operations in the same order as ``np.floor((turned + centre − origin)
    / step)``, in place on ``turned``, raveled."""
    turned += centre
    turned -= origin
    turned /= step
    return np.floor(turned, out=turned).astype(np.int64).ravel()


def _feature_distance(free: np.ndarray, iy: np.ndarray, ix: np.ndarray) -> np.ndarray:
    """``distance_transform_edt(free)[iy, ix]``, in pixels, bit for bit, without the distances
    of the pixels not asked for: the feature transform gives each pixel its nearest feature
    pixel, and the distance is taken only at ``(iy, ix)`` (integer offsets, so their squares
    and sums are exact whatever the order)."""
    # imported here: ``svgtile score`` measures the empty discs in its worker process, so the
    # command itself does not pay for scipy.ndimage (≈ 0.05 s)
    from scipy.ndimage import distance_transform_edt

    near = distance_transform_edt(free, return_distances=False, return_indices=True)
    dy = (near[0][iy, ix] - iy).astype(np.float64)
    dx = (near[1][iy, ix] - ix).astype(np.float64)
    return np.sqrt(dy * dy + dx * dx)


def _best_first(e: np.ndarray, k: int) -> np.ndarray:
    """The first ``k`` of ``np.argsort(-e, kind="stable")``, without sorting all of ``e``.

    The ``k`` largest values are found by partition; of those equal to the smallest of them,
    the first in index order are kept, so the order is that of the stable sort exactly.
    """
    if k >= len(e):
        return np.argsort(-e, kind="stable")
    if k == 0:
        return np.zeros(0, np.int64)
    cut = -np.partition(-e, k - 1)[k - 1]  # the k-th largest value
    above = np.flatnonzero(e > cut)
    tied = np.flatnonzero(e == cut)[: k - len(above)]
    chosen = np.concatenate([above, tied])
    chosen.sort()
    return chosen[np.argsort(-e[chosen], kind="stable")]


def _contains_grid(geom: shapely.Geometry, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """``shapely.contains_xy(geom, *np.meshgrid(xs, ys))``, shape ``(len(ys), len(xs))``: when
    ``geom`` is an axis-aligned rectangle (a rectangular region or its interior), by comparing
    the two axes once each — the same answer, the boundary is not inside — without a
    point-in-polygon test, or even a coordinate, for each of millions of raster pixels."""
    if shapely.get_type_id(geom) == 3 and shapely.get_num_interior_rings(geom) == 0:
        ring = shapely.get_coordinates(shapely.get_exterior_ring(geom))
        x0, y0, x1, y1 = geom.bounds
        if len(ring) == 5 and x0 < x1 and y0 < y1:
            corner = np.isin(ring[:, 0], (x0, x1)) & np.isin(ring[:, 1], (y0, y1))
            step = np.diff(ring, axis=0) != 0
            if corner.all() and (step[:, 0] != step[:, 1]).all():
                return ((ys > y0) & (ys < y1))[:, None] & ((xs > x0) & (xs < x1))[None, :]
    gx, gy = np.meshgrid(xs, ys)
    return shapely.contains_xy(geom, gx, gy)
