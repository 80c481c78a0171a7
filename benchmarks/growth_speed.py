"""Growth engine timings (issue 13): motifs per second with and without relaxation, peak memory.

Run: ``python benchmarks/growth_speed.py EXEMPLAR SIDE [SIDE …] [--relaxed-only] [--tile]`` — one
square region per SIDE (user units), seed 1, boundary clip; prints motifs, wall and CPU seconds
(the process's user + system time: on a shared machine the wall time is inflated by the load,
the CPU time much less) and peak RSS.  ``--tile`` imports EXEMPLAR as a seamless pattern tile.
The first run in a fresh checkout also compiles the growth kernel (cached afterwards); a warm-up
on a small region keeps that out of the figures.
"""

from __future__ import annotations

import resource
import sys
import time

from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize


def _cpu() -> float:
    u = resource.getrusage(resource.RUSAGE_SELF)
    return u.ru_utime + u.ru_stime


def main(argv: list[str]) -> None:
    flags = {a for a in argv if a.startswith("--")}
    args = [a for a in argv if not a.startswith("--")]
    ex, st = load_exemplar(args[0], as_tile="--tile" in flags, warn=lambda m: None)
    synthesize(ex, Region.rectangle(10, 10), "growth", seed=1, stats=st)  # compile / load the kernel
    for side in map(float, args[1:]):
        for relaxation in (True,) if "--relaxed-only" in flags else (True, False):
            t, c = time.perf_counter(), _cpu()
            r = synthesize(ex, Region.rectangle(side, side), "growth", seed=1, stats=st, params={"relaxation": relaxation})
            dt, dc = time.perf_counter() - t, _cpu() - c
            rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
            print(f"{args[0]} side={side:g} relaxation={relaxation} motifs={len(r)} seconds={dt:.2f} cpu={dc:.2f} "
                  f"peak_rss_mb={rss:.0f}", flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
