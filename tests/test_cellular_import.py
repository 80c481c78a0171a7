"""Bedded and brick tiles imported as cellular exemplars (issue 15, item 6), and synthesized."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile.analysis.stats import analyze
from svgtile.cli.main import main
from svgtile.core.cells import LINE
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.svg.reader import parse_exemplar, read_exemplar
from svgtile.svg.tilepieces import parse_tile
from svgtile.tiles.importer import TileRefused, import_bedded, import_tile

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"
FGDC = DATA / "fgdc-geologic-patterns" / "lithology"
needs_data = pytest.mark.skipif(not FGDC.is_dir(), reason="../shared/data (real symbol sets) is not beside the checkout")

HEAD = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 40 40">'
STROKE = 'fill="none" stroke="#000" stroke-width="0.3"'


def bricks(rows: int = 4, length: float = 20.0) -> str:
    """A hand-made limestone tile: 4 courses of 10, bricks 20 long in running bond, a dot in each."""
    h = 40 / rows
    parts = [f'<line x1="0" y1="{j * h}" x2="40" y2="{j * h}" {STROKE}/>' for j in range(rows)]
    for j in range(rows):
        for i in range(int(40 / length)):
            x = (i + 0.5 * (j % 2)) * length
            parts.append(f'<line x1="{x}" y1="{j * h}" x2="{x}" y2="{(j + 1) * h}" {STROKE}/>')
    return HEAD + "".join(parts) + "</svg>"


def imported(text: str, tmp_path: Path):
    src = tmp_path / "tile.svg"
    src.write_text(text)
    return import_tile(src)


def test_a_brick_tile_gives_courses_lengths_and_the_bond(tmp_path):
    t = imported(bricks(), tmp_path)
    d = t.cellular
    assert d["course"] == pytest.approx(10.0)
    assert d["length"] == pytest.approx(20.0)
    assert d["offset"] == pytest.approx(0.5)
    assert d["cell_style"].startswith("fill:none;stroke:#000") and "stroke-width:0.3" in d["cell_style"]
    assert "lines" not in d  # the cells' outlines draw the solid bedding
    ex = parse_exemplar(t.text, source="tile.svg")
    assert ex.cellular == d and len(ex.motifs) == 0


def test_a_dashed_bedding_tile_gives_dashes_per_row(tmp_path):
    rows = []
    for j in range(4):  # dashes 6 on, 4 off, each row shifted by half a period
        for i in range(4):
            x = (i * 10 + 5 * (j % 2)) % 40
            rows.append(f'<line x1="{x}" y1="{j * 10 + 5}" x2="{x + 6}" y2="{j * 10 + 5}" {STROKE}/>')
    # discrete dashes import as a scatter; the cellular reading of the same tile:
    tile = parse_tile(HEAD + "".join(rows) + "</svg>", source="dashes.svg")
    d = import_bedded(tile, TileRefused("unused", source="dashes.svg")).cellular
    assert d["course"] == pytest.approx(10.0)
    assert len(d["lines"]) == 4
    assert all(spec["dash"] == pytest.approx([6.0, 4.0]) and spec["every"] == 4 for spec in d["lines"])
    shifts = sorted(spec["shift"] for spec in d["lines"])
    assert shifts == pytest.approx([0.0, 0.0, 0.5, 0.5])


def test_a_zigzag_is_still_refused_with_the_reason(tmp_path):
    text = HEAD + f'<polyline points="0,20 10,2 20,38 30,2 40,20" {STROKE}/></svg>'
    with pytest.raises(TileRefused, match="continuous"):
        imported(text, tmp_path)


def test_synth_imports_and_draws_the_bricks(tmp_path, capsys):
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    out = tmp_path / "out.svg"
    # once, in a whole-suite run on a loaded machine, this exited 70 (not reproduced since): the
    # message says why if it happens again
    rc = main(["synth", str(src), "--import", "--size", "100x60", "--seed", "2", "-o", str(out)])
    assert rc == 0, capsys.readouterr().err
    text = out.read_text()
    assert 'engine="cellular"' in text and text.count('class="svgtile-face"') > 10
    ex = tmp_path / "ex.svg"
    assert main(["import", str(src), "-o", str(ex)]) == 0
    assert read_exemplar(ex).cellular["length"] == pytest.approx(20.0)
    again = tmp_path / "again.svg"
    assert main(["synth", str(ex), "--size", "100x60", "--seed", "2", "-o", str(again)]) == 0
    strip = lambda p: p.read_text().split("<defs")[1]  # noqa: E731 (the metadata names the exemplar)
    assert strip(out) == strip(again)


@needs_data
def test_fgdc_limestone_627():
    t = import_tile(FGDC / "627.svg")
    d = t.cellular
    assert d["course"] == pytest.approx(54.125 / 14, rel=1e-3)  # 14 bedding lines per tile
    assert d["length"] == pytest.approx(54.125 / 4, rel=1e-3)  # 4 bricks per course
    assert abs(d["offset"] - 0.5) < 0.05
    # the stubs of the joints the tile's bottom edge cuts are parts of joints, not motifs (ticks)
    assert len(t.kind) == 0 and "motifs" not in d


def test_joint_stubs_cut_by_the_tile_edge_belong_to_their_joints(tmp_path):
    """The bricks tile moved down by 2: the last course's joints cross the tile's edge, drawn as
    strokes of 8 at the bottom and stubs of 2 at the top (a fifth of a course, too short to be
    joints themselves)."""
    parts = [f'<line x1="0" y1="{j * 10 + 2}" x2="40" y2="{j * 10 + 2}" {STROKE}/>' for j in range(4)]
    for j in range(4):
        for i in range(2):
            x = (i + 0.5 * (j % 2)) * 20
            y0, y1 = j * 10 + 2, j * 10 + 12
            if y1 <= 40:
                parts.append(f'<line x1="{x}" y1="{y0}" x2="{x}" y2="{y1}" {STROKE}/>')
            else:
                parts.append(f'<line x1="{x}" y1="{y0}" x2="{x}" y2="40" {STROKE}/>')
                parts.append(f'<line x1="{x}" y1="0" x2="{x}" y2="{y1 - 40}" {STROKE}/>')
    t = imported(HEAD + "".join(parts) + "</svg>", tmp_path)
    d = t.cellular
    assert d["course"] == pytest.approx(10.0) and d["length"] == pytest.approx(20.0)
    assert len(t.kind) == 0 and "motifs" not in d


@needs_data
@pytest.mark.parametrize(("code", "least"), [("657", 20)])
def test_fgdc_fragments_drawn_over_the_linework_are_kept(code, least):
    """Peat's fragments (657) are larger than a course and drawn over the lines: imported as
    motifs laid over the cells, placed at the tile's bearing, not turned by the courses' 135°.
    (Ore's lenses, 733, were the second case: its cross-hatched bands, 66 % of its strokes, are
    left out by any reading as courses, so the tile is refused: test_fgdc_tiles_whose_cells_would_leave_out_a_quarter_are_refused.)"""
    t = import_tile(FGDC / f"{code}.svg")
    assert len(t.kind) >= least and t.cellular["motifs"].get("over") is True
    ex = parse_exemplar(t.text, source=code)
    stats = analyze(ex)
    w = t.box[2]
    r = synthesize(ex, Region(shapely.box(0, 0, 2 * w, 2 * w)), "cellular", seed=1, stats=stats, boundary="inside")
    assert len(r.arrangement) >= least  # (before: 0 of 733's, a few of 657's)
    arc = (r.arrangement.angle - stats.arc_start[r.arrangement.kind]) % 360.0
    assert (arc <= stats.arc_width[r.arrangement.kind] + 1e-6).all()


@needs_data
def test_import_and_synth_give_a_texture_for_105_of_the_116_fgdc_tiles():
    """Issue 15's done-when: scatter or cellular, at least 105 textures and no crash.  Cellular
    ones are synthesized on a small L-shaped unit (courses, no overlap, inside)."""
    files = sorted(FGDC.glob("*.svg"))
    assert len(files) == 116
    textures, cellular, refused = 0, 0, []
    for path in files:
        try:
            t = import_tile(path)
        except TileRefused as exc:
            refused.append(path.stem)
            assert "continuous" in str(exc) or "leave out" in str(exc), str(exc)
            continue
        textures += 1
        if t.cellular is None:
            continue  # scatter tiles: tests/test_import.py synthesizes each one
        ex = parse_exemplar(t.text, source=str(path))
        w = t.box[2]
        unit = shapely.Polygon([(0, 0), (1.2 * w, 0), (1.2 * w, 0.5 * w), (0.6 * w, 0.5 * w), (0.6 * w, w), (0, w)])
        r = synthesize(ex, Region(unit), "cellular", seed=0, stats=analyze(ex), boundary="inside")
        assert len(r.cells) > 0, path.name
        cells = r.cells.cells
        assert shapely.covered_by(cells, shapely.buffer(unit, 1e-3)).all(), path.name
        lines = r.cells.shapes[r.cells.feature == LINE]
        assert shapely.covered_by(lines, shapely.buffer(unit, 1e-3)).all(), path.name
        cellular += 1
    # 105 at the time of writing (44 cellular); refused: 630 632 633 634 643 649 650 651 706 707 720 —
    # cross-bedding, hexagons, brick ends drawn as arcs, contorted foliation.  102 since issue 12's
    # linework figure (2026-12-04): 705, 709 and 733 were accepted as cells that left out 40–66 %
    # of their strokes (tests/test_cellular_linework.py), now refused with that share
    assert textures >= 102, f"{textures} textures; refused: {refused}"
    assert {"705", "709", "733"} <= set(refused)
    assert cellular >= 40
    assert np.isin(["627", "641", "624", "658"], [f.stem for f in files]).all()


@needs_data
@pytest.mark.parametrize(("code", "share"), [("705", "40%"), ("709", "44%"), ("733", "66%")])
def test_fgdc_tiles_whose_cells_would_leave_out_a_quarter_are_refused(code, share, capsys):
    """Drawn as cells, 709 (contorted gneiss) came out a grid of straight lines, 705 half as dark
    with its streaks, 733 hatching without its cross-hatched bands (linework figures, 709/705/733:
    S −1.01, 0.43, 0.06; ink 0.48, 0.58, 0.71): what the bedding and joints leave out is the pattern.  The
    refusal is one line giving the share, and 717 (14 % left out) is still read as cells."""
    with pytest.raises(TileRefused, match=f"leave out .*{share} of its stroke length"):
        import_tile(FGDC / f"{code}.svg")
    assert main(["import", str(FGDC / f"{code}.svg"), "-o", "-"]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"{code}.svg" in err[0] and share in err[0]
    assert import_tile(FGDC / "717.svg").cellular is not None


def test_import_bedded_reraises_the_refusal_for_nothing_bedded():
    tile = parse_tile(HEAD + f'<polyline points="0,20 10,2 20,38 30,2 40,20" {STROKE}/></svg>', source="z.svg")
    refusal = TileRefused("not discrete motifs: a test", source="z.svg")
    with pytest.raises(TileRefused, match="a test"):
        import_bedded(tile, refusal)
