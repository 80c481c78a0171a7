"""``svgtile score`` in one process and on two, alternated in one process (issue 11).

    python benchmarks/score_two_cores.py EXEMPLAR TEXTURE [ROUNDS]

Each round measures the texture as ``svgtile score --jobs 1`` and ``--jobs 2`` do (read, the
baselines in the worker while reading, the footprint figures there while the others are
measured here; :mod:`svgtile.cli.score`) and prints one Markdown row each: wall, this process's
CPU (user + sys, the reading and its own figures), the worker's CPU (reaped at the end of the
round), and how long this process waited for the worker's two answers.  With the worker
answering before it is asked (waits ≈ 0), this process's CPU is the time a user waits on a
quiet machine, whatever the load makes of the wall.  The figures of both are compared
(``Score`` equality) and the imports are not counted (both pay them).  Run from the repository
root with the venv's python.
"""

from __future__ import annotations

import gc
import resource
import sys
import time
from concurrent.futures import Future

from svgtile.cli.common import load
from svgtile.cli.score import _second_process
from svgtile.metrics import likeness, score
from svgtile.metrics.scoring import worker_result
from svgtile.svg.texture import read_texture

waits: list[float] = []
_result = Future.result


def _timed_result(self, timeout=None):
    start = time.perf_counter()
    try:
        return _result(self, timeout)
    finally:
        waits.append(time.perf_counter() - start)


Future.result = _timed_result


def cpu(who: int) -> float:
    r = resource.getrusage(who)
    return r.ru_utime + r.ru_stime


def run(exemplar, stats, texture: str, jobs: int):
    likeness._BASELINES.clear()
    waits.clear()
    gc.disable()
    wall, own, child = time.perf_counter(), cpu(resource.RUSAGE_SELF), cpu(resource.RUSAGE_CHILDREN)
    with _second_process(jobs) as pool:
        early = pool.submit(likeness.baseline_distances, exemplar, stats) if pool is not None else None
        arr, region = read_texture(texture, exemplar)
        result = score(exemplar, stats, arr, region, pool=pool, baselines=worker_result(early))
        wall = time.perf_counter() - wall
        own = cpu(resource.RUSAGE_SELF) - own
        if pool is not None:
            pool.shutdown(wait=True)  # reaps the worker, so that its CPU is counted
    gc.enable()
    load = open("/proc/loadavg").read().split()[0]
    shown = " + ".join(f"{w:.2f}" for w in waits) or "–"
    print(f"| --jobs {jobs} | {load} | {wall:.2f} s | {own:.2f} s | {cpu(resource.RUSAGE_CHILDREN) - child:.2f} s | {shown} |")
    return result


def main() -> None:
    exemplar, texture = sys.argv[1:3]
    rounds = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    ex, stats = load(exemplar)
    print("| command | load | wall | this process's CPU | worker's CPU | waited for the worker |")
    print("|---|---:|---:|---:|---:|---:|")
    for _ in range(rounds):
        one, two = run(ex, stats, texture, 1), run(ex, stats, texture, 2)
        assert one == two, "the figures differ"


if __name__ == "__main__":
    main()
