"""svgtile import: pattern tiles to exemplars (issue 4), on hand-made tiles and the real symbol sets.

Real files come from ``../shared/data`` beside the checkout; those tests skip when it is absent.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile.analysis.stats import analyze, distance_matrix, periodic_distance_matrix
from svgtile.cli.main import main
from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import Prototype
from svgtile.errors import ExemplarError
from svgtile.svg.reader import parse_exemplar, read_exemplar
from svgtile.svg.tilepieces import parse_tile
from svgtile.tiles.importer import TileRefused, import_pieces, import_tile

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"
FGDC = DATA / "fgdc-geologic-patterns" / "lithology"
CEC = DATA / "usgs-fgdc-cecgeology"
OSM = DATA / "osm-carto" / "generating_patterns"
needs_data = pytest.mark.skipif(not FGDC.is_dir(), reason="../shared/data (real symbol sets) is not beside the checkout")

HEAD = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
STROKE = 'fill="none" stroke="#000" stroke-width="0.2"'


def tile(body: str, head: str = HEAD) -> object:
    return import_pieces(parse_tile(head + body + "</svg>", source="tile.svg"))


# ----------------------------------------------------------------------------- hand-made tiles


def test_frame_dropped_and_cut_stroke_reassembled_across_the_edge():
    t = tile(
        f'<rect x="0" y="0" width="10" height="10" style="fill:none;stroke:#000"/>'
        f'<line x1="8" y1="5" x2="10" y2="5" {STROKE}/><line x1="0" y1="5" x2="2" y2="5" {STROKE}/>'
        f'<circle cx="5" cy="2" r="1" {STROKE}/>'
    )
    assert len(t) == 2 and t.kinds == 2
    assert sorted(t.pieces.tolist()) == [1, 2]
    assert t.wrapped.tolist().count(True) == 1
    assert any("frame" in n for n in t.notes)
    ex = parse_exemplar(t.text)
    line = int(np.flatnonzero(t.pieces == 2)[0])
    # the reassembled dash is 4 long and centred on the edge (x = 0 or 10), inside the tile
    assert np.isclose(t.xy[line, 0] % 10, 0, atol=1e-6) or np.isclose(t.xy[line, 0] % 10, 10, atol=1e-6)
    assert len(ex.motifs) == 2  # a motif centred on the tile's edge is kept
    width = np.ptp(shapely.get_coordinates(ex.kinds[ex.motifs.kind[line]].footprint)[:, 0])
    assert width == pytest.approx(4.0, abs=0.01)


def test_hatching_is_refused_with_a_reason():
    with pytest.raises(TileRefused, match="continuous lines or hatching"):
        tile(f'<line x1="0" y1="3" x2="10" y2="3" {STROKE}/><line x1="0" y1="7" x2="10" y2="7" {STROKE}/>')


def test_solid_fill_is_refused():
    with pytest.raises(TileRefused, match="solid fill"):
        tile('<rect x="0" y="0" width="10" height="10" fill="#000"/>')


def test_empty_tile_is_refused():
    with pytest.raises(TileRefused, match="draws nothing"):
        tile('<rect x="0" y="0" width="10" height="10" style="fill:none"/>')


def test_periodic_duplicates_are_dropped():
    t = tile('<circle cx="5" cy="5" r="1" fill="#000"/><circle cx="15" cy="5" r="1" fill="#000"/>'
             '<circle cx="5" cy="5" r="1" fill="#000"/>')  # fmt: skip
    assert len(t) == 1
    assert any("repeating others" in n for n in t.notes)


def test_rotated_copies_share_a_kind_with_the_right_angle():
    t = tile('<polygon points="1,1 4,1 1,2" fill="#000"/><polygon points="7,6 7,9 6,6" fill="#000"/>')
    assert t.kinds == 1
    ex = parse_exemplar(t.text)
    turn = abs(ex.motifs.angle[1] - ex.motifs.angle[0]) % 360
    assert min(turn, 360 - turn) == pytest.approx(90.0, abs=0.5)


def test_scaled_copies_are_different_kinds():
    t = tile(f'<circle cx="2" cy="2" r="0.5" {STROKE}/><circle cx="7" cy="2" r="1" {STROKE}/>'
             f'<circle cx="2" cy="7" r="0.5" {STROKE}/><circle cx="7" cy="7" r="1" {STROKE}/>')  # fmt: skip
    assert len(t) == 4 and t.kinds == 2


def test_different_paint_makes_different_kinds():
    t = tile('<circle cx="2" cy="2" r="1" fill="#000"/><circle cx="7" cy="7" r="1" fill="#f00"/>')
    assert t.kinds == 2


def test_dot_from_zero_length_line_has_the_stroke_diameter():
    t = tile('<line x1="3" y1="3" x2="3" y2="3" style="stroke:#000;stroke-width:0.8;stroke-linecap:round"/>')
    ex = parse_exemplar(t.text)
    assert ex.kinds[0].prototype.area == pytest.approx(np.pi * 0.4**2, rel=0.01)


def test_touching_and_contained_pieces_are_one_motif():
    t = tile(f'<rect x="2" y="2" width="3" height="3" {STROKE}/><circle cx="3.5" cy="3.5" r="0.8" {STROKE}/>'
             f'<line x1="7" y1="7" x2="9" y2="9" {STROKE}/><line x1="7" y1="9" x2="9" y2="7" {STROKE}/>')  # fmt: skip
    assert len(t) == 2 and sorted(t.pieces.tolist()) == [2, 2]


def _scattered_pairs(pair: bool, n: int = 12, seed: int = 5) -> str:
    """A 40 x 40 tile of n crosses scattered with a minimum gap; each with a dot beside it at the
    same offset in the cross's own frame (rotated with it) when ``pair``."""
    rng = np.random.default_rng(seed)
    xy: list[np.ndarray] = []
    while len(xy) < n:
        p = rng.uniform(3, 37, 2)
        if all(np.hypot(*(p - q)) > 9 for q in xy):
            xy.append(p)
    body = []
    for k, (x, y) in enumerate(xy):
        turn = 90 * (k % 4)
        g = f'<g transform="translate({x:.3f} {y:.3f}) rotate({turn})">'
        g += f'<path d="M-1.5 0H1.5M0 -1.5V1.5" {STROKE}/>'
        if pair:
            g += '<circle cx="3" cy="1" r="0.4" fill="#000"/>'
        body.append(g + "</g>")
    return '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 40 40">' + "".join(body)


def test_parts_at_a_recurring_offset_are_one_motif():
    t = tile("", head=_scattered_pairs(True))
    assert len(t) == 12 and t.kinds == 1
    assert set(t.pieces.tolist()) == {3}  # the cross's two strokes and the dot


L_SHAPE = '<path d="M-1.5 -1 L1.5 -1 L1.5 -0.3 L-0.8 -0.3 L-0.8 1.5 L-1.5 1.5 Z" fill="#000"/>'


@pytest.mark.parametrize("turns", [0.0, 37.0, None])
def test_a_round_part_beside_a_shape_is_joined_in_rotated_copies(turns):
    """A dot's angle means nothing: the offset to it is taken in its partner's frame (reviewer's
    case: L + dot under rotate(37 k) or random angles came out as 24 one-part motifs)."""
    rng = np.random.default_rng(5)
    xy = []
    while len(xy) < 12:
        p = rng.uniform(3, 37, 2)
        if all(np.hypot(*((p - q + 20) % 40 - 20)) > 9 for q in xy):  # apart across the edges too
            xy.append(p)
    angles = np.random.default_rng(7).uniform(0, 360, 12) if turns is None else turns * np.arange(12)
    body = "".join(f'<g transform="translate({x:.3f} {y:.3f}) rotate({a:.3f})">{L_SHAPE}<circle cx="3" cy="1" r="0.4" fill="#000"/></g>'
                   for (x, y), a in zip(xy, angles, strict=True))  # fmt: skip
    t = tile("", head='<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 40 40">' + body)
    assert len(t) == 12 and t.kinds == 1 and set(t.pieces.tolist()) == {2}


def test_support_counts_links_within_one_on_every_coordinate():
    from svgtile.tiles.repeat import _support

    rng = np.random.default_rng(2)
    feat = np.round(rng.uniform(0, 4, (400, 3)), 1)  # on the 0.1 grid, where the count is exact
    feat = np.r_[feat, np.repeat(feat[:5], 50, axis=0)]  # lattice-like pile-ups of one point
    want = (np.abs(feat[:, None] - feat[None]).max(axis=2) <= 1.0 + 1e-9).sum(axis=1)
    assert np.array_equal(_support(feat), want)


def test_a_lattice_of_parts_is_not_joined():
    dots = "".join(f'<circle cx="{x}" cy="{y}" r="0.4" fill="#000"/>' for x in (2.5, 7.5) for y in (2.5, 7.5))
    t = tile(dots + f'<path d="M4 5H6" {STROKE}/>')
    assert len(t) == 5 and set(t.pieces.tolist()) == {1}
    lone = tile("", head=_scattered_pairs(False))
    assert len(lone) == 12 and set(lone.pieces.tolist()) == {2}


def test_round_trip_is_exact():
    t = tile(f'<polygon points="1,1 4,1 1,2" {STROKE}/><polygon points="7,6 7,9 6,6" {STROKE}/>'
             f'<line x1="8" y1="1" x2="10" y2="1" {STROKE}/><line x1="0" y1="1" x2="1" y2="1" {STROKE}/>')  # fmt: skip
    ex = parse_exemplar(t.text)
    assert ex.period == (10.0, 10.0)
    assert len(ex.motifs) == len(t)
    np.testing.assert_allclose(ex.motifs.xy, t.xy, atol=1e-4)
    np.testing.assert_allclose(ex.motifs.angle, np.round(t.angle, 4), atol=1e-4)
    assert ex.motifs.kind.tolist() == t.kind.tolist()
    assert ex.region.equals(shapely.box(0, 0, 10, 10))


def test_bad_period_attribute_is_a_clear_error():
    text = tile(f'<circle cx="5" cy="5" r="1" {STROKE}/>').text.replace('period="10 10"', 'period="10 x"')
    with pytest.raises(ExemplarError, match="period"):
        parse_exemplar(text)


# ----------------------------------------------------------------------------- periodic analysis


def test_periodic_distances_measure_across_the_edges():
    square = Prototype.from_geometry(shapely.box(-0.5, -0.5, 0.5, 0.5), tolerance=0.0)
    arr = Arrangement(np.array([0, 0]), np.array([[1.0, 5.0], [8.0, 5.0]]), np.zeros(2), np.ones(2))
    plain, _, _ = distance_matrix(arr, [square])
    wrapped, measured, overlaps = periodic_distance_matrix(arr, [square], (10.0, 10.0))
    assert plain[0, 0] == pytest.approx(6.0)
    assert wrapped[0, 0] == pytest.approx(2.0)  # 8 -> 11 is 3 apart, less the two half widths
    assert measured[0, 0] and overlaps == 0


def test_periodic_overlap_across_an_edge_counts_once():
    square = Prototype.from_geometry(shapely.box(-1, -1, 1, 1), tolerance=0.0)
    arr = Arrangement(np.array([0, 0]), np.array([[0.5, 5.0], [9.0, 5.0]]), np.zeros(2), np.ones(2))
    assert distance_matrix(arr, [square])[2] == 0
    assert periodic_distance_matrix(arr, [square], (10.0, 10.0))[2] == 1


def test_analyze_honours_the_period():
    t = tile(f'<circle cx="1" cy="5" r="0.5" {STROKE}/><circle cx="8.5" cy="5" r="0.5" {STROKE}/>')
    ex = parse_exemplar(t.text)
    gap = analyze(ex).distance[0, 0]
    flat = parse_exemplar(t.text.replace(' svgtile:period="10 10"', ""))
    assert flat.period is None
    assert gap == pytest.approx(2.5 - 1.2, abs=0.05)  # prototypes are slightly grown outlines
    assert analyze(flat).distance[0, 0] == pytest.approx(7.5 - 1.2, abs=0.05)


# ----------------------------------------------------------------------------- real symbol sets


@needs_data
def test_fgdc_730_is_43_motifs_of_one_kind():
    t = import_tile(FGDC / "730.svg")
    assert len(t) == 43 and t.kinds == 1


@needs_data
@pytest.mark.parametrize("other", ["IGM_fixedcolor/igm730.svg", "IGM/igm730.svg"])
def test_second_vectorisation_of_730_gives_the_same_motif_set(other):
    a, b = import_tile(FGDC / "730.svg"), import_tile(CEC / other)
    assert (len(b), b.kinds) == (len(a), a.kinds)
    ea, eb = parse_exemplar(a.text), parse_exemplar(b.text)
    assert eb.kinds[0].prototype.area == pytest.approx(ea.kinds[0].prototype.area, rel=0.01)

    def spacing(ex):  # nearest periodic neighbour of every motif: invariant under the y-flip
        w, h = ex.period
        xy = ex.motifs.xy
        d = xy[:, None, :] - xy[None, :, :]
        d -= np.round(d / [w, h]) * [w, h]
        r = np.hypot(d[..., 0], d[..., 1])
        np.fill_diagonal(r, np.inf)
        return np.sort(r.min(axis=1))

    np.testing.assert_allclose(spacing(eb), spacing(ea), atol=0.02)


@needs_data
def test_fgdc_729_pairs_two_lines_into_one_motif():
    t = import_tile(FGDC / "729.svg")
    lines = len(re.findall(r"<line ", (FGDC / "729.svg").read_text()))
    assert t.pieces.sum() == lines == 114
    # every motif is one pair; pairs cut at the tile's edge come back as two pairs of halves
    assert set(t.pieces[~t.wrapped].tolist()) == {2}
    assert set(t.pieces[t.wrapped].tolist()) <= {2, 4}
    assert len(t) == 56


@needs_data
def test_fgdc_dots_have_the_stroke_diameter():
    text = (FGDC / "601.svg").read_text()
    dot = re.search(r'style="[^"]*stroke-width:([0-9.]+);stroke-linecap:round;[^"]*" x1="([^"]+)" y1="([^"]+)" x2="\2" y2="\3"', text)
    width = float(dot.group(1))
    ex = parse_exemplar(import_tile(FGDC / "601.svg").text)
    common = int(np.argmax(np.bincount(ex.motifs.kind)))
    x0, y0, x1, y1 = ex.kinds[common].footprint.bounds
    assert (x1 - x0, y1 - y0) == (pytest.approx(width, rel=0.01), pytest.approx(width, rel=0.01))


@needs_data
def test_malformed_file_is_a_clear_error(capsys):
    bad = CEC / "SED_fixedcolor" / "sed663.svg"
    with pytest.raises(ExemplarError, match=r"sed663\.svg: not a well-formed XML file"):
        import_tile(bad)
    assert main(["import", str(bad), "-o", "-"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "sed663.svg" in err[0]


@needs_data
@pytest.mark.parametrize("code, why", [("624", "hatching"), ("658", "solid fill"), ("703", "continuous")])
def test_fgdc_non_discrete_patterns_are_refused_as_scatters(code, why):
    """The scatter stage refuses them; since issue 15 import_tile reads them as cellular patterns
    (tests/test_cellular_import.py), and only a tile that is not bedded stays refused."""
    with pytest.raises(TileRefused, match=why):
        import_pieces(parse_tile((FGDC / f"{code}.svg").read_bytes(), source=f"{code}.svg"))
    assert import_tile(FGDC / f"{code}.svg").cellular is not None


@needs_data
def test_fgdc_contorted_foliation_is_still_refused():
    with pytest.raises(TileRefused, match="continuous"):
        import_tile(FGDC / "706.svg")


def flattened(path: Path) -> tuple[str, np.ndarray]:
    """A jsdotpattern tile flattened the way osm-carto's svg_pattern.sh does: every unique
    instance's outline (cut at the tile's edge, the cut-off parts wrapped round) in one compound
    path.  Returns the SVG and the ground-truth kind of each unique instance."""
    ex = read_exemplar(path)
    x0, y0, x1, y1 = ex.region.bounds
    w, h = x1 - x0, y1 - y0
    arr = ex.motifs
    key = np.round(np.mod(arr.xy - [x0, y0], [w, h]), 3) % [w, h]
    _, first = np.unique(np.c_[arr.kind, key], axis=0, return_index=True)
    arr = arr.take(np.sort(first))
    box = shapely.box(x0, y0, x1, y1)
    d = []
    for k, xy, angle in zip(arr.kind, arr.xy, np.radians(arr.angle), strict=True):
        c, s = np.cos(angle), np.sin(angle)
        world = shapely.transform(ex.kinds[k].footprint, lambda p, c=c, s=s, xy=xy: p @ np.array([[c, s], [-s, c]]) + xy)
        for dx in (-w, 0, w):
            for dy in (-h, 0, h):
                for poly in shapely.get_parts(shapely.intersection(shapely.transform(world, lambda p, dx=dx, dy=dy: p + np.array((dx, dy))), box)):
                    if poly.geom_type == "Polygon" and poly.area > 0:
                        pts = shapely.get_coordinates(poly.exterior)[:-1]
                        d.append("M" + " L".join(f"{x:.4f} {y:.4f}" for x, y in pts) + " Z")
    svg = (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{x0:g} {y0:g} {w:g} {h:g}">'
           f'<rect x="{x0:g}" y="{y0:g}" width="{w:g}" height="{h:g}" fill="none"/>'
           f'<path fill="#6b8d5e" d="{" ".join(d)}"/></svg>')  # fmt: skip
    return svg, arr.kind


@needs_data
@pytest.mark.parametrize(
    "name",
    [
        "scrub",
        "wetland",
        "marsh",
        "swamp",
        "reed",
        "bog",
        "mangrove",
        "reef",
        "salt-dots-2",
    ],
)
def test_osm_flattened_patterns_recover_the_ground_truth(name):
    """Every jsdotpattern tile whose classes differ in shape (beach's 78 classes are rotations of
    one pebble, so kinds up to rotation cannot match them; rock layers two of its 310 defs at each of
    its 900 positions, so its uses are not motifs)."""
    svg, truth = flattened(OSM / f"{name}.svg")
    t = import_pieces(parse_tile(svg, source=name))
    assert len(t) == len(truth)
    assert sorted(np.bincount(t.kind).tolist()) == sorted(np.bincount(truth).tolist())


# ----------------------------------------------------------------------------- command line


def _tile(tmp_path):
    """A 10 × 10 tile of two triangles and a dash cut by its edge (3 motifs, 2 kinds)."""
    src = tmp_path / "tile.svg"
    src.write_text(HEAD + f'<polygon points="1,1 4,1 1,2" {STROKE}/><polygon points="7,6 7,9 6,6" {STROKE}/>'
                   f'<line x1="8" y1="4" x2="10" y2="4" {STROKE}/><line x1="0" y1="4" x2="1" y2="4" {STROKE}/></svg>')  # fmt: skip
    return src


def test_cli_import_and_synth_import(tmp_path, capsys):
    src = _tile(tmp_path)
    before = src.read_bytes()
    out = tmp_path / "ex.svg"
    assert main(["import", str(src), "-o", str(out)]) == 0
    assert "3 motif(s) of 2 kind(s), 1 reassembled" in capsys.readouterr().err
    assert len(read_exemplar(out).motifs) == 3
    a, b = tmp_path / "a.svg", tmp_path / "b.svg"
    assert main(["synth", str(src), "--import", "--size", "40", "--seed", "3", "-o", str(a)]) == 0
    assert main(["synth", str(out), "--size", "40", "--seed", "3", "-o", str(b)]) == 0
    assert 'imported="tile"' in a.read_text() and "imported=" not in b.read_text()  # for svgtile score
    strip = lambda p: re.sub(r' imported="tile"|exemplar="[^"]*"', "", p.read_text())  # noqa: E731
    assert strip(a) == strip(b)
    assert src.read_bytes() == before


def test_score_imports_the_tile_a_texture_was_made_from(tmp_path, capsys):
    src = _tile(tmp_path)
    before = src.read_bytes()
    made = tmp_path / "made.svg"
    assert main(["synth", str(src), "--import", "--size", "60", "--seed", "3", "-o", str(made)]) == 0
    capsys.readouterr()
    # its run record says the tile was imported: score imports it too, and says so
    assert main(["score", str(src), str(made), "--json"]) == 0
    out, err = capsys.readouterr()
    assert "(synth --import): importing" in err and "--no-import" in err
    assert main(["score", str(src), str(made), "--json", "--import"]) == 0
    again, err = capsys.readouterr()
    assert again == out and "(synth --import)" not in err  # asked for: the same figures, no note
    # svgtile's import of the tile under the tile's own name is not imported again: the same figures
    (tmp_path / "imported").mkdir()
    same_name = tmp_path / "imported" / "tile.svg"
    assert main(["import", str(src), "-o", str(same_name)]) == 0
    capsys.readouterr()
    assert main(["score", str(same_name), str(made), "--json"]) == 0
    mine, err = capsys.readouterr()
    assert "(synth --import)" not in err
    strip = lambda text: re.sub(r'"exemplar": "[^"]*"', "", text)  # noqa: E731
    assert strip(mine) == strip(out)
    # --no-import: the raw tile as drawn, whose kinds are not the texture's
    assert main(["score", str(src), str(made), "--no-import"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "made.svg" in err[0] and "pass --import" in err[0]
    # a texture made from the imported file records no import: the raw tile needs --import, and
    # without it the one-line error says so
    ex = tmp_path / "ex.svg"
    assert main(["import", str(src), "-o", str(ex)]) == 0
    plain = tmp_path / "plain.svg"
    assert main(["synth", str(ex), "--size", "60", "--seed", "3", "-o", str(plain)]) == 0
    capsys.readouterr()
    assert main(["score", str(src), str(plain)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "plain.svg" in err[0] and "--import" in err[0]
    assert main(["score", str(src), str(plain), "--import"]) == 0
    # a record of another file's import is not this exemplar's: no import is made for it
    other = tmp_path / "other.svg"
    other.write_bytes(src.read_bytes())
    capsys.readouterr()
    assert main(["score", str(other), str(made)]) == 1
    assert "(synth --import)" not in capsys.readouterr().err
    assert src.read_bytes() == before


def test_synth_import_records_the_import_alike_whole_and_tiled(tmp_path):
    src = _tile(tmp_path)
    whole, tiled = tmp_path / "whole.svg", tmp_path / "tiled.svg"
    args = ["synth", str(src), "--import", "--size", "60", "--seed", "3"]
    assert main([*args, "-o", str(whole)]) == 0
    assert main([*args, "-o", str(tiled), "--tile-size", "25"]) == 0
    assert 'imported="tile"' in whole.read_text() and tiled.read_bytes() == whole.read_bytes()


def test_compare_imports_a_tile_and_its_textures_say_so(tmp_path, capsys):
    pytest.importorskip("resvg_py")
    src = _tile(tmp_path)
    folder = tmp_path / "cmp"
    assert main(["compare", str(src), "--import", "--size", "60", "--engines", "tile,random", "--png", str(folder)]) == 0
    assert "likeness L" in capsys.readouterr().out
    texture = folder / "random.svg"
    assert 'imported="tile"' in texture.read_text()
    assert main(["score", str(src), str(texture)]) == 0
    assert "(synth --import): importing" in capsys.readouterr().err


def test_cli_refused_tile_is_one_line(tmp_path, capsys):
    src = tmp_path / "hatch.svg"
    # a zigzag joining its own repeat: continuous, and no bedding rows (a straight line would be one)
    src.write_text(HEAD + f'<polyline points="0,5 2.5,1 5,9 7.5,1 10,5" {STROKE}/></svg>')
    out = tmp_path / "ex.svg"
    assert main(["import", str(src), "-o", str(out)]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "hatch.svg" in err[0] and "hatching" in err[0]
    assert not out.exists()


@needs_data
def test_every_fgdc_lithology_tile_imports_and_synthesizes_cleanly_or_is_refused():
    """Issue 4's done-when: every one of the 116 tiles is either refused with a reason or imports
    and synthesizes (patch engine, 1.5 x 1.5 tiles) with no overlap and no rule violation."""
    from conftest import arrange

    from svgtile.core.region import Region
    from svgtile.metrics import conflict_counts

    files = sorted(FGDC.glob("*.svg"))
    assert len(files) == 116
    accepted, problems = 0, []
    for path in files:
        try:
            t = import_tile(path)
        except TileRefused as exc:
            assert any(why in str(exc) for why in ("not discrete motifs", "solid fill", "leave out")), str(exc)
            continue
        if t.cellular is not None:  # bedded and brick tiles: tests/test_cellular_import.py
            continue
        ex = parse_exemplar(t.text, source=str(path))
        stats = analyze(ex)
        x0, y0, w, h = t.box
        region = Region.rectangle(1.5 * w, 1.5 * h, x0, y0)
        arr = arrange("patch", ex, region, rng=np.random.default_rng(0), stats=stats)
        found = conflict_counts(arr, ex.prototypes, stats, np.ones(len(arr), dtype=bool))
        if len(arr) == 0 or found.overlaps_total or found.violators_total:
            problems.append((path.name, len(arr), found.overlaps_total, found.violators_total))
        accepted += 1
    assert not problems
    assert accepted >= 58  # 61 of 116 at the time of writing; a drop means a regression


@pytest.mark.parametrize(
    ("head", "message"),
    [
        ('viewBox="0 0 1e308 1e308"', "tile .* is not finite or beyond"),
        ('width="1e300" height="5"', "tile .* is not finite or beyond"),
    ],
)
def test_tile_of_overflowing_size_is_refused(head, message):
    with pytest.raises(ExemplarError, match=message):
        parse_tile(f'<svg xmlns="http://www.w3.org/2000/svg" {head}><circle cx="5" cy="5" r="1"/></svg>', source="t.svg")


def test_shape_blown_up_by_a_transform_is_refused():
    svg = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 50 50">'
           '<g transform="scale(1e150)"><circle r="1"/></g><circle cx="5" cy="5" r="1"/></svg>')  # fmt: skip
    with pytest.raises(ExemplarError, match="transform"):
        parse_tile(svg, source="t.svg")


# ----------------------------------------------------------------------------- whole icons (issue 12.5)


def test_subpaths_of_one_path_stay_one_icon_unless_they_stand_apart():
    """A paw drawn as one <path> of a pad and four toes is one motif; dashes drawn as one
    <path> of subpaths a pattern spacing apart stay separate motifs."""
    paw = ('<path d="M4 5 h2 v1.6 h-2 z M3.6 3.9 h0.6 v0.6 h-0.6 z M4.5 3.5 h0.6 v0.6 h-0.6 z '
           'M5.4 3.5 h0.6 v0.6 h-0.6 z M6.3 3.9 h0.6 v0.6 h-0.6 z" fill="#000"/>')  # fmt: skip
    t = tile(paw)
    assert len(t.kind) == 1
    dashes = '<path d="M1 2 h2 M6 2 h2 M1 7 h2 M6 7 h2" stroke="#000" stroke-width="0.3"/>'
    assert len(tile(dashes).kind) == 4


@needs_data
@pytest.mark.parametrize(("name", "motifs", "kinds"), [("dog_park", 2, 1), ("grave_yard_muslim", 1, 1)])
def test_osm_icons_are_imported_whole(name, motifs, kinds):
    t = import_tile(DATA / "osm-carto" / "patterns" / f"{name}.svg")
    assert (len(t.kind), int(t.kind.max()) + 1) == (motifs, kinds)


@needs_data
def test_fgdc_626_pieces_that_almost_touch_are_one_motif_and_nothing_overlaps():
    t = import_tile(FGDC / "626.svg")
    stats = analyze(parse_exemplar(t.text, source="626.svg"))
    assert stats.overlaps == 0


def test_import_writes_svgtile_prefixes_whatever_was_imported_first(tmp_path):
    """ElementTree's prefixes are process-wide: registered where the namespaces are defined
    (svg/dialect), so an import run in a fresh process (as ``svgtile import`` is, its command
    loaded alone) writes ``svgtile:period``, never ``ns0:``/``ns1:`` — found by this suite when
    test_import ran first."""
    import subprocess
    import sys

    src = tmp_path / "tile.svg"
    src.write_text(HEAD + f'<circle cx="1" cy="5" r="0.5" {STROKE}/><circle cx="8.5" cy="5" r="0.5" {STROKE}/></svg>')
    code = f"from svgtile.tiles.importer import import_tile; print(import_tile({str(src)!r}).text)"
    text = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "svgtile:period=" in text and "ns0:" not in text and "ns1:" not in text


# ----------------------------------------------------------------------------- groups and own overlaps (issue 12.5)

XLINK_HEAD = '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 10 10">'
#: A paw as five separate shapes: a pad and four toes 0.1–0.5 apart (none touching).
PAW = ('<rect x="4" y="5" width="2" height="1.6"/><rect x="3.6" y="3.9" width="0.6" height="0.6"/>'
       '<rect x="4.5" y="3.5" width="0.6" height="0.6"/><rect x="5.4" y="3.5" width="0.6" height="0.6"/>'
       '<rect x="6.3" y="3.9" width="0.6" height="0.6"/>')  # fmt: skip


def own_overlap_count(t) -> int:
    return analyze(parse_exemplar(t.text, source="t.svg")).overlaps


def test_children_of_one_group_stay_one_icon_unless_they_stand_apart():
    """A paw drawn as a <g> of five shapes is one motif (ungrouped, the toes are motifs of their
    own); a <g> of dashes a pattern spacing apart stays four motifs, small or large."""
    assert (len(tile(f"<g>{PAW}</g>")), len(tile(PAW))) == (1, 5)
    assert len(tile('<g stroke="#000" stroke-width="0.3"><path d="M1 2 h2"/><path d="M6 2 h2"/>'
                    '<path d="M1 7 h2"/><path d="M6 7 h2"/></g>')) == 4  # fmt: skip
    small = ('<g stroke="#000" stroke-width="0.1"><path d="M1 1 h0.5"/><path d="M3.5 1 h0.5"/>'
             '<path d="M1 3.5 h0.5"/><path d="M3.5 3.5 h0.5"/></g><circle cx="8" cy="8" r="0.2"/>')  # fmt: skip
    assert len(tile(small)) == 5


def test_an_icon_used_in_two_places_is_two_whole_motifs_of_one_kind():
    t = tile(f'<defs><g id="paw" transform="scale(0.5)">{PAW}</g></defs>'
             '<use xlink:href="#paw"/><use xlink:href="#paw" x="5" y="5"/>', head=XLINK_HEAD)  # fmt: skip
    assert (len(t), t.kinds, t.pieces.tolist()) == (2, 1, [5, 5])


def test_a_group_cut_at_the_tile_edge_is_one_motif():
    """The paw drawn across the right edge (two toes beyond it) and again a period to the left,
    as jsdotpattern writes periodic copies: the wrapped pieces are still one icon."""
    moved = f'<g transform="translate(4.5 0)">{PAW}</g><g transform="translate(-5.5 0)">{PAW}</g>'
    t = tile(moved)
    assert (len(t), t.pieces.tolist(), bool(t.wrapped[0])) == (1, [5], True)


def test_a_motif_inside_anothers_outline_is_joined_to_it():
    """A ring of two arcs (closed only together) round a dot: as separate motifs the ring's
    footprint would cover the dot; the importer joins them.  A dot outside stays apart."""
    ring = (f'<path d="M3 5 A2 2 0 0 1 7 5" {STROKE}/><path d="M7 5 A2 2 0 0 1 3 5" {STROKE}/>')
    t = tile(ring + '<circle cx="5" cy="5" r="0.3"/>')
    assert (len(t), own_overlap_count(t)) == (1, 0)
    assert any("joined 1 pair" in n for n in t.notes)
    apart = tile(ring + '<circle cx="9" cy="9" r="0.3"/>')
    assert (len(apart), own_overlap_count(apart), apart.notes) == (2, 0, ())


def test_a_near_copy_that_would_overlap_a_neighbour_keeps_its_own_drawing():
    """Two rectangles 7 % apart in width match as one kind, drawn as the first (wider) one; in
    the second's place that drawing would cover the dot 0.04 beside it.  The second gets a kind
    of its own, and the exemplar has no overlap."""
    body = '<rect x="0.93" y="2" width="2.14" height="1"/><rect x="5" y="7" width="2" height="1"/><circle cx="7.19" cy="7.5" r="0.15"/>'
    t = tile(body)
    assert (len(t), t.kinds, own_overlap_count(t)) == (3, 3, 0)
    assert any("keep their own drawing" in n for n in t.notes)
    far = tile(body.replace('cx="7.19"', 'cx="8.5"'))  # nothing near: one kind for both rectangles
    assert (far.kinds, own_overlap_count(far)) == (2, 0)


@needs_data
@pytest.mark.parametrize("name", ["scrub", "wetland", "marsh", "swamp", "reed", "bog", "mangrove", "reef", "salt-dots-2"])
def test_osm_jsdotpattern_tiles_import_one_motif_per_use(name):
    """The raw jsdotpattern files draw each motif as a <use> of a <g> def, with periodic copies
    written out: the import has one motif per unique use and the classes of the defs (marsh,
    reed, bog and mangrove split icons cut at the edge before <g> grouping: 489–491 motifs)."""
    _, truth = flattened(OSM / f"{name}.svg")
    t = import_tile(OSM / f"{name}.svg")
    assert len(t) == len(truth)
    assert sorted(np.bincount(t.kind).tolist()) == sorted(np.bincount(truth).tolist())


@needs_data
@pytest.mark.parametrize(
    "path",
    [
        "fgdc-geologic-patterns/lithology/614.svg",  # a lens drawn as its kind's first reached a dot
        "equinor-lithology/svg/11030.svg",  # dots 0.1–0.2 from pebbles
        "equinor-lithology/svg/11026.svg",  # pebbles and dashes 0.2 apart along each row
    ],
)
def test_real_tiles_drawn_a_hair_apart_import_without_overlaps_or_joins(path):
    """Motifs the tile draws 0.1–0.2 apart, within the default outline's tolerance: the outlines
    once met, and the importer joined them (11030), gave them kinds of their own (614) or, where
    joined they would have made an endless row, left the exemplar overlapping (11026).  The
    exemplar's prototypes now keep apart what the drawing keeps apart
    (:func:`svgtile.core.footprint.separated`): no overlap, nothing joined."""
    t = import_tile(DATA / path)
    assert own_overlap_count(t) == 0
    assert not any("joined" in n or "keep their own drawing" in n for n in t.notes), t.notes


def test_motifs_that_would_join_their_own_repeat_are_not_joined():
    """Motif 0 overlaps motif 1 five units on, and motif 1 overlaps motif 0 five units on: joined,
    0 would be its own repeat ten units on (a continuous pattern), so nothing is joined."""
    from svgtile.tiles.overlaps import merge_motifs

    pairs, shift = np.array([[0, 1], [1, 0]]), np.array([[5.0, 0.0], [5.0, 0.0]])
    got = merge_motifs(np.array([0, 1]), np.zeros((2, 2)), np.zeros((2, 2)), pairs, shift)
    assert got == "a motif would join its own repeat"
    closed = merge_motifs(np.array([0, 1]), np.zeros((2, 2)), np.zeros((2, 2)), pairs[:1], shift[:1])
    assert not isinstance(closed, str) and closed[0].tolist() == [0, 0]
