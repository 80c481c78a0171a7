"""Cells and lines of a cellular texture (legakis2001 §3.3, §5.4), as a struct of arrays.

A cellular engine's output is not only motifs: it is *cells* — bricks, blocks, stones, rhombs,
each one polygon — and *lines* (bedding), each one polyline.  :class:`Cellwork` holds both beside
the :class:`~svgtile.core.arrangement.Arrangement` of the motifs set inside cells; the SVG writer
draws every shape as a ``<path>`` with its style, the GeoJSON writer as a Polygon or LineString.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

#: What a shape is: a cell of a corner, of an edge, of the face, or a (bedding) line.
FEATURES = ("corner", "edge", "face", "line")
CORNER, EDGE, FACE, LINE = range(4)


def geometry_array(items: list) -> np.ndarray:
    """A 1-D object array of shapely geometries (``np.array`` would unpack multi-part ones)."""
    out = np.empty(len(items), dtype=object)
    out[:] = items
    return out


@dataclass(frozen=True, eq=False)
class Cellwork:
    """The cells and lines of a texture.

    Attributes
    ----------
    shapes : (n,) object array of shapely Polygons (cells) and LineStrings (lines), user units,
        each cell already shrunk for mortar (its drawn shape, not the space it claimed)
    feature : (n,) int array, an index into :data:`FEATURES`
    style : (n,) int array, an index into ``styles``
    styles : tuple of str, the CSS ``style`` attribute of each style (``fill:none;stroke:#000`` …)
    """

    shapes: np.ndarray
    feature: np.ndarray
    style: np.ndarray
    styles: tuple[str, ...]

    def __post_init__(self) -> None:
        n = len(self.shapes)
        if not (len(self.feature) == len(self.style) == n):
            raise ValueError("Cellwork columns differ in length")

    def __len__(self) -> int:
        return len(self.shapes)

    @property
    def cells(self) -> np.ndarray:
        """(c,) the cell polygons (features corner, edge and face)."""
        return self.shapes[self.feature != LINE]

    @property
    def lines(self) -> np.ndarray:
        """(l,) the lines."""
        return self.shapes[self.feature == LINE]

    def take(self, index: np.ndarray) -> Cellwork:
        return Cellwork(self.shapes[index], self.feature[index], self.style[index], self.styles)

    @classmethod
    def empty(cls, styles: tuple[str, ...] = ()) -> Cellwork:
        return cls(np.empty(0, dtype=object), np.zeros(0, np.int64), np.zeros(0, np.int64), styles)

    def in_reading_order(self, decimals: int = 4) -> Cellwork:
        """Features in :data:`FEATURES` order, then rows, then columns of a representative point:
        a stable, diff-friendly output."""
        if len(self) == 0:
            return self
        shapes = shapely.set_precision(self.shapes, 10.0**-decimals)
        keep = ~shapely.is_empty(shapes)
        shapes = shapes[keep]
        pt = shapely.get_coordinates(shapely.point_on_surface(shapes)) if len(shapes) else np.zeros((0, 2))
        feature, style = self.feature[keep], self.style[keep]
        order = np.lexsort((pt[:, 0], pt[:, 1], style, feature))
        return Cellwork(shapes[order], feature[order], style[order], self.styles)
