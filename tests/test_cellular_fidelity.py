"""Cellular textures that look like their FGDC tiles (issue 15's last note): line weights,
the import's cells-or-scatter decision, fragments and grounds, the fewest half bricks, map units
and wavy lines.  Each test names what a cartographer would see go wrong."""

from __future__ import annotations

import io
import re
import xml.etree.ElementTree as ET
from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely
from test_cellular import l_unit, run

from svgtile.analysis.stats import analyze
from svgtile.core.cells import LINE
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.cellular.joints import outline_only
from svgtile.svg.reader import parse_exemplar
from svgtile.tiles.importer import import_tile

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"
FGDC = DATA / "fgdc-geologic-patterns" / "lithology"
needs_data = pytest.mark.skipif(not FGDC.is_dir(), reason="../shared/data (real symbol sets) is not beside the checkout")


@cache
def fgdc(code: str):
    """(imported tile, exemplar, analysis) of an FGDC lithology tile."""
    t = import_tile(FGDC / f"{code}.svg")
    ex = parse_exemplar(t.text, source=f"{code}.svg")
    return t, ex, analyze(ex)


def stroked(cells) -> np.ndarray:
    """(k,) what the cellwork strokes: its lines and the outlines of its outlined cells."""
    draws = np.array([outline_only(css) for css in cells.styles], dtype=bool)[cells.style]
    line = cells.feature == LINE
    return np.r_[cells.shapes[line & draws], shapely.boundary(cells.shapes[~line & draws])]


# ----------------------------------------------------------------------------- (a) line weights


def test_each_joint_is_stroked_once_and_the_unit_outline_not_at_all(tmp_path):
    cells = run(tmp_path=tmp_path).cells
    drawn = stroked(cells)
    assert len(drawn) and (cells.feature == LINE).any()
    total = shapely.length(drawn).sum()
    assert total == pytest.approx(shapely.union_all(drawn).length, rel=1e-6), "a joint is stroked twice"
    # the unit's outline (the map draws it) carries no stroke: at most the joints' ends touch it
    on_edge = shapely.intersection(shapely.union_all(drawn), shapely.buffer(l_unit().boundary, 1e-3)).length
    assert on_edge < 1e-3 * total
    # yet every cell side inside the unit is drawn: the joints cover the cells' shared sides
    sides = shapely.difference(shapely.union_all(shapely.boundary(cells.cells)), shapely.buffer(l_unit().boundary, 1e-3))
    assert shapely.difference(sides, shapely.buffer(shapely.union_all(drawn), 1e-3)).length < 1e-3 * total


def _ink(svg_root: ET.Element, box, pixels_per_unit: float) -> float:
    """Mean ink (0 white … 1 black) of an SVG drawing rendered at ``pixels_per_unit``, a sixth in
    from each side."""
    from PIL import Image

    from svgtile.apps.preview import render_png

    x0, y0, w, h = box
    svg_root.set("viewBox", f"{x0} {y0} {w} {h}")
    svg_root.set("width", str(w))
    svg_root.set("height", str(h))
    png = render_png(ET.tostring(svg_root, encoding="unicode"), round(w * pixels_per_unit))
    img = np.asarray(Image.open(io.BytesIO(png)).convert("L"), dtype=np.float64) / 255.0
    m = img.shape[0] // 6
    return 1.0 - float(img[m:-m, m:-m].mean())


@needs_data
def test_fgdc_627_limestone_is_as_dark_as_its_tile_on_screen():
    """Joints stroked twice looked 1.67 times as dark as the tile at a legend's 1.4 pixels per unit."""
    pytest.importorskip("resvg_py")
    from svgtile.apps.swatches import _swatch

    _, original, (texture,) = _swatch(FGDC / "627.svg", "627", None, 3.0, 1)
    ratio = _ink(*texture, 1.4) / _ink(*original, 1.4)
    assert 0.85 <= ratio <= 1.15, f"texture / tile ink {ratio:.2f}"


@needs_data
@pytest.mark.parametrize("code", ["627", "635", "641"])
def test_fgdc_strokes_keep_the_tiles_widths(code):
    t, ex, stats = fgdc(code)
    tile_widths = set(re.findall(r"stroke-width:\s*([0-9.]+)", (FGDC / f"{code}.svg").read_text()))
    w = t.box[2]
    r = synthesize(ex, Region(shapely.box(0, 0, 2 * w, 2 * w)), "cellular", seed=1, stats=stats)
    out = set()
    for css in r.cells.styles:
        out |= set(re.findall(r"stroke-width:\s*([0-9.]+)", css))
    assert out and {float(v) for v in out} <= {float(v) for v in tile_widths}


# ----------------------------------------------------------------------------- (d) interbedded courses


@needs_data
def test_fgdc_637_dashes_and_dots_in_bricks_are_not_courses():
    d = fgdc("637")[0].cellular
    bands = d["bands"]
    # 14 brick courses per tile, not 27 (the rows of dashes inside the bricks were read as courses)
    assert len(bands["rows"]) == 14 and bands["cut"] == list(range(14))
    assert d["course"] == pytest.approx(54.125 / 14, rel=1e-3)
    assert d["length"] == pytest.approx(54.242 / 4, rel=0.02)
    assert "lines" not in d and d["motifs"]["share"] > 0.5  # the dashes and dots are set in the bricks


@needs_data
def test_fgdc_677_alternates_brick_courses_and_dashed_shale():
    d = fgdc("677")[0].cellular
    rows, cut = d["bands"]["rows"], d["bands"]["cut"]
    assert len(rows) == 21 and cut == list(range(2, 21, 3))  # one brick course in three rows
    heights = np.diff(np.r_[rows, d["bands"]["period"]])
    assert np.all(heights[cut] > 1.5 * np.delete(heights, cut).max())  # bricks are the tall courses
    assert len(d["lines"]) == 7 and all("dash" in spec for spec in d["lines"])  # solid rows: the cells draw them
    assert "motifs" not in d


@needs_data
def test_fgdc_672_brick_courses_between_dashed_shale():
    d = fgdc("672")[0].cellular
    rows, cut, period = d["bands"]["rows"], d["bands"]["cut"], d["bands"]["period"]
    assert len(cut) == 3  # three brick courses per tile …
    heights = np.diff(np.r_[rows, period])
    assert np.allclose(heights[cut], 3.3, atol=0.15)  # … between solid rows 3.3 apart (no row inside)
    # the two solid rows of each brick course are the cells' outlines; the other rows, dashed lines
    assert len(d["lines"]) == len(rows) - 2 * 3 and all("dash" in spec for spec in d["lines"])


@needs_data
def test_banded_cells_lie_only_in_the_cut_courses():
    t, ex, stats = fgdc("677")
    bands = t.cellular["bands"]
    r = synthesize(ex, Region(shapely.box(0, 0, 120, 120)), "cellular", seed=1, stats=stats, boundary="inside")
    cells = r.cells.cells
    assert len(cells) > 40
    y = shapely.bounds(cells)[:, [1, 3]]
    period, rows = bands["period"], np.array(bands["rows"])
    lower = (y[:, 0] % period)[:, None] - rows[None, :]
    j = np.argmin(np.abs(lower), axis=1)
    assert np.abs(lower[np.arange(len(j)), j]).max() < 1e-3  # every cell starts on a row …
    assert np.isin(j, bands["cut"]).all()  # … of a cut course …
    height = np.diff(np.r_[rows, period])[j]
    assert np.all(y[:, 1] - y[:, 0] <= height + 1e-3)  # … and stays in it


@needs_data
@pytest.mark.parametrize("code", ["646", "647"])
def test_fgdc_slanted_joints_in_interbedded_courses_make_rhombs(code):
    d = fgdc(code)[0].cellular
    assert d["tree"][-1]["generator"] == "rhombs" and abs(d["rhomb_angle"]) > 15
    assert len(d["bands"]["cut"]) == len(d["bands"]["rows"])  # every course, even the one astride the tile's side


def test_bands_are_checked_when_a_description_is_read():
    from svgtile.engines.cellular.tree import parse_description
    from svgtile.errors import ParameterError

    ok = parse_description({"course": 2.0, "bands": {"period": 10.0, "rows": [0.0, 3.0, 6.5], "cut": [1]}})
    assert ok.bands.rows == (0.0, 3.0, 6.5) and ok.bands.cut == (1,)
    for bad in ({"period": 10.0, "rows": [3.0, 1.0], "cut": []}, {"period": 10.0, "rows": [0.0, 12.0], "cut": []},
                {"period": 0, "rows": [0.0], "cut": []}, {"period": 10.0, "rows": [0.0], "cut": [1]},
                {"period": 10.0, "rows": [0.0]}):  # fmt: skip
        with pytest.raises(ParameterError, match="bands"):
            parse_description({"bands": bad}, "t.json")


# ----------------------------------------------------------------------------- (b) fewest half bricks


def _cut_face_cells(result, whole_area: float) -> int:
    from svgtile.core.cells import FACE

    face = result.cells.shapes[result.cells.feature == FACE]
    return int((shapely.area(face) < whole_area - 1e-3).sum())


def test_the_face_takes_the_bond_with_the_fewest_half_bricks(tmp_path):
    """§5.2: of the two ways of pairing blocks into bricks, the one making fewer bricks.  Eleven
    courses j = 1 … 11 of bricks 14 long in a face 140 wide: the world's bond cuts the six odd
    courses at both ends (12 halves), the other phase the five even ones (10)."""
    face_only = {"course": 6.0, "length": 14.0, "offset": 0.5, "tree": [{"feature": "face", "generator": "bricks"}]}
    box = shapely.box(0, 6, 140, 72)
    fewest = run(face_only, shape=box, tmp_path=tmp_path)
    anchored = run(face_only, shape=box, tmp_path=tmp_path, halves="anchored")
    assert _cut_face_cells(anchored, 84.0) == 12
    assert _cut_face_cells(fewest, 84.0) == 10
    assert shapely.area(fewest.cells.cells).sum() == pytest.approx(box.area)  # the same area, filled


def test_fewest_half_bricks_never_cuts_more_than_the_anchored_bond(tmp_path):
    fewest, anchored = run(tmp_path=tmp_path), run(tmp_path=tmp_path, halves="anchored")
    assert _cut_face_cells(fewest, 84.0) <= _cut_face_cells(anchored, 84.0)


# ----------------------------------------------------------------------------- (e) wavy lines


def test_a_wavy_line_follows_its_profile(tmp_path):
    wave = [0.0, 0.5, 0.0, -0.5]  # a zigzag 1 across, every 8 along
    d = {"course": 6.0, "length": 14.0, "tree": [{"feature": "face", "generator": "none"}],
         "lines": [{"every": 1, "start": 0, "wave": wave, "wave_period": 8.0}]}  # fmt: skip
    lines = run(d, shape=shapely.box(0, 0, 64, 30), tmp_path=tmp_path).cells.lines
    assert len(lines) >= 4
    xy = shapely.get_coordinates(lines)
    course = np.round(xy[:, 1] / 6.0)
    across = xy[:, 1] - 6.0 * course
    assert np.ptp(across) == pytest.approx(1.0, abs=1e-3)  # not drawn straight
    expect = np.interp(xy[:, 0] % 8.0, [0, 2, 4, 6], wave, period=8.0)
    assert np.abs(across - expect).max() < 1e-3  # world-anchored: the same profile on every course


@needs_data
def test_fgdc_663_wavy_bedding_is_imported_with_its_wave():
    d = fgdc("663")[0].cellular
    waves = [spec for spec in d["lines"] if spec.get("wave")]
    assert waves, "the wavy rows were imported straight"
    for spec in waves:
        assert np.ptp(spec["wave"]) > 0.2 and spec["wave_period"] == pytest.approx(fgdc("663")[0].box[2], rel=1e-3)
    straight = import_tile(FGDC / "627.svg").cellular
    assert not any(spec.get("wave") for spec in straight.get("lines") or ())
