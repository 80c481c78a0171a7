"""Placements to GIS files, and the symbols and QGIS style beside them (``--with-style``).

``synth`` and ``map`` write one point per motif; by the output's suffix this is

* ``.geojson`` with no CRS to carry (the region came from an SVG, a ``--size`` or a GeoJSON
  file): svgtile's own GeoJSON text (:func:`svgtile.gis.geojson.placements_text`), stable line by
  line, as in earlier versions;
* ``.gpkg``, ``.shp``, ``.fgb``, or ``.geojson`` from a layer with a CRS: a Point layer written by
  GDAL (:func:`svgtile.gis.layers.write_points`) in the input's CRS.

With ``--with-style``, ``OUT.qml`` (QGIS loads a ``.qml`` named like the layer file as its
default style) and the folder ``OUT-symbols/`` of per-kind SVGs (a sub-folder per class for
``map``) are written beside the output.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from svgtile.apps.load import load_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.errors import OutputError
from svgtile.files import write_file
from svgtile.gis import geojson, layers
from svgtile.gis.symbols import file_stem, qml_style, symbol_documents

if TYPE_CHECKING:
    from svgtile.apps.mapfill import MapFill


def style_paths(out: str | Path) -> tuple[Path, Path]:
    """``(OUT.qml, OUT-symbols/)`` for the output ``out``."""
    out = Path(out)
    return out.with_suffix(".qml"), out.with_name(out.stem + "-symbols")


def write_symbols(exemplar: Exemplar, folder: str | Path) -> list[Path]:
    """Write each kind of ``exemplar`` as ``folder/KIND.svg`` (:func:`symbol_documents`); the folder is made."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise OutputError("exists and is not a folder", source=str(folder))
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot make the folder ({exc.strerror or exc})", source=str(folder)) from None
    written = []
    for name, text in symbol_documents(exemplar).items():
        write_file(text, folder / name)
        written.append(folder / name)
    return written


def write_style(out: str | Path, exemplars: dict[str | None, Exemplar]) -> Path:
    """The symbols and QGIS style of the placements file ``out`` (see the module docstring).

    Parameters
    ----------
    out : the placements file
    exemplars : ``{None: exemplar}`` for ``synth``; ``{class: exemplar}`` for ``map``

    Returns
    -------
    The ``.qml`` file.
    """
    qml, folder = style_paths(out)
    by_class = None not in exemplars
    for cls, ex in sorted(exemplars.items(), key=lambda item: str(item[0])):
        write_symbols(ex, folder / file_stem(cls) if by_class else folder)
    write_file(qml_style(str(folder.resolve()), by_class=by_class), qml)
    return qml


def exemplar_collection(exemplar: Exemplar, arr: Arrangement, *, unit: float = 1.0) -> dict:
    """The placements FeatureCollection of a texture synthesized from ``exemplar`` (``synth``)."""
    radius = np.array([k.prototype.radius for k in exemplar.kinds])
    return geojson.placements(arr, [k.name for k in exemplar.kinds], radius, unit=unit)


def placements_collection(result: MapFill) -> dict:
    """Every region's motifs as a GeoJSON FeatureCollection of points, with ``region`` and ``class``."""
    features = []
    for r, arr in zip(result.regions, result.results, strict=True):
        if arr is None:
            continue
        ex, _ = load_exemplar(str(result.styles.classes[r.cls].exemplar))
        for f in exemplar_collection(ex, arr)["features"]:
            f["properties"] = {"region": r.ident, "class": r.cls, **f["properties"]}
            features.append(f)
    return {"type": "FeatureCollection", "features": features}


def write_placements(collection: dict, out: str | Path, *, crs: str | None, protect: tuple = ()) -> None:
    """Write a placements FeatureCollection (:func:`svgtile.gis.geojson.placements`) to ``out``.

    Parameters
    ----------
    collection : the motifs as GeoJSON features, map frame, already rounded
    out : ``.geojson``, ``.gpkg``, ``.shp`` or ``.fgb`` (or ``-``: GeoJSON text on standard output)
    crs : the input's CRS, carried to the output; None for none
    protect : the inputs, never overwritten
    """
    if str(out) == "-" or (layers.DRIVERS.get(Path(out).suffix.lower()) == "GeoJSON" and crs is None):
        write_file(geojson.placements_text(collection), out, protect=protect)
        return
    from svgtile.files import check_output

    check_output(out, protect=protect)
    layers.write_points(layers.Points.from_collection(collection), out, crs=crs)
