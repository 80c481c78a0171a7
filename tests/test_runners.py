"""Tiled synthesis and Dask (issue 19): a tiled run, on any scheduler, in any completion order,
writes the bytes of the whole run.

The cluster tests start their own ``distributed.LocalCluster`` of two single-threaded worker
processes (no dashboard) and stop it after.
"""

from __future__ import annotations

import math
import random
import re
import time
from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import TINY

from svgtile import analyze, read_exemplar
from svgtile.apps.mapfill import fill_map, parse_styles
from svgtile.cli.main import main
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import ENGINES, synthesize
from svgtile.files import atomic_output
from svgtile.runners import schedule
from svgtile.runners.schedule import Unit, check_scheduler, consume
from svgtile.runners.spool import Spool
from svgtile.runners.tiling import (
    WHOLE,
    Bands,
    Tile,
    anchored,
    plan,
    synthesize_tile,
    synthesize_tiled,
)
from svgtile.svg.writer import result_document

REPO = Path(__file__).resolve().parents[1]
EXEMPLARS = REPO / "exemplars"
#: Engines that declare a finite reach: each must be tile-exact.
EXACT = [n for n, e in ENGINES.items() if math.isfinite(e.reach(read_exemplar(EXEMPLARS / "gravel.svg"), e.Params()))]


@cache
def load(name: str):
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    return ex, analyze(ex)


def holed_region() -> Region:
    """A slanted unit with a round inlier and a slot, and a road to avoid across it all."""
    outer = shapely.Polygon([(3, 2), (200, 9), (190, 150), (14, 140)])
    shape = outer.difference(shapely.Point(100, 75).buffer(30)).difference(shapely.box(30, 40, 80, 56))
    return Region(shape, avoid=shapely.LineString([(0, 120), (220, 95)]).buffer(4))


def columns(arr: Arrangement) -> np.ndarray:
    return np.concatenate([arr.kind[:, None], arr.xy, arr.angle[:, None], arr.scale[:, None]], axis=1)


# ----------------------------------------------------------------------------- tiling


@pytest.mark.parametrize("name", EXACT)
@pytest.mark.parametrize(("exemplar", "boundary"), [("gravel", "clip"), ("chert-nodules", "inside")])
def test_a_tiled_run_is_the_whole_run(name, exemplar, boundary):
    """Tile sides smaller than a motif (edges through motifs), about one exemplar, and several;
    the unit's hole, slot and avoid zones cross tile edges.  Growth regrows the cells a tile
    depends on (its reach is 0 in cells, not in work), so it is run on sides of 24 and 64 only:
    edges still run through motifs, at a tenth of the cost of 7.5-unit tiles."""
    ex, stats = load(exemplar)
    region = holed_region()
    whole = synthesize(ex, region, name, seed=5, stats=stats, boundary=boundary)
    assert len(whole) > 300
    for size in (7.5, 64.0) if name == "tile" else (24.0, 64.0):
        tiles = plan(region, ex, name, size)
        assert len(tiles) > 1 and not any(t.whole for t in tiles)
        tiled = synthesize_tiled(ex, region, name, size, seed=5, stats=stats, boundary=boundary)
        assert columns(tiled).tobytes() == columns(whole.arrangement).tobytes(), size


@pytest.mark.parametrize("name", [n for n in ENGINES if n not in EXACT])
def test_an_engine_that_is_not_tile_exact_runs_whole(name):
    ex, stats = load("gravel")
    region = Region.rectangle(120, 90)
    assert plan(region, ex, name, 30.0) == [WHOLE]
    whole = synthesize(ex, region, name, seed=2, stats=stats).arrangement
    assert columns(synthesize_tiled(ex, region, name, 30.0, seed=2, stats=stats)).tobytes() == columns(whole).tobytes()


def test_tiles_are_world_anchored_half_open_cells():
    ex, _ = load("gravel")
    a = plan(Region.rectangle(100, 100), ex, "tile", 25.0)
    b = plan(Region.rectangle(100, 100, x=60, y=-40), ex, "tile", 25.0)
    shared = {(t.i, t.j) for t in a} & {(t.i, t.j) for t in b}
    assert shared and all(t.cell == (t.i * 25.0, t.j * 25.0, (t.i + 1) * 25.0, (t.j + 1) * 25.0) for t in a + b)
    assert [t.j for t in a] == sorted(t.j for t in a)  # world order: bands, then columns
    arr = Arrangement(np.zeros(4), [[0, 0], [25, 0], [24.99999, 24.99999], [-1e-9, 10]], np.zeros(4), np.ones(4))
    assert anchored(arr, Tile(0, 0, (0.0, 0.0, 25.0, 25.0), 1.0)).tolist() == [True, False, True, False]
    with pytest.raises(Exception, match="--tile-size must be a positive number"):
        plan(Region.rectangle(10, 10), ex, "tile", -1.0)


def test_bands_come_out_the_same_in_any_completion_order():
    ex, stats = load("chert-nodules")
    region = holed_region()
    tiles = plan(region, ex, "tile", 50.0)
    parts = [synthesize_tile(ex, region, "tile", t, seed=1, stats=stats) for t in tiles]
    outs = set()
    for trial in range(4):
        got: dict[int, Arrangement] = {}
        collect = Bands(tiles, got.__setitem__)
        order = list(range(len(tiles)))
        random.Random(trial).shuffle(order)
        for n in order:
            collect.add(n, parts[n])
        assert collect.done
        outs.add(columns(Arrangement.concat([got[b] for b in sorted(got)])).tobytes())
    whole = synthesize(ex, region, "tile", seed=1, stats=stats).arrangement
    assert outs == {columns(whole).tobytes()}


# ----------------------------------------------------------------------------- writing


def test_spool_gives_back_each_piece(tmp_path):
    with Spool(str(tmp_path)) as spool:
        spool.put((1, 0), "b" * 3_000_000)
        spool.put((0, 0), "")
        spool.put((0, 1), "ä")
        out = tmp_path / "x"
        with open(out, "wb") as fh:
            for key in [(0, 0), (0, 1), (1, 0)]:
                spool.copy(key, fh)
        assert spool.size((0, 0)) == 0 and out.read_text() == "ä" + "b" * 3_000_000


def test_atomic_output_leaves_the_old_file_on_failure(tmp_path):
    out = tmp_path / "o.svg"
    out.write_text("old")
    with pytest.raises(RuntimeError), atomic_output(out) as fh:
        fh.write(b"half a file")
        raise RuntimeError("a unit broke the writer")
    assert out.read_text() == "old" and sorted(p.name for p in tmp_path.iterdir()) == ["o.svg"]
    with atomic_output(out) as fh:
        fh.write(b"new")
    assert out.read_text() == "new"


def synth(tmp_path, name, *extra, engine="tile", size="260x190", exemplar="chert-nodules.svg"):
    out = tmp_path / name
    rc = main(["synth", str(EXEMPLARS / exemplar), "--size", size, "--engine", engine, "--seed", "4", "-o", str(out),
               *extra])  # fmt: skip
    return rc, out


@pytest.mark.parametrize("suffix", ["svg", "geojson"])
def test_synth_on_the_local_scheduler_writes_the_whole_runs_bytes(tmp_path, suffix):
    rc, whole = synth(tmp_path, f"whole.{suffix}")
    assert rc == 0
    for n, extra in enumerate([("--tile-size", "33"), ("--scheduler", "local", "--tile-size", "90", "--jobs", "2"),
                               ("--scheduler", "local")]):  # fmt: skip
        rc, out = synth(tmp_path, f"t{n}.{suffix}", *extra)
        assert rc == 0 and out.read_bytes() == whole.read_bytes(), extra


def test_synth_of_an_empty_texture_streams_the_same_bytes(tmp_path):
    """A region no whole motif fits in: the writer's empty-group case."""
    _, whole = synth(tmp_path, "w.svg", "--boundary", "inside", size="1x1")
    _, tiled = synth(tmp_path, "t.svg", "--boundary", "inside", "--tile-size", "20", size="1x1")
    assert "<use" not in whole.read_text() and tiled.read_bytes() == whole.read_bytes()


def test_a_failed_tile_is_reported_and_the_others_written(tmp_path, monkeypatch, capsys):
    import svgtile.apps.tiled as tiled

    real = tiled.synthesize_tile

    def flaky(exemplar, region, engine, tile, **kw):
        if (tile.i, tile.j) == (1, 1):
            raise MemoryError
        return real(exemplar, region, engine, tile, **kw)

    monkeypatch.setattr(tiled, "synthesize_tile", flaky)
    rc, out = synth(tmp_path, "o.svg", "--tile-size", "60", "--jobs", "1")
    err = capsys.readouterr().err
    assert rc == 1 and "svgtile: warning: tile 1,1 not filled: out of memory" in err
    assert re.search(r"error: .*o\.svg: 1 of \d+ tiles failed", err) and all(line.startswith("svgtile: ") for line in err.splitlines())
    monkeypatch.setattr(tiled, "synthesize_tile", real)
    _, whole = synth(tmp_path, "w.svg")
    uses = [u for u in whole.read_text().splitlines() if "<use" in u]
    written = [u for u in out.read_text().splitlines() if "<use" in u]
    missing = set(uses) - set(written)
    assert missing and not set(written) - set(uses)
    xy = np.array([[float(v) for v in u.split("translate(")[1].split(")")[0].split()] for u in missing])
    assert ((xy >= 60) & (xy < 120)).all()


def test_a_bad_scheduler_is_one_line(tmp_path, capsys):
    with pytest.raises(Exception, match="--scheduler must be local, processes or a Dask scheduler address"):
        check_scheduler("cluster")
    rc, out = synth(tmp_path, "o.svg", "--scheduler", "everywhere")
    err = capsys.readouterr().err
    assert rc == 1 and not out.exists() and err.count("\n") == 1 and "--scheduler must be" in err


# ----------------------------------------------------------------------------- maps

MAP = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 260 160">
  <path id="basin" class="nod" fill-rule="evenodd" d="M0 0 H170 V160 H0 Z M40 40 H100 V100 H40 Z"/>
  <path id="inlier" class="dots" d="M45 45 H95 V95 H45 Z"/>
  <path id="ridge" class="pat" d="M170 0 H260 V160 H170 Z"/>
</svg>
"""


def styles_text(folder: Path) -> str:
    (folder / "tiny.svg").write_text(TINY)
    nod = EXEMPLARS / "chert-nodules.svg"
    return f"""seed = 2
[classes.nod]
exemplar = "{nod}"
engine = "tile"
unit = 0.8
boundary = "inside"
[classes.dots]
exemplar = "tiny.svg"
engine = "tile"
[classes.pat]
exemplar = "tiny.svg"
"""


@pytest.fixture
def mapdir(tmp_path) -> Path:
    (tmp_path / "map.svg").write_text(MAP)
    (tmp_path / "styles.toml").write_text(styles_text(tmp_path))
    return tmp_path


def fill(folder: Path, name: str, *extra) -> tuple[int, Path]:
    out = folder / name
    return main(["map", str(folder / "map.svg"), "--styles", str(folder / "styles.toml"), "-o", str(out), *extra]), out


@pytest.mark.parametrize("suffix", ["svg", "geojson"])
def test_a_tiled_map_is_the_whole_map(mapdir, suffix):
    rc, whole = fill(mapdir, f"whole.{suffix}", "--jobs", "1")
    assert rc == 0 and whole.stat().st_size > 10_000
    for n, extra in enumerate([("--tile-size", "17", "--jobs", "1"), ("--tile-size", "45", "--jobs", "2")]):
        rc, out = fill(mapdir, f"t{n}.{suffix}", *extra)
        assert rc == 0 and out.read_bytes() == whole.read_bytes(), extra


def test_fill_map_keeps_or_streams_the_same_bands(mapdir):
    from svgtile.apps.mapfill import read_styles

    styles = read_styles(mapdir / "styles.toml")
    kept = fill_map(mapdir / "map.svg", styles, seed=2, jobs=1, tile_size=23.0)
    whole = fill_map(mapdir / "map.svg", styles, seed=2, jobs=1)
    streamed: dict = {}
    fill_map(mapdir / "map.svg", styles, seed=2, jobs=1, tile_size=23.0,
             sink=lambda n, r, b, arr: streamed.setdefault(n, {}).__setitem__(b, arr))  # fmt: skip
    assert len(streamed[0]) > 3  # the basin came in bands
    for n, arr in enumerate(whole.results):
        assert columns(kept.results[n]).tobytes() == columns(arr).tobytes()
        bands = Arrangement.concat([streamed[n][b] for b in sorted(streamed[n])])
        assert columns(bands).tobytes() == columns(arr).tobytes()


def test_a_failed_tile_of_a_map_is_reported_and_its_region_written(mapdir, monkeypatch, capsys):
    import svgtile.apps.mapfill as mapfill

    real = mapfill.synthesize_tile

    def flaky(exemplar, region, engine, tile, **kw):
        if not tile.whole and (tile.i, tile.j) == (1, 1):
            raise ValueError("boom")
        return real(exemplar, region, engine, tile, **kw)

    monkeypatch.setattr(mapfill, "synthesize_tile", flaky)
    rc, out = fill(mapdir, "o.svg", "--tile-size", "40", "--jobs", "1")
    err = capsys.readouterr().err
    assert rc == 1 and "region 'basin tile 1,1' not filled: internal error: ValueError: boom" in err
    assert "region 'inlier tile 1,1' not filled" in err and "2 regions or tiles failed" in err
    text = out.read_text()
    assert 'id="svgtile-basin"' in text and 'id="svgtile-inlier"' in text and 'failed="2"' in text
    _, whole = fill(mapdir, "w.svg", "--jobs", "1")
    lost = set(whole.read_text().splitlines()) - set(text.splitlines())
    assert sum("<use" in line for line in lost) > 5


def test_parse_styles_is_untouched_by_the_runner_options():
    """The map's new options are command options, not styles keys."""
    with pytest.raises(Exception, match="unknown key 'tile_size'"):
        parse_styles({"tile_size": 3, "classes": {"a": {"exemplar": "x.svg"}}})


# ----------------------------------------------------------------------------- a cluster


@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as lc, \
            distributed.Client(lc) as client:  # fmt: skip
        yield lc, client


def tile_units(region, ex, stats, size):
    from svgtile.apps.tiled import _tile

    tiles = plan(region, ex, "tile", size)
    p = ENGINES["tile"].Params()
    return tiles, [Unit(f"t{t.i},{t.j}", _tile, (ex, stats, region, "tile", t, 3, "clip", p)) for t in tiles]


def test_one_or_two_workers_any_completion_order_same_motifs(cluster):
    lc, client = cluster
    ex, stats = load("gravel")
    region = holed_region()
    whole = columns(synthesize(ex, region, "tile", seed=3, stats=stats).arrangement).tobytes()
    tiles, units = tile_units(region, ex, stats, 55.0)

    def gather(order=None) -> bytes:
        got: dict[int, Arrangement] = {}
        collect = Bands(tiles, got.__setitem__)
        seen = []
        consume(client, units, lambda n, arr, err: (seen.append(n), collect.add(n, arr)), order=order)
        assert sorted(seen) == list(range(len(units)))
        return columns(Arrangement.concat([got[b] for b in sorted(got)])).tobytes()

    assert len(client.scheduler_info()["workers"]) == 2
    assert gather() == whole
    assert gather(order=lambda fs: fs[::-1]) == whole
    assert gather(order=lambda fs: random.Random(7).sample(fs, len(fs))) == whole
    lc.scale(1)
    deadline = time.monotonic() + 60
    while len(client.scheduler_info()["workers"]) > 1 and time.monotonic() < deadline:
        time.sleep(0.1)
    assert len(client.scheduler_info()["workers"]) == 1
    try:
        assert gather() == whole
    finally:
        lc.scale(2)
        client.wait_for_workers(2)


def test_a_cluster_address_writes_the_local_bytes(cluster, mapdir, tmp_path):
    lc, _ = cluster
    rc, local = fill(mapdir, "local.svg", "--jobs", "1")
    assert rc == 0
    rc, remote = fill(mapdir, "remote.svg", "--scheduler", lc.scheduler_address, "--tile-size", "30")
    assert rc == 0 and remote.read_bytes() == local.read_bytes()
    rc, whole = synth(tmp_path, "w.svg")
    rc2, out = synth(tmp_path, "c.svg", "--scheduler", lc.scheduler_address, "--tile-size", "70")
    assert rc == rc2 == 0 and out.read_bytes() == whole.read_bytes()


def test_a_unit_failing_on_the_cluster_is_one_message(cluster):
    _, client = cluster
    got = {}
    consume(client, [Unit("ok", abs, (-2,)), Unit("bad", math.sqrt, (-1.0,))], lambda n, v, e: got.setdefault(n, (v, e)))
    assert got == {0: (2, None), 1: (None, "internal error: ValueError: math domain error")}


def test_the_processes_scheduler_starts_its_own_cluster(mapdir):
    rc, local = fill(mapdir, "local.geojson", "--jobs", "1")
    rc2, out = fill(mapdir, "proc.geojson", "--scheduler", "processes", "--jobs", "2", "--tile-size", "50")
    assert rc == rc2 == 0 and out.read_bytes() == local.read_bytes()


def test_run_hands_each_result_over_once_on_every_local_path():
    for workers in (1, 2):
        got: list = []
        schedule.run([Unit("sq", pow, (n, 2)) for n in range(6)], lambda n, v, e, got=got: got.append((n, v, e)),
                     workers=workers)  # fmt: skip
        assert sorted(got) == [(n, n * n, None) for n in range(6)]


def test_a_texture_document_is_head_lines_tail():
    """svg_document is head + lines + tail (the streaming writer's split)."""
    ex, stats = load("gravel")
    result = synthesize(ex, Region.rectangle(50, 40), "tile", seed=1, stats=stats)
    from svgtile.svg.writer import svg_document_parts, use_elements

    head, tail = svg_document_parts(ex, result.region, boundary="clip", params=result.metadata())
    assert result_document(result) == head + "\n".join(use_elements(result.arrangement, ex.kinds)) + tail


def test_a_failing_writer_is_raised_not_blamed_on_the_units():
    def on_done(n, value, error):
        if n == 2:
            raise OSError("disk full")

    for workers in (1, 2):
        with pytest.raises(OSError, match="disk full"):
            schedule.run([Unit("sq", pow, (n, 2)) for n in range(5)], on_done, workers=workers)
