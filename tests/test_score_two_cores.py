"""``svgtile score`` on two cores gives the figures it gives on one, bit for bit.

The baselines' neighbourhood distance is measured in a forked worker process while the texture
is read, the conflicts and the texture's empty disc there while the other figures are measured
here (issue 11's last criterion; timings in benchmarks/README.md, "`svgtile score` on two
cores").  Each test compares the JSON of both (``repr`` of every float), so a figure that comes
back different, or from the wrong place, fails.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import sys
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

from svgtile import metrics
from svgtile.analysis.stats import analyze
from svgtile.cli.main import main
from svgtile.cli.score import _default_jobs, _second_process
from svgtile.core.region import Region
from svgtile.metrics.likeness import baseline_distances
from svgtile.svg.reader import read_exemplar
from svgtile.svg.writer import svg_document

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
FORK = "fork" in multiprocessing.get_all_start_methods()
LINUX = sys.platform.startswith("linux")


@pytest.fixture(scope="module")
def gravel():
    """A gravel texture of about 2,800 motifs, its exemplar, analysis and region."""
    ex = read_exemplar(EXEMPLARS / "gravel.svg")
    stats = analyze(ex)
    region = Region.rectangle(380, 380)
    arr = arrange("patch", ex, region, rng=np.random.default_rng(5), stats=stats)
    return ex, stats, arr, region


def _json(result: metrics.Score) -> str:
    return json.dumps(result.to_dict(), allow_nan=True)


def _fork_pool() -> ProcessPoolExecutor:
    return ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"))


# every figure's path: sampled (footprints built where looked at), every motif, and --exact
CASES = {"sampled": {"sample_above": 1000, "sample_motifs": 600}, "whole": {}, "exact": {"exact": True}}


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("executor", ["process", "thread"])
def test_figures_measured_in_a_worker_are_the_serial_ones(gravel, case, executor):
    if executor == "process" and not FORK:
        pytest.skip("no fork on this system: svgtile score measures in one process")
    ex, stats, arr, region = gravel
    serial = metrics.score(ex, stats, arr, region, **CASES[case])
    assert (serial.sample is not None) == (case == "sampled")
    with _fork_pool() if executor == "process" else ThreadPoolExecutor(1) as pool:
        early = pool.submit(baseline_distances, ex, stats)
        parallel = metrics.score(ex, stats, arr, region, pool=pool, baselines=early.result(), **CASES[case])
    assert _json(parallel) == _json(serial)
    assert serial.overlaps_total == 0 and serial.empty_disc_radius > 0 and serial.likeness is not None


def test_baselines_handed_in_are_the_ones_it_measures(gravel):
    ex, stats, arr, region = gravel
    known = baseline_distances(ex, stats)
    given = metrics.score(ex, stats, arr, region, baselines=known)
    assert (given.neighbourhood_tile, given.neighbourhood_random) == known
    # handed-in baselines are used as they are, not measured again
    odd = metrics.score(ex, stats, arr, region, baselines=(known[0], known[1] + 1.0))
    assert odd.neighbourhood_random == known[1] + 1.0 and odd.likeness != given.likeness


class _DeadWorker(Executor):
    """An executor whose worker died before it answered (killed, out of memory)."""

    def submit(self, fn, /, *args, **kwargs):
        future = Future()
        future.set_exception(BrokenExecutor("the worker died"))
        return future


def test_a_dead_worker_leaves_the_figures_to_this_process(gravel):
    ex, stats, arr, region = gravel
    serial = metrics.score(ex, stats, arr, region, sample_above=1000, sample_motifs=600)
    orphan = metrics.score(ex, stats, arr, region, sample_above=1000, sample_motifs=600, pool=_DeadWorker())
    assert _json(orphan) == _json(serial)


def test_jobs_chooses_one_or_two_processes():
    with _second_process(1) as pool:
        assert pool is None
    with _second_process(2) as pool:
        assert isinstance(pool, ProcessPoolExecutor) if LINUX else pool is None

@pytest.mark.skipif(not hasattr(os, "sched_getaffinity"), reason="no affinity to pretend")
@pytest.mark.parametrize("cores, load, jobs", [(1, 0.0, 1), (2, 0.0, 2), (2, 0.9, 2), (2, 1.2, 1), (4, 2.9, 2), (4, 3.2, 1)])
def test_two_processes_by_default_where_a_second_core_is_idle(monkeypatch, cores, load, jobs):
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cores)))
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load))
    assert _default_jobs() == jobs
    with _second_process(None) as pool:
        assert isinstance(pool, ProcessPoolExecutor) if jobs == 2 and LINUX else pool is None


@pytest.mark.parametrize("flag", [[], ["--json"]])
def test_cli_prints_the_same_with_one_or_two_jobs(tmp_path, capsys, gravel, flag):
    ex, _, arr, region = gravel
    (tmp_path / "t.svg").write_text(svg_document(ex, arr, region, boundary="clip", params={"engine": "patch"}))
    outs = []
    for jobs in ("1", "2"):
        assert main(["score", str(EXEMPLARS / "gravel.svg"), str(tmp_path / "t.svg"), "--jobs", jobs, *flag]) == 0
        outs.append(capsys.readouterr().out)
    assert outs[0] == outs[1] and "likeness" in outs[0]


def test_bad_texture_with_two_jobs_is_one_line(tmp_path, capsys):
    (tmp_path / "broken.svg").write_text("<svg><g></svg")
    rc = main(["score", str(EXEMPLARS / "gravel.svg"), str(tmp_path / "broken.svg"), "--jobs", "2"])
    out, err = capsys.readouterr()
    assert rc == 1 and out == ""
    assert err.count("\n") == 1 and err.startswith("svgtile: error: ") and "broken.svg" in err


_KILLED_COMMAND = """
import os, sys, time
from svgtile.cli.score import _second_process
with _second_process(2) as pool:
    print(pool.submit(os.getpid).result(), flush=True)
    time.sleep(60)
"""


@pytest.mark.skipif(not LINUX, reason="the second process is Linux's")
def test_a_worker_dies_with_a_command_killed_outright():
    """A command killed by SIGKILL (or the out-of-memory killer) cleans nothing up; its worker
    must not wait for work for ever as an orphan."""
    import signal
    import subprocess
    import time

    cmd = subprocess.Popen([sys.executable, "-c", _KILLED_COMMAND], stdout=subprocess.PIPE, text=True)
    try:
        worker = int(cmd.stdout.readline())
        os.kill(worker, 0)  # alive
        cmd.kill()
        cmd.wait(10)
        for _ in range(100):
            try:
                os.kill(worker, 0)
            except ProcessLookupError:
                break
            with open(f"/proc/{worker}/stat") as f:  # a zombie of init's is gone too
                if f.read().split(") ")[-1].startswith("Z"):
                    break
            time.sleep(0.05)
        else:
            os.kill(worker, signal.SIGKILL)
            pytest.fail("the worker outlived its command")
    finally:
        cmd.kill()


_SLOW_BASELINES = """
import sys, time
import svgtile.cli.score as cli_score
from svgtile.cli.main import main

def slow(*args, **kwargs):
    time.sleep(30)

cli_score.baseline_distances = slow  # the worker, forked from here, measures this one
sys.exit(main(["score", sys.argv[1], sys.argv[2], "--jobs", "2"]))
"""


@pytest.mark.skipif(not LINUX, reason="the second process is Linux's")
def test_a_bad_texture_with_two_jobs_does_not_wait_for_the_worker(tmp_path):
    """The texture is read while the worker measures the baselines; when it is bad, the command
    says so and ends at once — its exit used not to come until the worker's figure was done."""
    import subprocess
    import time

    (tmp_path / "broken.svg").write_text("<svg><g></svg")
    t = time.monotonic()
    done = subprocess.run([sys.executable, "-c", _SLOW_BASELINES, str(EXEMPLARS / "gravel.svg"),
                           str(tmp_path / "broken.svg")], capture_output=True, text=True, timeout=60)  # fmt: skip
    took = time.monotonic() - t
    assert done.returncode == 1 and done.stdout == ""
    assert done.stderr.count("\n") == 1 and "broken.svg" in done.stderr, done.stderr
    assert took < 15, took
