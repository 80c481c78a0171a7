"""Motif footprints: one prototype per kind, world footprints in bulk, and pair queries.

The footprint is what the eye sees as a motif's extent — the interior of its closed outlines
(filled or not, holes filled) plus its stroke band — and it is what overlaps and the distances of
almeraj2013 §3.1 are measured on.  A kind's footprint is computed once in its local frame
(:class:`Prototype`); world footprints for a whole arrangement are built in one vectorised pass
(:func:`world_footprints`), and every neighbour question goes through :func:`near_pairs` (a k-d
tree over centroids with a per-pair bound) followed by exact GEOS distances on the survivors.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.core.arrangement import Arrangement, periodic_block

#: Outline tolerance of prototypes, relative to the motif's radius (see Prototype.from_geometry).
SIMPLIFY = 0.025


@dataclass(frozen=True, eq=False)
class Prototype:
    """A kind's footprint in its local frame (origin at the footprint centroid).

    Attributes
    ----------
    rings : tuple of (k, 2) float arrays, user units
        Closed exterior rings (first point repeated last), one per connected part.
    area : float
        Area of the exact footprint (not of the outline) at scale 1, square user units.
    radius : float
        Largest distance from the origin to the footprint, user units.
    inner : float
        Radius of the largest disc about the origin inside the footprint (0 if the origin is
        outside it), user units: two motifs whose such discs overlap surely overlap.
    excess : float
        How far the outline reaches beyond the exact footprint, user units (measured on the
        outline densified to a quarter of the tolerance, plus that quarter).
    """

    rings: tuple[np.ndarray, ...]
    area: float
    radius: float
    inner: float
    excess: float = 0.0

    @classmethod
    def from_geometry(cls, geom: shapely.Geometry, tolerance: float = SIMPLIFY) -> Prototype:
        """Build from a (Multi)Polygon already centred on its centroid; holes are dropped.

        The outline is simplified within ``tolerance`` × its radius and then grown by as much, so
        the prototype covers the exact footprint with few vertices: every distance and overlap
        test in a texture of a million motifs runs on these outlines.
        """
        pts = shapely.get_coordinates(geom)
        exact = shapely.union_all([shapely.Polygon(p.exterior) for p in shapely.get_parts(geom)])
        # the tolerance follows the motif's size, but a thin motif (a dash) is only as wide as
        # 2·area/perimeter, and growing it by a share of its length would fatten it
        thickness = 2.0 * exact.area / max(exact.length, 1e-12)
        tol = min(tolerance * float(np.hypot(pts[:, 0], pts[:, 1]).max()), 1.5 * tolerance * thickness)
        if tol > 0:
            geom = shapely.buffer(shapely.simplify(geom, tol), tol, join_style="mitre", mitre_limit=4.0)
        parts = shapely.get_parts(geom)
        rings = tuple(
            np.asarray(shapely.get_coordinates(shapely.get_exterior_ring(p)), dtype=np.float64)
            for p in parts
            if not p.is_empty
        )
        if not rings:
            raise ValueError("empty footprint")
        pts = np.concatenate(rings)
        filled = shapely.union_all([shapely.polygons(r) for r in rings])
        origin = shapely.Point(0.0, 0.0)
        inner = float(filled.exterior.distance(origin)) if filled.geom_type == "Polygon" else 0.0
        if not filled.contains(origin):
            inner = 0.0
        radius = float(np.hypot(pts[:, 0], pts[:, 1]).max())
        excess = 0.0
        if tol > 0:  # simplified, then grown with mitred corners: measured, not bounded
            outline = shapely.get_coordinates(shapely.segmentize(shapely.MultiLineString(list(rings)), tol / 4))
            excess = _farthest_outside(outline, exact) + tol / 4
        return cls(rings, float(exact.area), radius, inner, excess)

    def geometry(self) -> shapely.Geometry:
        """The footprint as one shapely geometry in the local frame."""
        polys = [shapely.polygons(r) for r in self.rings]
        return polys[0] if len(polys) == 1 else shapely.multipolygons(polys)


#: Each side of a pair the drawing keeps a gap ``g`` apart may reach at most this share of it
#: beyond its exact footprint (:func:`separated`; the prototype's ``excess``), so two rebuilt
#: outlines stay apart with room to spare: 2 × 0.4 g < g.
GAP_SHARE = 0.4
#: Rounds of :func:`separated`; a kind still meeting a neighbour after them takes its exact outline.
SEPARATE_ROUNDS = 3
#: Pairs of motifs whose bounding discs meet, at most, that are measured (here and by the crowding
#: check, :mod:`svgtile.analysis.crowding`): beyond it even listing them is costly.
MAX_NEAR_PAIRS = 2_000_000


def separated(protos: list[Prototype], exact: list[shapely.Geometry | None], arr: Arrangement,
              period: tuple[float, float] | None = None) -> list[Prototype]:  # fmt: skip
    """The prototypes, those of kinds whose outlines overlap where their exact footprints stay
    apart rebuilt with a finer tolerance, so that the analysis does not see overlaps the drawing has not.

    :meth:`Prototype.from_geometry` simplifies each outline within a fortieth of the motif's
    radius and grows it as much, mitred: at a sharp corner it reaches up to four times that
    beyond the exact footprint (``excess``).  Two motifs drawn closer than that (Equinor 11026:
    pebbles 0.2 units from the dashes they sit on; their outlines reached 0.27–0.36 beyond) then
    share area in the analysis, which counts the exemplar as overlapping and holds its copies to
    a rule it breaks itself (a stamp of the tile lost one motif of each pair).

    Each round finds the pairs whose outlines share area while their exact footprints are a gap
    ``g`` apart, and rebuilds every kind in one whose outline reaches more than :data:`GAP_SHARE`
    of its narrowest such gap (in its own units: over the motif's scale) beyond its footprint,
    with the tolerance scaled so that it reaches that share (the excess follows the tolerance);
    after :data:`SEPARATE_ROUNDS` rounds a kind still in such a pair takes its exact outline
    (tolerance 0, no excess).  A pair is left alone where either kind has no exact footprint, and
    nothing is done on an exemplar so crowded that the crowding check refuses it
    (:data:`MAX_NEAR_PAIRS`).  Kinds never rebuilt keep their prototype (the same object).

    Parameters
    ----------
    protos : the kinds' prototypes, k
    exact : the kinds' exact footprints in the same local frames (None: kept as it is)
    arr : the exemplar's motifs
    period : (w, h), user units, if the pattern repeats: pairs across its edges count too

    Returns
    -------
    list of k prototypes
    """
    if (len(arr) < 2 and period is None) or len(arr) == 0:
        return list(protos)
    if period is not None:
        arr = periodic_block(arr, period)
    if near_pair_bound(arr.xy, float(np.median(motif_radius(arr, protos)))) > MAX_NEAR_PAIRS:
        return list(protos)
    has = np.array([g is not None for g in exact])
    plain: list[Prototype] = []  # the exact outlines, built when a pair first needs them
    out, tolerance = list(protos), np.full(len(protos), SIMPLIFY)
    for rnd in range(SEPARATE_ROUNDS + 1):
        i, j = near_pairs(arr.xy, motif_radius(arr, out), 0.0)
        if len(i) > MAX_NEAR_PAIRS:
            return list(protos)
        keep = has[arr.kind[i]] & has[arr.kind[j]]
        i, j = i[keep], j[keep]
        geoms = world_footprints(arr, out)
        meet = overlapping(geoms, i, j, shapely.distance(geoms[i], geoms[j]))
        i, j = i[meet], j[meet]
        if not len(i):
            break
        if not plain:
            plain = [Prototype.from_geometry(g, tolerance=0.0) if g is not None else p
                     for g, p in zip(exact, protos, strict=True)]  # fmt: skip
        gap = shapely.distance(*(world_footprints(arr.take(idx), plain) for idx in (i, j)))
        apart = gap > 0
        if not apart.any():
            break
        i, j, gap = i[apart], j[apart], gap[apart]
        narrowest = np.full(len(protos), np.inf)
        np.minimum.at(narrowest, arr.kind[i], gap / arr.scale[i])
        np.minimum.at(narrowest, arr.kind[j], gap / arr.scale[j])
        for k in np.flatnonzero(narrowest < np.inf):
            if rnd == SEPARATE_ROUNDS:
                out[k] = plain[k]
                continue
            if out[k].excess > GAP_SHARE * narrowest[k]:
                tolerance[k] *= min(GAP_SHARE * narrowest[k] / out[k].excess, 0.5)
                out[k] = Prototype.from_geometry(exact[k], tolerance=float(tolerance[k]))
    return out


def near_pair_bound(xy: np.ndarray, cell: float) -> int:
    """Pairs of centres that share a grid cell of side ``cell`` — a lower bound of the pairs
    closer than ``cell`` — counted in O(n log n) without listing them.

    Parameters
    ----------
    xy : (n, 2) float array, motif centres, user units
    cell : grid spacing, user units (> 0)
    """
    if len(xy) < 2 or not cell > 0:
        return 0
    keys = np.floor((xy - xy.min(axis=0)) / cell).astype(np.int64)
    _, counts = np.unique(keys, axis=0, return_counts=True)
    return int((counts * (counts - 1) // 2).sum())


def _farthest_outside(pts: np.ndarray, shape: shapely.Geometry) -> float:
    """max over ``pts`` ((k, 2) float array) of the distance to ``shape`` (0 inside it).

    The same figure as ``shapely.distance(points, shape).max()``, from a tree of the outline's
    segments instead of a walk of every segment per point: an outline of 10,000 vertices
    sampled at 50,000 points (osm-carto flowerbed_mid_zoom.svg) took a minute.
    """
    shapely.prepare(shape)
    outside = pts[~shapely.contains_xy(shape, pts[:, 0], pts[:, 1])]
    if len(outside) == 0:
        return 0.0
    segments = []
    for ring in shapely.get_rings(shapely.get_parts(shape)):
        xy = shapely.get_coordinates(ring)
        segments.append(np.stack([xy[:-1], xy[1:]], axis=1))
    tree = shapely.STRtree(shapely.linestrings(np.concatenate(segments)))
    _, dist = tree.query_nearest(shapely.points(outside), return_distance=True, all_matches=False)
    return float(dist.max())


def rotation(angle_deg: np.ndarray) -> np.ndarray:
    """(…, 2, 2) rotation matrices in SVG's ``rotate()`` sense (clockwise on screen, y down)."""
    a = np.radians(angle_deg)
    c, s = np.cos(a), np.sin(a)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def world_footprints(arr: Arrangement, protos: list[Prototype]) -> np.ndarray:
    """World footprints of every motif, built without a per-motif Python loop.

    Parameters
    ----------
    arr : Arrangement of n motifs.
    protos : list of Prototype, indexed by ``arr.kind``.

    Returns
    -------
    (n,) object array of shapely Polygons (MultiPolygons for multi-part kinds).
    """
    out = np.empty(len(arr), dtype=object)
    for k, proto in enumerate(protos):
        idx = np.flatnonzero(arr.kind == k)
        if len(idx) == 0:
            continue
        a = np.radians(arr.angle[idx])
        c = (np.cos(a) * arr.scale[idx])[:, None]
        s = (np.sin(a) * arr.scale[idx])[:, None]
        sizes = np.array([len(r) for r in proto.rings])
        local = np.concatenate(proto.rings)  # (v, 2)
        world = np.empty((len(idx), len(local), 2))
        world[:, :, 0] = c * local[:, 0] - s * local[:, 1] + arr.xy[idx, 0, None]
        world[:, :, 1] = s * local[:, 0] + c * local[:, 1] + arr.xy[idx, 1, None]
        closed = all(len(r) >= 4 and (r[0] == r[-1]).all() for r in proto.rings)
        if closed:  # straight from the coordinates (≈ 6× faster than rings, then polygons; the same geometries)
            ends = np.r_[0, np.cumsum(np.tile(sizes, len(idx)))]
            parts = np.arange(len(idx) * len(sizes) + 1)
            if len(sizes) == 1:
                polys = shapely.from_ragged_array(shapely.GeometryType.POLYGON, world.reshape(-1, 2), (ends, parts))
            else:
                offsets = (ends, parts, parts[:: len(sizes)])
                polys = shapely.from_ragged_array(shapely.GeometryType.MULTIPOLYGON, world.reshape(-1, 2), offsets)
        else:
            ring_id = np.repeat(np.arange(len(idx) * len(sizes)), np.tile(sizes, len(idx)))
            polys = shapely.polygons(shapely.linearrings(world.reshape(-1, 2), indices=ring_id))
            if len(sizes) > 1:
                polys = shapely.multipolygons(polys, indices=np.repeat(np.arange(len(idx)), len(sizes)))
        out[idx] = polys
    return out


def motif_radius(arr: Arrangement, protos: list[Prototype], *, inner: bool = False) -> np.ndarray:
    """(n,) bounding radius of each motif about its centroid (inscribed radius if ``inner``)."""
    radius = np.array([p.inner if inner else p.radius for p in protos])
    return radius[arr.kind] * arr.scale


def near_pairs(
    xy: np.ndarray, radius: np.ndarray, reach: float | np.ndarray, kind: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs ``i < j`` whose bounding discs come closer than ``reach``.

    A pair can only have footprint distance below ``reach`` if
    ``|xy_i - xy_j| - radius_i - radius_j < reach``; this is the filter applied.

    Parameters
    ----------
    xy : (n, 2) float array, centroids.
    radius : (n,) float array, bounding radii.
    reach : float, or (k, k) array indexed by ``kind`` for a per-kind-pair reach.
    kind : (n,) int array, required when ``reach`` is a matrix.

    Returns
    -------
    i, j : (p,) int arrays.
    """
    n = len(xy)
    empty = np.zeros(0, np.int64), np.zeros(0, np.int64)
    if n < 2:
        return empty
    # Candidates come from one k-d tree per size class (radii within a factor 2), each pair of
    # classes searched with its own largest radii and reach: one search with the largest motif's
    # radius would pair every small motif with all small motifs around it (till: clasts 10 × the
    # size of the grains), and a tree per kind would cost a search per pair of kinds (FGDC 606
    # has 62 kinds).
    group = np.zeros(n, np.int64) if kind is None else np.asarray(kind)
    floor = max(float(radius.max()) * 1e-3, 1e-300)
    size = np.floor(np.log2(np.maximum(radius, floor) / floor)).astype(np.int64)
    classes = np.unique(size)
    members = [np.flatnonzero(size == c) for c in classes]
    trees = [cKDTree(xy[m]) for m in members]
    rmax = [float(radius[m].max()) for m in members]
    present = [np.unique(group[m]) for m in members]
    parts = []
    for a in range(len(classes)):
        for b in range(a, len(classes)):
            r = reach[np.ix_(present[a], present[b])].max() if np.ndim(reach) == 2 else reach
            bound = rmax[a] + rmax[b] + float(r)
            if not bound > 0:  # no kind pair of these classes asked for (−inf), or none can be this close:
                continue  # and a k-d tree given r < 0 searches within |r| (r = −inf: every pair)
            if a == b:
                pairs = trees[a].query_pairs(bound, output_type="ndarray")
                i, j = members[a][pairs[:, 0]], members[a][pairs[:, 1]]
            else:
                found = trees[a].sparse_distance_matrix(trees[b], bound, output_type="ndarray")
                i, j = members[a][found["i"]], members[b][found["j"]]
            parts.append((i, j))
    if not parts:
        return empty
    i = np.concatenate([p[0] for p in parts]).astype(np.int64)
    j = np.concatenate([p[1] for p in parts]).astype(np.int64)
    if len(i) == 0:
        return empty
    gap = np.hypot(*(xy[i] - xy[j]).T) - radius[i] - radius[j]
    r = reach[group[i], group[j]] if np.ndim(reach) == 2 else reach
    keep = gap < r
    i, j = i[keep], j[keep]
    swap = i > j
    i[swap], j[swap] = j[swap], i[swap]
    return i, j


def overlapping(geoms: np.ndarray, i: np.ndarray, j: np.ndarray, dist: np.ndarray) -> np.ndarray:
    """(p,) bool: do footprints i and j share area (touching does not count)?"""
    out = np.zeros(len(i), dtype=bool)
    zero = dist <= 0
    if zero.any():
        out[zero] = ~shapely.touches(geoms[i[zero]], geoms[j[zero]])
    return out
