"""Reading map regions and avoid zones: ``MAP.svg#ID``, GIS layer specs, classed units.

A *region spec* names where an output region comes from:

* ``MAP.svg#ID`` — the element with that id: any closed shape or group of shapes, transforms of
  the element and its ancestors applied, holes by each shape's fill rule;
* ``FILE.gpkg``, ``FILE.shp``, ``FILE.fgb``, ``FILE.geojson`` — every Polygon and MultiPolygon
  of the layer, merged; ``FILE.gpkg#LAYER``, ``#LAYER:FID``, ``#LAYER?WHERE`` select a layer and
  features (:mod:`svgtile.gis.layers`); ``FILE.geojson#ID`` — the feature whose ``id`` (or
  ``properties.id``, or ``properties.name``) is ID.

An *avoid spec* ``MAP.svg#ID`` names the labels, lines or shapes the texture must keep clear of:
texts as estimated boxes, shapes as their footprints, lines as their stroke, each grown by a
margin (:meth:`svgtile.svg.mapdoc.SvgShapes.keep_clear`); a GeoJSON avoid spec takes its polygons
as they are and grows lines and points by the margin (so does any GIS layer spec).

Map units in a map SVG carry a *class* (:func:`class_of`), which the styles file of
``svgtile map`` maps to an exemplar.  The SVG geometry itself is read by
:class:`svgtile.svg.mapdoc.SvgShapes` (the svg package is the one that uses svgelements).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from svgtile.core.flow import FlowField
from svgtile.core.region import Region
from svgtile.engines.base import Controls
from svgtile.errors import ParameterError, RegionError
from svgtile.gis import geojson, layers
from svgtile.gis.layers import is_gis
from svgtile.svg.dialect import CONTAINERS, INKSCAPE_NS, NOT_RENDERED, SHAPES
from svgtile.svg.mapdoc import SvgShapes

#: Default growth of avoid zones, user units (clear space around labels and lines).
AVOID_MARGIN = 2.0
#: Larger margins are refused: no map is this wide, and growing a shape by ~1e150 overflows.
MAX_AVOID_MARGIN = 1e12


@dataclass(frozen=True, eq=False)
class MapRegion:
    """One map unit to fill.

    Attributes
    ----------
    ident : str
        Element or feature id (generated as ``TAG-N`` when it has none).
    cls : str or None
        Its class (the key into the styles file).
    shape : shapely (Multi)Polygon, user units of the map (SVG frame: y down)
    matrix : (3, 3) float array or None
        For an SVG element: from the user space of the element's parent to the root's (its
        inverse places the texture group beside the element).  None for GeoJSON.
    element : the SVG element, or None
    """

    ident: str
    cls: str | None
    shape: shapely.Geometry
    matrix: np.ndarray | None = None
    element: ET.Element | None = None


def split_spec(spec: str) -> tuple[Path, str | None]:
    """``"map.svg#unit-3"`` -> ``(Path("map.svg"), "unit-3")``; no ``#``: id None."""
    path, sep, ident = str(spec).partition("#")
    if sep and not ident:
        raise RegionError("empty id after '#'", source=str(spec))
    return Path(path), (ident if sep else None)


def read_region_shape(spec: str) -> shapely.Geometry:
    """The geometry a region spec names (see the module docstring), in user units."""
    if is_gis(spec):
        regions, _ = layers.read_regions(spec)
        return shapely.union_all([r.shape for r in regions])
    path, ident = split_spec(spec)
    if ident is None:
        raise RegionError("name the region's element: MAP.svg#ID", source=str(path))
    doc = SvgShapes.read(path)
    shape = doc.area(doc.element(ident))
    if shape.is_empty or shape.area <= 0:
        raise RegionError(f"element #{ident} encloses no area (is it a closed shape?)", source=str(path))
    return shape


def read_avoid_shape(spec: str, margin: float = AVOID_MARGIN) -> shapely.Geometry:
    """The avoid zone an avoid spec names, grown by ``margin`` user units."""
    if is_gis(spec):
        return layers.read_zones(spec, margin)
    path, ident = split_spec(spec)
    if ident is None:
        raise RegionError("name the element to avoid: MAP.svg#ID", source=str(path))
    doc = SvgShapes.read(path)
    zone = doc.keep_clear(doc.element(ident), margin)
    if zone.is_empty or zone.area <= 0:
        raise RegionError(f"element #{ident} gives no zone to avoid (an empty group, or lines with --avoid-margin 0)", source=str(path))
    return zone


def class_of(el: ET.Element, attribute: str | None = None) -> list[str]:
    """The class names an element may carry, most specific first.

    ``attribute`` (e.g. ``data-unit``) if given and present, then each token of ``class``, then
    the Inkscape label (``inkscape:label``, the name shown in Inkscape's Objects panel).
    """
    names = []
    if attribute and attribute in el.attrib:
        names.append(el.attrib[attribute].strip())
    names += el.attrib.get("class", "").split()
    label = el.attrib.get(f"{{{INKSCAPE_NS}}}label")
    if label:
        names.append(label.strip())
    return [n for n in names if n]


def classed_regions(doc: SvgShapes, classes: set[str], attribute: str | None = None) -> list[MapRegion]:
    """Every shape or group of ``doc`` whose class is one of ``classes``, in document order.

    The outermost classed element wins: a classed group is one region, its children are not
    looked at.  Elements in ``<defs>``, symbols, clip paths and the like are never regions.
    """
    out: list[MapRegion] = []
    counter: dict[str, int] = {}

    def walk(node: ET.Element) -> None:
        for child in node:
            tag = child.tag.rsplit("}", 1)[-1] if isinstance(child.tag, str) else ""
            if tag in NOT_RENDERED or tag not in (*SHAPES, *CONTAINERS, "svg"):
                continue
            match = next((c for c in class_of(child, attribute) if c in classes), None)
            if match is None:
                if tag in (*CONTAINERS, "svg"):
                    walk(child)
                continue
            counter[tag] = counter.get(tag, 0) + 1
            ident = child.attrib.get("id") or f"{tag}-{counter[tag]}"
            parent = doc.parents.get(child)
            matrix = doc.matrix(parent) if parent is not None else np.eye(3)
            out.append(MapRegion(ident, match, doc.area(child), matrix, child))

    walk(doc.root)
    return out


def synth_region(
    size: tuple[float, float] | None, region: str | None, avoid: tuple[str, ...] = (), margin: float = AVOID_MARGIN
) -> Region:
    """The output region of ``svgtile synth``: ``--size`` or ``--region``, less ``--avoid`` zones.

    Parameters
    ----------
    size : (width, height) user units of a rectangle at the origin, or None
    region : a region spec (see the module docstring), or None
    avoid : avoid specs
    margin : growth of avoid zones, user units
    """
    if (size is None) == (region is None):
        raise ParameterError("give either --size WIDTHxHEIGHT or --region MAP.svg#ID / FILE.gpkg")
    if not (0 <= margin <= MAX_AVOID_MARGIN):
        raise ParameterError(f"--avoid-margin must be a number from 0 to {MAX_AVOID_MARGIN:g}, not {margin:g}")
    zone = shapely.union_all([read_avoid_shape(spec, margin) for spec in avoid]) if avoid else None
    if region is None:
        rect = Region.rectangle(*size)
        return rect if zone is None else Region.from_geometry(rect.shape, avoid=zone, source="--size")
    return Region.from_geometry(read_region_shape(region), avoid=zone, source=region)


def _geojson_control(path: Path, option: str) -> bool:
    """Whether a control spec names a GeoJSON file (other GIS formats are refused: controls are
    read from ``MAP.svg#ID`` or ``FILE.geojson``)."""
    if not is_gis(path):
        return False
    if path.suffix.lower() != ".geojson":
        raise RegionError(f"{option} reads lines from MAP.svg#ID or FILE.geojson, not a {path.suffix} layer",
                          source=str(path))  # fmt: skip
    return True


def read_lines(spec: str, option: str) -> list[tuple[np.ndarray, float]]:
    """The polylines a control spec names, with their stroke widths (user units).

    ``MAP.svg#ID``: the strokes of that element (:meth:`SvgShapes.strokes`); ``FILE.geojson[#ID]``:
    the LineStrings, MultiLineStrings and polygon rings of the file (width 0).
    """
    path, ident = split_spec(spec)
    gj = _geojson_control(Path(path), option)
    if gj:
        out = []
        for g in shapely.get_parts(shapely.get_parts(geojson.read_geometry(path, feature=ident))):
            if shapely.get_type_id(g) == 3:  # a polygon: its rings
                out += [(shapely.get_coordinates(r), 0.0) for r in shapely.get_parts(shapely.boundary(g))]
            elif shapely.get_type_id(g) == 1:
                out.append((shapely.get_coordinates(g), 0.0))
        lines_out = [(p, w) for p, w in out if len(p) >= 2]
    else:
        if ident is None:
            raise RegionError(f"name the element: {option} MAP.svg#ID", source=str(path))
        doc = SvgShapes.read(path)
        lines_out = [(p, w) for p, w in doc.strokes(doc.element(ident)) if len(p) >= 2]
    if not lines_out:
        raise RegionError(f"{option}: {'feature' if gj else 'element'} {ident or ''} draws no line".replace("  ", " "),
                          source=str(path))  # fmt: skip
    return lines_out


def read_controls(flow: tuple[str, ...] = (), barrier: tuple[str, ...] = (), grow_within: tuple[str, ...] = ()) -> Controls:
    """The map controls of ``--flow``, ``--barrier`` and ``--grow-within`` (Ijiri et al. 2008 §6).

    * flow: the strokes' tangents, interpolated (:class:`~svgtile.core.flow.FlowField`);
    * barrier: the strokes as lines (their width ignored: a barrier is a line);
    * grow-within: the closed shapes' area, and every stroke grown by half its width (the brush);
      for GeoJSON, the polygons.
    """
    field = None
    if flow:
        lines = [p for spec in flow for p, _ in read_lines(spec, "--flow")]
        field = FlowField.from_strokes(lines, source=" ".join(flow))
    barriers = None
    if barrier:
        barriers = shapely.union_all([shapely.linestrings(p) for spec in barrier for p, _ in read_lines(spec, "--barrier")])
    within = None
    if grow_within:
        parts = []
        for spec in grow_within:
            path, ident = split_spec(spec)
            if _geojson_control(Path(path), "--grow-within"):
                parts.append(shapely.union_all([r.shape for r in geojson.read_regions(path, feature=ident)]))
                continue
            if ident is None:
                raise RegionError("name the element: --grow-within MAP.svg#ID", source=str(path))
            doc = SvgShapes.read(path)
            el = doc.element(ident)
            area = doc.area(el)
            brush = [shapely.buffer(shapely.linestrings(p), w / 2) for p, w in doc.strokes(el) if w > 0 and len(p) >= 2]
            shape = shapely.union_all([area, *brush])
            if shape.is_empty or shape.area <= 0:
                raise RegionError(f"--grow-within: element #{ident} has no area and no stroke width", source=str(path))
            parts.append(shape)
        within = shapely.union_all(parts)
    return Controls(flow=field, barriers=barriers, grow_within=within)
