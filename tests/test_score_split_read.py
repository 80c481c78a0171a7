"""The ``<use>`` scan of a texture split across two processes reads what one process reads.

``svgtile score --jobs 2`` hands the second half of a large texture's ``<use>`` lines to its
worker (:func:`svgtile.svg.texture.start_reading`); the halves are joined with the groups
renumbered in order of first appearance (:func:`svgtile.svg.uselines.joined`).  These tests
hold the split read to the serial one bit for bit: at every cut of a small texture, on
textures with several kinds, rotations, scales and kind suffixes, with odd and tiny line
counts, a worker that dies, and a half that is not in svgtile's own form.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import select
from concurrent.futures import (
    BrokenExecutor,
    Executor,
    Future,
    ProcessPoolExecutor,
    ThreadPoolExecutor,
)
from pathlib import Path

import numpy as np
import pytest
from conftest import arrange
from test_cli_score import VARIED

from svgtile.analysis.stats import analyze
from svgtile.cli.main import main
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.svg import uselines
from svgtile.svg.reader import parse_exemplar, read_exemplar
from svgtile.svg.texture import _own_use_block, read_texture
from svgtile.svg.uselines import OwnLines, joined, scan, start_block
from svgtile.svg.writer import svg_document

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
FORK = "fork" in multiprocessing.get_all_start_methods()


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    return a.dtype == b.dtype and a.shape == b.shape and np.ascontiguousarray(a).tobytes() == np.ascontiguousarray(b).tobytes()


def _same_lines(a: OwnLines, b: OwnLines) -> bool:
    poses = all(_same(getattr(a.pose, f), getattr(b.pose, f)) for f in ("t", "scale", "angle", "cos", "sin"))
    return (_same(a.group, b.group) and _same(a.first, b.first) and a.keys == b.keys and a.first_lines == b.first_lines
            and a.first_columns == b.first_columns and poses)  # fmt: skip


def _varied_texture(path: Path, n: int | None = None, engine: str = "random", seed: int = 4):
    """A texture of the varied exemplar: two symbols, <use> attributes, scaled uses, matrix() and
    rotate() suffixes — seven kinds; its first ``n`` motifs if given."""
    ex = parse_exemplar(VARIED)
    region = Region.rectangle(300, 220)
    arr = arrange(engine, ex, region, rng=np.random.default_rng(seed), stats=analyze(ex))
    if n is not None:  # n centred well inside the viewBox (one outside it is not read), kinds mixed
        inside = np.flatnonzero((arr.xy > 5).all(axis=1) & (arr.xy < [295, 215]).all(axis=1))
        each = [inside[arr.kind[inside] == k][:9] for k in range(len(ex.kinds))]
        arr = arr.take(np.random.default_rng(seed).permutation(np.concatenate(each))[:n])
    path.write_text(svg_document(ex, arr, region, boundary="none", params={}))
    return ex


def _body(path: Path) -> str:
    block = start_block(path.read_bytes(), None, 1)
    assert block is not None, "svgtile's own texture must take the text scan"
    return block.body


def test_the_halves_joined_at_every_cut_are_the_whole_scan(tmp_path):
    _varied_texture(tmp_path / "t.svg", 60)
    lines = _body(tmp_path / "t.svg").split("\n")
    whole = scan("\n".join(lines))
    assert len(whole.first) >= 5, "several kinds, so that the renumbering is tested"
    for k in range(1, len(lines)):
        both = joined(scan("\n".join(lines[:k])), scan("\n".join(lines[k:])))
        assert _same_lines(both, whole), k


def test_a_kind_first_met_in_the_second_half_is_numbered_after_the_first_halfs(tmp_path):
    ex = read_exemplar(EXEMPLARS / "gravel.svg")
    rng = np.random.default_rng(8)
    n = 41  # odd
    kind = np.zeros(n, np.int64)
    kind[30:] = [1, 2, 0, 2, 1, 3, 3, 0, 2, 1, 3][: n - 30]
    kind[5] = 2  # kind 2 first met in the first half, kinds 1 and 3 only in the second
    arr = Arrangement(kind % len(ex.kinds), rng.uniform(5, 195, (n, 2)), rng.uniform(-180, 180, n), np.ones(n))
    path = tmp_path / "t.svg"
    path.write_text(svg_document(ex, arr, Region.rectangle(200, 200), boundary="none", params={}))
    body = _body(path)
    whole = scan(body)
    middle = body.find("\n", len(body) // 2)
    first, second = scan(body[:middle]), scan(body[middle + 1 :])
    assert len(first.first) < len(whole.first)  # the second half brings new groups
    assert _same_lines(joined(first, second), whole)


def _read_both(path: Path, ex, pool: Executor, split_above: int = 1):
    serial = read_texture(path, ex)
    split = read_texture(path, ex, pool=pool, split_above=split_above)
    for field in ("kind", "xy", "angle", "scale"):
        assert _same(getattr(split[0], field), getattr(serial[0], field)), field
    assert split[1].shape.equals(serial[1].shape)
    return serial, split


@pytest.mark.skipif(not FORK, reason="no fork on this system: svgtile score reads in one process")
@pytest.mark.parametrize(
    ("name", "engine", "options"),
    [
        ("gravel", "patch", {}),  # every motif rotated
        ("breccia-plain", "patch", {"vary_orientation": True}),
        ("chert-nodules", "tile", {}),
        ("varied", "random", {}),  # scaled uses, a matrix() suffix, <use> attributes
        ("varied", "tile", {}),
    ],
)
def test_the_split_read_is_the_serial_read_in_a_forked_worker(tmp_path, name, engine, options):
    path = tmp_path / "t.svg"
    if name == "varied":
        ex = _varied_texture(path, engine=engine)
    else:
        ex = read_exemplar(EXEMPLARS / f"{name}.svg")
        region = Region.rectangle(150, 110, x=-3.5, y=2.25)
        arr = arrange(engine, ex, region, rng=np.random.default_rng(4), stats=analyze(ex), **options)
        path.write_text(svg_document(ex, arr, region, boundary="clip", params={}))
    calls, futures = [], []
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork")) as pool:
        submit = pool.submit
        pool.submit = lambda fn, *a, **k: calls.append(fn.__name__) or futures.append(submit(fn, *a, **k)) or futures[-1]
        serial, _ = _read_both(path, ex, pool)
    assert calls == ["scan_lent"] and len(serial[0]) > 20
    # forked at the hand-over, the worker found the document in its memory and scanned its part
    assert isinstance(futures[0].result(), OwnLines)


@pytest.mark.skipif(not FORK, reason="no fork on this system: svgtile score reads in one process")
def test_a_worker_forked_before_the_document_was_read_leaves_its_part_here(tmp_path):
    """The worker scans its part in the document it inherited (score11e); one forked before the
    file was read holds no such document: it says so (False) and this process scans the part."""
    ex = _varied_texture(tmp_path / "t.svg")
    futures = []
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork")) as pool:
        pool.submit(int).result()  # forked now, before the read
        submit = pool.submit
        pool.submit = lambda fn, *a, **k: futures.append(submit(fn, *a, **k)) or futures[-1]
        serial, _ = _read_both(tmp_path / "t.svg", ex, pool)
    assert len(futures) == 1 and futures[0].result() is False and len(serial[0]) > 100
    assert uselines._LENT is None, "the document is not held after the read"


@pytest.mark.skipif(not FORK, reason="no fork on this system: svgtile score reads in one process")
def test_this_process_scans_its_part_once_the_worker_has_begun_and_leaves_no_descriptor_open(tmp_path, monkeypatch):
    """The executor's threads need the GIL to pass the task on, and this process's own scan holds
    it for long stretches: the worker's scan began up to 0.13 s after this process's (score11f).  ``cut_document`` now
    scans this process's part only once the worker has said it began (a byte on the lent
    document's pipe), and the pipe is closed when the document is taken back."""
    monkeypatch.setattr(uselines, "START_WAIT", 30.0)  # a slow fork on a loaded machine is no failure
    _varied_texture(tmp_path / "t.svg")
    data = (tmp_path / "t.svg").read_bytes()
    fds = sorted(os.listdir("/proc/self/fd")) if Path("/proc/self/fd").is_dir() else None
    begun = []
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork")) as pool:
        block = start_block(data, pool, 1)  # the worker is forked here, before the patch below
        assert block is not None and block.far is not None
        pipe = uselines._LENT[3][0]
        here = uselines.scan
        monkeypatch.setattr(uselines, "scan", lambda text: begun.append(select.select([pipe], [], [], 0)[0]) or here(text))
        assert uselines.cut_document(data, block) is not None
    assert begun == [[pipe]], "this process scanned before the worker had begun"
    assert uselines._LENT is None
    if fds is not None:
        assert sorted(os.listdir("/proc/self/fd")) == fds


@pytest.mark.skipif(not FORK, reason="no fork on this system: svgtile score reads in one process")
def test_a_pipe_that_cannot_be_polled_costs_the_wait_not_the_read(tmp_path, monkeypatch):
    """The wait only saves time: where the pipe cannot be polled (no ``select.poll``, a descriptor
    ``poll`` refuses) the read goes on at once and reads the same."""

    class NoPoll:
        POLLIN = select.POLLIN

        @staticmethod
        def poll():
            raise OSError("no poll here")

    ex = _varied_texture(tmp_path / "t.svg")
    monkeypatch.setattr(uselines, "select", NoPoll)
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork")) as pool:
        serial, _ = _read_both(tmp_path / "t.svg", ex, pool)
    assert len(serial[0]) > 100 and uselines._LENT is None


@pytest.mark.parametrize("n", [1, 2, 3, 7])
def test_tiny_and_odd_textures_read_the_same(tmp_path, n):
    ex = _varied_texture(tmp_path / "t.svg", n)
    with ThreadPoolExecutor(1) as pool:
        serial, _ = _read_both(tmp_path / "t.svg", ex, pool)
    assert len(serial[0]) == n


def test_small_textures_are_not_split(tmp_path):
    ex = _varied_texture(tmp_path / "t.svg", 50)

    class Refusing(Executor):
        def submit(self, fn, /, *args, **kwargs):
            raise AssertionError("a texture below split_above was handed over")

    _read_both(tmp_path / "t.svg", ex, Refusing(), split_above=51)


class _DeadWorker(Executor):
    """An executor whose worker died before it answered (killed, out of memory)."""

    def submit(self, fn, /, *args, **kwargs):
        future = Future()
        future.set_exception(BrokenExecutor("the worker died"))
        return future


def test_a_dead_worker_leaves_its_half_to_this_process(tmp_path):
    ex = _varied_texture(tmp_path / "t.svg")
    serial, _ = _read_both(tmp_path / "t.svg", ex, _DeadWorker())
    assert len(serial[0]) > 100


@pytest.mark.parametrize("where", ["first half", "second half"])
def test_a_line_not_in_svgtiles_form_in_either_half_is_parsed_whole(tmp_path, where):
    ex = _varied_texture(tmp_path / "t.svg")
    text = (tmp_path / "t.svg").read_text()
    lines = text.split("\n")
    uses = [i for i, line in enumerate(lines) if line.lstrip().startswith("<use ")]
    at = uses[len(uses) // 4] if where == "first half" else uses[-2]
    lines[at] = lines[at].replace("<use ", '<use  ', 1)  # two spaces: XML, but not as svgtile writes it
    (tmp_path / "e.svg").write_text("\n".join(lines))
    assert _own_use_block((tmp_path / "e.svg").read_bytes()) is None
    with ThreadPoolExecutor(1) as pool:
        assert _own_use_block((tmp_path / "e.svg").read_bytes(), pool=pool, split_above=1) is None
        _read_both(tmp_path / "e.svg", ex, pool)


@pytest.mark.parametrize("where", ["first half", "second half"])
def test_a_nested_group_among_the_lines_is_parsed_whole(tmp_path, where):
    """The motif group's end is found as the document's last ``</g>`` (score11d: not searched
    for over all the lines): a group nested among the lines puts a ``</g>`` before it, which
    no ``<use>`` line matches, so the bulk read declines and the whole document is parsed —
    the same motifs as the file without the nested group (it has no transform)."""
    ex = _varied_texture(tmp_path / "t.svg")
    lines = (tmp_path / "t.svg").read_text().split("\n")
    uses = [i for i, line in enumerate(lines) if line.lstrip().startswith("<use ")]
    at = uses[len(uses) // 4] if where == "first half" else uses[-3]
    lines[at : at + 2] = ["    <g>", *lines[at : at + 2], "    </g>"]
    (tmp_path / "e.svg").write_text("\n".join(lines))
    assert _own_use_block((tmp_path / "e.svg").read_bytes()) is None
    plain = read_texture(tmp_path / "t.svg", ex)
    with ThreadPoolExecutor(1) as pool:
        assert _own_use_block((tmp_path / "e.svg").read_bytes(), pool=pool, split_above=1) is None
        nested, _ = _read_both(tmp_path / "e.svg", ex, pool)
    for field in ("kind", "xy", "angle", "scale"):
        assert _same(getattr(nested[0], field), getattr(plain[0], field)), field


@pytest.mark.skipif(not FORK, reason="no fork on this system: svgtile score reads in one process")
def test_score_with_two_jobs_prints_the_same_when_the_read_is_split(tmp_path, capsys, monkeypatch):
    """With two jobs the worker, forked after the imports, scans the last part of the lines
    first (score11d: the fork before the imports, where a core was idle, is gone: it was never
    faster).  The figures are those of one process."""
    ex = read_exemplar(EXEMPLARS / "gravel.svg")
    region = Region.rectangle(300, 300)
    arr = arrange("patch", ex, region, rng=np.random.default_rng(5), stats=analyze(ex))
    path = tmp_path / "t.svg"
    path.write_text(svg_document(ex, arr, region, boundary="clip", params={"engine": "patch"}))
    args = ["score", str(EXEMPLARS / "gravel.svg"), str(path), "--json"]
    assert main([*args, "--jobs", "1"]) == 0
    one = capsys.readouterr().out
    handed = []
    monkeypatch.setattr(uselines, "SPLIT_ABOVE", 100)
    monkeypatch.setattr(uselines, "start_block", _spy(uselines.start_block, handed))
    assert main([*args, "--jobs", "2"]) == 0
    assert handed == [True]
    assert capsys.readouterr().out == one and json.loads(one)["likeness"] is not None


def _spy(start_block, handed):
    def spied(data, pool, split_above):
        block = start_block(data, pool, split_above)
        handed.append(block.far is not None)
        return block

    return spied


class _BrokenPool(Executor):
    """An executor whose worker died before it was asked anything more: it refuses new work."""

    def submit(self, fn, /, *args, **kwargs):
        raise BrokenExecutor("a child process terminated abruptly")


def test_score_with_a_worker_dead_before_it_is_asked_measures_everything_here(tmp_path, capsys, monkeypatch):
    """A worker killed while the texture is read: the scan's half, the baselines and the
    footprint figures are refused by the broken pool and measured in this process, the same
    figures, exit 0 (it was an internal error, exit 70)."""
    from contextlib import contextmanager

    from svgtile.cli import score as score_cli

    ex = read_exemplar(EXEMPLARS / "gravel.svg")
    region = Region.rectangle(300, 300)
    arr = arrange("patch", ex, region, rng=np.random.default_rng(5), stats=analyze(ex))
    path = tmp_path / "t.svg"
    path.write_text(svg_document(ex, arr, region, boundary="clip", params={"engine": "patch"}))
    args = ["score", str(EXEMPLARS / "gravel.svg"), str(path), "--json"]
    assert main([*args, "--jobs", "1"]) == 0
    one = capsys.readouterr().out

    @contextmanager
    def broken(jobs):
        yield _BrokenPool()

    monkeypatch.setattr(score_cli, "_second_process", broken)
    monkeypatch.setattr(uselines, "SPLIT_ABOVE", 100)
    assert main([*args, "--jobs", "2"]) == 0
    assert capsys.readouterr().out == one
