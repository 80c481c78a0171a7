"""The output region and how motifs meet its boundary.

Boundary modes, as map makers know them from QGIS's fill symbol clipping:

* ``inside`` — keep a motif only if its whole footprint lies inside the region;
* ``centroid`` — keep it if its centroid lies inside;
* ``clip`` — keep every motif that touches the region; the output clips them to it (default);
* ``none`` — keep every motif that touches the region, unclipped.

"Touches" is decided on footprint outlines, which reach up to :attr:`Prototype.excess
<svgtile.core.footprint.Prototype>` beyond the drawn motif; they must meet the region shrunk by that
much, so every motif kept for ``clip`` or ``none`` really touches it.

A region is any shapely (Multi)Polygon: several parts, and holes (inliers of another map unit),
whose edges the boundary mode treats like the outer edge.  *Avoid zones* (labels, linework,
symbols the texture must keep clear of) are cut out of the region, and in every mode a motif
whose footprint meets one is dropped: whatever the mode does at the unit's edge, nothing is ever
drawn over a label.  Edit stability: engines anchor randomness in world coordinates, so changing
the outline changes only motifs near the change (measured in ``tests/test_region.py``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import Prototype, motif_radius, world_footprints
from svgtile.errors import RegionError

BOUNDARY_MODES = ("inside", "centroid", "clip", "none")
#: SVG's ``fill-rule`` values (SVG 1.1 §11.3); ``nonzero`` is the initial one.
FILL_RULES = ("nonzero", "evenodd")


@dataclass(frozen=True, eq=False)
class Region:
    """The area to fill.

    Attributes
    ----------
    shape : shapely Polygon or MultiPolygon, user units
        The area to fill (holes are holes), avoid zones already cut out.
    avoid : shapely geometry or None, user units
        Avoid zones: no motif footprint may meet them, whatever the boundary mode.
    """

    shape: shapely.Geometry
    avoid: shapely.Geometry | None = None

    def __post_init__(self) -> None:
        avoid = self.avoid
        if avoid is not None and (avoid.is_empty or avoid.area <= 0):
            avoid = None
        object.__setattr__(self, "avoid", avoid)
        if avoid is not None:
            object.__setattr__(self, "shape", _polygonal(shapely.difference(self.shape, avoid)))
            shapely.prepare(avoid)
        if self.shape.is_empty or self.shape.area <= 0:
            raise RegionError("the output region has no area" + (" outside its avoid zones" if avoid else ""))
        shapely.prepare(self.shape)

    @classmethod
    def from_geometry(
        cls, geom: shapely.Geometry, *, avoid: shapely.Geometry | None = None, source: str | None = None
    ) -> Region:
        """A region from any geometry: made valid, only its polygons kept, parts merged.

        Parameters
        ----------
        geom : shapely geometry, user units (a GeometryCollection's lines and points are ignored)
        avoid : shapely geometry, user units, optional; polygonal (lines must be buffered first)
        source : names the input in error messages

        Raises
        ------
        RegionError
            When nothing with area is left.
        """
        shape = _polygonal(shapely.make_valid(geom)) if geom is not None else shapely.Polygon()
        if shape.is_empty or shape.area <= 0:
            raise RegionError("the region has no area", source=source)
        if avoid is not None:
            avoid = _polygonal(shapely.make_valid(avoid))
            if not shapely.difference(shape, avoid).area > 0:
                raise RegionError("the region lies wholly inside its avoid zones", source=source)
        return cls(shape, avoid)

    @classmethod
    def rectangle(cls, width: float, height: float, x: float = 0.0, y: float = 0.0) -> Region:
        if not (width > 0 and height > 0 and np.isfinite(width) and np.isfinite(height)):
            raise RegionError(f"the output size {width:g}x{height:g} must be positive")
        return cls(shapely.box(x, y, x + width, y + height))

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        return tuple(float(v) for v in self.shape.bounds)

    @property
    def area(self) -> float:
        return float(self.shape.area)

    def keep(
        self, arr: Arrangement, protos: list[Prototype], mode: str, geoms: np.ndarray | None = None
    ) -> np.ndarray:
        """(n,) bool: which motifs the boundary mode keeps.

        Footprints are only built (unless given as ``geoms``) for motifs whose bounding disc
        meets the boundary; the others are decided by their centroid alone.

        Parameters
        ----------
        arr : the motifs
        protos : kind prototypes
        mode : one of :data:`BOUNDARY_MODES`
        geoms : (n,) world footprints of ``arr``, optional
        """
        if mode not in BOUNDARY_MODES:
            raise ValueError(f"unknown boundary mode {mode!r}")
        if len(arr) == 0:
            return np.zeros(0, dtype=bool)
        result = self._keep_mode(arr, protos, mode, geoms)
        if self.avoid is not None and result.any():
            result[result] = self.clear(arr.take(result), protos, None if geoms is None else geoms[result])
        return result

    def clear(self, arr: Arrangement, protos: list[Prototype], geoms: np.ndarray | None = None) -> np.ndarray:
        """(n,) bool: which motifs' footprints stay clear of the avoid zones (all, if none)."""
        ok = np.ones(len(arr), dtype=bool)
        if self.avoid is None or len(arr) == 0:
            return ok
        r = motif_radius(arr, protos)
        near = np.flatnonzero(shapely.dwithin(self.avoid, shapely.points(arr.xy), r))
        if len(near):
            found = geoms[near] if geoms is not None else world_footprints(arr.take(near), protos)
            ok[near] = ~shapely.intersects(self.avoid, found)
        return ok

    def _keep_mode(self, arr, protos, mode, geoms) -> np.ndarray:
        x, y = arr.xy[:, 0], arr.xy[:, 1]
        if mode == "centroid":
            return shapely.contains_xy(self.shape, x, y)
        r = float(motif_radius(arr, protos).max())
        surely_in = shapely.contains_xy(self._grown(-r), x, y)
        surely_out = ~shapely.contains_xy(self._grown(r), x, y)
        unsure = np.flatnonzero(~surely_in & ~surely_out)
        found = geoms[unsure] if geoms is not None else world_footprints(arr.take(unsure), protos)
        result = surely_in.copy()
        if mode == "inside":
            result[unsure] = shapely.contains(self.shape, found)
        else:  # the outline reaches a little beyond the motif: it must meet the region by more
            excess = np.array([p.excess for p in protos])[arr.kind[unsure]] * arr.scale[unsure]
            # each motif's own excess, rounded up to a ladder of 2^(1/4) steps: few shrunk regions
            step = np.where(excess > 0, np.exp2(np.ceil(4 * np.log2(np.maximum(excess, 1e-300))) / 4), 0.0)
            for e in np.unique(step):
                mine = step == e
                result[unsure[mine]] = shapely.intersects(self._grown(-float(e)) if e > 0 else self.shape, found[mine])
        return result

    def _grown(self, r: float) -> shapely.Geometry:
        """The shape buffered by ``r`` (negative: shrunk), prepared and kept: engines ask for
        the same few radii round after round, and a map unit may have thousands of vertices."""
        cache = self.__dict__.setdefault("_buffers", {})
        if r not in cache:
            if len(cache) > 16:
                cache.clear()
            cache[r] = shapely.buffer(self.shape, r)
            shapely.prepare(cache[r])
        return cache[r]

    def interior(self, margin: float) -> shapely.Geometry:
        """The region shrunk by ``margin`` (where border effects cannot reach)."""
        return shapely.buffer(self.shape, -margin)


def winding_fill(rings: list[np.ndarray], rule: str = "nonzero") -> shapely.Geometry:
    """The area SVG paints for closed rings under a fill rule, holes and self-crossings included.

    The rings' linework is noded and polygonized into faces; a face is painted when the winding
    number of its interior point is non-zero (``nonzero``) or odd (``evenodd``), as in SVG 1.1
    §11.3.  Works for self-intersecting rings, rings drawn in any direction and rings of any
    number of vertices.  Map regions (:class:`svgtile.svg.mapdoc.SvgShapes`) and Inkscape
    containers (:func:`svgtile.apps.inkscape.read_containers`) both come from here.

    Parameters
    ----------
    rings : list of (k, 2) float arrays, user units (each closed implicitly, as SVG fills; a
        closing point is optional); rings with fewer than 3 distinct points enclose nothing
    rule : "nonzero" or "evenodd"

    Returns
    -------
    shapely (Multi)Polygon, possibly empty (then always an empty Polygon).

    Raises
    ------
    ValueError
        ``rule`` is not one of :data:`FILL_RULES`.
    """
    if rule not in FILL_RULES:
        raise ValueError(f"unknown fill rule {rule!r}")
    rings = [np.asarray(r, dtype=np.float64).reshape(-1, 2) for r in rings]
    rings = [r for r in rings if len(np.unique(np.round(r, 12), axis=0)) >= 3]
    if not rings:
        return shapely.Polygon()
    closed = [r if np.array_equal(r[0], r[-1]) else np.vstack([r, r[:1]]) for r in rings]
    lines = shapely.union_all(shapely.linestrings(np.concatenate(closed), indices=np.repeat(
        np.arange(len(closed)), [len(r) for r in closed])))
    faces = np.array(shapely.get_parts(shapely.polygonize(shapely.get_parts(lines))), dtype=object)
    if len(faces) == 0:
        return shapely.Polygon()
    probe = shapely.get_coordinates(shapely.point_on_surface(faces))  # (f, 2)
    wind = winding_numbers(closed, probe[:, 0], probe[:, 1])
    painted = wind % 2 == 1 if rule == "evenodd" else wind != 0
    return shapely.union_all(faces[painted]) if painted.any() else shapely.Polygon()


def winding_numbers(rings: list[np.ndarray], x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(m,) int: the winding number of all ``rings`` together around each point (x[i], y[i]).

    Parameters
    ----------
    rings : closed polylines, each a (k, 2) float array (the closing edge is implied; an explicit
        closing point adds a zero-length edge, which counts nothing)
    x, y : (m,) float arrays, the points, which must not lie on an edge

    Counts signed crossings of the horizontal ray to the right of each point (Sunday's
    algorithm): a loop over rings, points and edges vectorised, so memory stays (m, k) for the
    largest ring rather than (m, all edges).
    """
    px = np.asarray(x, dtype=np.float64)[:, None]
    py = np.asarray(y, dtype=np.float64)[:, None]
    wind = np.zeros(len(px), dtype=np.int64)
    for r in rings:
        r = np.asarray(r, dtype=np.float64).reshape(-1, 2)
        if len(r) < 2:
            continue
        a, b = r, np.roll(r, -1, axis=0)
        left = (b[:, 0] - a[:, 0]) * (py - a[:, 1]) - (px - a[:, 0]) * (b[:, 1] - a[:, 1])
        up = (a[:, 1] <= py) & (b[:, 1] > py) & (left > 0)
        down = (a[:, 1] > py) & (b[:, 1] <= py) & (left < 0)
        wind += up.sum(axis=1) - down.sum(axis=1)
    return wind


def _polygonal(geom: shapely.Geometry) -> shapely.Geometry:
    """The polygons of ``geom`` (at any depth of collection), merged; empty if it has none."""
    parts = [p for p in shapely.get_parts(geom) if not p.is_empty]
    polys = []
    for part in parts:
        if isinstance(part, shapely.Polygon):
            polys.append(part)
        elif isinstance(part, (shapely.MultiPolygon, shapely.GeometryCollection)):
            polys.append(_polygonal(part))
    polys = [p for p in polys if not p.is_empty and p.area > 0]
    return shapely.union_all(polys) if polys else shapely.Polygon()
