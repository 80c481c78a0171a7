"""The output region and how motifs meet its boundary.

Boundary modes, as map makers know them from QGIS's fill symbol clipping:

* ``inside`` — keep a motif only if its whole footprint lies inside the region;
* ``centroid`` — keep it if its centroid lies inside;
* ``clip`` — keep every motif that touches the region; the output clips them to it (default);
* ``none`` — keep every motif that touches the region, unclipped.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from .arrangement import Arrangement
from .errors import RegionError
from .footprint import Prototype, motif_radius, world_footprints

BOUNDARY_MODES = ("inside", "centroid", "clip", "none")


@dataclass(frozen=True, eq=False)
class Region:
    """The area to fill.

    Attributes
    ----------
    shape : shapely Polygon or MultiPolygon, user units (holes are holes)
    """

    shape: shapely.Geometry

    def __post_init__(self) -> None:
        if self.shape.is_empty or self.shape.area <= 0:
            raise RegionError("the output region has no area")
        shapely.prepare(self.shape)

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
        x, y = arr.xy[:, 0], arr.xy[:, 1]
        if mode == "centroid" or len(arr) == 0:
            return shapely.contains_xy(self.shape, x, y)
        r = float(motif_radius(arr, protos).max())
        surely_in = shapely.contains_xy(shapely.buffer(self.shape, -r), x, y)
        surely_out = ~shapely.contains_xy(shapely.buffer(self.shape, r), x, y)
        unsure = np.flatnonzero(~surely_in & ~surely_out)
        found = geoms[unsure] if geoms is not None else world_footprints(arr.take(unsure), protos)
        test = shapely.contains if mode == "inside" else shapely.intersects
        result = surely_in.copy()
        result[unsure] = test(self.shape, found)
        return result

    def interior(self, margin: float) -> shapely.Geometry:
        """The region shrunk by ``margin`` (where border effects cannot reach)."""
        return shapely.buffer(self.shape, -margin)
