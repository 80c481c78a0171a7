"""Issue 16 item 1: no command ever overwrites one of its inputs, and nothing is written first.

Every command gets the same check (:func:`svgtile.cli.common.command_paths` in
:mod:`svgtile.cli.main`), so each case names an input other than the exemplar as the output,
under several spellings, and asserts: exit 1, one line naming the clash, every input byte for
byte as it was, and no file added to the folder.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import pytest
from conftest import TINY

from svgtile.cli.main import main

MAP = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 60 60">'
       '<rect id="qal" class="tiny" x="0" y="0" width="40" height="40"/>'
       '<text id="labels" x="5" y="5">Qal</text></svg>')  # fmt: skip
GEOJSON = ('{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"class":"tiny"},'
           '"geometry":{"type":"Polygon","coordinates":[[[0,0],[40,0],[40,-40],[0,-40],[0,0]]]}}]}')  # fmt: skip


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    (tmp_path / "ex.svg").write_text(TINY)
    (tmp_path / "map.svg").write_text(MAP)
    (tmp_path / "other.svg").write_text(MAP)
    (tmp_path / "a.geojson").write_text(GEOJSON)
    (tmp_path / "names.csv").write_text("name,code\nTiny,ex\n")
    (tmp_path / "styles.toml").write_text('[classes.tiny]\nexemplar = "ex.svg"\n')
    os.link(tmp_path / "map.svg", tmp_path / "hard.svg")
    (tmp_path / "link.svg").symlink_to("other.svg")
    (tmp_path / "sub").mkdir()
    return tmp_path


def snapshot(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest() if p.is_file() else "dir"
            for p in sorted(folder.rglob("*"))}  # fmt: skip


CASES = {
    "synth --region map": ["synth", "ex.svg", "--region", "map.svg#qal", "-o", "map.svg"],
    "synth --region map, hard link": ["synth", "ex.svg", "--region", "map.svg#qal", "-o", "hard.svg"],
    "synth --avoid map, ../ spelling": ["synth", "ex.svg", "--size", "30", "--avoid", "map.svg#labels",
                                        "-o", "sub/../map.svg"],
    "synth --region geojson": ["synth", "ex.svg", "--region", "a.geojson", "-o", "a.geojson"],
    "synth --avoid geojson": ["synth", "ex.svg", "--size", "30", "--avoid", "a.geojson", "-o", "./a.geojson"],
    "map --avoid other": ["map", "map.svg", "--styles", "styles.toml", "--avoid", "other.svg#labels",
                          "-o", "other.svg"],
    "map --avoid other, symlink": ["map", "map.svg", "--styles", "styles.toml", "--avoid", "link.svg#labels",
                                   "-o", "other.svg"],
    "map styles": ["map", "map.svg", "--styles", "styles.toml", "-o", "styles.toml"],
    "map exemplar of a class": ["map", "map.svg", "--styles", "styles.toml", "-o", "ex.svg"],
    "swatches --names": ["swatches", "ex.svg", "--names", "names.csv", "-o", "names.csv"],
    "import": ["import", "ex.svg", "-o", "ex.svg"],
    "compare --png with the exemplar as tile.svg": ["compare", "sub/tile.svg", "--size", "30", "--engines",
                                                    "patch,tile", "--png", "sub"],
}


@pytest.mark.parametrize("args", CASES.values(), ids=CASES.keys())
def test_no_command_overwrites_an_input(folder, args, capsys, monkeypatch):
    monkeypatch.chdir(folder)
    (folder / "sub" / "tile.svg").write_text(TINY)
    before = snapshot(folder)
    rc = main(args)
    err = capsys.readouterr().err
    assert rc == 1
    assert "refusing to overwrite" in err and len(err.strip().splitlines()) == 1, err
    assert snapshot(folder) == before  # nothing changed, nothing added (no PNG of another engine)


def test_the_same_commands_write_when_the_output_is_new(folder, capsys, monkeypatch):
    """The check refuses clashes only: the region file is read and a new output written."""
    monkeypatch.chdir(folder)
    assert main(["synth", "ex.svg", "--region", "map.svg#qal", "--avoid", "map.svg#labels", "-o", "out.svg",
                 "--seed", "1"]) == 0  # fmt: skip
    assert "<use" in (folder / "out.svg").read_text()
    assert main(["synth", "ex.svg", "--region", "a.geojson", "-o", "out.geojson", "--seed", "1"]) == 0
    assert '"Point"' in (folder / "out.geojson").read_text()
