"""Combinations of options that the merges of issues 11–19 brought together (merge review)."""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path

import pytest
from test_cellular_import import bricks

from svgtile.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
GRAVEL = ROOT / "exemplars" / "gravel.svg"


def test_a_cellular_texture_keeps_its_cells_with_scheduler_or_tile_size(tmp_path, capsys):
    # the tiled writers draw motifs only: the cells must not be dropped on the way
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    whole = tmp_path / "whole.svg"
    assert main(["synth", str(src), "--import", "--size", "100x60", "--seed", "2", "-o", str(whole)]) == 0
    assert whole.read_text().count('class="svgtile-face"') > 10
    for n, extra in enumerate([("--scheduler", "local"), ("--tile-size", "30")]):
        out = tmp_path / f"tiled{n}.svg"
        assert main(["synth", str(src), "--import", "--size", "100x60", "--seed", "2", "-o", str(out), *extra]) == 0
        assert out.read_bytes() == whole.read_bytes()
        assert "draws cells" in capsys.readouterr().err


def test_with_style_is_written_by_a_tiled_run_and_refused_for_cells(tmp_path, capsys):
    out = tmp_path / "t.geojson"
    args = ["synth", str(GRAVEL), "--engine", "tile", "--size", "60x60", "--seed", "1", "--with-style"]
    assert main([*args, "-o", str(out), "--tile-size", "30"]) == 0
    assert out.exists() and out.with_suffix(".qml").exists()
    assert any(out.with_name("t-symbols").iterdir())
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    cells = tmp_path / "c.geojson"
    capsys.readouterr()
    rc = main(["synth", str(src), "--import", "--size", "100x60", "--seed", "2", "--engine", "cellular", "--with-style",
              "-o", str(cells)])
    err = capsys.readouterr().err
    assert rc != 0 and not cells.exists() and "--with-style" in err and err.count("\n") == 1


def test_a_cellular_exemplar_without_motifs_gives_no_warnings(tmp_path, capsys):
    # the crowding check (issue 16) took the median of no radii for a brick tile of lines only (issue 15)
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    out = tmp_path / "out.svg"
    assert main(["synth", str(src), "--import", "--size", "100x60", "--seed", "2", "-o", str(out)]) == 0
    assert "warning" not in capsys.readouterr().err


def test_refine_crosses_no_barrier_and_stays_in_the_growth_area():
    # --refine (issue 14) moved growth's motifs (issue 13) across a --barrier: seed 1 put one on it
    import numpy as np
    import shapely

    from svgtile import analyze, read_exemplar
    from svgtile.core.footprint import world_footprints
    from svgtile.core.region import Region
    from svgtile.engines import Controls, synthesize

    ex = read_exemplar(GRAVEL)
    st = analyze(ex)
    bar = shapely.LineString([(40, -5), (42, 105)])
    spray = shapely.Point(40, 40).buffer(30)
    for controls, inside in ((Controls(barriers=bar), None), (Controls(grow_within=spray), spray)):
        runs = [synthesize(ex, Region.rectangle(80, 80), "growth", seed=1, stats=st, controls=controls, refine=r)
                for r in (0, 3)]  # fmt: skip
        plain, refined = (r.arrangement for r in runs)
        assert len(refined) == len(plain) and not np.array_equal(refined.xy, plain.xy)  # refine did move motifs
        if inside is None:
            assert not shapely.intersects(world_footprints(refined, ex.prototypes), bar).any()
        else:
            assert shapely.contains_xy(inside, refined.xy[:, 0], refined.xy[:, 1]).all()


def test_a_refined_tiled_run_says_why_it_runs_whole(tmp_path, capsys):
    # the tile engine is tile-exact: it is --refine that makes the run whole
    out = tmp_path / "r.svg"
    args = ["synth", str(GRAVEL), "--engine", "tile", "--size", "60x60", "--seed", "1", "--tile-size", "30"]
    assert main([*args, "--refine", "1", "-o", str(out)]) == 0
    assert "--refine 1 is not tile-exact" in capsys.readouterr().err
    assert main([*args, "-o", str(tmp_path / "t.svg")]) == 0
    assert "not tile-exact" not in capsys.readouterr().err


def test_a_label_map_is_an_input_the_output_may_not_overwrite(tmp_path, capsys):
    # the input guard (issue 16) read option values as paths, but --label (issue 15) is NAME=MAP.svg#ID
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    m = tmp_path / "map.svg"
    m.write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 60 60"><path id="river" d="M0 30 H60" '
                 'fill="none" stroke="#00f"/></svg>')  # fmt: skip
    before = m.read_bytes()
    rc = main(["synth", str(src), "--import", "--engine", "cellular", "--size", "60x60", "--seed", "1",
               "--label", f"edge={m}#river", "-o", str(m)])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 1 and m.read_bytes() == before and "refusing to overwrite an input file (--label" in err


@pytest.mark.parametrize("extra", [("--engine", "patch"), ("--engine", "growth"), ("--engine", "tile", "--tile-size", "30")])
def test_a_motif_engine_refuses_a_pattern_of_cells_only_in_one_line(tmp_path, capsys, extra):
    # issue 15 lets an imported brick tile have no motif; the motif engines crashed on it (exit 70)
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    ex = tmp_path / "ex.svg"
    assert main(["import", str(src), "-o", str(ex)]) == 0
    out = tmp_path / "out.svg"
    capsys.readouterr()
    rc = main(["synth", str(ex), "--size", "60x60", "--seed", "1", "-o", str(out), *extra])
    err = capsys.readouterr().err
    assert rc == 1 and not out.exists() and err.count("\n") == 1 and "--engine cellular or auto" in err


def test_analyze_rings_of_a_pattern_of_cells_only_is_one_line(tmp_path, capsys):
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    assert main(["analyze", str(src), "--import"]) == 0
    capsys.readouterr()
    assert main(["analyze", str(src), "--import", "--rings"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--rings shows the rings of motifs" in err


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes")
def test_a_tree_description_is_read_with_the_input_bound(tmp_path, capsys):
    # --tree (issue 15) read its file whole and unchecked; inputs are read by files.read_input (issue 16)
    ex = tmp_path / "ex.svg"
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    assert main(["import", str(src), "-o", str(ex)]) == 0
    fifo = tmp_path / "tree.toml"
    os.mkfifo(fifo)

    def feed() -> None:  # a writer for as long as a reader might come (else a read would block)
        end = time.monotonic() + 5
        while time.monotonic() < end:
            try:
                fd = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)
            except OSError:
                time.sleep(0.05)
                continue
            os.write(fd, b"x = [")
            os.close(fd)
            return

    threading.Thread(target=feed, daemon=True).start()
    capsys.readouterr()
    rc = main(["synth", str(ex), "--engine", "cellular", "--size", "60x60", "--seed", "1", "--tree", str(fifo),
               "-o", str(tmp_path / "out.svg")])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 1 and "not a regular file" in err and err.count("\n") == 1


def test_score_says_a_cellular_texture_is_not_measured(tmp_path, capsys):
    # score (issue 12.1) read a cellular texture's cells (issue 15) as motifs of unknown kinds
    src = tmp_path / "tile.svg"
    src.write_text(bricks())
    ex, out = tmp_path / "ex.svg", tmp_path / "out.svg"
    assert main(["import", str(src), "-o", str(ex)]) == 0
    assert main(["synth", str(ex), "--size", "60x60", "--seed", "1", "-o", str(out)]) == 0
    capsys.readouterr()
    assert main(["score", str(ex), str(out)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "a cellular texture" in err
