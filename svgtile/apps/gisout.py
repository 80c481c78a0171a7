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
from svgtile.files import check_output, write_file
from svgtile.gis import geojson, layers
from svgtile.gis.symbols import file_stem, qml_style, symbol_documents

if TYPE_CHECKING:
    from svgtile.apps.mapfill import MapFill


def style_paths(out: str | Path) -> tuple[Path, Path]:
    """``(OUT.qml, OUT-symbols/)`` for the output ``out``."""
    out = Path(out)
    return out.with_suffix(".qml"), out.with_name(out.stem + "-symbols")


def check_style(out: str | Path, *, protect: tuple = ()) -> None:
    """Raise :class:`OutputError` now, before the work, if :func:`write_style` could not write
    ``OUT.qml`` and ``OUT-symbols/`` beside ``out`` (so a failing style never follows a written
    layer)."""
    qml, folder = style_paths(out)
    check_output(qml, protect=protect)
    if folder.exists() and not folder.is_dir():
        raise OutputError("exists and is not a folder", source=str(folder))


def write_symbols(exemplar: Exemplar, folder: str | Path, *, protect: tuple = ()) -> list[Path]:
    """Write each kind of ``exemplar`` as ``folder/KIND.svg`` (:func:`symbol_documents`); the folder is made.

    Every file is checked before the first is written, so a symbol named like an input (``protect``:
    the exemplar ``dot.svg`` holding a kind ``dot``, written into its own folder) stops the run
    with nothing written.
    """
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise OutputError("exists and is not a folder", source=str(folder))
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot make the folder ({exc.strerror or exc})", source=str(folder)) from None
    documents = symbol_documents(exemplar)
    for name in documents:
        check_output(folder / name, protect=protect)
    for name, text in documents.items():
        write_file(text, folder / name, protect=protect)
    return [folder / name for name in documents]


def write_style(out: str | Path, exemplars: dict[str | None, Exemplar], *, protect: tuple = ()) -> Path:
    """The symbols and QGIS style of the placements file ``out`` (see the module docstring).

    Parameters
    ----------
    out : the placements file
    exemplars : ``{None: exemplar}`` for ``synth``; ``{class: exemplar}`` for ``map``
    protect : the inputs, never overwritten

    Returns
    -------
    The ``.qml`` file.
    """
    qml, folder = style_paths(out)
    by_class = None not in exemplars
    for cls, ex in sorted(exemplars.items(), key=lambda item: str(item[0])):
        write_symbols(ex, folder / file_stem(cls) if by_class else folder, protect=protect)
    write_file(qml_style(str(folder.resolve()), by_class=by_class), qml, protect=protect)
    return qml


#: One part of a placements layer: an exemplar, its motifs (working frame, map units), and the
#: region and class they fill (both None for ``synth``).
Part = tuple[Exemplar, Arrangement, "str | None", "str | None"]


def filled_exemplars(result: MapFill) -> dict[str, Exemplar]:
    """The exemplar of each class at least one region of a map fill was filled with, by class
    (sorted), each loaded once: what :func:`map_parts` and :func:`write_style` need."""
    used = sorted({r.cls for r, ok in zip(result.regions, result.filled, strict=True) if ok})
    return {cls: load_exemplar(str(result.styles.classes[cls].exemplar))[0] for cls in used}


def map_parts(result: MapFill, exemplars: dict[str, Exemplar] | None = None) -> list[Part]:
    """The parts of a map fill: each filled region with its class's exemplar, in region order.

    ``exemplars`` is :func:`filled_exemplars` of ``result`` (loaded here if None).
    """
    exemplars = filled_exemplars(result) if exemplars is None else exemplars
    return [(exemplars[r.cls], arr, r.ident, r.cls)
            for r, arr in zip(result.regions, result.results, strict=True) if arr is not None]  # fmt: skip


def collection(parts: list[Part]) -> dict:
    """The parts as a GeoJSON FeatureCollection (:func:`svgtile.gis.geojson.placements`), with
    ``region`` and ``class`` first where the parts have them."""
    features = []
    for ex, arr, region, cls in parts:
        radius = np.array([k.prototype.radius for k in ex.kinds])
        for f in geojson.placements(arr, [k.name for k in ex.kinds], radius)["features"]:
            if region is not None:
                f["properties"] = {"region": region, "class": cls, **f["properties"]}
            features.append(f)
    return {"type": "FeatureCollection", "features": features}


def points(parts: list[Part]) -> layers.Points:
    """The parts as columns in the map frame (y up), in bulk: what :func:`collection` holds."""
    cols: dict[str, list] = {name: [] for name in ("xy", "kind", "angle", "scale", "size", "region", "cls")}
    for ex, arr, region, cls in parts:
        names = np.array([k.name for k in ex.kinds], dtype=object)
        radius = np.array([k.prototype.radius for k in ex.kinds])
        cols["xy"].append(arr.xy * np.array([1.0, -1.0]))
        cols["kind"].append(names[arr.kind])
        cols["angle"].append(arr.angle)
        cols["scale"].append(arr.scale)
        cols["size"].append(2.0 * radius[arr.kind] * arr.scale)
        cols["region"].append(np.full(len(arr), region, dtype=object))
        cols["cls"].append(np.full(len(arr), cls, dtype=object))
    if not parts:
        return layers.Points(np.zeros((0, 2)), *(np.zeros(0, dtype=t) for t in (object, float, float, float)))
    joined = {k: np.concatenate(v) for k, v in cols.items()}
    classed = parts[0][2] is not None
    return layers.Points(joined["xy"], joined["kind"], joined["angle"], joined["scale"], joined["size"],
                         joined["region"] if classed else None, joined["cls"] if classed else None)  # fmt: skip


def write_placements(parts: list[Part], out: str | Path, *, crs: str | None, protect: tuple = ()) -> None:
    """Write the motifs of ``parts`` as a point layer to ``out`` (see the module docstring).

    Parameters
    ----------
    parts : ``[(exemplar, motifs, region, class)]``; one part with region None for ``synth``
    out : ``.geojson``, ``.gpkg``, ``.shp`` or ``.fgb`` (or ``-``: GeoJSON text on standard output)
    crs : the input's CRS, carried to the output; None for none
    protect : the inputs, never overwritten
    """
    if str(out) == "-" or (layers.DRIVERS.get(Path(out).suffix.lower()) == "GeoJSON" and crs is None):
        write_file(geojson.placements_text(collection(parts)), out, protect=protect)
        return
    check_output(out, protect=protect)
    layers.write_points(points(parts), out, crs=crs)
