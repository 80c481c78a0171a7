"""GeoJSON in and out: map units as regions, motif placements as points (RFC 7946 shapes).

**Frames.**  GeoJSON's y axis points up (north), SVG's down.  svgtile works in an SVG-like frame,
so reading negates y and writing negates it back: a texture synthesized from a GeoJSON region
looks on the map as its exemplar looks on screen, and an angle means the same everywhere —
degrees clockwise as seen on the map, which is QGIS's marker rotation.

**Units.**  One exemplar user unit is ``unit`` map units (e.g. metres of a projected CRS): regions
are divided by it before synthesis and placements multiplied by it after (see
:func:`to_working` and :func:`placements_text`).  Geographic (degree) coordinates should be
projected first; svgtile does not reproject.

**Placements** are one Point feature per motif with properties

* ``kind`` — the kind's name (its symbol id in the exemplar);
* ``angle`` — rotation, degrees clockwise on the map, about the motif's footprint centroid;
* ``scale`` — size relative to the exemplar's drawing of that kind;
* ``size`` — width in map units of the square, centred on the point, that holds the motif's
  footprint at any rotation (``2 · radius · scale · unit``): a data-defined marker size.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.errors import RegionError
from svgtile.files import read_input

#: Decimals written for coordinates (map units can be metres or feet: sub-millimetre).
COORD_DECIMALS = 6
#: Decimals written for angles, scales and sizes.
VALUE_DECIMALS = 4


@dataclass(frozen=True, eq=False)
class Feature:
    """A polygonal feature read from GeoJSON (shape in the working frame: y negated)."""

    ident: str
    cls: str | None
    shape: shapely.Geometry


def load(path: str | Path) -> dict:
    """The parsed GeoJSON object; a RegionError naming the file if it is not JSON."""
    try:
        text = read_input(path, error=RegionError).decode("utf-8")
    except UnicodeDecodeError:
        raise RegionError("not a UTF-8 text file", source=str(path)) from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise RegionError(f"not valid JSON ({exc.msg} at line {exc.lineno})", source=str(path)) from None
    except RecursionError:
        raise RegionError("not valid GeoJSON (arrays or objects nested too deeply)", source=str(path)) from None
    if not isinstance(data, dict) or "type" not in data:
        raise RegionError("not a GeoJSON object (no 'type')", source=str(path))
    return data


def _features(data: dict, source: str) -> list[dict]:
    kind = data.get("type")
    if kind == "FeatureCollection":
        feats = data.get("features")
        if not isinstance(feats, list):
            raise RegionError("FeatureCollection without a 'features' list", source=source)
        return [f for f in feats if isinstance(f, dict)]
    if kind == "Feature":
        return [data]
    return [{"type": "Feature", "geometry": data, "properties": {}}]


def _ident(feature: dict, n: int) -> str:
    props = feature.get("properties") or {}
    for value in (feature.get("id"), props.get("id"), props.get("name")):
        if value is not None and str(value).strip():
            return str(value).strip()
    return f"feature-{n + 1}"


def _geometry(geometry: object, source: str, ident: str) -> shapely.Geometry:
    """A shapely geometry in the working frame (y negated), or a RegionError."""
    if not isinstance(geometry, dict):
        raise RegionError(f"feature {ident!r} has no geometry", source=source)
    try:
        geom = shapely.from_geojson(json.dumps(geometry))
    except (shapely.errors.GEOSException, ValueError, TypeError) as exc:
        raise RegionError(f"feature {ident!r} has an unreadable geometry ({' '.join(str(exc).split())})", source=source) from None
    coords = shapely.get_coordinates(geom)
    if len(coords) and not np.isfinite(coords).all():
        raise RegionError(f"feature {ident!r} has non-finite coordinates", source=source)
    return flip(geom)


def flip(geom: shapely.Geometry) -> shapely.Geometry:
    """``geom`` mirrored in the x axis (GeoJSON frame <-> working frame); 2D only."""
    return shapely.transform(geom, lambda c: c * np.array([1.0, -1.0]))


def read_regions(path: str | Path, *, class_property: str | None = None, feature: str | None = None) -> list[Feature]:
    """The Polygon and MultiPolygon features of a GeoJSON file, in the working frame.

    Parameters
    ----------
    class_property : name of the property holding each feature's class (for ``svgtile map``)
    feature : keep only the feature with this id (``id``, ``properties.id`` or ``.name``)

    Raises
    ------
    RegionError
        Unreadable file, no polygonal feature, or no feature with the id asked for.
    """
    source = str(path)
    feats = _features(load(path), source)
    out = []
    for n, f in enumerate(feats):
        ident = _ident(f, n)
        if feature is not None and ident != feature:
            continue
        geometry = f.get("geometry")
        if not isinstance(geometry, dict) or geometry.get("type") not in ("Polygon", "MultiPolygon"):
            if feature is not None:
                raise RegionError(f"feature {ident!r} is not a Polygon or MultiPolygon", source=source)
            continue
        props = f.get("properties") or {}
        cls = props.get(class_property) if class_property else None
        shape = shapely.make_valid(_geometry(geometry, source, ident))
        out.append(Feature(ident, None if cls is None else str(cls), shape))
    if feature is not None and not out:
        raise RegionError(f"no feature with id {feature!r}", source=source)
    if not out:
        raise RegionError("no Polygon or MultiPolygon feature", source=source)
    return out


def read_zones(path: str | Path, margin: float, *, feature: str | None = None) -> shapely.Geometry:
    """Avoid zones from GeoJSON, working frame: polygons as they are, everything grown by ``margin``."""
    source = str(path)
    parts = _geometries(path, feature, "no feature to avoid")
    zone = shapely.union_all(shapely.buffer(np.array(parts, dtype=object), margin, quad_segs=4))
    if zone.is_empty or zone.area <= 0:
        raise RegionError("the features give no zone to avoid (lines with margin 0?)", source=source)
    return zone


def read_geometry(path: str | Path, *, feature: str | None = None) -> shapely.Geometry:
    """Every geometry of a GeoJSON file (or the feature with id ``feature``), merged into one
    collection, in the working frame; a RegionError if there is none."""
    return shapely.GeometryCollection(_geometries(path, feature, "no feature"))


def _geometries(path: str | Path, feature: str | None, none: str) -> list[shapely.Geometry]:
    """The geometries of every feature of a GeoJSON file (or of the one with id ``feature``), in
    the working frame; a RegionError starting with ``none`` if there is none."""
    source = str(path)
    named = [(_ident(f, n), f) for n, f in enumerate(_features(load(path), source))]
    parts = [_geometry(f.get("geometry"), source, ident) for ident, f in named if feature in (None, ident)]
    if not parts:
        raise RegionError(none + (f" with id {feature!r}" if feature else ""), source=source)
    return parts


def to_working(geom: shapely.Geometry, unit: float) -> shapely.Geometry:
    """Map units -> exemplar user units (divide by ``unit``, about the origin: world anchoring
    keeps its meaning)."""
    return geom if unit == 1.0 else shapely.transform(geom, lambda c: c / unit)


def placements(arr: Arrangement, names: list[str], radius: np.ndarray, *, unit: float = 1.0) -> dict:
    """The GeoJSON FeatureCollection of ``arr``'s motifs (see the module docstring).

    Parameters
    ----------
    arr : motifs in the working frame, exemplar user units
    names : (k,) kind names, indexed by ``arr.kind``
    radius : (k,) bounding radius of each kind at scale 1, user units
    unit : map units per exemplar user unit
    """
    x = np.round(arr.xy[:, 0] * unit, COORD_DECIMALS) + 0.0
    y = np.round(-arr.xy[:, 1] * unit, COORD_DECIMALS) + 0.0
    angle = np.round(arr.angle, VALUE_DECIMALS) + 0.0
    scale = np.round(arr.scale * unit, VALUE_DECIMALS) + 0.0
    size = np.round(2.0 * np.asarray(radius)[arr.kind] * arr.scale * unit, VALUE_DECIMALS) + 0.0
    features = [
        {"type": "Feature", "geometry": {"type": "Point", "coordinates": [xi, yi]},
         "properties": {"kind": names[k], "angle": a, "scale": s, "size": z}}
        for k, xi, yi, a, s, z in zip(arr.kind.tolist(), x.tolist(), y.tolist(), angle.tolist(),
                                      scale.tolist(), size.tolist(), strict=True)
    ]  # fmt: skip
    return {"type": "FeatureCollection", "features": features}


def cellwork_features(cells, *, unit: float = 1.0) -> list[dict]:
    """GeoJSON features of a cellular texture's cells (Polygons) and lines (LineStrings), in the
    GeoJSON frame (y up) and map units; properties ``feature`` (corner, edge, face, line) and
    ``style`` (the SVG style they are drawn with).

    Parameters
    ----------
    cells : :class:`~svgtile.core.cells.Cellwork`, working frame, exemplar user units
    unit : map units per exemplar user unit
    """
    from svgtile.core.cells import FEATURES

    if cells is None or len(cells) == 0:
        return []
    shapes = shapely.transform(cells.shapes, lambda c: np.round(c * np.array([unit, -unit]), COORD_DECIMALS) + 0.0)
    shapes = shapely.orient_polygons(shapes)  # RFC 7946: exteriors counter-clockwise
    return [
        {"type": "Feature", "geometry": json.loads(shapely.to_geojson(g)),
         "properties": {"feature": FEATURES[f], "style": cells.styles[s]}}
        for g, f, s in zip(shapes, cells.feature.tolist(), cells.style.tolist(), strict=True)
    ]  # fmt: skip


def placements_text(collection: dict) -> str:
    """A FeatureCollection as text: one feature per line, stable, ending with a newline."""
    head = '{"type": "FeatureCollection", "features": [\n'
    body = ",\n".join(json.dumps(f, separators=(", ", ": "), allow_nan=False) for f in collection["features"])
    return head + body + ("\n" if body else "") + "]}\n"


def read_placements(path: str | Path, names: list[str], *, unit: float = 1.0) -> Arrangement:
    """Motifs from a placements file written by :func:`placements` (the inverse, for round trips).

    Parameters
    ----------
    names : the kind names, whose positions become ``kind`` indices
    unit : map units per exemplar user unit, as written
    """
    source = str(path)
    index = {n: i for i, n in enumerate(names)}
    rows = []
    for n, f in enumerate(_features(load(path), source)):
        geometry, props = f.get("geometry") or {}, f.get("properties") or {}
        try:
            x, y = (float(v) for v in geometry["coordinates"][:2])
            row = (index[props["kind"]], x / unit, -y / unit, float(props["angle"]), float(props["scale"]) / unit)
        except (KeyError, TypeError, ValueError, IndexError):
            raise RegionError(f"feature {_ident(f, n)!r} is not a placement (Point with kind, angle, scale)", source=source) from None
        if not all(math.isfinite(v) for v in row[1:]):
            raise RegionError(f"feature {_ident(f, n)!r} has non-finite values", source=source)
        rows.append(row)
    if not rows:
        return Arrangement.empty()
    table = np.array(rows, dtype=np.float64)
    return Arrangement(table[:, 0].astype(np.int64), table[:, 1:3], table[:, 3], table[:, 4])


def exemplar_placements(exemplar, arr: Arrangement, *, unit: float = 1.0, cells=None) -> str:
    """The placements file of a texture synthesized from ``exemplar`` (``synth -o X.geojson``);
    a cellular texture's cells and lines (:func:`cellwork_features`) come first."""
    names = [k.name for k in exemplar.kinds]
    radius = np.array([k.prototype.radius for k in exemplar.kinds])
    collection = placements(arr, names, radius, unit=unit)
    if cells is not None:
        collection["features"] = cellwork_features(cells, unit=unit) + collection["features"]
    return placements_text(collection)
