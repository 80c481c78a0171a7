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

from .errors import RegionError

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

    def keep(self, geoms: np.ndarray, xy: np.ndarray, mode: str) -> np.ndarray:
        """(n,) bool: which motifs the boundary mode keeps.

        Parameters
        ----------
        geoms : (n,) world footprints
        xy : (n, 2) centroids
        mode : one of :data:`BOUNDARY_MODES`
        """
        if mode == "inside":
            return shapely.contains(self.shape, geoms)
        if mode == "centroid":
            return shapely.contains_xy(self.shape, xy[:, 0], xy[:, 1])
        if mode in ("clip", "none"):
            return shapely.intersects(self.shape, geoms)
        raise ValueError(f"unknown boundary mode {mode!r}")

    def interior(self, margin: float) -> shapely.Geometry:
        """The region shrunk by ``margin`` (where border effects cannot reach)."""
        return shapely.buffer(self.shape, -margin)
