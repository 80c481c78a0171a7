"""GIS layers through pyogrio (issue 18): layer specs, GeoPackage / Shapefile / FlatGeobuf round
trips with the CRS kept and holes respected, points defaulting to --boundary inside, symbol export
and the QGIS style, the QGIS plugin's install and its fill command."""

from __future__ import annotations

import json
import warnings
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely
from pyogrio import raw

from svgtile.apps import qgis as qg
from svgtile.apps.load import load_exemplar
from svgtile.cli.main import main
from svgtile.engines import ENGINES, engines_with, public_params
from svgtile.errors import RegionError
from svgtile.gis import geojson, layers, symbols

CRS = "EPSG:32633"
#: A unit with a hole (map frame, y up, metres) and a plain neighbour.
OUTER = shapely.box(0, 0, 80, 60)
HOLE = shapely.box(30, 20, 50, 40)
HOLED = OUTER.difference(HOLE)
NEIGHBOUR = shapely.box(80, 0, 140, 60)


def write_units(path, crs=CRS, driver=None):
    """A polygon layer ``units`` (fields unit, name) with a holed unit (fid 1 in a GeoPackage)."""
    kw = {"layer": "units"} if str(path).endswith(".gpkg") else {}
    with warnings.catch_warnings():  # pyogrio warns that a layer without a CRS has none
        warnings.simplefilter("ignore", UserWarning)
        raw.write(path, shapely.to_wkb(np.array([HOLED, NEIGHBOUR])),
                  [np.array(["Ksh", "Qal"], dtype=object), np.array(["holed", "plain"], dtype=object)],
                  ["unit", "name"], geometry_type="Polygon", crs=crs, driver=driver, **kw)  # fmt: skip
    return path


def read_points(path):
    meta, _, wkb, fields = raw.read(path, return_fids=True)
    return meta, shapely.from_wkb(wkb), dict(zip(meta["fields"], fields, strict=True))


@pytest.mark.parametrize(
    ("spec", "expected"),
    [
        ("u.gpkg", layers.Spec(layers.Path("u.gpkg"))),
        ("u.gpkg#units", layers.Spec(layers.Path("u.gpkg"), "units")),
        ("u.gpkg#units:3", layers.Spec(layers.Path("u.gpkg"), "units", 3)),
        ("u.gpkg#:3", layers.Spec(layers.Path("u.gpkg"), None, 3)),
        ("u.gpkg#units?unit='Ksh'", layers.Spec(layers.Path("u.gpkg"), "units", None, "unit='Ksh'")),
        ("u.shp#?unit = 'a#b'", layers.Spec(layers.Path("u.shp"), None, None, "unit = 'a#b'")),
        ("u.geojson#west", layers.Spec(layers.Path("u.geojson"), ident="west")),
        ("u.geojson#:0", layers.Spec(layers.Path("u.geojson"), None, 0)),
    ],
)
def test_layer_specs(spec, expected):
    assert layers.parse_spec(spec) == expected


@pytest.mark.parametrize(
    ("spec", "message"),
    [("u.gpkg#", "empty selector"), ("u.gpkg#units:x", "feature id must be an integer"),
     ("u.gpkg#units?", "empty condition"), ("u.csv", "not a GIS file")],
)  # fmt: skip
def test_bad_layer_specs(spec, message):
    with pytest.raises(RegionError, match=message):
        layers.parse_spec(spec)


@pytest.mark.parametrize("suffix", [".gpkg", ".shp", ".fgb"])
def test_region_round_trip_keeps_crs_and_respects_the_hole(tmp_path, tiny, capsys, suffix):
    units = write_units(tmp_path / f"units{suffix}")
    select = "#units?unit='Ksh'" if suffix == ".gpkg" else "#?unit='Ksh'"
    out = tmp_path / f"texture{suffix}"
    rc = main(["synth", str(tiny), "--region", f"{units}{select}", "-o", str(out), "--seed", "3", "--with-style"])
    assert rc == 0, capsys.readouterr().err
    meta, points, fields = read_points(out)
    assert meta["crs"] == CRS
    assert list(meta["fields"]) == ["kind", "angle", "scale", "size"]
    assert len(points) > 50
    assert shapely.within(points, HOLED).all()  # y up: the map frame, not the SVG one
    assert not shapely.intersects(points, HOLE).any()
    ex, _ = load_exemplar(str(tiny))
    names = [k.name for k in ex.kinds]
    assert set(fields["kind"]) <= set(names)
    assert (out.with_suffix(".qml")).is_file() and (tmp_path / "texture-symbols" / "dot.svg").is_file()


def test_points_default_to_boundary_inside(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    outs = {}
    for name, extra in (("default", []), ("inside", ["--boundary", "inside"]), ("clip", ["--boundary", "clip"])):
        out = tmp_path / f"{name}.geojson"
        assert main(["synth", str(tiny), "--region", f"{units}#units:1", "-o", str(out), "--seed", "2", *extra]) == 0
        outs[name] = json.loads(out.read_text())["features"]  # GDAL names the layer by the file
    assert outs["default"] == outs["inside"]
    assert outs["default"] != outs["clip"]
    # every motif's footprint is inside the holed unit (map frame)
    data = json.loads((tmp_path / "default.geojson").read_text())
    assert data["crs"]["properties"]["name"].endswith("32633")  # GeoJSON from a layer with a CRS carries it
    ex, _ = load_exemplar(str(tiny))
    arr = geojson.read_placements(tmp_path / "default.geojson", [k.name for k in ex.kinds])
    from svgtile.core.footprint import world_footprints

    feet = world_footprints(arr, [k.prototype for k in ex.kinds])
    assert shapely.within(feet, geojson.flip(HOLED).buffer(1e-6)).all()


def test_geojson_points_without_crs_keep_svgtiles_own_text(tmp_path, tiny, capsys):
    out = tmp_path / "t.geojson"
    assert main(["synth", str(tiny), "--size", "60x40", "-o", str(out), "--seed", "1"]) == 0
    text = out.read_text()
    assert text.startswith('{"type": "FeatureCollection", "features": [\n{"type": "Feature"')
    assert '"crs"' not in text


def test_map_from_a_geopackage_to_a_shapefile(tmp_path, tiny, write_svg, capsys):
    units = write_units(tmp_path / "units.gpkg")
    (tmp_path / "styles.toml").write_text(
        'class_property = "unit"\nseed = 4\n[classes.Ksh]\nexemplar = "tiny.svg"\n[classes.Qal]\nexemplar = "tiny.svg"\ngrid = "hex"\n')
    out = tmp_path / "filled.shp"
    rc = main(["map", str(units), "--styles", str(tmp_path / "styles.toml"), "-o", str(out), "--jobs", "1", "--with-style"])
    assert rc == 0, capsys.readouterr().err
    meta, points, fields = read_points(out)
    assert meta["crs"] == CRS and list(meta["fields"]) == ["kind", "angle", "scale", "size", "region", "class"]
    ksh = fields["class"] == "Ksh"
    assert set(fields["region"][ksh]) == {"1"} and set(fields["region"][~ksh]) == {"2"}
    assert shapely.within(points[ksh], HOLED).all() and shapely.within(points[~ksh], NEIGHBOUR).all()
    assert (tmp_path / "filled-symbols" / "Ksh" / "dot.svg").is_file()
    assert '&quot;class&quot;' in (tmp_path / "filled.qml").read_text()


def test_geojson_has_a_crs_only_when_it_names_one(tmp_path, tiny, capsys):
    named = write_units(tmp_path / "named.geojson", driver="GeoJSON")  # GDAL writes a crs member
    assert '"crs"' in named.read_text() and layers.crs_of(named) == CRS
    plain = tmp_path / "plain.geojson"
    plain.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "id": "a", "properties": {}, "geometry": json.loads(shapely.to_geojson(OUTER))}]}))  # fmt: skip
    assert layers.crs_of(plain) is None and layers.crs_of(f"{plain}#a") is None
    out = tmp_path / "t.gpkg"
    assert main(["synth", str(tiny), "--region", f"{plain}#:0", "-o", str(out), "--seed", "1"]) == 0
    assert read_points(out)[0]["crs"] is None  # OGR would say WGS 84; svgtile does not guess
    assert main(["synth", str(tiny), "--region", f"{named}#:0", "-o", str(out), "--seed", "1"]) == 0
    assert read_points(out)[0]["crs"] == CRS


def test_an_input_without_crs_gives_an_output_without_crs(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg", crs=None)
    out = tmp_path / "t.gpkg"
    assert main(["synth", str(tiny), "--region", f"{units}#units:2", "-o", str(out), "--seed", "1"]) == 0
    assert read_points(out)[0]["crs"] is None


@pytest.mark.parametrize(
    ("select", "message"),
    [("#nolayer", "no layer 'nolayer' (the file has units)"), ("#units:9", "no feature with id 9"),
     ("#units?nofield=1", "cannot read"), ("#units?unit='none'", "no feature where unit='none'")],
)  # fmt: skip
def test_bad_layer_input_is_one_line_and_no_output(tmp_path, tiny, capsys, select, message):
    units = write_units(tmp_path / "units.gpkg")
    out = tmp_path / "t.gpkg"
    rc = main(["synth", str(tiny), "--region", f"{units}{select}", "-o", str(out), "--seed", "1"])
    err = capsys.readouterr().err
    assert rc == 1 and err.count("\n") == 1 and message in err and str(units) in err
    assert not out.exists()


def test_an_avoid_layer_in_another_crs_is_refused(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    other = write_units(tmp_path / "other.gpkg", crs="EPSG:4326")
    out = tmp_path / "t.svg"
    rc = main(["synth", str(tiny), "--region", f"{units}#units:1", "--avoid", f"{other}#units:2", "-o", str(out), "--seed", "1"])
    err = capsys.readouterr().err
    assert rc == 1 and "its CRS (EPSG:4326) is not the layer's (EPSG:32633); reproject it first" in err and not out.exists()


def test_map_points_default_to_inside_unless_the_styles_say(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    base = 'class_property = "unit"\nseed = 4\n[classes.Ksh]\nexemplar = "tiny.svg"\n'
    found = {}
    for name, extra in (("default", ""), ("inside", 'boundary = "inside"\n'), ("clip", 'boundary = "clip"\n')):
        (tmp_path / f"{name}.toml").write_text(base + extra)
        out = tmp_path / f"{name}.fgb"
        assert main(["map", str(units), "--styles", str(tmp_path / f"{name}.toml"), "-o", str(out), "--jobs", "1"]) == 0
        _, points, fields = read_points(out)
        found[name] = (shapely.get_coordinates(points).tolist(), fields["kind"].tolist())
    assert found["default"] == found["inside"] != found["clip"]


def test_the_region_file_is_never_overwritten(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    before = units.read_bytes()
    rc = main(["synth", str(tiny), "--region", f"{units}#units:1", "-o", str(units), "--seed", "1"])
    assert rc == 1 and "refusing to overwrite an input file" in capsys.readouterr().err
    assert units.read_bytes() == before


@pytest.mark.parametrize(("name", "message"), [("bad.gpkg", "not recognized as being in a supported file format"),
                                                ("none.shp", "no such file")])  # fmt: skip
def test_an_unreadable_layer_file_is_one_line(tmp_path, tiny, capsys, name, message):
    if name.startswith("bad"):
        (tmp_path / name).write_text("garbage")
    rc = main(["synth", str(tiny), "--region", str(tmp_path / name), "-o", str(tmp_path / "t.gpkg"), "--seed", "1"])
    err = capsys.readouterr().err
    assert rc == 1 and err.count("\n") == 1 and message in err and "It might help" not in err


def test_with_style_needs_a_gis_output(tmp_path, tiny, capsys):
    assert main(["synth", str(tiny), "--size", "20", "-o", str(tmp_path / "t.svg"), "--with-style"]) == 1
    assert "--with-style goes with a GIS output" in capsys.readouterr().err


# ----------------------------------------------------------------------------- symbols


def test_symbols_are_square_pages_centred_on_the_anchor(tmp_path, tiny, capsys):
    folder = tmp_path / "sym"
    assert main(["symbols", str(tiny), "-o", str(folder)]) == 0
    ex, _ = load_exemplar(str(tiny))
    for kind in ex.kinds:
        root = ET.parse(folder / f"{kind.name}.svg").getroot()
        x, y, w, h = (float(v) for v in root.get("viewBox").split())
        assert w == h == pytest.approx(2 * kind.prototype.radius, abs=1e-4)
        assert x == y == pytest.approx(-kind.prototype.radius, abs=1e-4)
        assert not root.findall(".//{http://www.w3.org/2000/svg}symbol")  # Qt draws no <symbol>
        use = root.find("{http://www.w3.org/2000/svg}use")
        assert use.get("{http://www.w3.org/1999/xlink}href") == f"#{kind.href}"
    # bar is drawn away from its origin: its use carries the offset to the footprint centroid
    assert "translate(0 0) translate(" in (folder / "bar.svg").read_text()
    style = ET.parse(folder / "svgtile.qml").getroot()
    layer = style.find(".//layer")
    assert layer.get("class") == "SvgMarker"
    props = {o.get("name"): o for o in layer.find("data_defined_properties").iter("Option") if o.get("type") == "Map"}
    expr = props["name"].find("Option[@name='expression']").get("value")
    assert expr.startswith(f"'{folder.resolve()}/'") and '"kind"' in expr
    assert props["size"].find("Option[@name='field']").get("value") == "size"
    assert props["angle"].find("Option[@name='field']").get("value") == "angle"
    assert layer.find("Option/Option[@name='size_unit']").get("value") == "MapUnit"


@pytest.mark.parametrize("name", ["tiny", "viewbox", "plain"])
def test_each_symbol_file_draws_its_kind_centred_on_the_anchor(tmp_path, write_svg, name):
    """Read back by svgtile itself, each symbol file is one motif of the same shape, at the origin."""
    from conftest import EXEMPLARS

    ex, _ = load_exemplar(str(write_svg(EXEMPLARS[name], f"{name}.svg")))
    docs = symbols.symbol_documents(ex)
    assert len(docs) == len(ex.kinds)
    for (file, text), kind in zip(docs.items(), ex.kinds, strict=True):
        back, _ = load_exemplar(str(write_svg(text, file)))
        assert len(back.motifs) == 1
        assert np.allclose(back.motifs.xy[0], 0, atol=2e-3)  # the anchor is the page's centre
        assert back.kinds[0].footprint.area == pytest.approx(kind.footprint.area, rel=2e-3)


# ----------------------------------------------------------------------------- QGIS plugin


def test_qgis_install_records_python_and_every_engine_parameter(tmp_path, capsys):
    profile = tmp_path / "profile"
    (profile / "QGIS").mkdir(parents=True)
    (profile / "QGIS" / "QGIS3.ini").write_text("[General]\nx=1\n\n[PythonPlugins]\nother=true\n")
    assert main(["qgis", "install", "--profile", str(profile)]) == 0
    target = profile / "python" / "plugins" / "svgtile_qgis"
    assert {p.name for p in target.iterdir()} >= {*qg.PLUGIN_FILES, qg.CONFIG_NAME}
    config = json.loads((target / qg.CONFIG_NAME).read_text())
    # every engine but those of cells (cellular: the plugin writes points), and their parameters
    cells = {n for n, e in ENGINES.items() if hasattr(e, "place_cells")}
    assert cells and set(config["engines"]) == set(ENGINES) - cells
    assert [p["name"] for p in config["params"]] == [n for n in public_params() if set(engines_with(n)) - cells]
    assert "tree" not in [p["name"] for p in config["params"]]
    assert "patch" in config["engines"] and "inside" in config["boundary_modes"]
    ini = (profile / "QGIS" / "QGIS3.ini").read_text()
    assert "x=1" in ini and "other=true" in ini and "svgtile_qgis=true" in ini
    assert main(["qgis", "install", "--profile", str(profile)]) == 0  # again: an update
    assert (profile / "QGIS" / "QGIS3.ini").read_text().count("svgtile_qgis=true") == 1
    assert main(["qgis", "uninstall", "--profile", str(profile)]) == 0 and not target.exists()
    assert main(["qgis", "uninstall", "--profile", str(profile)]) == 1


def test_qgis_plugin_imports_no_scientific_python():
    """The plugin runs in QGIS's Python: it may import QGIS and the standard library only."""
    import ast

    for path in qg.plugin_source().glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] if isinstance(node, ast.ImportFrom) and node.level == 0 else []  # fmt: skip
            for name in names:
                assert name.split(".")[0] in {"qgis", "json", "os", "subprocess", "time"}, (path.name, name)


def test_qgis_fill_by_class_and_avoid_crs_check(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    out = tmp_path / "f.gpkg"
    rc = main(["qgis", "fill", str(units), "--exemplar", str(tiny), "--class-field", "unit", "--seed", "1",
               "-o", str(out), "--with-style", "--jobs", "1", "--grid", "hex"])  # fmt: skip
    assert rc == 0, capsys.readouterr().err
    _, points, fields = read_points(out)
    assert set(fields["class"]) == {"Ksh", "Qal"}
    assert shapely.within(points[fields["class"] == "Ksh"], HOLED).all()
    other = write_units(tmp_path / "other.gpkg", crs="EPSG:4326")
    rc = main(["qgis", "fill", str(units), "--exemplar", str(tiny), "--seed", "1", "-o", str(tmp_path / "g.gpkg"),
               "--avoid", f"{other}#units:2"])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 1 and "is not the layer's" in err and "reproject" in err and not (tmp_path / "g.gpkg").exists()
    rc = main(["qgis", "fill", str(units), "--styles", str(tmp_path / "s.toml"), "--seed", "1", "-o", str(out)])
    assert rc == 1 and "needs --class-field" in capsys.readouterr().err


@pytest.mark.parametrize("command", ["map", "qgis"])
def test_an_avoid_layer_is_never_overwritten(tmp_path, tiny, capsys, command):
    units = write_units(tmp_path / "units.gpkg")
    roads = tmp_path / "roads.gpkg"
    raw.write(roads, shapely.to_wkb(np.array([shapely.LineString([(90, 5), (130, 55)])])), [], [], layer="roads",
              geometry_type="LineString", crs=CRS)  # fmt: skip
    before = roads.read_bytes()
    (tmp_path / "s.toml").write_text('class_property = "unit"\nseed = 4\n[classes.Qal]\nexemplar = "tiny.svg"\n')
    args = (["map", str(units), "--styles", str(tmp_path / "s.toml")] if command == "map"
            else ["qgis", "fill", str(units), "--exemplar", str(tiny), "--seed", "1"])  # fmt: skip
    rc = main([*args, "--avoid", f"{roads}#roads", "-o", str(roads), "--jobs", "1"])
    err = capsys.readouterr().err
    assert rc == 1 and err.count("\n") == 1 and "refusing to overwrite an input file" in err
    assert roads.read_bytes() == before


def test_an_avoid_layer_in_another_crs_is_refused_before_it_cuts_the_region(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    other = write_units(tmp_path / "other.gpkg", crs="EPSG:4326")  # its unit 1 covers the region in numbers
    out = tmp_path / "t.gpkg"
    rc = main(["synth", str(tiny), "--region", f"{units}#units:1", "--avoid", f"{other}#units:1", "-o", str(out), "--seed", "1"])
    err = capsys.readouterr().err
    assert rc == 1 and "its CRS (EPSG:4326) is not the layer's (EPSG:32633)" in err and not out.exists()


def test_symbols_never_overwrite_the_exemplar(tmp_path, tiny, capsys):
    exemplar = tmp_path / "dot.svg"  # holds a kind "dot": FOLDER/dot.svg would be the exemplar itself
    exemplar.write_bytes(tiny.read_bytes())
    before = exemplar.read_bytes()
    rc = main(["symbols", str(exemplar), "-o", str(tmp_path)])
    err = capsys.readouterr().err
    assert rc == 1 and err.count("\n") == 1 and "refusing to overwrite an input file" in err
    assert exemplar.read_bytes() == before and not (tmp_path / "bar.svg").exists()


@pytest.mark.parametrize("blocker", ["t.qml/", "t-symbols"])
def test_a_style_that_cannot_be_written_stops_before_the_layer(tmp_path, tiny, capsys, blocker):
    """--with-style: OUT.qml a folder or OUT-symbols a file is one line, and no layer is written."""
    units = write_units(tmp_path / "units.gpkg")
    (tmp_path / blocker.rstrip("/")).mkdir() if blocker.endswith("/") else (tmp_path / blocker).write_text("")
    out = tmp_path / "t.gpkg"
    for args in (["synth", str(tiny), "--region", f"{units}#units:1", "--seed", "1"],
                 ["qgis", "fill", str(units), "--exemplar", str(tiny), "--seed", "1", "--jobs", "1"]):  # fmt: skip
        rc = main([*args, "-o", str(out), "--with-style"])
        err = capsys.readouterr().err
        assert rc == 1 and err.count("\n") == 1 and blocker.rstrip("/") in err
        assert not out.exists()


def test_qgis_install_keeps_a_latin1_ini_byte_for_byte(tmp_path, capsys):
    profile = tmp_path / "profile"
    (profile / "QGIS").mkdir(parents=True)
    before = b"[General]\nname=caf\xe9\n\n[PythonPlugins]\nother=true\n"  # not UTF-8
    (profile / "QGIS" / "QGIS3.ini").write_bytes(before)
    assert main(["qgis", "install", "--profile", str(profile)]) == 0, capsys.readouterr().err
    after = (profile / "QGIS" / "QGIS3.ini").read_bytes()
    assert after == before.replace(b"[PythonPlugins]\n", b"[PythonPlugins]\nsvgtile_qgis=true\n")


def test_kinds_sharing_a_symbol_file_name_are_refused(tmp_path, tiny, capsys):
    """QGIS's style finds a kind's file by its name: 'a b' and 'a-b' cannot both be a-b.svg."""
    text = tiny.read_text().replace('"dot"', '"a b"').replace('"#dot"', '"#a b"').replace('"bar"', '"a-b"')
    exemplar = tmp_path / "clash.svg"
    exemplar.write_text(text.replace('"#bar"', '"#a-b"'))
    rc = main(["symbols", str(exemplar), "-o", str(tmp_path / "symbols")])
    err = capsys.readouterr().err
    assert rc == 1 and err.count("\n") == 1 and "would share the symbol file a-b.svg" in err
    assert not (tmp_path / "symbols").exists() or not any((tmp_path / "symbols").iterdir())


def test_qgis_fill_says_a_tables_avoid_is_not_used(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    (tmp_path / "s.toml").write_text('avoid = ["labels"]\n[classes.Qal]\nexemplar = "tiny.svg"\n')
    rc = main(["qgis", "fill", str(units), "--styles", str(tmp_path / "s.toml"), "--class-field", "unit",
               "--seed", "1", "-o", str(tmp_path / "f.gpkg"), "--jobs", "1"])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 0 and "avoid = ['labels'] is not used here; give those layers as --avoid" in err


def test_a_replaced_shapefile_loses_its_stale_spatial_index(tmp_path, tiny, capsys):
    units = write_units(tmp_path / "units.gpkg")
    out = tmp_path / "t.shp"
    assert main(["synth", str(tiny), "--region", f"{units}#units:1", "-o", str(out), "--seed", "1"]) == 0
    (tmp_path / "t.qix").write_bytes(b"an index of the old points")  # QGIS: Create Spatial Index
    assert main(["synth", str(tiny), "--region", f"{units}#units:2", "-o", str(out), "--seed", "1"]) == 0
    assert not (tmp_path / "t.qix").exists()
    _, points, _ = read_points(out)
    assert shapely.within(points, NEIGHBOUR).all()
