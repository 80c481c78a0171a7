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
