"""svgtile's side of the Inkscape extension: container areas, the fill command, install/uninstall."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import TINY

from svgtile.apps import inkscape as ink
from svgtile.cli.main import main
from svgtile.core.region import winding_fill
from svgtile.files import same_file

FAR = [[20, 0], [24, 0], [24, 4], [20, 4]]


def _containers(path: Path, *items) -> Path:
    path.write_text(json.dumps({"containers": [
        {"id": ident, "fill_rule": rule, "rings": rings} for ident, rule, rings in items
    ]}))  # fmt: skip
    return path


def test_containers_with_rings_of_different_lengths_are_read(tmp_path):
    # a square with a triangular hole: the rings have 4 and 3 vertices (the old container_shape
    # built one array of all rings and failed with "not a containers file" here)
    square = [[0, 0], [10, 0], [10, 10], [0, 10]]
    triangle = [[2, 2], [2, 6], [6, 2]]  # clockwise against the square: a hole under nonzero
    c = _containers(tmp_path / "c.json", ("a", "nonzero", [square, triangle]), ("b", "evenodd", [square, triangle[::-1]]))
    (a, shape_a), (b, shape_b) = ink.read_containers(c)
    assert (a, b) == ("a", "b")
    assert shape_a.area == pytest.approx(92) and shape_b.area == pytest.approx(92)
    assert not shape_a.contains(shapely.Point(3, 3)) and shape_a.contains(shapely.Point(8, 8))


def test_fill_writes_one_texture_per_container(tmp_path):
    ex = tmp_path / "ex.svg"
    ex.write_text(TINY)
    big = [[0, 0], [60, 0], [60, 40], [0, 40]]
    hole = [[20, 10], [20, 30], [40, 30], [40, 10]]
    c = _containers(tmp_path / "c.json", ("a", "nonzero", [big, hole]), ("b", "evenodd", [FAR]))
    code = main(["inkscape", "fill", str(ex), str(c), "--out-dir", str(tmp_path), "--seed", "1",
                 "--boundary", "centroid"])  # fmt: skip
    assert code == 0
    first = (tmp_path / "texture-0.svg").read_text()
    assert 'container="a"' in first and "<use" in first
    assert (tmp_path / "texture-1.svg").is_file()
    xy = np.array([m.split() for m in re.findall(r'transform="translate\(([-\d.]+ [-\d.]+)\)', first)], float)
    area = winding_fill([np.array(big, float), np.array(hole, float)])
    assert len(xy) > 10 and shapely.contains_xy(area, xy[:, 0], xy[:, 1]).all()


def test_fill_same_seed_same_bytes(tmp_path):
    ex = tmp_path / "ex.svg"
    ex.write_text(TINY)
    c = _containers(tmp_path / "c.json", ("a", "nonzero", [[[0, 0], [50, 0], [50, 50], [0, 50]]]))
    texts = []
    for out in ("o1", "o2"):
        (tmp_path / out).mkdir()
        assert main(["inkscape", "fill", str(ex), str(c), "--out-dir", str(tmp_path / out), "--seed", "4"]) == 0
        texts.append((tmp_path / out / "texture-0.svg").read_bytes())
    assert texts[0] == texts[1]


@pytest.mark.parametrize(
    ("content", "needle"),
    [
        ("{", "not a containers file"),
        ("[" * 100_000 + "]" * 100_000, "nested too deeply"),
        ('{"containers": []}', "lists no containers"),
        ('{"containers": [{"id": "x", "rings": [[[0, 0], [1, 0], [0, 1]]], "fill_rule": "odd"}]}', "unknown fill rule"),
        ('{"containers": [{"id": "x", "rings": [[[0, 0], [1, 0], [0, NaN]]]}]}', "not finite"),
        ('{"containers": [{"id": "flat", "rings": [[[0, 0], [5, 0], [9, 0]]]}]}', "the shape 'flat' encloses no area"),
    ],
)
def test_fill_errors_are_one_line(tmp_path, capsys, content, needle):
    ex = tmp_path / "ex.svg"
    ex.write_text(TINY)
    c = tmp_path / "c.json"
    c.write_text(content)
    assert main(["inkscape", "fill", str(ex), str(c), "--out-dir", str(tmp_path), "--seed", "1"]) == 1
    err = capsys.readouterr().err.strip()
    assert err.startswith("svgtile: error:") and needle in err and "\n" not in err
    assert not list(tmp_path.glob("texture-*"))


def test_fill_refuses_huge_containers(tmp_path, capsys):
    ex = tmp_path / "ex.svg"
    ex.write_text(TINY)
    c = _containers(tmp_path / "c.json", ("huge", "nonzero", [[[0, 0], [1e5, 0], [1e5, 1e5], [0, 1e5]]]))
    assert main(["inkscape", "fill", str(ex), str(c), "--out-dir", str(tmp_path), "--seed", "1"]) == 1
    assert "the shape 'huge' would hold about" in capsys.readouterr().err


def test_fill_refuses_a_selection_of_minutes_for_a_slow_engine(tmp_path, capsys):
    """Inkscape waits for the extension: shapes each under the motif limit, but together minutes of
    growth, are refused before any is filled."""
    ex = tmp_path / "ex.svg"
    ex.write_text(TINY)
    side = 4000  # TINY holds 0.0125 motifs per unit²: 200,000 motifs per shape, 2 shapes
    shapes = [(f"s{i}", "nonzero", [[[i * side, 0], [(i + 1) * side, 0], [(i + 1) * side, side], [i * side, side]]])
              for i in range(2)]  # fmt: skip
    c = _containers(tmp_path / "c.json", *shapes)
    assert main(["inkscape", "fill", str(ex), str(c), "--out-dir", str(tmp_path), "--seed", "1", "--engine", "growth"]) == 1
    err = capsys.readouterr().err
    assert "the selection would hold about" in err and "of work for engine 'growth'" in err and "fill a smaller area" in err
    assert not list(tmp_path.glob("texture-*.svg"))


# ----------------------------------------------------------------------------- install


def test_install_copies_the_extension_and_records_this_python(tmp_path, capsys):
    assert main(["inkscape", "install", "--user-dir", str(tmp_path)]) == 0
    folder = tmp_path / "extensions" / "svgtile"
    assert str(folder) in capsys.readouterr().out
    for name in ink.EXTENSION_FILES:
        assert (folder / name).read_bytes() == (ink.extension_source() / name).read_bytes()
    config = json.loads((folder / ink.CONFIG_NAME).read_text())
    assert same_file(config["python"], sys.executable)
    # again: updates in place
    (folder / "svgtile_fill.py").write_text("old")
    assert main(["inkscape", "install", "--user-dir", str(tmp_path)]) == 0
    assert (folder / "svgtile_fill.py").read_bytes() == (ink.extension_source() / "svgtile_fill.py").read_bytes()
    assert main(["inkscape", "uninstall", "--user-dir", str(tmp_path)]) == 0
    assert not folder.exists() and (tmp_path / "extensions").is_dir()


def test_uninstall_when_not_installed(tmp_path, capsys):
    assert main(["inkscape", "uninstall", "--user-dir", str(tmp_path)]) == 1
    assert "not installed here" in capsys.readouterr().err


def test_install_never_overwrites_a_foreign_folder(tmp_path, capsys):
    folder = tmp_path / "extensions" / "svgtile"
    folder.mkdir(parents=True)
    (folder / "mine.txt").write_text("keep")
    assert main(["inkscape", "install", "--user-dir", str(tmp_path)]) == 1
    assert "was not made by 'svgtile inkscape install'" in capsys.readouterr().err
    assert main(["inkscape", "uninstall", "--user-dir", str(tmp_path)]) == 1
    assert (folder / "mine.txt").read_text() == "keep"


def test_default_user_dir_honours_inkscape_profile_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("INKSCAPE_PROFILE_DIR", str(tmp_path / "profile"))
    assert ink.user_data_dir() == tmp_path / "profile"
    assert main(["inkscape", "install"]) == 0
    assert (tmp_path / "profile" / "extensions" / "svgtile" / ink.CONFIG_NAME).is_file()
