"""``svgtile map`` with cellular classes (issue 15): a limestone unit filled with cells beside a
scatter unit, through the map writers (SVG, GeoJSON), a clear refusal for point layers, and edges
labelled by the map's own lines."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import TINY
from test_cellular_import import bricks

from svgtile.apps.mapfill import fill_map, parse_styles, read_styles
from svgtile.cli.main import main
from svgtile.core.footprint import world_footprints
from svgtile.errors import ParameterError
from svgtile.svg.dialect import SVG_NS
from svgtile.svg.reader import read_exemplar
from svgtile.tiles.importer import import_tile

#: An L-shaped limestone unit with a hole, a scatter unit in its bend, a fault between them.
MAP = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 200">
  <path id="ls" class="limestone" fill="#eef" fill-rule="evenodd" d="M0 0 H200 V80 H90 V200 H0 Z M30 30 H60 V60 H30 Z"/>
  <path id="sc" class="dots" fill="#efe" d="M200 0 H300 V200 H90 V80 H200 Z"/>
  <path id="faults" d="M90 80 L200 80" stroke="#f00" fill="none"/>
</svg>
"""
LS = shapely.Polygon([(0, 0), (200, 0), (200, 80), (90, 80), (90, 200), (0, 200)], [[(30, 30), (60, 30), (60, 60), (30, 60)]])
SC = shapely.Polygon([(200, 0), (300, 0), (300, 200), (90, 200), (90, 80), (200, 80)])
#: No engine named for limestone: its exemplar (an imported brick tile) is cellular.
STYLES = """seed = 4
boundary = "inside"
[classes.limestone]
exemplar = "limestone.svg"
[classes.dots]
exemplar = "tiny.svg"
"""
RED = "fill:none;stroke:#ff0000;stroke-width:0.6"
#: Bricks 10 x 20 whose edges along a fault are red blocks (legakis2001 §4.1: routing by label).
TREE = {"course": 10, "length": 20, "offset": 0.5, "cell_style": "fill:none;stroke:#000;stroke-width:0.3",
        "tree": [{"feature": "edge", "label": "fault", "generator": "edge_blocks", "style": RED},
                 {"feature": "corner", "generator": "corner"},
                 {"feature": "edge", "generator": "edge_bricks"},
                 {"feature": "face", "generator": "bricks"}]}  # fmt: skip


@pytest.fixture
def folder(tmp_path) -> Path:
    (tmp_path / "tile.svg").write_text(bricks())
    (tmp_path / "limestone.svg").write_text(import_tile(tmp_path / "tile.svg").text)
    (tmp_path / "tiny.svg").write_text(TINY)
    (tmp_path / "map.svg").write_text(MAP)
    (tmp_path / "styles.toml").write_text(STYLES)
    (tmp_path / "tree.json").write_text(json.dumps(TREE))
    return tmp_path


def cli(folder: Path, out: str, *extra: str, styles: str = "styles.toml") -> int:
    return main(["map", str(folder / "map.svg"), "--styles", str(folder / styles), "-o", str(folder / out),
                 "--jobs", "1", *extra])  # fmt: skip


def test_a_cellular_exemplar_makes_its_class_cellular(folder):
    styles = read_styles(folder / "styles.toml")
    assert styles.classes["limestone"].engine == "cellular"
    assert styles.classes["dots"].engine == "patch"


def test_cells_fill_the_limestone_unit_only_and_never_overlap(folder):
    result = fill_map(folder / "map.svg", read_styles(folder / "styles.toml"), seed=4, jobs=1)
    assert not result.errors and result.filled == [True, True]
    (ls, sc), cells = result.regions, result.cells
    assert (ls.ident, sc.ident) == ("ls", "sc") and cells[1] is None
    polys = cells[0].cells
    assert len(polys) > 100
    assert shapely.covered_by(polys, shapely.buffer(LS, 1e-6)).all()  # in the unit, none cut (inside mode)
    assert shapely.area(shapely.intersection(polys, SC)).max() < 1e-9
    tree = shapely.STRtree(polys)
    i, j = tree.query(polys, predicate="intersects")
    pair = i < j
    assert shapely.area(shapely.intersection(polys[i[pair]], polys[j[pair]])).max() < 1e-9
    # the scatter unit is filled with its motifs, and the brick tile has none to set in cells
    assert len(result.results[0]) == 0 and len(result.results[1]) > 50
    ex = read_exemplar(folder / "tiny.svg")
    assert shapely.covered_by(world_footprints(result.results[1], ex.prototypes), shapely.buffer(SC, 1e-6)).all()


def paths_and_uses(svg: Path) -> dict[str, tuple[int, int]]:
    """Texture group id -> (cell paths, uses) in it."""
    root = ET.parse(svg).getroot()
    out = {}
    for g in root.iter(f"{{{SVG_NS}}}g"):
        if g.get("data-svgtile-class"):
            out[g.get("id")] = (len(g.findall(f".//{{{SVG_NS}}}path")), len(g.findall(f".//{{{SVG_NS}}}use")))
    return out


def test_the_map_svg_draws_cells_in_the_limestone_group(folder, capsys):
    assert cli(folder, "filled.svg") == 0, capsys.readouterr().err
    counts = paths_and_uses(folder / "filled.svg")
    assert counts["svgtile-ls"][0] > 100 and counts["svgtile-ls"][1] == 0
    assert counts["svgtile-sc"][0] == 0 and counts["svgtile-sc"][1] > 50
    text = (folder / "filled.svg").read_text()
    assert 'class="svgtile-face"' in text and 'class="svgtile-line"' in text
    # in parallel, and cut into tiles (a cellular unit is run whole), the same bytes
    assert cli(folder, "again.svg", "--tile-size", "50") == 0
    assert (folder / "again.svg").read_bytes() == (folder / "filled.svg").read_bytes()
    assert main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o",
                 str(folder / "par.svg"), "--jobs", "2"]) == 0  # fmt: skip
    assert (folder / "par.svg").read_bytes() == (folder / "filled.svg").read_bytes()


def test_the_map_geojson_has_cell_polygons_and_motif_points(folder, capsys):
    assert cli(folder, "filled.geojson") == 0, capsys.readouterr().err
    feats = json.loads((folder / "filled.geojson").read_text())["features"]
    kinds = {}
    for f in feats:
        kinds.setdefault(f["properties"]["region"], set()).add(f["geometry"]["type"])
    assert kinds["sc"] == {"Point"} and "Polygon" in kinds["ls"]
    assert kinds["ls"] <= {"Polygon", "LineString", "MultiLineString"} and len(kinds["ls"]) >= 2  # cells, joints
    polys = shapely.from_geojson([json.dumps(f["geometry"]) for f in feats if f["geometry"]["type"] == "Polygon"])
    flipped = shapely.transform(LS, lambda c: c * np.array([1.0, -1.0]))  # GeoJSON: y up
    assert shapely.covered_by(polys, shapely.buffer(flipped, 1e-3)).all()


@pytest.mark.parametrize("out", ["filled.gpkg", "filled.fgb"])
def test_a_point_layer_refuses_a_cellular_class_by_name(folder, capsys, out):
    assert cli(folder, out) != 0
    err = capsys.readouterr().err
    assert "class 'limestone' is cellular" in err and len(err.strip().splitlines()) == 1
    assert not (folder / out).exists()


def red_cells(folder: Path, styles: str) -> tuple[np.ndarray, float]:
    """The red shapes of the limestone unit, map units, and the class's unit."""
    styles = read_styles(folder / styles)
    result = fill_map(folder / "map.svg", styles, seed=4, jobs=1)
    assert not result.errors, result.errors
    cells, unit = result.cells[0], styles.classes["limestone"].unit
    if RED not in cells.styles:
        return np.empty(0, dtype=object), unit
    shapes = cells.shapes[cells.style == cells.styles.index(RED)]
    return shapely.transform(shapes, lambda c: c * unit), unit


@pytest.mark.parametrize("unit", [1, 2])
def test_the_maps_own_fault_line_routes_its_edge_to_its_own_generator(folder, unit):
    base = 'exemplar = "limestone.svg"\ntree = "tree.json"\n'
    (folder / "plain.toml").write_text(STYLES.replace('exemplar = "limestone.svg"\n', base + f"unit = {unit}\n"))
    (folder / "fault.toml").write_text(STYLES.replace('exemplar = "limestone.svg"\n',
                                                      base + f'unit = {unit}\nlabel = "fault=#faults"\n'))  # fmt: skip
    assert len(red_cells(folder, "plain.toml")[0]) == 0
    red, unit = red_cells(folder, "fault.toml")
    assert len(red) > 0
    fault = shapely.LineString([(90, 80), (200, 80)])
    course = TREE["course"] * unit  # the red blocks lie in the course along the fault …
    assert shapely.covered_by(red, shapely.buffer(fault, course + 1e-6)).all()
    x0, _, x1, _ = shapely.union_all(red).bounds  # … and line it (between the corner cells)
    assert x1 - x0 > 0.6 * fault.length


def test_a_label_in_the_styles_file_is_checked_and_resolved(folder):
    with pytest.raises(ParameterError, match=r"classes\.limestone: label 'fault'"):
        parse_styles({"classes": {"limestone": {"exemplar": "x.svg", "engine": "cellular", "label": "fault"}}})
    styles = parse_styles({"classes": {"limestone": {"exemplar": "x.svg", "engine": "cellular", "tree": "t.json",
                                                     "label": "fault=#faults,coast=lines.svg#coast"}}},
                          folder=folder)  # fmt: skip
    params = styles.classes["limestone"].params
    assert params["label"] == f"fault=#faults,coast={folder / 'lines.svg'}#coast"
    assert params["tree"] == str(folder / "t.json")


def test_the_qgis_provider_refuses_a_cellular_class_by_name(folder):
    from svgtile.apps.qgis import fill

    (folder / "units.geojson").write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"class": "limestone"},
         "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [50, 0], [50, 50], [0, 50], [0, 0]]]}}]}))  # fmt: skip
    with pytest.raises(ParameterError, match="class 'limestone' is cellular"):
        fill(str(folder / "units.geojson"), exemplar=None, styles_file=str(folder / "styles.toml"), class_field="class",
             engine="patch", params={}, boundary="inside", unit=1.0, seed=1)  # fmt: skip
