"""``svgtile map``: every classed unit filled with its own style, failures isolated, GeoJSON maps."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import shapely
from conftest import PLAIN, TINY, VIEWBOX

from svgtile.apps.mapfill import fill_map, parse_styles, read_styles
from svgtile.cli.main import main
from svgtile.core.footprint import world_footprints
from svgtile.errors import ParameterError
from svgtile.svg.dialect import SVG_NS
from svgtile.svg.mapdoc import SvgShapes
from svgtile.svg.reader import read_exemplar

REPO = Path(__file__).parents[1]

MAP = """<?xml version="1.0"?>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
     xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd" viewBox="0 0 120 80">
  <!-- a comment that must survive -->
  <sodipodi:namedview id="view"/>
  <path id="u1" class="dots" fill="#eee" fill-rule="evenodd" d="M0 0 H60 V80 H0 Z M15 25 H45 V55 H15 Z"/>
  <g transform="translate(60 0)">
    <path id="u2" inkscape:label="plain" fill="#ddd" d="M0 0 H60 V40 H0 Z"/>
  </g>
  <path id="u3" data-unit="rings" class="ignored" d="M60 40 H120 V80 H60 Z"/>
  <g id="labels"><text x="90" y="62" font-size="8" text-anchor="middle">Ring</text></g>
</svg>
"""

STYLES = """
seed = 3
class_attribute = "data-unit"
avoid = ["labels"]
avoid_margin = 1

[classes.dots]
exemplar = "tiny.svg"
boundary = "inside"

[classes.plain]
exemplar = "plain.svg"
engine = "random"

[classes.rings]
exemplar = "viewbox.svg"
grid = "hex"
"""


@pytest.fixture
def folder(tmp_path) -> Path:
    for name, text in (("tiny.svg", TINY), ("plain.svg", PLAIN), ("viewbox.svg", VIEWBOX),
                       ("map.svg", MAP), ("styles.toml", STYLES)):  # fmt: skip
        (tmp_path / name).write_text(text)
    return tmp_path


def groups(path: Path) -> dict[str, ET.Element]:
    root = ET.parse(path).getroot()
    return {g.get("id"): g for g in root.iter(f"{{{SVG_NS}}}g") if g.get("data-svgtile-class")}


def hrefs(group: ET.Element) -> set[str]:
    return {u.get("{http://www.w3.org/1999/xlink}href") for u in group}


def test_every_region_filled_with_its_own_style(folder):
    styles = read_styles(folder / "styles.toml")
    result = fill_map(folder / "map.svg", styles, seed=3, jobs=1)
    assert [(r.ident, r.cls) for r in result.regions] == [("u1", "dots"), ("u2", "plain"), ("u3", "rings")]
    assert not result.errors
    doc = SvgShapes.read(folder / "map.svg")
    labels = doc.keep_clear(doc.element("labels"), 1.0)
    for region, arr in zip(result.regions, result.results, strict=True):
        ex = read_exemplar(styles.classes[region.cls].exemplar)
        assert len(arr) > 5
        assert arr.kind.max() < len(ex.kinds)
        fp = world_footprints(arr, ex.prototypes)
        assert shapely.intersects(region.shape, fp).all()  # every motif belongs to its region
        assert not shapely.intersects(labels, fp).any()
        if region.cls == "dots":  # boundary "inside": whole motifs only, none in the hole
            assert shapely.contains(region.shape, fp).all()
            assert not shapely.intersects(shapely.box(15, 25, 45, 55).buffer(-1e-6), fp).any()
    u2 = result.regions[1]
    assert u2.shape.bounds == pytest.approx((60, 0, 120, 40))  # the group's translate applied


def test_map_cli_writes_one_texture_group_per_region(folder, capsys):
    out = folder / "filled.svg"
    rc = main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out), "--seed", "3"])
    assert rc == 0, capsys.readouterr().err
    text = out.read_text()
    assert "a comment that must survive" in text and "<sodipodi:namedview" in text
    g = groups(out)
    assert set(g) == {"svgtile-u1", "svgtile-u2", "svgtile-u3"}
    # each group uses only its own style's symbols, and no other group uses them
    prefixes = {"svgtile-u1": "#svgtile-dots-", "svgtile-u2": "#svgtile-plain-", "svgtile-u3": "#svgtile-rings-"}
    for ident, group in g.items():
        refs = hrefs(group)
        assert refs and all(r.startswith(prefixes[ident]) for r in refs), (ident, refs)
    # every referenced symbol is defined once
    ids = re.findall(r'\sid="([^"]+)"', text)
    assert len(ids) == len(set(ids))
    assert all(ref[1:] in ids for group in g.values() for ref in hrefs(group))
    # the texture of u2 undoes its parent's translate, and sits right after its unit
    root = ET.parse(out).getroot()
    parent = next(p for p in root.iter() if any(c.get("id") == "u2" for c in p))
    children = [c.get("id") for c in parent]
    assert children[children.index("u2") + 1] == "svgtile-u2"
    assert g["svgtile-u2"].get("transform") == "matrix(1 0 0 1 -60 0)"
    # the input is unchanged
    assert (folder / "map.svg").read_text() == MAP


def test_parallel_and_serial_runs_give_the_same_bytes(folder, capsys):
    outs = []
    for jobs in ("1", "2"):
        out = folder / f"filled-{jobs}.svg"
        assert main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out),
                     "--seed", "3", "--jobs", jobs]) == 0  # fmt: skip
        outs.append(out.read_bytes())
    assert outs[0] == outs[1]


def test_one_failing_region_does_not_lose_the_others(folder, capsys):
    (folder / "broken.svg").write_text("<svg><circle r='1'></svg")
    styles = STYLES.replace('exemplar = "plain.svg"', 'exemplar = "broken.svg"')
    (folder / "styles.toml").write_text(styles)
    progress = []
    result = fill_map(folder / "map.svg", read_styles(folder / "styles.toml"), seed=3, jobs=2,
                      progress=lambda *a: progress.append(a))  # fmt: skip
    assert set(result.errors) == {"u2"} and "broken.svg" in result.errors["u2"]
    assert result.results[1] is None and len(result.results[0]) > 5 and len(result.results[2]) > 5
    assert sorted(p[0] for p in progress) == [1, 2, 3] and {p[2] for p in progress} == {"u1", "u2", "u3"}
    # the CLI writes the others, reports the failure in one line, and exits 1
    out = folder / "filled.svg"
    rc = main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out), "--seed", "3"])
    err = capsys.readouterr().err
    assert rc == 1
    assert set(groups(out)) == {"svgtile-u1", "svgtile-u3"}
    assert "region 'u2' not filled" in err and "1 of 3 regions failed" in err
    assert all(line.startswith("svgtile: ") for line in err.splitlines())


def test_region_failing_inside_synthesis_is_isolated(folder):
    # an avoid zone covering u3 whole makes that region unusable, not the run
    styles = read_styles(folder / "styles.toml")
    (folder / "cover.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg"><rect id="c" x="55" y="35" width="70" height="50"/></svg>')
    result = fill_map(folder / "map.svg", styles, seed=3, jobs=1, avoid=(f"{folder / 'cover.svg'}#c",))
    assert set(result.errors) == {"u3"} and "avoid" in result.errors["u3"]
    assert result.results[0] is not None


def test_region_above_the_motif_limit_fails_alone(folder, capsys, monkeypatch):
    # a tiny unit makes a region countless exemplar widths wide: refused, not run out of memory
    styles = STYLES.replace('engine = "random"', 'engine = "random"\nunit = 1e-6')
    (folder / "styles.toml").write_text(styles)
    out = folder / "filled.svg"
    rc = main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out),
               "--seed", "3", "--jobs", "1"])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 1
    assert "region 'u2' not filled: the region would hold about" in err and "raise unit of class 'plain'" in err
    assert set(groups(out)) == {"svgtile-u1", "svgtile-u3"}


def test_geojson_map_with_class_property(folder, capsys):
    data = {"type": "FeatureCollection", "features": [
        {"type": "Feature", "id": "west", "properties": {"class": "dots"},
         "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [60, 0], [60, 40], [0, 40], [0, 0]]]}},
        {"type": "Feature", "id": "east", "properties": {"class": "rings"},
         "geometry": {"type": "Polygon", "coordinates": [[[60, 0], [120, 0], [120, 40], [60, 40], [60, 0]]]}},
        {"type": "Feature", "id": "other", "properties": {"class": "unknown"},
         "geometry": {"type": "Polygon", "coordinates": [[[0, 40], [60, 40], [60, 80], [0, 80], [0, 40]]]}},
    ]}  # fmt: skip
    (folder / "map.geojson").write_text(json.dumps(data))
    (folder / "styles.toml").write_text(STYLES.replace('avoid = ["labels"]', ""))
    out = folder / "filled.geojson"
    rc = main(["map", str(folder / "map.geojson"), "--styles", str(folder / "styles.toml"), "-o", str(out), "--seed", "1"])
    assert rc == 0, capsys.readouterr().err
    feats = json.loads(out.read_text())["features"]
    by_region = {}
    for f in feats:
        by_region.setdefault(f["properties"]["region"], []).append(f)
    assert set(by_region) == {"west", "east"}
    for name, box in (("west", shapely.box(0, 0, 60, 40)), ("east", shapely.box(60, 0, 120, 40))):
        pts = shapely.points([f["geometry"]["coordinates"] for f in by_region[name]])
        assert shapely.dwithin(box, pts, 5).all()  # in map coordinates, y up
    out_svg = folder / "filled.svg"
    assert main(["map", str(folder / "map.geojson"), "--styles", str(folder / "styles.toml"), "-o", str(out_svg), "--seed", "1"]) == 0
    assert set(groups(out_svg)) == {"svgtile-west", "svgtile-east"}


@pytest.mark.parametrize(
    ("toml", "message"),
    [
        ({}, "no [classes.NAME] table"),
        ({"classes": {"a": {}}}, "no exemplar"),
        ({"classes": {"a": {"exemplar": "x.svg", "engine": "magic"}}}, "engine must be one of"),
        ({"classes": {"a": {"exemplar": "x.svg", "boundary": "sideways"}}}, "--boundary must be one of"),
        ({"classes": {"a": {"exemplar": "x.svg", "overlap": "lots"}}}, "wrong type"),
        ({"classes": {"a": {"exemplar": "x.svg", "colour": 1}}}, "unknown key 'colour'"),
        ({"colour": 1, "classes": {"a": {"exemplar": "x.svg"}}}, "unknown key 'colour'"),
        ({"classes": {"a": {"exemplar": "x.svg", "unit": 0}}}, "unit must be a positive number"),
        ({"avoid_margin": -1, "classes": {"a": {"exemplar": "x.svg"}}}, "avoid_margin"),
        ({"avoid_margin": 1e300, "classes": {"a": {"exemplar": "x.svg"}}}, "avoid_margin must be a number from 0"),
        ({"avoid_margin": True, "classes": {"a": {"exemplar": "x.svg"}}}, "avoid_margin"),
    ],
)
def test_bad_styles_are_one_line_errors(toml, message):
    with pytest.raises(ParameterError) as info:
        parse_styles(toml, source="styles.toml")
    assert message in str(info.value) and str(info.value).startswith("styles.toml: ")


def test_unreadable_styles_file(folder, capsys):
    (folder / "styles.toml").write_text("seed = = 1")
    rc = main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(folder / "o.svg")])
    err = capsys.readouterr().err
    assert rc == 1 and "not a valid TOML file" in err and len(err.splitlines()) == 1
    assert not (folder / "o.svg").exists()


def test_example_map_is_filled_by_one_command(tmp_path, capsys):
    example = REPO / "examples" / "geomap.svg"
    if not example.exists():
        pytest.skip("examples/ missing")
    out = tmp_path / "filled.svg"
    rc = main(["map", str(example), "--styles", str(REPO / "examples" / "geomap-styles.toml"), "-o", str(out)])
    assert rc == 0, capsys.readouterr().err
    assert set(groups(out)) == {"svgtile-qal", "svgtile-qm", "svgtile-qt", "svgtile-ksh", "svgtile-tb"}
    for group in groups(out).values():
        assert len(group) > 50


def _run_seed(path: Path) -> str:
    run = next(ET.parse(path).getroot().iter("{urn:svgtile:run:1}run"))
    return run.get("seed")


@pytest.mark.parametrize(("top", "cli", "want"), [
    ("seed = 1", [], "1"),                        # every class's seed is the styles' 1: say so, not 0
    ("seed = 1", ["--seed", "5"], "1"),           # the styles' seed wins over --seed for every class
    ("", ["--seed", "5"], "5"),                   # no class seed: the run's
])  # fmt: skip
def test_map_metadata_records_the_seed_used(folder, top, cli, want):
    (folder / "styles.toml").write_text(STYLES.replace("seed = 3", top))
    out = folder / "filled.svg"
    assert main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out), *cli]) == 0
    assert _run_seed(out) == want


def test_map_metadata_names_each_class_seed_when_they_differ(folder):
    styles = STYLES.replace("seed = 3\n", "").replace('boundary = "inside"', 'boundary = "inside"\nseed = 2')
    styles = styles.replace('engine = "random"', 'engine = "random"\nseed = 4').replace('grid = "hex"', 'grid = "hex"\nseed = 4')
    (folder / "styles.toml").write_text(styles)
    out = folder / "filled.svg"
    assert main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out)]) == 0
    assert _run_seed(out) == "dots=2 plain=4 rings=4"


def test_map_help_lists_every_styles_key(capsys):
    from svgtile.apps.mapfill import CLASS_KEYS, RUN_KEYS

    assert main(["map", "--help"]) == 0
    text = capsys.readouterr().out
    missing = [k for k in (*CLASS_KEYS, *RUN_KEYS) if k != "classes" and k not in text]
    assert not missing, missing


def test_map_metadata_names_the_run_seed_beside_a_class_seed(folder, capsys):
    styles = STYLES.replace("seed = 3\n", "").replace('boundary = "inside"', 'boundary = "inside"\nseed = 7')
    (folder / "styles.toml").write_text(styles)
    out = folder / "filled.svg"
    assert main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out), "--seed", "5"]) == 0
    assert _run_seed(out) == "dots=7 plain=5 rings=5"


def test_an_unused_map_seed_is_said(folder, capsys):
    out = folder / "filled.svg"  # STYLES has a top-level seed: every class's
    assert main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out), "--seed", "5"]) == 0
    assert "--seed 5 is not used" in capsys.readouterr().err


def test_a_top_level_engine_parameter_no_class_takes_is_refused():
    from svgtile.apps.mapfill import parse_styles

    with pytest.raises(ParameterError, match="junction at the top level is a parameter of no class's engine"):
        parse_styles({"junction": 0.3, "classes": {"a": {"exemplar": "x.svg", "engine": "random"}}})
    with pytest.raises(ParameterError, match="engine must be one of"):
        parse_styles({"classes": {"a": {"exemplar": "x.svg", "engine": ["patch"]}}})


@pytest.mark.parametrize("out_name", ["filled.svg", "filled.geojson", "filled.gpkg"])
def test_a_unit_too_small_for_any_motif_is_named_in_a_warning(folder, capsys, out_name):
    """As synth says "no motif fits", map names each unit it leaves empty (streamed or GIS output)."""
    tiny_unit = '<path id="u4" class="dots" d="M0 0 H0.001 V0.001 H0 Z"/>\n</svg>'
    (folder / "map.svg").write_text(MAP.replace("</svg>", tiny_unit))
    out = folder / out_name
    rc = main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out), "--seed", "3"])
    err = capsys.readouterr().err
    assert rc == 0 and out.exists()
    empty = [line for line in err.splitlines() if "no motif fits" in line]
    assert empty == ["svgtile: warning: no motif fits in region 'u4' (class 'dots'); it is left empty"], err
