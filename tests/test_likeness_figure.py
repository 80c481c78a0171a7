"""Likeness L in the score (issue 12 item 1): known answers of E and L against the baselines."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from svgtile import analyze, read_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import likeness as order
from svgtile.metrics import score
from svgtile.svg.reader import parse_exemplar

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
STEP = 10.0  # lattice step of the periodic tile, user units
CELLS = 6  # the tile holds CELLS × CELLS motifs


def lattice_tile() -> str:
    """A periodic tile (as ``svgtile import`` writes one): a slightly jittered square lattice of
    dots and bars, the bars on a diagonal of their own, so that kinds and positions both matter."""
    rng = np.random.default_rng(4)
    side = CELLS * STEP
    uses = []
    for i in range(CELLS):
        for j in range(CELLS):
            x, y = (np.array([i, j]) + 0.5) * STEP + rng.normal(scale=0.4, size=2)
            href = "bar" if i == j else "dot"
            uses.append(f'<use xlink:href="#{href}" transform="translate({x:.3f} {y:.3f})"/>')
    return (
        '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
        f'xmlns:svgtile="urn:svgtile:run:1" viewBox="0 0 {side} {side}">'
        '<defs><symbol id="dot" overflow="visible"><circle r="1.5"/></symbol>'
        '<symbol id="bar" overflow="visible"><rect x="-2.5" y="-1" width="5" height="2"/></symbol></defs>'
        f'<rect id="region" x="0" y="0" width="{side}" height="{side}" fill="none" '
        f'svgtile:period="{side} {side}"/>{"".join(uses)}</svg>'
    )


@pytest.fixture(scope="module")
def tile():
    ex = parse_exemplar(lattice_tile(), source="lattice.svg")
    assert ex.period is not None and len(ex.motifs) == CELLS * CELLS
    return ex, analyze(ex)


def test_translated_copy_scores_zero_and_likeness_one(tile):
    ex, stats = tile
    region = Region.rectangle(400, 300)
    arr = synthesize(ex, region, "tile", seed=3, stats=stats).arrangement
    shift = np.array([137.3, -52.9])  # not a multiple of the period
    moved = dataclasses.replace(arr, xy=arr.xy + shift)
    s = score(ex, stats, moved, Region.rectangle(400, 300, *shift))
    assert s.neighbourhood_distance == pytest.approx(0.0, abs=1e-9)
    assert s.neighbourhood_tile == pytest.approx(0.0, abs=1e-9)  # a periodic tile's copies meet seamlessly
    assert s.neighbourhood_random > 1.0
    assert s.likeness == pytest.approx(1.0)


def test_lattice_against_a_scatter_scores_high_and_likeness_near_zero(tile):
    ex, stats = tile
    region = Region.rectangle(500, 500)
    scatter = synthesize(ex, region, "random", seed=9, stats=stats).arrangement
    s = score(ex, stats, scatter, region)
    assert s.neighbourhood_distance > 1.0
    assert abs(s.likeness) < 0.2  # another seed and region than the baseline's: noise only
    moved = synthesize(ex, region, "tile", seed=9, stats=stats).arrangement
    assert s.neighbourhood_distance > 20 * max(score(ex, stats, moved, region).neighbourhood_distance, 0.05)


@pytest.mark.parametrize("engine, expected", [("tile", 1.0), ("random", 0.0)])
def test_the_baselines_score_their_end_of_the_scale(engine, expected):
    ex = read_exemplar(EXEMPLARS / "gravel.svg")  # not periodic: tile's seams cost, E_tile > 0
    stats = analyze(ex)
    region = order.baseline_region(ex, stats)
    arr = synthesize(ex, region, engine, seed=order.BASELINE_SEED, stats=stats).arrangement
    s = score(ex, stats, arr, region)
    assert s.neighbourhood_tile > 0.05
    assert s.neighbourhood_random > 2 * s.neighbourhood_tile
    assert s.likeness == pytest.approx(expected, abs=1e-12)


def test_baselines_are_synthesized_once_per_exemplar(monkeypatch, tile):
    ex = parse_exemplar(lattice_tile(), source="lattice.svg")  # a fresh object: nothing cached
    stats = analyze(ex)
    calls = []
    real = order.synthesize
    monkeypatch.setattr(order, "synthesize", lambda *a, **kw: calls.append(a[2]) or real(*a, **kw))
    first = order.baseline_distances(ex, stats)
    assert calls == ["tile", "random"]
    assert order.baseline_distances(ex, stats) == first
    assert calls == ["tile", "random"]


def test_turns_follow_the_exemplars_arcs():
    kinds = {name: order.turns_allowed(analyze(read_exemplar(EXEMPLARS / f"{name}.svg")))
             for name in ("gravel", "boulders", "shale", "marsh", "till")}  # fmt: skip
    assert kinds == {"gravel": True, "boulders": True, "shale": False, "marsh": False, "till": False}


def test_the_same_texture_gives_the_same_figure_and_the_sample_is_bounded(tile):
    ex, stats = tile
    region = Region.rectangle(900, 900)
    arr = synthesize(ex, region, "random", seed=2, stats=stats).arrangement
    inside = np.ones(len(arr), dtype=bool)
    assert inside.sum() > order.SAMPLE
    a = order.texture_distance(ex, stats, arr, inside)
    b = order.texture_distance(ex, stats, arr, inside)
    assert a == b and math.isfinite(a)


def test_score_json_and_text_carry_the_likeness(tmp_path):
    from click.testing import CliRunner

    from svgtile.apps.compare import FIGURES
    from svgtile.cli.main import cli

    runner = CliRunner()
    out = tmp_path / "t.svg"
    ex = str(EXEMPLARS / "shale.svg")
    assert runner.invoke(cli, ["synth", ex, "-o", str(out), "--size", "400x400", "--seed", "1"]).exit_code == 0
    got = runner.invoke(cli, ["score", ex, str(out), "--json"])
    assert got.exit_code == 0, got.output
    data = json.loads(got.output)
    keys = ["neighbourhood_distance", "neighbourhood_tile", "neighbourhood_random", "likeness"]
    assert list(data)[-4:] == keys
    assert data["likeness"] == pytest.approx(
        (data["neighbourhood_random"] - data["neighbourhood_distance"])
        / (data["neighbourhood_random"] - data["neighbourhood_tile"])
    )
    text = runner.invoke(cli, ["score", ex, str(out)]).output
    width = max(len(label) for _, label, _ in FIGURES)
    assert f"{'likeness L':<{width}}  {data['likeness']:9.2f}" in text
    assert f"{data['neighbourhood_tile']:9.3f}  {data['neighbourhood_random']:.3f}" in text


def test_an_exemplar_without_neighbourhoods_has_no_likeness():
    from conftest import TINY

    ex = parse_exemplar(TINY, source="tiny.svg")  # 5 motifs: none has 6 neighbours
    stats = analyze(ex)
    region = Region.rectangle(200, 150)
    arr = synthesize(ex, region, "patch", seed=1, stats=stats).arrangement
    s = score(ex, stats, arr, region)
    assert s.motifs > 0
    assert s.neighbourhood_distance is s.neighbourhood_tile is s.neighbourhood_random is s.likeness is None
