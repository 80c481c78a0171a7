"""Writing a filled map or a tiled texture as its bands finish (issue 19 item 3).

The motifs of each finished band (:mod:`svgtile.runners.tiling`) are formatted at once — as
``<use>`` lines or GeoJSON features — and spooled to disk (:class:`svgtile.runners.spool.Spool`);
when every unit is done, the document is written head first, the bands in world order, straight
from the spool into a temporary file that is renamed into place (:func:`svgtile.files.atomic_output`).
The text is byte for byte what :func:`svgtile.svg.writer.map_document`,
:func:`svgtile.svg.writer.svg_document` and :func:`svgtile.gis.geojson.placements_text` give for
the whole arrangement, but no more than one band is ever held in memory.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np

from svgtile.apps.load import load_exemplar
from svgtile.apps.mapfill import MapFill, Styles
from svgtile.core.arrangement import Arrangement
from svgtile.core.cells import Cellwork
from svgtile.core.exemplar import Exemplar, Kind
from svgtile.files import atomic_output
from svgtile.gis import geojson
from svgtile.runners.spool import Spool
from svgtile.svg.numbers import fmt
from svgtile.svg.writer import (
    MapLayer,
    cell_elements,
    map_document_parts,
    prefixed_defs,
    svg_document_parts,
    use_elements,
)

GEOJSON_HEAD = '{"type": "FeatureCollection", "features": [\n'
GEOJSON_TAIL = "]}\n"
#: The band a cellular unit's cells are spooled as: before its motifs (band 0, a unit run whole).
CELL_BAND = -1


def class_prefix(cls: str) -> str:
    """The id prefix of a class's symbols in a filled map."""
    return "svgtile-" + re.sub(r"[^A-Za-z0-9_.-]+", "-", cls).strip("-") + "-"


class BandWriter:
    """Formats each finished band as the output's text and spools it, by ``(unit, band)``.

    Parameters
    ----------
    spool : where the text goes
    kind : ``"svg"`` or ``"geojson"``
    """

    def __init__(self, spool: Spool, kind: str) -> None:
        self.spool, self.kind = spool, kind
        self.bands: dict[int, list[int]] = {}

    def svg(self, unit: int, band: int, arr: Arrangement, kinds: tuple[Kind, ...]) -> None:
        """Spool a band's ``<use>`` lines (``kinds``: the hrefs its motifs point at)."""
        self._put(unit, band, "\n".join(use_elements(arr, kinds)))

    def features(self, unit: int, band: int, arr: Arrangement, exemplar: Exemplar, props: dict | None = None,
                 *, unit_scale: float | None = None) -> None:  # fmt: skip
        """Spool a band's GeoJSON features (``props`` first in each feature's properties)."""
        names = [k.name for k in exemplar.kinds]
        radius = np.array([k.prototype.radius for k in exemplar.kinds])
        feats = geojson.placements(arr, names, radius, **({} if unit_scale is None else {"unit": unit_scale}))["features"]
        if props:
            for f in feats:
                f["properties"] = {**props, **f["properties"]}
        self._put(unit, band, ",\n".join(json.dumps(f, separators=(", ", ": "), allow_nan=False) for f in feats))

    def cells_svg(self, unit: int, cells: Cellwork, scale: float = 1.0) -> None:
        """Spool a cellular unit's cells and lines as ``<path>`` lines (in the exemplar's user
        units, in a ``scale(SCALE)`` group when its class's unit is not 1, so that strokes scale
        with the cells), drawn before its motifs."""
        lines = cell_elements(cells)
        if lines and scale != 1.0:
            lines = [f'    <g transform="scale({fmt(scale)})">', *(f"  {line}" for line in lines), "    </g>"]
        self._put(unit, CELL_BAND, "\n".join(lines))

    def cell_features(self, unit: int, cells: Cellwork, props: dict | None = None, *, scale: float = 1.0) -> None:
        """Spool a cellular unit's cells (Polygons) and lines (LineStrings) as GeoJSON features in
        map units (``scale`` map units per user unit), ``props`` first, before its motifs."""
        feats = geojson.cellwork_features(cells, unit=scale)
        if props:
            for f in feats:
                f["properties"] = {**props, **f["properties"]}
        self._put(unit, CELL_BAND, ",\n".join(json.dumps(f, separators=(", ", ": "), allow_nan=False) for f in feats))

    def _put(self, unit: int, band: int, text: str) -> None:
        self.spool.put((unit, band), text)
        self.bands.setdefault(unit, []).append(band)

    def pieces(self, unit: int) -> list[tuple[int, int]]:
        """The non-empty pieces of ``unit``, in world order."""
        return [(unit, b) for b in sorted(self.bands.get(unit, ())) if self.spool.size((unit, b))]

    def copy(self, pieces: list[tuple[int, int]], out, sep: bytes) -> None:
        """The pieces to ``out``, ``sep`` between them."""
        for n, key in enumerate(pieces):
            if n:
                out.write(sep)
            self.spool.copy(key, out)


def write_map_svg(out: str | Path, result: MapFill, bands: BandWriter, params: dict, *,
                  protect: tuple = ()) -> None:  # fmt: skip
    """The filled map, as :func:`svgtile.svg.writer.map_document` would write it."""
    styles: Styles = result.styles
    written = [n for n, ok in enumerate(result.filled) if ok]
    defs, kinds, grounds = [], {}, {}
    for cls in sorted({result.regions[n].cls for n in written}):
        ex, _ = load_exemplar(str(styles.classes[cls].exemplar))
        style_defs, kinds[cls] = prefixed_defs(ex, class_prefix(cls))
        defs.extend(style_defs)
        grounds[cls] = ex.ground
    layers = []
    for n in written:
        r = result.regions[n]
        layers.append(MapLayer(r.ident, r.cls, r.shape, kinds[r.cls], Arrangement.empty(),
                               styles.classes[r.cls].boundary, r.element, r.matrix, grounds[r.cls]))  # fmt: skip
    doc = result.doc
    parts = map_document_parts(None if doc is None else doc.root, defs, layers, params=params,
                               namespaces=() if doc is None else doc.namespaces)  # fmt: skip
    with atomic_output(out, protect=protect) as fh:
        fh.write(parts[0].encode("utf-8"))
        for n, part in zip(written, parts[1:], strict=True):
            pieces = bands.pieces(n)
            if pieces:
                fh.write(b"\n")
                bands.copy(pieces, fh, b"\n")
                fh.write(b"\n")
            fh.write(part.encode("utf-8"))


def write_geojson(out: str | Path, units: list[int], bands: BandWriter, *, protect: tuple = ()) -> None:
    """Every unit's features, units in the given order, as
    :func:`svgtile.gis.geojson.placements_text` would write them."""
    pieces = [key for n in units for key in bands.pieces(n)]
    with atomic_output(out, protect=protect) as fh:
        fh.write(GEOJSON_HEAD.encode("utf-8"))
        bands.copy(pieces, fh, b",\n")
        fh.write((("\n" if pieces else "") + GEOJSON_TAIL).encode("utf-8"))


def write_texture_svg(out: str | Path, exemplar: Exemplar, region, bands: BandWriter, *, boundary: str,
                      params: dict, protect: tuple = ()) -> None:  # fmt: skip
    """One texture (unit 0's bands), as :func:`svgtile.svg.writer.svg_document` would write it."""
    head, tail = svg_document_parts(exemplar, region, boundary=boundary, params=params)
    pieces = bands.pieces(0)
    with atomic_output(out, protect=protect) as fh:
        if pieces:
            fh.write(head.encode("utf-8"))
            bands.copy(pieces, fh, b"\n")
        else:
            fh.write(head.rstrip(" ").removesuffix("\n").encode("utf-8"))
        fh.write(tail.encode("utf-8"))
