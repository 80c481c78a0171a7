"""GIS vector layers in and out through GDAL/OGR (pyogrio): GeoPackage, Shapefile, GeoJSON, FlatGeobuf.

**Addressing.**  A *layer spec* names features of a file::

    FILE                     every feature of the file's only (or first) layer
    FILE#LAYER               every feature of that layer (GeoPackages hold several)
    FILE#LAYER:FID           the feature with that feature id (``fid`` in QGIS)
    FILE#LAYER?WHERE         the features an OGR SQL condition selects, e.g. ``units.gpkg#units?unit='Ksh'``
    FILE#:FID, FILE#?WHERE   the same in the only (or first) layer

For GeoJSON files ``FILE.geojson#ID`` (no ``:`` or ``?``) keeps its meaning of earlier versions —
the feature whose ``id``, ``properties.id`` or ``properties.name`` is ID — and is read by
:mod:`svgtile.gis.geojson`, which pyogrio cannot do (OGR exposes either the feature id or a
property, never that fallback chain).

**Frames and CRS.**  As in :mod:`svgtile.gis.geojson`: map y points up, the working frame's down,
so reading negates y and writing negates it back; angles are degrees clockwise on the map (QGIS
marker rotation).  The CRS of the input is carried to the output as OGR reports it (WKT or
``AUTHORITY:CODE``); a layer without one gives an output without one — svgtile never guesses or
reprojects.

**Placements** are written as a Point layer with the fields ``kind, angle, scale, size`` (see
:mod:`svgtile.gis.geojson`) and, for ``svgtile map``, ``region`` and ``class``.
"""

from __future__ import annotations

import os
import re
import shutil
import tempfile
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from svgtile.errors import OutputError, RegionError
from svgtile.gis import geojson
from svgtile.gis.geojson import COORD_DECIMALS, VALUE_DECIMALS, Feature

#: OGR driver by file suffix.
DRIVERS = {".gpkg": "GPKG", ".shp": "ESRI Shapefile", ".geojson": "GeoJSON", ".json": "GeoJSON", ".fgb": "FlatGeobuf"}
#: Files a Shapefile is made of (written and replaced together).
SHAPEFILE_PARTS = (".shp", ".shx", ".dbf", ".prj", ".cpg")
#: Spatial indexes beside a Shapefile (QGIS's and ESRI's), stale once the Shapefile is replaced.
SHAPEFILE_INDEXES = (".qix", ".sbn", ".sbx")
#: The point layer's name in a GeoPackage output.
POINTS_LAYER = "svgtile"


def is_gis(path: str | Path) -> bool:
    """Whether ``path`` (a file, or a spec with ``#…``) is a GIS vector file svgtile reads."""
    return Path(str(path).partition("#")[0]).suffix.lower() in DRIVERS


@dataclass(frozen=True)
class Spec:
    """A parsed layer spec (see the module docstring)."""

    path: Path
    layer: str | None = None
    fid: int | None = None
    where: str | None = None
    ident: str | None = None  # GeoJSON ``#ID`` (legacy addressing)

    @property
    def legacy(self) -> bool:
        return self.ident is not None or (self.driver == "GeoJSON" and self.fid is None and self.where is None and self.layer is None)

    @property
    def driver(self) -> str:
        return DRIVERS[self.path.suffix.lower()]


def parse_spec(spec: str | Path) -> Spec:
    """``"units.gpkg#units:3"`` -> ``Spec(Path("units.gpkg"), "units", fid=3)``; RegionError if malformed."""
    text = str(spec)
    path, sep, sel = text.partition("#")
    if sep and not sel:
        raise RegionError("empty selector after '#' (FILE#LAYER, FILE#LAYER:FID or FILE#LAYER?WHERE)", source=text)
    p = Path(path)
    if p.suffix.lower() not in DRIVERS:
        raise RegionError(f"not a GIS file svgtile reads ({', '.join(DRIVERS)})", source=text)
    if not sel:
        return Spec(p)
    layer, qmark, where = sel.partition("?")
    if qmark and not where.strip():
        raise RegionError("empty condition after '?'", source=text)
    layer, colon, fid = layer.partition(":")
    number = None
    if colon:
        try:
            number = int(fid)
        except ValueError:
            raise RegionError(f"feature id must be an integer, not {fid!r}", source=text) from None
    if DRIVERS[p.suffix.lower()] == "GeoJSON" and not colon and not qmark:
        return Spec(p, ident=layer)
    return Spec(p, layer or None, number, where.strip() if qmark else None)


def _read(spec: Spec, source: str, columns: list[str] | None = None) -> tuple[dict, np.ndarray, np.ndarray, list]:
    """(meta, fids, WKB geometries, field arrays) of the features ``spec`` selects."""
    from pyogrio import raw
    from pyogrio.errors import DataLayerError, DataSourceError, FieldError, GeometryError

    try:
        _check_layer(spec, source)
        meta, fids, geometry, fields = raw.read(
            spec.path, layer=spec.layer, where=spec.where, fids=None if spec.fid is None else [spec.fid],
            columns=columns, return_fids=True, force_2d=True,
        )  # fmt: skip
    except RegionError:
        raise
    except (DataSourceError, DataLayerError, FieldError, GeometryError) as exc:
        if spec.fid is not None and "fid" in str(exc):
            raise RegionError(f"no feature with id {spec.fid}", source=source) from None
        raise RegionError(f"cannot read ({_gdal_message(exc)})", source=source) from None
    except Exception as exc:  # pyogrio raises plain errors for a bad WHERE, a bad fid …
        if spec.fid is not None and "fid" in str(exc):
            raise RegionError(f"no feature with id {spec.fid}", source=source) from None
        raise RegionError(f"cannot read ({type(exc).__name__}: {' '.join(str(exc).split())})", source=source) from None
    if spec.fid is not None and len(fids) == 0:
        raise RegionError(f"no feature with id {spec.fid}", source=source)
    if spec.where is not None and len(fids) == 0:
        raise RegionError(f"no feature where {spec.where}", source=source)
    return meta, np.asarray(fids), np.asarray(geometry, dtype=object), list(fields)


def _check_layer(spec: Spec, source: str) -> None:
    """RegionError unless ``spec``'s file exists and has its layer (if it names one); GDAL's own
    errors pass through."""
    import pyogrio

    if not spec.path.is_file() and not spec.path.is_dir():
        raise RegionError("no such file", source=source)
    if spec.layer is not None:
        names = [name for name, _ in pyogrio.list_layers(spec.path)]
        if spec.layer not in names:
            raise RegionError(f"no layer {spec.layer!r} (the file has {', '.join(names)})", source=source)


def _gdal_message(exc: BaseException) -> str:
    """GDAL's message on one line, without its advice about driver prefixes (svgtile picks the
    driver by the suffix)."""
    return " ".join(str(exc).split("; It might help")[0].split()).rstrip(".")


def crs_of(spec: str | Path | None) -> str | None:
    """The CRS of the layer a spec names (``AUTHORITY:CODE`` or WKT), None if it has none.

    A GeoJSON file has one only if it says so (:func:`_declares_crs`).
    """
    if spec is None or not is_gis(spec):
        return None
    s = parse_spec(spec)
    if s.driver == "GeoJSON" and not _declares_crs(s.path):
        return None
    import pyogrio

    try:
        _check_layer(s, str(spec))
        return pyogrio.read_info(s.path, layer=s.layer).get("crs")
    except RegionError:
        raise
    except Exception as exc:
        raise RegionError(f"cannot read ({_gdal_message(exc)})", source=str(spec)) from None


def _declares_crs(path: Path) -> bool:
    """Whether a GeoJSON file names its CRS (a ``crs`` member, as GDAL writes for other CRSs than
    WGS 84).  OGR reports WGS 84 for one that does not; svgtile takes that as no CRS, since
    svgtile's own GeoJSON (and many hand-made files) hold projected map units without saying so."""
    try:
        data = geojson.load(path)
    except RegionError:
        return False
    return isinstance(data.get("crs"), dict)


def common_crs(region: str | Path | None, others: tuple[str, ...] | list[str] = ()) -> str | None:
    """The CRS of the layer ``region`` names, after checking that every other layer spec in
    ``others`` (avoid layers) has the same one or none.  svgtile does not reproject.

    Raises
    ------
    RegionError
        An avoid layer in another CRS than the region's.
    """
    crs = crs_of(region)
    for spec in others:
        other = crs_of(spec)
        if crs is not None and other is not None and other != crs:
            raise RegionError(f"its CRS ({short_crs(other)}) is not the layer's ({short_crs(crs)}); reproject it first", source=str(spec))
    return crs


def short_crs(crs: str) -> str:
    """A CRS for a message: ``EPSG:…`` as it is, WKT by its name."""
    match = re.match(r'\s*\w+\["([^"]+)"', crs)
    return match.group(1) if match else crs


def _geometries(wkb: np.ndarray, source: str) -> np.ndarray:
    try:
        geoms = shapely.from_wkb(wkb)
    except shapely.errors.GEOSException as exc:
        raise RegionError(f"unreadable geometry ({' '.join(str(exc).split())})", source=source) from None
    coords = shapely.get_coordinates(geoms)
    if len(coords) and not np.isfinite(coords).all():
        raise RegionError("a feature has non-finite coordinates", source=source)
    return geoms


def read_regions(spec: str | Path, *, class_property: str | None = None) -> tuple[list[Feature], str | None]:
    """The polygonal features a layer spec names, in the working frame (y negated), and the CRS.

    Parameters
    ----------
    spec : a layer spec (see the module docstring)
    class_property : the field holding each feature's class (``svgtile map``)

    Returns
    -------
    features : one :class:`~svgtile.gis.geojson.Feature` per Polygon or MultiPolygon feature;
        ``ident`` is the feature id (QGIS's ``fid``), ``cls`` the class field's value as text
    crs : the layer's CRS, or None
    """
    source = str(spec)
    s = parse_spec(spec)
    if s.legacy:
        return geojson.read_regions(s.path, class_property=class_property, feature=s.ident), crs_of(s.path)
    meta, fids, wkb, fields = _read(s, source)
    names = list(meta["fields"])
    if class_property is not None and class_property not in names:
        raise RegionError(f"no field {class_property!r} (the layer has {', '.join(names) or 'no fields'})", source=source)
    classes = fields[names.index(class_property)] if class_property is not None else None
    geoms = _geometries(wkb, source)
    kind = shapely.get_type_id(geoms)
    keep = np.flatnonzero((kind == 3) | (kind == 6))  # Polygon, MultiPolygon
    if len(keep) == 0:
        raise RegionError("no Polygon or MultiPolygon feature" + (" selected" if s.fid is not None or s.where else ""), source=source)
    shapes = shapely.make_valid(flip_all(geoms[keep]))
    out = []
    for i, shape in zip(keep.tolist(), shapes, strict=True):
        value = None if classes is None or classes[i] is None else str(classes[i])
        out.append(Feature(str(int(fids[i])), value, shape))
    return out, (meta.get("crs") if s.driver != "GeoJSON" or _declares_crs(s.path) else None)


def flip_all(geoms: np.ndarray) -> np.ndarray:
    """Every geometry mirrored in the x axis (map frame <-> working frame), in bulk."""
    return shapely.transform(geoms, lambda c: c * np.array([1.0, -1.0]))


def read_zones(spec: str | Path, margin: float) -> shapely.Geometry:
    """Avoid zones from a layer spec, working frame: polygons as they are, everything grown by ``margin``."""
    s = parse_spec(spec)
    if s.legacy:
        return geojson.read_zones(s.path, margin, feature=s.ident)
    _, _, wkb, _ = _read(s, str(spec), columns=[])
    geoms = flip_all(_geometries(wkb, str(spec)))
    geoms = geoms[~shapely.is_empty(geoms)]
    if len(geoms) == 0:
        raise RegionError("no feature to avoid", source=str(spec))
    zone = shapely.union_all(shapely.buffer(geoms, margin, quad_segs=4))
    if zone.is_empty or zone.area <= 0:
        raise RegionError("the features give no zone to avoid (lines with margin 0?)", source=str(spec))
    return zone


# ----------------------------------------------------------------------------- placements


@dataclass(frozen=True, eq=False)
class Points:
    """Placements as columns, map frame (y up), map units.

    Attributes
    ----------
    xy : (n, 2) float array, map units
    kind : (n,) object array of kind names
    angle : (n,) float array, degrees clockwise on the map
    scale : (n,) float array
    size : (n,) float array, map units (the marker size, see :mod:`svgtile.gis.geojson`)
    region, cls : (n,) object arrays, or None (``synth`` has neither)
    """

    xy: np.ndarray
    kind: np.ndarray
    angle: np.ndarray
    scale: np.ndarray
    size: np.ndarray
    region: np.ndarray | None = None
    cls: np.ndarray | None = None


def write_points(points: Points, out: str | Path, *, crs: str | None) -> None:
    """Write ``points`` as a Point layer to ``out`` (driver by suffix), atomically.

    The layer goes to a temporary folder beside ``out`` and is moved into place (for a Shapefile,
    every part), so a failure never leaves half a layer and an existing file stays as it was.
    A GeoPackage's layer is named :data:`POINTS_LAYER`.

    Raises
    ------
    OutputError
        Unknown suffix, or GDAL could not write.
    """
    from pyogrio import raw

    out = Path(out)
    driver = DRIVERS.get(out.suffix.lower())
    if driver is None:
        raise OutputError(f"not a GIS format svgtile writes ({', '.join(DRIVERS)})", source=str(out))
    fields = ["kind", "angle", "scale", "size"]
    data = [points.kind.astype(object), np.round(points.angle, VALUE_DECIMALS) + 0.0,
            np.round(points.scale, VALUE_DECIMALS) + 0.0, np.round(points.size, VALUE_DECIMALS) + 0.0]  # fmt: skip
    if points.region is not None:
        fields += ["region", "class"]
        data += [points.region.astype(object), points.cls.astype(object)]
    xy = np.round(points.xy, COORD_DECIMALS) + 0.0
    wkb = shapely.to_wkb(shapely.points(xy)) if len(xy) else np.array([], dtype=object)
    try:
        tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}.", dir=out.parent))
    except OSError as exc:
        raise OutputError(f"cannot write here ({exc.strerror or exc})", source=str(out)) from None
    try:
        target = tmp / out.name
        # GeoPackage 1.2: what the GDAL of QGIS 3.22 (Debian 12) reads without a warning
        options = {"layer": POINTS_LAYER, "dataset_options": {"VERSION": "1.2"}} if driver == "GPKG" else {}
        if driver == "GeoJSON":
            options["layer_options"] = {"COORDINATE_PRECISION": str(COORD_DECIMALS)}
        with warnings.catch_warnings():  # no CRS is what the input had: no warning about it
            warnings.filterwarnings("ignore", message=".*crs.*not provided", category=UserWarning)
            raw.write(target, wkb, data, fields, driver=driver, geometry_type="Point", crs=crs, encoding="UTF-8"
                      if driver == "ESRI Shapefile" else None, **options)  # fmt: skip
        if driver == "ESRI Shapefile":
            for part in sorted(tmp.iterdir()):
                os.replace(part, out.with_name(out.stem + part.name[len(target.stem):]))
            if crs is None:  # a .prj left from an earlier run would claim a CRS
                out.with_suffix(".prj").unlink(missing_ok=True)
            for index in SHAPEFILE_INDEXES:  # a spatial index of the old points would hide the new
                out.with_suffix(index).unlink(missing_ok=True)
        else:
            os.replace(target, out)
    except OutputError:
        raise
    except Exception as exc:
        raise OutputError(f"cannot write ({' '.join(str(exc).split())})", source=str(out)) from None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
