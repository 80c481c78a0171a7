"""GeoJSON in and out: polygon regions (y up), placements as points, round trips, errors."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import TINY, arrange

from svgtile.apps.mapread import read_region_shape
from svgtile.cli.main import main
from svgtile.core.region import Region
from svgtile.errors import RegionError
from svgtile.gis import geojson
from svgtile.svg.reader import parse_exemplar, read_exemplar

SQUARE_WITH_HOLE = {
    "type": "Polygon",
    "coordinates": [[[0, 0], [60, 0], [60, 50], [0, 50], [0, 0]], [[20, 20], [40, 20], [40, 30], [20, 30], [20, 20]]],
}
TWO_PARTS = {
    "type": "MultiPolygon",
    "coordinates": [[[[100, 0], [130, 0], [130, 30], [100, 30], [100, 0]]], [[[140, 0], [150, 0], [150, 10], [140, 10], [140, 0]]]],
}


def collection(*features) -> dict:
    return {"type": "FeatureCollection", "features": list(features)}


def feature(geometry, ident=None, **props) -> dict:
    f = {"type": "Feature", "geometry": geometry, "properties": props}
    if ident is not None:
        f["id"] = ident
    return f


@pytest.fixture
def units(tmp_path) -> Path:
    path = tmp_path / "units.geojson"
    data = collection(
        feature(SQUARE_WITH_HOLE, "a", unit="Qal"),
        feature(TWO_PARTS, "b", unit="Ksh"),
        feature({"type": "LineString", "coordinates": [[0, 0], [5, 5]]}, "fault"),
    )
    path.write_text(json.dumps(data))
    return path


def test_regions_are_read_with_holes_parts_and_y_flipped(units):
    feats = geojson.read_regions(units, class_property="unit")
    assert [(f.ident, f.cls) for f in feats] == [("a", "Qal"), ("b", "Ksh")]  # the line is skipped
    a, b = feats
    assert a.shape.area == pytest.approx(60 * 50 - 20 * 10)
    assert a.shape.bounds == pytest.approx((0, -50, 60, 0))  # y up -> y down
    assert b.shape.geom_type == "MultiPolygon" and b.shape.area == pytest.approx(1000)


def test_region_spec_picks_one_feature_or_merges_all(units):
    assert read_region_shape(f"{units}#b").area == pytest.approx(1000)
    assert read_region_shape(str(units)).area == pytest.approx(2800 + 1000)


@pytest.mark.parametrize(
    ("text", "spec", "message"),
    [
        ("{not json", "", "not valid JSON"),
        ("[1, 2]", "", "not a GeoJSON object"),
        ("[" * 100_000 + "]" * 100_000, "", "nested too deeply"),
        (json.dumps(collection(feature({"type": "Point", "coordinates": [1, 2]}))), "", "no Polygon or MultiPolygon"),
        (json.dumps(collection(feature(SQUARE_WITH_HOLE, "a"))), "#zz", "no feature with id 'zz'"),
        (json.dumps(collection(feature({"type": "Point", "coordinates": [1, 2]}, "p"))), "#p", "not a Polygon"),
        (json.dumps(collection(feature({"type": "Polygon", "coordinates": [[1]]}, "x"))), "", "unreadable geometry"),
    ],
)
def test_bad_geojson_is_one_line_naming_the_file(tmp_path, text, spec, message):
    path = tmp_path / "bad.geojson"
    path.write_text(text)
    with pytest.raises(RegionError) as info:
        read_region_shape(f"{path}{spec}")
    assert message in str(info.value) and str(path) in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("unit", [1.0, 2.5])
def test_placements_round_trip(tmp_path, unit):
    ex = parse_exemplar(TINY)
    region = Region.from_geometry(shapely.box(0, 0, 50, 40))
    arr = arrange("patch", ex, region, rng=np.random.default_rng(2), vary_orientation=True)
    names = [k.name for k in ex.kinds]
    radius = np.array([k.prototype.radius for k in ex.kinds])
    path = tmp_path / "texture.geojson"
    path.write_text(geojson.placements_text(geojson.placements(arr, names, radius, unit=unit)))
    data = json.loads(path.read_text())
    assert len(data["features"]) == len(arr) > 10
    first = data["features"][0]
    assert first["geometry"]["type"] == "Point"
    assert set(first["properties"]) == {"kind", "angle", "scale", "size"}
    back = geojson.read_placements(path, names, unit=unit)
    assert (back.kind == arr.kind).all()
    assert np.allclose(back.xy, arr.xy, atol=1e-5)
    assert np.allclose(back.angle, arr.angle, atol=1e-4)
    assert np.allclose(back.scale, arr.scale, atol=1e-4)
    # y is up in GeoJSON, and the size covers the motif at any rotation
    assert np.allclose([f["geometry"]["coordinates"][1] for f in data["features"]], -arr.xy[:, 1] * unit, atol=1e-5)
    assert np.allclose([f["properties"]["size"] for f in data["features"]], 2 * radius[arr.kind] * arr.scale * unit, atol=1e-4)


def test_synth_from_geojson_region_to_geojson_points(tmp_path, units, capsys, write_svg):
    exemplar = write_svg(TINY, "tiny.svg")
    out = tmp_path / "texture.geojson"
    rc = main(["synth", str(exemplar), "--region", f"{units}#a", "-o", str(out), "--seed", "4", "--boundary", "inside"])
    assert rc == 0, capsys.readouterr().err
    ex = read_exemplar(exemplar)
    arr = geojson.read_placements(out, [k.name for k in ex.kinds])
    assert len(arr) > 10
    # points are in the map's own frame: inside feature "a", none in its hole
    pts = shapely.points(arr.xy * np.array([1.0, -1.0]))
    polygon = shapely.from_geojson(json.dumps(SQUARE_WITH_HOLE))
    assert shapely.contains(polygon, pts).all()
    # the same run as SVG draws the same motifs
    svg = tmp_path / "texture.svg"
    assert main(["synth", str(exemplar), "--region", f"{units}#a", "-o", str(svg), "--seed", "4", "--boundary", "inside"]) == 0
    assert svg.read_text().count("<use ") == len(arr)


def test_bad_placements_file(tmp_path):
    path = tmp_path / "p.geojson"
    path.write_text(json.dumps(collection(feature({"type": "Point", "coordinates": [0, 0]}, "m", kind="dot"))))
    with pytest.raises(RegionError, match="not a placement"):
        geojson.read_placements(path, ["dot"])
