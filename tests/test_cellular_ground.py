"""A tile's painted background is the ground its pattern is drawn on (issue 15: FGDC 659's black
ground was dropped with the frame): imported as ``svgtile:ground``, painted under the texture by
``synth`` and ``map``; a tile with none writes exactly what it did."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from svgtile.cli.main import main
from svgtile.errors import ExemplarError
from svgtile.svg.reader import parse_exemplar, read_exemplar
from svgtile.tiles.importer import import_tile

HEAD = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 40 40">'
#: White lenses on black, as FGDC 659 draws them.
LENSES = "".join(f'<ellipse cx="{x}" cy="{y}" rx="6" ry="2" fill="#FFFFFF" stroke="#000" stroke-width="0.3"/>'
                 for x, y in ((10, 10), (30, 20), (12, 30)))  # fmt: skip
GROUNDED = HEAD + '<rect x="0" y="0" width="40" height="40"/>' + LENSES + "</svg>"  # black: the default fill
PLAIN = HEAD + '<rect x="0" y="0" width="40" height="40" fill="none" stroke="none"/>' + LENSES + "</svg>"


def grounds(text: str) -> list[str]:
    return re.findall(r'<path class="svgtile-ground" style="fill:([^;"]+);stroke:none"', text)


def test_a_painted_background_is_imported_as_the_ground(tmp_path):
    (tmp_path / "tile.svg").write_text(GROUNDED)
    ex = parse_exemplar(import_tile(tmp_path / "tile.svg").text, source="tile.svg")
    assert ex.ground == "black" and len(ex.motifs) == 3
    (tmp_path / "plain.svg").write_text(PLAIN)
    assert parse_exemplar(import_tile(tmp_path / "plain.svg").text, source="plain.svg").ground is None


@pytest.mark.parametrize("boundary", ["clip", "inside"])
def test_synth_paints_the_ground_under_the_motifs(tmp_path, capsys, boundary):
    (tmp_path / "tile.svg").write_text(GROUNDED)
    out = tmp_path / "out.svg"
    assert main(["synth", str(tmp_path / "tile.svg"), "--import", "--size", "80x60", "--seed", "1",
                 "--boundary", boundary, "-o", str(out)]) == 0, capsys.readouterr().err  # fmt: skip
    text = out.read_text()
    assert grounds(text) == ["black"]
    assert text.index("svgtile-ground") < text.index("<use")  # under the motifs
    (tmp_path / "plain.svg").write_text(PLAIN)
    assert main(["synth", str(tmp_path / "plain.svg"), "--import", "--size", "80x60", "--seed", "1",
                 "--boundary", boundary, "-o", str(out)]) == 0  # fmt: skip
    assert grounds(out.read_text()) == []


@pytest.mark.parametrize("boundary", ["clip", "inside"])
def test_a_texture_with_a_ground_is_read_back_as_its_motifs(tmp_path, boundary):
    """score (and propagate) read a grounded texture: the ground is paint, not a motif."""
    from svgtile.svg.texture import read_texture

    tile = tmp_path / "tile.svg"
    tile.write_text(GROUNDED)
    (tmp_path / "ex.svg").write_text(import_tile(tile).text)
    ex = read_exemplar(tmp_path / "ex.svg")
    out = tmp_path / "out.svg"
    assert main(["synth", str(tmp_path / "ex.svg"), "--size", "120x90", "--seed", "1", "--boundary", boundary,
                 "-o", str(out)]) == 0  # fmt: skip
    text = out.read_text()
    assert grounds(text) == ["black"]
    arr, _ = read_texture(out, ex)
    assert len(arr) == text.count("<use ") > 0
    assert main(["score", str(tmp_path / "ex.svg"), str(out)]) == 0
    # the general reader (a comment before the motifs: not svgtile's own form) skips the ground too
    out.write_text(text.replace("<metadata>", "<!-- edited --><metadata>", 1))
    arr2, _ = read_texture(out, ex)
    assert len(arr2) == len(arr)


def test_a_map_unit_is_painted_with_its_class_ground(tmp_path, capsys):
    (tmp_path / "tile.svg").write_text(GROUNDED)
    assert main(["import", str(tmp_path / "tile.svg"), "-o", str(tmp_path / "coal.svg")]) == 0
    (tmp_path / "map.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
                                      '<path id="c" class="coal" d="M0 0 H100 V100 H0 Z"/></svg>')  # fmt: skip
    (tmp_path / "styles.toml").write_text('seed = 1\n[classes.coal]\nexemplar = "coal.svg"\n')
    out = tmp_path / "filled.svg"
    assert main(["map", str(tmp_path / "map.svg"), "--styles", str(tmp_path / "styles.toml"), "-o", str(out),
                 "--jobs", "1"]) == 0, capsys.readouterr().err  # fmt: skip
    assert grounds(out.read_text()) == ["black"]


@pytest.mark.parametrize("value", ["red;stroke:url(#x)", "", "#12"])
def test_a_ground_that_is_no_colour_is_refused(tmp_path, value):
    path = Path(tmp_path / "ex.svg")
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" xmlns:svgtile="urn:svgtile:run:1" viewBox="0 0 20 20">'
                    f'<rect id="region" width="20" height="20" fill="none" svgtile:ground="{value}"/>'
                    '<circle cx="5" cy="5" r="1"/></svg>')  # fmt: skip
    with pytest.raises(ExemplarError, match="svgtile:ground"):
        read_exemplar(path)


@pytest.mark.parametrize("paint", ['fill="#000" fill-opacity="0.2"', 'style="fill:#000;opacity:30%"',
                                   'fill="currentColor"'])  # fmt: skip
def test_a_translucent_or_inherited_background_is_no_ground(tmp_path, paint):
    (tmp_path / "tile.svg").write_text(HEAD + f'<rect x="0" y="0" width="40" height="40" {paint}/>' + LENSES + "</svg>")
    assert parse_exemplar(import_tile(tmp_path / "tile.svg").text, source="tile.svg").ground is None
