"""The growth engine (Ijiri et al. 2008, issue 13): its stages on hand-made inputs, its map tools
(flow, barrier, growth area) and their CLI options.  The engine's invariants (overlaps, boundary
modes, seeds, edit stability, tiled runs) are in tests/test_engines_contract.py; its likeness on
the regular FGDC/osm-carto tiles in tests/test_growth_regular.py."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely
from test_baselines import brute_force_conflicts

from svgtile import analyze, read_exemplar
from svgtile.cli.main import main
from svgtile.core.flow import FlowField
from svgtile.core.region import Region
from svgtile.engines import Controls, make_params, synthesize
from svgtile.engines.growth.connectivity import reference_rings, regularity, ring_of
from svgtile.engines.growth.engine import kind_priority
from svgtile.engines.growth.matching import Weights, best_match
from svgtile.engines.growth.relax import relax
from svgtile.errors import ParameterError
from svgtile.svg.reader import parse_exemplar

REPO = Path(__file__).resolve().parents[1]


def lattice_tile(rows: int, cols: int, dx: float, dy: float, shift: float = 0.0, r: float = 0.6) -> str:
    """A repeating tile of dots on a (sheared) lattice, as ``svgtile import`` writes one."""
    dots = "".join(f'<circle cx="{(i + 0.5) * dx + (j % 2) * shift:.4f}" cy="{(j + 0.5) * dy:.4f}" r="{r}"/>'
                   for j in range(rows) for i in range(cols))  # fmt: skip
    w, h = cols * dx, rows * dy
    return (f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:svgtile="urn:svgtile:run:1" viewBox="0 0 {w} {h}">'
            f'<rect id="region" width="{w}" height="{h}" fill="none" svgtile:period="{w} {h}"/>{dots}</svg>')  # fmt: skip


@cache
def square():
    ex = parse_exemplar(lattice_tile(4, 4, 5.0, 5.0))
    return ex, analyze(ex)


@cache
def shale():
    ex = read_exemplar(REPO / "exemplars" / "shale.svg")
    return ex, analyze(ex)


# -- §4 connectivity ------------------------------------------------------------------------------
@pytest.mark.parametrize(("tile", "size"), [
    (lattice_tile(4, 4, 5.0, 5.0), 4),          # square lattice: the diagonals are dropped
    (lattice_tile(4, 4, 5.0, 4.33, 2.5), 6),    # hexagonal lattice: six neighbours
    (lattice_tile(4, 8, 3.0, 8.0), 4),          # rows: two along the row, one above, one below
])  # fmt: skip
def test_a_lattice_tile_has_periodic_whole_rings_of_one_shape(tile, size):
    ex = parse_exemplar(tile)
    assert ex.period is not None
    rings = reference_rings(ex)
    assert len(rings) == len(ex.motifs)  # periodic: every motif has a whole ring
    assert (rings.size == size).all()
    assert regularity(rings) == 1.0


def test_an_irregular_exemplar_is_not_regular_and_border_motifs_give_no_ring():
    ex, _ = shale()
    rings = reference_rings(ex)
    assert 0 < len(rings) < len(ex.motifs)
    assert regularity(rings) < 0.75


def test_ring_of_is_counter_clockwise_from_the_open_side():
    pts = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [2.0, 0.0]])  # (2, 0) is shadowed by (1, 0)
    order = ring_of(pts, np.zeros(2))
    assert list(order) == [0, 1, 2]  # the widest gap is from (−1, 0) round to (1, 0)


# -- §5.2–5.3 matching ----------------------------------------------------------------------------
def test_best_match_finds_the_shift_and_the_fit_rotation():
    ex, _ = square()
    rings = reference_rings(ex)
    ring = int(np.flatnonzero(rings.size == 4)[0])
    rel = rings.rel[ring, :4]
    angle = np.radians(20.0)
    rot = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
    tar = rel[[2, 3]] @ rot.T  # two neighbours, starting at slot 2, turned 20°
    kinds = rings.nkind[ring, [2, 3]]
    noise = np.zeros(len(rings))
    (_, k, theta, err), = best_match(rings, tar, kinds, kinds, want=-1, rotation="fit", flow_angle=0.0,
                                     weights=Weights(), noise=noise)  # fmt: skip
    # the square ring matches under four shifts, each with its own quarter turn
    assert err < 1e-9 and (np.degrees(theta) - 20.0 + 45.0) % 90.0 == pytest.approx(45.0, abs=1e-6)
    turn = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    assert np.allclose(np.roll(rel, -k, axis=0)[:2] @ turn.T, tar)
    (_, _, theta0, err0), = best_match(rings, tar, kinds, kinds, want=-1, rotation="none", flow_angle=0.0,
                                       weights=Weights(), noise=noise)  # fmt: skip
    assert theta0 == 0.0 and err0 > 0.1


def test_a_reference_ring_smaller_than_the_target_is_ignored():
    ex, _ = square()
    rings = reference_rings(ex)
    tar = np.array([[5.0, 0], [3, 3], [0, 5], [-5, 0], [0, -5]])
    got = best_match(rings, tar, np.zeros(5, int), np.zeros(5, int), want=-1, rotation="none", flow_angle=0.0,
                     weights=Weights(), noise=np.zeros(len(rings)))  # fmt: skip
    assert got == []


# -- §5.5 relaxation ------------------------------------------------------------------------------
def test_relaxation_pulls_a_jittered_lattice_back_to_its_ring_shapes():
    ex, _ = square()
    rings = reference_rings(ex)
    grid = np.stack(np.meshgrid(np.arange(8) * 5.0, np.arange(8) * 5.0), -1).reshape(-1, 2)
    jitter = np.random.default_rng(0).normal(0, 0.4, grid.shape)
    jitter[0] = 0
    xy = grid + jitter
    ring = np.zeros(len(xy), np.int64)  # every dot copies ring 0 (all rings are alike)
    out = relax(rings, xy, ring, np.zeros(len(xy)), 0)
    assert np.array_equal(out[0], xy[0])  # eq. (6): the first element stays
    err_before = np.abs(xy - grid).mean()
    err_after = np.abs(out - grid).mean()
    assert err_after < 0.5 * err_before


# -- §5.1 priorities and parameters ----------------------------------------------------------------
def test_default_priorities_put_large_kinds_first_and_can_be_given():
    ex = read_exemplar(REPO / "exemplars" / "boulders.svg")
    area = np.array([k.prototype.geometry().area for k in ex.kinds])
    level = kind_priority(ex, {})
    assert level[np.argmax(area)] >= level[np.argmin(area)]
    name = ex.kinds[0].name
    assert kind_priority(ex, {name: 7})[0] == 7
    with pytest.raises(ParameterError, match="the exemplar has no kind 'nope'"):
        kind_priority(ex, {"nope": 1})


@pytest.mark.parametrize(("params", "message"), [
    ({"priority": "stone"}, "is not KIND=N"),
    ({"priority": "stone=big"}, "is not KIND=N"),
    ({"rotation": "spin"}, "rotation must be one of"),
    ({"relax_every": -1}, "relax_every must be at least 0"),
])  # fmt: skip
def test_bad_parameters_are_clear_errors(params, message):
    with pytest.raises(ParameterError, match=message):
        make_params("growth", params)


def test_rotation_flow_needs_a_flow_field():
    ex, st = square()
    with pytest.raises(ParameterError, match="--rotation flow needs a flow field"):
        synthesize(ex, Region.rectangle(40, 40), "growth", seed=1, stats=st, params={"rotation": "flow"})


def test_a_square_lattice_tile_grows_into_its_own_lattice():
    ex, st = square()
    arr = synthesize(ex, Region.rectangle(100, 80), "growth", seed=3, stats=st, boundary="centroid").arrangement
    assert len(arr) == 20 * 16
    assert np.allclose((arr.xy - 2.5) / 5.0, np.round((arr.xy - 2.5) / 5.0), atol=1e-3)


# -- §6 tools -------------------------------------------------------------------------------------
def bend() -> FlowField:
    t = np.linspace(0, 1, 30)
    return FlowField.from_strokes([np.c_[t * 160, 15 + 100 * t**2]])


def test_a_flow_stroke_turns_the_texture_with_it():
    ex, st = shale()
    field = bend()
    res = synthesize(ex, Region.rectangle(160, 120), "growth", seed=4, stats=st, controls=Controls(flow=field))
    arr = res.arrangement
    assert len(arr) > 150 and brute_force_conflicts(arr, ex, st) == (0, 0)
    # shale's bars lie along x in the exemplar: a motif follows the flow when its angle, less its
    # reference's (the exemplar's arc), is the field's direction there
    base = st.arc_start[arr.kind] + st.arc_width[arr.kind] / 2
    off = (arr.angle - base - field.angle(arr.xy) + 180.0) % 360.0 - 180.0
    within = np.abs(off) <= 15.0 + st.arc_width[arr.kind] / 2
    assert within.mean() >= 0.9, f"only {within.mean():.3f} of motifs within 15° of the flow"
    plain = synthesize(ex, Region.rectangle(160, 120), "growth", seed=4, stats=st).arrangement
    off0 = (plain.angle - st.arc_start[plain.kind] - st.arc_width[plain.kind] / 2 - field.angle(plain.xy) + 180) % 360 - 180
    assert (np.abs(off0) <= 15.0 + st.arc_width[plain.kind] / 2).mean() < 0.6  # the check can fail


def test_a_barrier_is_never_crossed_and_both_sides_are_filled():
    ex, st = shale()
    river = shapely.LineString([(70, -10), (95, 130)])
    arr = synthesize(ex, Region.rectangle(160, 120), "growth", seed=5, stats=st,
                     controls=Controls(barriers=river)).arrangement  # fmt: skip
    from svgtile.core.footprint import world_footprints

    assert not shapely.intersects(world_footprints(arr, ex.prototypes), river).any()
    side = np.sign((95 - 70) * (arr.xy[:, 1] + 10) - (130 + 10) * (arr.xy[:, 0] - 70))
    left, right = (side > 0).sum(), (side < 0).sum()
    plain = len(synthesize(ex, Region.rectangle(160, 120), "growth", seed=5, stats=st).arrangement)
    assert left > 0.3 * plain and right > 0.3 * plain and left + right > 0.85 * plain
    assert brute_force_conflicts(arr, ex, st) == (0, 0)


def test_a_growth_area_limits_the_texture():
    ex, st = shale()
    spray = shapely.Point(80, 60).buffer(40)
    arr = synthesize(ex, Region.rectangle(160, 120), "growth", seed=6, stats=st,
                     controls=Controls(grow_within=spray)).arrangement  # fmt: skip
    assert shapely.contains_xy(spray, arr.xy[:, 0], arr.xy[:, 1]).all()
    plain = synthesize(ex, Region.rectangle(160, 120), "growth", seed=6, stats=st).arrangement
    inside = shapely.contains_xy(spray, plain.xy[:, 0], plain.xy[:, 1]).sum()
    assert 0.85 * inside <= len(arr) <= 1.1 * inside


MAP = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 120 90">
  <path id="flow" d="M 0 10 C 40 10 80 50 120 85" fill="none" stroke="red" stroke-width="2"/>
  <path id="river" d="M 50 -5 L 70 100" fill="none" stroke="blue" stroke-width="3"/>
  <g id="spray"><circle cx="30" cy="45" r="20"/><path d="M 75 15 L 110 75" fill="none" stroke="#000" stroke-width="15"/></g>
  <g id="empty"/>
</svg>"""


def test_cli_reads_the_tools_from_a_map(tmp_path):
    (tmp_path / "map.svg").write_text(MAP)
    exemplar = str(REPO / "exemplars" / "shale.svg")
    m = str(tmp_path / "map.svg")
    for opts in (["--flow", m + "#flow"], ["--barrier", m + "#river"], ["--grow-within", m + "#spray"]):
        out = tmp_path / "o.svg"
        assert main(["synth", exemplar, "-o", str(out), "--size", "120x90", "--engine", "growth", "--seed", "1", *opts]) == 0
        assert out.read_text().count("<use") > 50
    out = tmp_path / "spray.svg"
    main(["synth", exemplar, "-o", str(out), "--size", "120x90", "--engine", "growth", "--seed", "1",
          "--grow-within", m + "#spray"])  # fmt: skip
    full = tmp_path / "full.svg"
    main(["synth", exemplar, "-o", str(full), "--size", "120x90", "--engine", "growth", "--seed", "1"])
    assert out.read_text().count("<use") < 0.7 * full.read_text().count("<use")


@pytest.mark.parametrize(("opts", "message"), [
    (["--engine", "tile", "--flow", "{m}#flow"], "engine 'tile' cannot honour --flow (engines that do: growth"),
    (["--engine", "growth", "--flow", "{m}#nothing"], "no element with id 'nothing'"),
    (["--engine", "growth", "--barrier", "{m}"], "name the element: --barrier MAP.svg#ID"),
    (["--engine", "growth", "--flow", "{m}#empty"], "draws no line"),
])  # fmt: skip
def test_cli_refuses_bad_tools_in_one_line(tmp_path, capsys, opts, message):
    (tmp_path / "map.svg").write_text(MAP)
    out = tmp_path / "o.svg"
    opts = [o.format(m=tmp_path / "map.svg") for o in opts]
    rc = main(["synth", str(REPO / "exemplars" / "shale.svg"), "-o", str(out), "--size", "60", "--seed", "1", *opts])
    err = capsys.readouterr().err
    assert rc == 1 and not out.exists()
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_analyze_shows_and_draws_the_ring_shapes(tmp_path, capsys):
    tile = tmp_path / "rows.svg"
    tile.write_text(lattice_tile(4, 8, 3.0, 8.0))
    png = tmp_path / "rings.png"
    assert main(["analyze", str(tile), "--rings", "--png", str(png)]) == 0
    out = capsys.readouterr().out
    assert "32 motifs with a whole ring (periodic): 32×4 neighbours" in out
    assert "1 class(es) of alike rings, regularity 1.00 (rows or a lattice)" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["analyze", str(REPO / "exemplars" / "shale.svg"), "--rings"]) == 0
    assert "(irregular)" in capsys.readouterr().out
