"""The linework figures of a tile's texture (:mod:`svgtile.metrics.linework`): render, compare.

The tile is stamped (a ``<pattern>`` of its own elements, as on the swatch sheet) and the texture
synthesized on the same area of :data:`TILES` × :data:`TILES` tiles; both are rendered with resvg
(:func:`svgtile.apps.preview.render_png`) at one scale over the same window, the inner
``TILES − 2`` tiles (one tile in from each side, away from where the texture is clipped), the
window's longer side :data:`PIXELS` pixels.  Needs the ``png`` extra and Pillow (to read the PNG).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from svgtile.apps.preview import render_png
from svgtile.apps.swatches import _swatch
from svgtile.metrics.linework import Linework, grey, measure
from svgtile.svg.writer import fmt

#: The area synthesized, in tiles per side (the window is the inner TILES − 2).
TILES = 4
#: Pixels along the window's longer side.
PIXELS = 512


def render_window(root: ET.Element, window: tuple[float, float, float, float], pixels: int = PIXELS) -> np.ndarray:
    """(h, w) grey ink (0 white … 1 black) of the SVG ``root`` over ``window`` (x, y, w, h; user
    units), its longer side ``pixels`` pixels."""
    x, y, w, h = window
    root = ET.fromstring(ET.tostring(root))  # a copy: the panel stays as it was
    root.set("viewBox", f"{fmt(x)} {fmt(y)} {fmt(w)} {fmt(h)}")
    root.set("width", fmt(w))
    root.set("height", fmt(h))
    width = round(pixels * w / max(w, h))
    return grey(render_png(ET.tostring(root, encoding="unicode"), width))


def tile_images(path: str | Path, seed: int = 1, engine: str = "auto"):
    """(stamped tile, texture) grey images of the tile at ``path`` (:func:`render_window`), or
    None if the tile or the engine refuses it."""
    path = Path(path)
    _, original, (texture,) = _swatch(path, path.stem, None, float(TILES), seed, engines=(engine,))
    if original is None or texture is None:
        return None
    x0, y0, sw, sh = texture[1]
    w, h = sw / TILES, sh / TILES
    window = (x0 + w, y0 + h, (TILES - 2) * w, (TILES - 2) * h)
    return render_window(original[0], window), render_window(texture[0], window)


def measure_tile(path: str | Path, seed: int = 1, engine: str = "auto") -> Linework | None:
    """The linework figures of ``engine``'s texture of the tile at ``path`` (seed ``seed``)
    against the tile stamped; None if refused."""
    images = tile_images(path, seed, engine)
    return None if images is None else measure(*images)
