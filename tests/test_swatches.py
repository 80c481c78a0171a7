"""svgtile swatches: a legend sheet of pattern tiles (issue 4, item 3)."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from svgtile.apps.swatches import collect, read_names, swatch_sheet
from svgtile.cli.main import main
from svgtile.errors import ExemplarError
from svgtile.svg.dialect import SVG_NS

HEAD = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
STROKE = 'fill="none" stroke="#000" stroke-width="0.2"'
GOOD = HEAD + f'<polygon id="a" points="1,1 4,1 1,2" {STROKE}/><circle cx="7" cy="7" r="1" {STROKE}/></svg>'
# a zigzag joining its own repeat: continuous, with no bedding rows (a straight line across the tile
# is bedding since issue 15, drawn by the cellular engine)
HATCH = HEAD + f'<polyline points="0,5 2.5,1 5,9 7.5,1 10,5" {STROKE}/></svg>'
DATA = Path(__file__).resolve().parents[2] / "shared" / "data"


@pytest.fixture
def tiles(tmp_path):
    folder = tmp_path / "set"
    folder.mkdir()
    (folder / "b-good.svg").write_text(GOOD)
    (folder / "a-hatch.svg").write_text(HATCH)
    (folder / "notes.txt").write_text("not a tile")
    return folder


def test_collect_sorts_directories_and_keeps_svg_only(tiles):
    assert [p.name for p in collect([str(tiles)])] == ["a-hatch.svg", "b-good.svg"]


def test_sheet_shows_texture_or_reason(tiles):
    sheet = swatch_sheet(collect([str(tiles)]), columns=2, names={"b-good": "Good pattern"})
    assert (sheet.accepted, sheet.refused) == (1, 1)
    hatch, good = sheet.swatches
    assert "hatching" in hatch.refused and good.refused is None
    assert good.motifs == 2 and good.texture > 2 * 4  # 3 x 3 tiles hold about 18 motifs
    root = ET.fromstring(sheet.text)
    texts = " ".join(t.text or "" for t in root.iter(f"{{{SVG_NS}}}text"))
    assert "b-good Good pattern" in texts and "refused:" in texts
    assert good.likeness is not None and hatch.likeness is None
    assert f"b-good Good pattern  L {good.likeness:.2f}" in texts
    ids = [el.get("id") for el in root.iter() if el.get("id")]
    assert len(ids) == len(set(ids))  # every pattern's ids prefixed
    # the original tile is repeated through a pattern; the texture is a nested svg of <use>s
    assert len(list(root.iter(f"{{{SVG_NS}}}pattern"))) == 2
    uses = [u for u in root.iter(f"{{{SVG_NS}}}use")]
    assert len(uses) == good.texture


def test_engines_side_by_side_each_captioned_with_its_engine_and_likeness(tiles, tmp_path):
    """--engine given several times (issue 13: growth beside patch on the sheet): one texture panel per
    engine after the tile, in the order given, each captioned; a tile every engine refuses stays refused."""
    sheet = swatch_sheet(collect([str(tiles)]), columns=2, engines=("patch", "growth", "auto"))
    assert sheet.engines == ("patch", "growth", "auto") and (sheet.accepted, sheet.refused) == (1, 1)
    hatch, good = sheet.patterns
    assert [s.engine for s in good] == ["patch", "growth", "auto"] and all(s.refused is None for s in good)
    assert [s.chosen for s in good[:2]] == ["patch", "growth"] and all("hatching" in s.refused for s in hatch)
    root = ET.fromstring(sheet.text)
    cell = root.find(f"{{{SVG_NS}}}g[@id='swatch-2']")
    captions = [t.text for t in cell.iter(f"{{{SVG_NS}}}text")][1:]
    assert captions[0] == "tile"
    assert captions[1:3] == [f"{s.engine}  L {s.likeness:.2f}" for s in good[:2]]
    assert captions[3].startswith(f"auto ({good[2].chosen})")
    nested = [el for el in cell if el.tag == f"{{{SVG_NS}}}svg"]
    assert len(nested) == 4 and len({el.get("x") for el in nested}) == 4  # tile + 3 textures, apart
    uses = [len(list(el.iter(f"{{{SVG_NS}}}use"))) for el in nested[1:]]
    assert uses == [s.texture for s in good]
    ids = [el.get("id") for el in root.iter() if el.get("id")]
    assert len(ids) == len(set(ids))
    # one engine: no captions, L in the label — the sheet it always was
    one = ET.fromstring(swatch_sheet(collect([str(tiles)]), columns=2).text)
    assert "tile" not in [t.text for t in one.iter(f"{{{SVG_NS}}}text")]
    # through the CLI, an engine named twice is drawn once; an unknown engine is a one-line error
    out = tmp_path / "s.svg"
    assert main(["swatches", str(tiles / "b-good.svg"), "-o", str(out), "--engine", "patch", "--engine", "patch"]) == 0
    assert len([el for el in ET.parse(out).getroot().iter(f"{{{SVG_NS}}}svg")]) == 3  # sheet, tile, one texture
    assert main(["swatches", str(tiles / "b-good.svg"), "-o", str(tmp_path / "t.svg"), "--engine", "nope"]) != 0
    assert not (tmp_path / "t.svg").exists()


def test_read_names(tmp_path):
    table = tmp_path / "names.csv"
    table.write_text("file,code,name\nlithology/601.svg,601,Gravel\n")
    assert read_names(table) == {"601": "Gravel"}
    (tmp_path / "bad.csv").write_text("a,b\n1,2\n")
    with pytest.raises(ExemplarError, match="name"):
        read_names(tmp_path / "bad.csv")


def test_cli_swatches_svg_and_png(tiles, tmp_path, capsys):
    pytest.importorskip("resvg_py")
    out = tmp_path / "sheet.svg"
    assert main(["swatches", str(tiles), "-o", str(out), "--png", "--png-width", "400"]) == 0
    assert "1 of 2 pattern(s) synthesized, 1 refused" in capsys.readouterr().err
    assert ET.parse(out).getroot().tag == f"{{{SVG_NS}}}svg"
    png = out.with_suffix(".png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_swatches_errors_are_one_line(tmp_path, capsys):
    empty = tmp_path / "empty"
    empty.mkdir()
    assert main(["swatches", str(empty), "-o", str(tmp_path / "s.svg")]) == 1
    assert main(["swatches", str(empty), "-o", "-", "--png"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all(line.startswith("svgtile: error:") for line in err)


@pytest.mark.skipif(not (DATA / "usgs-fgdc-cecgeology").is_dir(), reason="../shared/data is not beside the checkout")
def test_malformed_tile_is_a_refused_swatch_not_a_crash():
    bad = DATA / "usgs-fgdc-cecgeology" / "SED_fixedcolor" / "sed663.svg"
    sheet = swatch_sheet([bad])
    assert sheet.refused == 1 and "well-formed" in sheet.swatches[0].refused


def test_tile_without_area_is_a_refused_swatch_not_a_crash(tmp_path):
    flat = tmp_path / "flat.svg"
    flat.write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 0 0"><circle cx="5" cy="5" r="1"/></svg>')
    sheet = swatch_sheet([flat])
    assert sheet.refused == 1 and "no area" in sheet.swatches[0].refused


def test_tile_failing_after_import_is_a_refused_swatch(tmp_path):
    # 1e308-wide tile: the import passes, the exemplar it makes does not (an infinite region)
    huge = tmp_path / "huge.svg"
    huge.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="1e308" height="1e308" viewBox="0 0 1e308 1e308">'
                    '<circle cx="5" cy="5" r="1"/><circle cx="15" cy="5" r="1"/></svg>')  # fmt: skip
    good = tmp_path / "good.svg"
    good.write_text(GOOD)
    sheet = swatch_sheet([huge, good])
    assert (sheet.accepted, sheet.refused) == (1, 1) and sheet.swatches[0].refused


def test_swatch_above_the_motif_limit_is_refused(tiles, tmp_path, capsys, monkeypatch):
    import svgtile.cli.tiles

    monkeypatch.setattr(svgtile.cli.tiles, "MAX_MOTIFS", 50)  # a 30 x 30 swatch of GOOD holds about 18
    out = tmp_path / "s.svg"
    # every pattern refused: no sheet, and the exit code says so (issue 16), with the reason
    assert main(["swatches", str(tiles / "b-good.svg"), "-o", str(out), "--size", "100"]) == 1
    err = capsys.readouterr().err
    assert "none of the 1 pattern(s) could be synthesized" in err and "would hold about 200 motifs (limit 50)" in err
    assert not out.exists()
