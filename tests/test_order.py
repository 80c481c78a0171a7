"""The exemplar's order (issue 12.2): rows, lattices, period, anisotropy, clustering, banding;
``--engine auto``'s choice from it; the patch engine's ``--grid lattice``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from conftest import XLINK, arrange

from svgtile.analysis.order import read_order
from svgtile.analysis.stats import analyze
from svgtile.cli.main import main
from svgtile.core.region import Region
from svgtile.engines import ENGINES, choose, synthesize
from svgtile.engines.choose import RULES, Rule, steerable
from svgtile.engines.patch.engine import _lattice_centres
from svgtile.engines.patch.lattice import lattice_steps
from svgtile.svg.reader import parse_exemplar

DOT = '<symbol id="dot" overflow="visible"><circle r="0.6"/></symbol>'
DASH = '<symbol id="dash" overflow="visible"><rect x="-1.2" y="-0.3" width="2.4" height="0.6"/></symbol>'


def exemplar(points, kinds=None, size=(40.0, 40.0), period=False):
    """An exemplar SVG of dots (kind 0) and dashes (kind 1) at ``points`` in a ``size`` box."""
    w, h = size
    kinds = [0] * len(points) if kinds is None else kinds
    uses = "".join(f'<use xlink:href="#{("dot", "dash")[k]}" transform="translate({x:.4f} {y:.4f})"/>'
                   for (x, y), k in zip(points, kinds, strict=True))  # fmt: skip
    attr = f' svgtile:period="{w:g} {h:g}"' if period else ""
    return parse_exemplar(
        f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK}" xmlns:svgtile="urn:svgtile:run:1" '
        f'viewBox="0 0 {w:g} {h:g}"><defs>{DOT}{DASH}</defs>'
        f'<rect id="region" x="0" y="0" width="{w:g}" height="{h:g}" fill="none"{attr}/>{uses}</svg>',
        source="t.svg",
    )


def grid_points(a=4.0, b=4.0, size=(40.0, 40.0), offset=0.0, jitter=0.0, seed=0):
    """Points on rows ``b`` apart, ``a`` apart along a row, every other row shifted by ``offset``."""
    rng = np.random.default_rng(seed)
    pts = [(x + (offset if j % 2 else 0.0) + 1.0, y + 1.0)
           for j, y in enumerate(np.arange(0, size[1] - 1e-9, b)) for x in np.arange(0, size[0] - 1e-9, a)]  # fmt: skip
    return [(x + rng.normal(0, jitter), y + rng.normal(0, jitter)) for x, y in pts]


def random_points(n, size=(40.0, 40.0), seed=1):
    rng = np.random.default_rng(seed)
    return [tuple(p) for p in rng.uniform(0.5, size[0] - 0.5, (n, 2))]


# ----------------------------------------------------------------------------- reading the order


def test_a_square_lattice_is_found_with_its_steps():
    o = read_order(exemplar(grid_points()))
    assert o.kind == "lattice"
    lengths = sorted(s.length for s in o.steps)
    assert lengths == pytest.approx([4.0, 4.0], abs=1e-9)
    assert sorted(round(s.angle) % 180 for s in o.steps) == [0, 90]
    assert all(s.support > 0.9 for s in o.steps)
    assert o.clustering == pytest.approx(2.0, abs=0.25)  # Clark-Evans R of a square lattice


def test_rows_with_irregular_spacing_between_them_are_rows_not_a_lattice():
    rng = np.random.default_rng(3)
    ys = np.cumsum(rng.uniform(3.0, 7.0, 8))
    pts = [(x + 1.0, y) for y in ys for x in np.arange(0, 38, 2.5)]
    shift = rng.uniform(0, 2.5, len(ys))  # each row starts somewhere else: no second step
    pts = [(x + shift[int(np.searchsorted(ys, y))], y) for x, y in pts]
    o = read_order(exemplar(pts, size=(45.0, 45.0)))
    assert o.kind == "rows"
    assert o.steps[0].length == pytest.approx(2.5, abs=0.05)
    assert o.rows_horizontal
    assert o.anisotropy > 0.8 and min(o.anisotropy_angle, 180 - o.anisotropy_angle) < 5


def test_a_random_scatter_has_no_order():
    o = read_order(exemplar(random_points(120)))
    assert o.kind == "scatter" and o.steps == ()
    assert not o.rows_horizontal
    assert o.anisotropy < 0.3
    assert 0.7 < o.clustering < 1.3


def test_a_clustered_scatter_has_clark_evans_below_one():
    rng = np.random.default_rng(4)
    centres = rng.uniform(5, 35, (10, 2))
    pts = [tuple(c + rng.normal(0, 0.6, 2)) for c in centres for _ in range(10)]
    assert read_order(exemplar(pts)).clustering < 0.6


def test_few_drawn_motifs_never_make_a_lattice():
    """Five points always share some step; the tiny test exemplar once read as a lattice."""
    assert read_order(exemplar(grid_points(size=(12.0, 8.0)))).kind == "scatter"


def test_a_tile_of_one_motif_is_a_lattice_of_its_period():
    o = read_order(exemplar([(3.0, 5.0)], size=(8.0, 6.0), period=True))
    assert o.kind == "lattice" and o.period == (8.0, 6.0)
    assert sorted(s.length for s in o.steps) == pytest.approx([6.0, 8.0])


def test_steps_are_between_motifs_of_one_kind():
    """Dots and dashes alternating along rows repeat at two motif steps, not one."""
    pts = grid_points(a=2.0, b=4.0)
    kinds = [i % 2 for i in range(len(pts))]
    o = read_order(exemplar(pts, kinds))
    assert o.kind == "lattice"
    assert sorted(s.length for s in o.steps) == pytest.approx([4.0, 4.0])


def test_banding_sees_dense_and_empty_strips_and_kinds_by_strip():
    rng = np.random.default_rng(5)
    pts, kinds = [], []
    for band in range(4):  # 5-unit bands of motifs, 5-unit gaps between them
        for _ in range(40):
            pts.append((rng.uniform(0.5, 39.5), band * 10 + rng.uniform(0.5, 4.5)))
            kinds.append(band % 2)
    banded = read_order(exemplar(pts, kinds))
    even = read_order(exemplar(random_points(160), [i % 2 for i in range(160)]))
    assert banded.banding > 0.3 and even.banding < 0.1
    assert banded.kind_banding > 0.3 and even.kind_banding < 0.1


# ----------------------------------------------------------------------------- --grid lattice


def test_lattice_steps_of_a_tile_are_its_period_and_of_a_drawn_lattice_are_its_steps():
    tile = read_order(exemplar(grid_points(), period=True))
    assert lattice_steps(tile, (40.0, 40.0), 0.05) == pytest.approx(np.array([[40.0, 0.0], [0.0, 40.0]]))
    drawn = read_order(exemplar(grid_points(a=3.0, b=5.0, size=(40, 40))))
    steps = lattice_steps(drawn, (40.0, 40.0), 0.05)
    # the multiples of the steps nearest to 0.95 × 40 = 38
    assert steps == pytest.approx(np.array([[39.0, 0.0], [0.0, 40.0]]))
    scatter = read_order(exemplar(random_points(100)))
    assert lattice_steps(scatter, (40.0, 40.0), 0.05) == pytest.approx(np.array([[38.0, 0.0], [0.0, 38.0]]))


def test_lattice_centres_cover_the_box_with_a_sheared_lattice():
    steps = np.array([[10.0, 0.0], [5.0, 8.0]])
    A, B, cx, cy = _lattice_centres(steps, (0.0, 0.0, 100.0, 60.0))
    assert ((cx >= 0) & (cx <= 100) & (cy >= 0) & (cy <= 60)).all()
    assert np.allclose(cx, A * 10 + B * 5) and np.allclose(cy, B * 8)
    # every point of the box lies within a cell's reach of a centre
    probe = np.random.default_rng(0).uniform([5, 5], [95, 55], (500, 2))
    d = np.hypot(probe[:, None, 0] - cx[None], probe[:, None, 1] - cy[None]).min(axis=1)
    assert d.max() <= math.hypot(7.5, 8) / 2 + 5


def test_lattice_grid_on_a_tile_continues_its_lattice_without_seams():
    """Copies on the period: the texture inside is the tile's pattern itself, every motif of it
    there once with its kind (the copies' centres, at whole periods, shift it by the tile's
    centre), none lost where copies meet."""
    pts = grid_points(a=4.0, b=4.0, offset=2.0)
    kinds = [(i // 10) % 2 for i in range(len(pts))]  # rows of dots and rows of dashes
    ex = exemplar(pts, kinds, period=True)
    arr = arrange("patch", ex, Region.rectangle(100.0, 90.0), seed=1, grid="lattice", max_rotation=0.0)
    assert np.allclose(arr.angle, 0.0)

    def interior(xy):
        return (xy[:, 0] > 5) & (xy[:, 0] < 95) & (xy[:, 1] > 5) & (xy[:, 1] < 85)

    shifts = np.array([(i, j) for i in range(-1, 4) for j in range(-1, 4)]) * 40.0 - 20.0
    want_xy = (np.array(pts)[None] + shifts[:, None]).reshape(-1, 2)
    want_kind = np.tile(kinds, len(shifts))
    keep = interior(want_xy)
    want = sorted(zip(map(tuple, np.round(want_xy[keep], 6)), want_kind[keep], strict=True))
    inside = interior(arr.xy)
    got = sorted(zip(map(tuple, np.round(arr.xy[inside], 6)), arr.kind[inside], strict=True))
    assert got == want


def test_patch_grid_choices_refuse_an_unknown_layout():
    from svgtile.engines.patch.engine import PatchParams
    from svgtile.errors import ParameterError

    with pytest.raises(ParameterError, match="square, hex or lattice"):
        PatchParams(grid="diagonal")


# ----------------------------------------------------------------------------- auto


def test_auto_puts_a_tile_with_a_lattice_on_its_period_grows_a_drawn_one_and_leaves_a_scatter_to_patch():
    tile = exemplar(grid_points(), period=True)
    c = choose(tile, analyze(tile))
    assert (c.engine, c.params, c.rule) == ("patch", {"grid": "lattice", "max_rotation": 0.0}, "tile-order")
    scatter = exemplar(random_points(100))
    c = choose(scatter, analyze(scatter))
    assert (c.engine, dict(c.params), c.rule) == ("patch", {}, "scatter")
    drawn = exemplar(grid_points())  # a drawn lattice is grown (see RULES)
    c = choose(drawn, analyze(drawn))
    assert (c.engine, dict(c.params), c.rule) == ("growth", {}, "drawn-order")
    # an option of patch's given with auto keeps auto to patch
    assert choose(drawn, analyze(drawn), available=steerable(ENGINES, (), ("max_rotation",))).rule == "scatter"


def test_a_rule_for_an_engine_not_registered_is_skipped(monkeypatch):
    import importlib

    module = importlib.import_module("svgtile.engines.choose")

    ex = exemplar(random_points(50))
    extra = Rule("growth-rows", lambda o, s, e: True, "growth", {"x": 1}, lambda o: "rows grow")
    monkeypatch.setattr(module, "RULES", (extra, *RULES))
    assert choose(ex, analyze(ex), available={"patch": None}).engine == "patch"
    assert choose(ex, analyze(ex), available={"patch": None, "growth": None}).engine == "growth"


def test_synthesize_auto_equals_the_engine_it_chooses():
    ex = exemplar(grid_points(offset=2.0), period=True)
    region = Region.rectangle(70.0, 50.0)
    auto = synthesize(ex, region, "auto", seed=4)
    same = synthesize(ex, region, "patch", seed=4, params={"grid": "lattice", "max_rotation": 0.0})
    assert auto.engine == "patch" and auto.params == same.params
    assert np.array_equal(auto.arrangement.xy, same.arrangement.xy)
    # a parameter given with auto wins over auto's own
    turned = synthesize(ex, region, "auto", seed=4, params={"max_rotation": 20.0})
    assert turned.params.max_rotation == 20.0 and turned.params.grid == "lattice"


def test_cli_synth_defaults_to_auto_and_says_its_choice(tmp_path, capsys):
    src = tmp_path / "tile.svg"
    out = tmp_path / "out.svg"
    w = 40
    uses = "".join(f'<use xlink:href="#dot" transform="translate({x:g} {y:g})"/>' for x, y in grid_points())
    src.write_text(f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK}" xmlns:svgtile="urn:svgtile:run:1" '
                   f'viewBox="0 0 {w} {w}"><defs>{DOT}</defs><rect id="region" x="0" y="0" width="{w}" height="{w}" '
                   f'fill="none" svgtile:period="{w} {w}"/>{uses}</svg>')  # fmt: skip
    assert main(["synth", str(src), "-o", str(out), "--size", "60x50", "--seed", "2"]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert err[0].startswith("svgtile: auto: engine patch (--grid lattice --max-rotation 0): a repeating tile with a lattice")
    assert "4 units at 0°" in err[0] and "4 units at 90°" in err[0]
    assert 'grid="lattice"' in out.read_text() or "lattice" in out.read_text()
    # a patch option given with auto is taken; an out-of-range one is refused before the work
    assert main(["synth", str(src), "-o", str(out), "--size", "60x50", "--seed", "2", "--overlap", "0.9"]) != 0
    assert "--overlap" in capsys.readouterr().err


def test_cli_analyze_prints_the_order_and_auto(tmp_path, capsys):
    src = tmp_path / "tile.svg"
    uses = "".join(f'<use xlink:href="#dot" transform="translate({x:g} {y:g})"/>' for x, y in grid_points(offset=2.0))
    src.write_text(f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK}" xmlns:svgtile="urn:svgtile:run:1" '
                   f'viewBox="0 0 40 40"><defs>{DOT}</defs><rect id="region" x="0" y="0" width="40" height="40" '
                   f'fill="none" svgtile:period="40 40"/>{uses}</svg>')  # fmt: skip
    assert main(["analyze", str(src)]) == 0
    text = capsys.readouterr().out
    assert "order         a lattice: steps 4 at 0.0°" in text
    assert "period        40 x 40" in text
    assert "-> --engine patch --grid lattice --max-rotation 0" in text
    assert main(["analyze", "--json", str(src)]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["order"]["kind"] == "lattice" and r["order"]["period"] == [40, 40]
    assert r["auto"] == {"engine": "patch", "params": {"grid": "lattice", "max_rotation": 0.0}, "rule": "tile-order",
                         "why": r["auto"]["why"]}  # fmt: skip


# ------------------------------------------------------------- a tile whose kinds interleave (issue 12)


def interleaved_tile():
    """A 32 × 32 tile like Equinor 30100: dashes on the lattice (16, 0), (8, 8), dots on the rest of
    the lattice (8, 0), (4, 4), so each dot's nearest dots lie along short diagonals no other dot
    shares and the step by which the whole pattern repeats is further out than six neighbours."""
    pts, kinds = [], []
    for y in range(0, 32, 4):
        for x in range((y // 4) % 2 * 4, 32, 8):
            pts.append((x + 1.0, y + 1.0))
            kinds.append(1 if y % 8 == 0 and (x - y) % 16 == 0 else 0)
    return pts, kinds


def test_a_tile_whose_kinds_interleave_is_a_lattice_of_the_steps_it_repeats_by():
    pts, kinds = interleaved_tile()
    assert sum(kinds) == 8 and len(pts) == 32
    ex = exemplar(pts, kinds, size=(32.0, 32.0), period=True)
    o = read_order(ex)
    assert o.kind == "lattice"
    xy, k = np.array(pts), np.array(kinds)
    for s in o.steps:  # each step maps every motif onto one of its own kind, across the tile's edges
        moved = (xy + s.vector) % 32.0
        hit = [np.any(np.all(np.isclose(xy, m), axis=1) & (k == km)) for m, km in zip(moved, k, strict=True)]
        assert all(hit) and s.support == 1.0 and s.spread < 1e-9
    assert {round(s.length, 6) for s in o.steps} <= {round(math.hypot(8, 8), 6), 16.0}
    assert choose(ex, analyze(ex)).rule == "tile-order"


def test_a_tile_of_scattered_kinds_gains_no_steps_from_the_wider_search():
    pts = random_points(40, size=(32.0, 32.0), seed=3)
    kinds = [i % 2 for i in range(len(pts))]
    assert read_order(exemplar(pts, kinds, size=(32.0, 32.0), period=True)).kind == "scatter"


EQUINOR_30100 = Path(__file__).resolve().parents[2] / "shared" / "data" / "equinor-lithology" / "svg" / "30100.svg"


@pytest.mark.skipif(not EQUINOR_30100.is_file(), reason="../shared/data (real symbol sets) is not beside the checkout")
def test_equinor_30100_is_read_as_its_exact_lattice_and_auto_stamps_it_unturned():
    from svgtile.tiles.importer import import_tile

    ex = parse_exemplar(import_tile(EQUINOR_30100).text, source="30100")
    o = read_order(ex)
    assert o.kind == "lattice" and all(s.spread < 1e-6 and s.support > 0.95 for s in o.steps)
    assert sorted(round(s.length, 6) for s in o.steps) == [round(math.hypot(8, 8), 6), 16.0]
    c = choose(ex, analyze(ex), order=o)
    assert (c.engine, c.params.get("max_rotation")) == ("patch", 0.0)
