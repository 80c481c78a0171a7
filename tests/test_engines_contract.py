"""The contract every registered engine keeps (svgtile.engines.base), one table over all of them.

A new engine joins these tests by being registered in :data:`svgtile.engines.ENGINES`.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import arrange
from test_baselines import brute_force_conflicts
from test_region import edit_stability

from svgtile import analyze, read_exemplar
from svgtile.apps.mapfill import parse_styles
from svgtile.cli.synth import synth
from svgtile.core.footprint import world_footprints
from svgtile.core.region import BOUNDARY_MODES, Region
from svgtile.engines import ENGINES, Result, get_engine, make_params, public_params, synthesize
from svgtile.engines.base import Engine, EngineParams
from svgtile.errors import ParameterError
from svgtile.svg.reader import parse_exemplar
from svgtile.svg.writer import result_document

REPO = Path(__file__).resolve().parents[1]
EXEMPLAR = REPO / "exemplars" / "gravel.svg"
NAMES = list(ENGINES)


@cache
def load(path: Path = EXEMPLAR):
    ex = read_exemplar(path)
    return ex, analyze(ex)


#: Two discs 1 unit apart across the tile's edge: every seam has a conflict the seed decides.
CROWDED_EDGE = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 20 20">
  <circle cx="0.6" cy="10" r="1"/><circle cx="19.4" cy="10" r="1"/><circle cx="10" cy="10" r="1"/>
  <circle cx="10" cy="4" r="1"/><circle cx="4" cy="16" r="1.2"/>
</svg>"""


def holed_region() -> Region:
    outer = shapely.Polygon([(3, 2), (260, 10), (240, 190), (20, 170)])
    return Region(outer.difference(shapely.Point(130, 95).buffer(35)))


@pytest.mark.parametrize("name", NAMES)
def test_engine_declares_the_protocol(name):
    engine = ENGINES[name]
    assert isinstance(engine, Engine) and engine.name == name and engine.summary
    assert issubclass(engine.Params, EngineParams)
    params = engine.Params()
    assert params.public_values().keys() == {p.name for p in engine.Params.public()}
    reach = engine.reach(load()[0], params)
    assert reach >= 0


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("mode", BOUNDARY_MODES)
def test_no_overlaps_no_violators_in_every_boundary_mode(name, mode):
    ex, stats = load()
    region = holed_region()
    arr = arrange(name, ex, region, seed=11, stats=stats, boundary=mode)
    assert len(arr) > 100
    assert brute_force_conflicts(arr, ex, stats) == (0, 0)
    geoms = world_footprints(arr, ex.prototypes)
    if mode == "inside":
        assert shapely.covered_by(geoms, shapely.buffer(region.shape, 1e-6)).all()
    elif mode == "centroid":
        assert shapely.covered_by(shapely.points(arr.xy), region.shape).all()
    else:
        assert shapely.intersects(geoms, region.shape).all()


@pytest.mark.parametrize("name", NAMES)
def test_same_seed_same_bytes_other_seed_other_output(name):
    ex, stats = load()
    region = Region.rectangle(220, 160)

    def text(seed):
        return result_document(synthesize(ex, region, name, seed=seed, stats=stats))

    def motifs(seed, exemplar=ex, stats=stats):
        arr = synthesize(exemplar, region, name, seed=seed, stats=stats).arrangement
        return np.concatenate([arr.kind[:, None], arr.xy, arr.angle[:, None], arr.scale[:, None]], axis=1)

    assert text(5) == text(5)
    if name == "tile":
        # the Tiling strategy draws only which motif of a pair conflicting across a seam leaves:
        # take an exemplar whose copies conflict across their seams
        ex2 = parse_exemplar(CROWDED_EDGE)
        outs = {motifs(s, ex2, analyze(ex2)).tobytes() for s in range(5, 13)}
        assert len(outs) > 1
    else:
        assert not np.array_equal(motifs(5), motifs(6))


@pytest.mark.parametrize("name", NAMES)
def test_far_motifs_survive_an_edit_of_the_region(name):
    stable, far = edit_stability(EXEMPLAR, radius_widths=4.0, engine=name)
    assert far > 500
    assert stable >= 0.95, f"{name}: only {stable:.3f} of the far motifs unchanged"


@pytest.mark.xfail(strict=True, reason="optimize: 0.498 of the far motifs unchanged (0.606 without renewal; the figure "
                   "swings with any change of the engine); the contract's case above (gravel, seed 3) is one of 2 in the 9 "
                   "cases of benchmarks/README.md renew14c where it holds")
def test_optimize_keeps_far_motifs_beyond_the_one_case():
    """The contract's edit on another drawn exemplar and seed: a known miss of the optimize engine."""
    stable, far = edit_stability(REPO / "exemplars" / "breccia-plain.svg", radius_widths=4.0, engine="optimize", seed=1)
    assert far > 500
    assert stable >= 0.95, f"optimize: only {stable:.3f} of the far motifs unchanged"


@pytest.mark.parametrize("name", NAMES)
def test_a_parameter_the_engine_does_not_have_is_an_error(name):
    ex, stats = load()
    with pytest.raises(ParameterError, match=f"engine {name!r} has no parameter 'no_such_thing'"):
        synthesize(ex, Region.rectangle(50, 50), name, seed=1, stats=stats, params={"no_such_thing": 1})
    others = [p for p in public_params() if p not in {q.name for q in ENGINES[name].Params.public()}]
    for other in others:
        with pytest.raises(ParameterError, match="has no parameter"):
            make_params(name, {other: public_params()[other].default})


@pytest.mark.parametrize("name", NAMES)
def test_a_bad_boundary_is_an_error(name):
    ex, stats = load()
    with pytest.raises(ParameterError, match="--boundary must be one of"):
        synthesize(ex, Region.rectangle(50, 50), name, seed=1, stats=stats, boundary="outside")


def test_unknown_engine_is_an_error():
    with pytest.raises(ParameterError, match="unknown engine 'magic'"):
        get_engine("magic")


@pytest.mark.parametrize("name", NAMES)
def test_result_carries_everything_a_writer_needs(name):
    ex, stats = load()
    region = Region.rectangle(80, 60)
    result = synthesize(ex, region, name, seed=3, stats=stats, boundary="inside")
    assert isinstance(result, Result)
    assert (result.exemplar, result.region, result.boundary, result.engine, result.seed) == (ex, region, "inside", name, 3)
    meta = result.metadata(size="80x60")
    assert meta["engine"] == name and meta["boundary"] == "inside" and meta["motifs"] == len(result)
    assert meta["seed"] == 3 and meta["size"] == "80x60"
    assert {k: meta[k] for k in result.params.public_values()} == result.params.public_values()
    assert "svgtile-clip" not in result_document(result)  # inside mode: whole motifs, no clip path
    with pytest.raises(ValueError, match="the run's own"):
        result.metadata(motifs=1)
    if "grid" in {p.name for p in ENGINES[name].Params.public()}:
        hexed = synthesize(ex, region, name, seed=3, stats=stats, params={"grid": "hex"})
        assert hexed.params.grid == "hex" and 'grid="hex"' in result_document(hexed)
    unseeded = synthesize(ex, region, name, rng=np.random.default_rng(3), stats=stats)
    assert "seed" not in unseeded.metadata()


def test_every_public_parameter_is_a_cli_option_and_a_styles_key():
    """The CLI and the styles file are made from the parameter classes: they cannot drift."""
    options = {o.name: o for o in synth.params}
    for engine in ENGINES.values():
        for p in engine.Params.public():
            assert p.option in options[p.name].opts, p.name
            value = p.choices[-1] if p.choices else (not p.default) if p.type is bool else p.default
            styles = parse_styles({"classes": {"a": {"exemplar": "x.svg", "engine": engine.name, p.name: value}}})
            assert styles.classes["a"].params == {p.name: value}
            without = [e for e in ENGINES if e != engine.name and p.name not in {q.name for q in ENGINES[e].Params.public()}]
            for other in without:
                with pytest.raises(ParameterError, match="has no parameter"):
                    parse_styles({"classes": {"a": {"exemplar": "x.svg", "engine": other, p.name: value}}})


def test_a_top_level_default_applies_only_to_engines_that_have_it():
    styles = parse_styles({"grid": "hex", "classes": {"p": {"exemplar": "x.svg"},
                                                      "t": {"exemplar": "x.svg", "engine": "tile"}}})  # fmt: skip
    assert styles.classes["p"].params == {"grid": "hex"}
    assert styles.classes["t"].params == {}


def test_cli_refuses_an_option_the_engine_does_not_have(tmp_path, capsys):
    from svgtile.cli.main import main

    out = tmp_path / "o.svg"
    rc = main(["synth", str(EXEMPLAR), "-o", str(out), "--size", "50", "--engine", "tile", "--grid", "hex"])
    err = capsys.readouterr().err
    assert rc == 1 and not out.exists()
    assert err == "svgtile: error: engine 'tile' has no parameter --grid (its parameters: --redraw-jitter)\n"


def test_an_engine_plug_in_registers_through_the_entry_point_group(monkeypatch):
    """A plug-in is an entry point in the ``svgtile.engines`` group naming an Engine object."""
    import svgtile.engines as engines

    class EP:
        def __init__(self, name, obj):
            self.name, self._obj = name, obj

        def load(self):
            if isinstance(self._obj, Exception):
                raise self._obj
            return self._obj

    tile = ENGINES["tile"]
    plug = type("Plug", (), {"name": "mirror", "summary": "a test engine", "Params": tile.Params,
                             "place": tile.place, "reach": tile.reach})()  # fmt: skip
    eps = [EP("mirror", plug), EP("patch", plug), EP("broken", ImportError("no"))]
    monkeypatch.setattr(engines, "entry_points", lambda group: eps if group == engines.ENTRY_POINT_GROUP else [])
    found = engines._registry()
    assert found["mirror"] is plug and found["patch"] is ENGINES["patch"] and "broken" not in found
    ex, stats = load()
    assert len(synthesize(ex, Region.rectangle(60, 60), found["mirror"], seed=1, stats=stats)) > 0


def test_synth_help_says_what_the_baselines_are_for(capsys):
    from svgtile.cli.main import main

    assert main(["synth", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    for name in ("tile", "random"):
        assert f"{name} = " in text
    assert text.count("a baseline for svgtile score and compare") == 2 and "leaves holes" in text


def test_a_broken_or_clashing_plug_in_is_refused_with_the_reason(monkeypatch):
    import svgtile.engines as engines

    class EP:
        def __init__(self, name, obj):
            self.name, self._obj = name, obj

        def load(self):
            return self._obj

    from dataclasses import dataclass

    @dataclass(frozen=True)
    class SeedParams(EngineParams):
        seed: int = engines.base.param(0, "a name every command has")

    tile = ENGINES["tile"]
    clash = type("Clash", (), {"name": "clash", "summary": "x", "Params": SeedParams, "place": tile.place,
                               "reach": tile.reach})()  # fmt: skip
    monkeypatch.setattr(engines, "entry_points", lambda group: [EP("clash", clash), EP("nothing", object())])
    monkeypatch.setattr(engines, "REFUSED", {})
    found = engines._registry()
    assert "clash" not in found and "nothing" not in found
    assert "reserves" in engines.REFUSED["clash"] and "not an engine" in engines.REFUSED["nothing"]
    monkeypatch.setattr(engines, "ENGINES", found)
    with pytest.raises(ParameterError, match="the plug-in of that name was refused"):
        engines.get_engine("clash")


@pytest.mark.parametrize(("params", "message"), [
    ({"overlap": "0.1"}, "overlap has the wrong type"),
    ({"vary_orientation": 1}, "vary_orientation has the wrong type"),
    ({"grid": 3}, "grid has the wrong type"),
    ({"density_rounds": -3}, "density_rounds must be at least 0"),
])  # fmt: skip
def test_a_value_of_the_wrong_type_or_range_is_a_clear_error(params, message):
    with pytest.raises(ParameterError, match=message):
        make_params("patch", params)


@pytest.mark.parametrize("name", [n for n in NAMES if np.isfinite(ENGINES[n].reach(load()[0], ENGINES[n].Params()))])
def test_a_finite_reach_makes_tiled_runs_equal_the_whole_run(name):
    """An engine that declares a finite reach is tile-exact: each tile synthesized with a halo of
    that reach (plus the motifs' own size), keeping the motifs anchored in the tile, gives together
    exactly the whole run (the contract the distributed runner will rely on)."""
    ex, stats = load()
    reach = ENGINES[name].reach(ex, ENGINES[name].Params())
    x0, y0, x1, y1 = ex.region.bounds
    halo = reach + max(x1 - x0, y1 - y0)
    whole = arrange(name, ex, Region.rectangle(240, 180), seed=2, stats=stats, boundary="centroid")

    def rows(arr, keep):
        cols = np.concatenate([arr.kind[:, None], arr.xy, arr.angle[:, None], arr.scale[:, None]], axis=1)
        return {tuple(r) for r in cols[keep]}

    tiled = set()
    for tx in (0, 120):
        for ty in (0, 90):
            grown = Region(shapely.box(tx, ty, tx + 120, ty + 90).buffer(halo, join_style="mitre")
                           .intersection(shapely.box(0, 0, 240, 180)))  # fmt: skip
            arr = arrange(name, ex, grown, seed=2, stats=stats, boundary="centroid")
            own = (arr.xy[:, 0] >= tx) & (arr.xy[:, 0] < tx + 120) & (arr.xy[:, 1] >= ty) & (arr.xy[:, 1] < ty + 90)
            tiled |= rows(arr, own)
    assert len(whole) > 200 and tiled == rows(whole, np.ones(len(whole), bool))
