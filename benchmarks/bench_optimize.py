"""Benchmark the optimize engine's solver (Ma, Wei & Tong 2011): 10 iterations over ~N motifs.

One case per process (peak RSS is the case's own).  The start is the patch engine's texture of
about N motifs (``--refine`` on patch, the issue's measure), or the optimize engine's own
patch start; timed apart: the start, the exemplar's samples and similarity sets, and each
iteration (search, assignment, non-penetration).

Run by hand:  python benchmarks/bench_optimize.py [EXEMPLAR] [--count 100000] [--iterations 10] [--rebalance]
It prints one Markdown table row for benchmarks/README.md, then (with ``--stages``) the CPU time
of each step of the iterations, measured in the same run by wrapping the solver's functions.
Wall time on the shared machine depends on its load; the process's CPU time much less.
"""

from __future__ import annotations

import argparse
import math
import platform
import resource
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_EXEMPLAR = HERE.parent / "exemplars" / "gravel.svg"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("exemplar", nargs="?", default=str(DEFAULT_EXEMPLAR))
    ap.add_argument("--count", type=int, default=100_000)
    ap.add_argument("--iterations", type=int, default=10)
    ap.add_argument("--stages", action="store_true", help="also print the CPU time of each step")
    ap.add_argument("--rebalance", action="store_true",
                    help="bring the kind mix back each iteration, as the engine does for a drawn exemplar")  # fmt: skip
    args = ap.parse_args()

    from svgtile import analyze, read_exemplar
    from svgtile.core.region import Region
    from svgtile.engines import synthesize
    from svgtile.engines.optimize import solver
    from svgtile.engines.optimize.samples import exemplar_samples
    from svgtile.engines.optimize.solver import Settings, refine

    ex = read_exemplar(args.exemplar)
    stats = analyze(ex)
    side = math.sqrt(args.count / stats.count_density)
    region = Region.rectangle(side, side)
    # warm the numba cache on a small run (compilation is once per machine, not per run)
    small = Region.rectangle(side / 20, side / 20)
    synthesize(ex, small, "patch", seed=1, stats=stats, refine=1)

    t0 = time.perf_counter()
    start = synthesize(ex, region, "patch", seed=1, stats=stats).arrangement
    t1 = time.perf_counter()
    samples = exemplar_samples(ex, Settings().neighbours)
    spent: dict[str, float] = {}
    if args.stages:
        for name in ("output_neighbourhoods", "first_candidates", "coherent_candidates", "search", "predictions",
                     "solve_positions", "assign_kinds", "pairings", "settle", "conflict_codes", "flawed"):  # fmt: skip
            setattr(solver, name, _timed(getattr(solver, name), name, spent))
    t2 = time.perf_counter()
    c2 = time.process_time()
    marks: list[float] = []
    _arr, energies = refine(start, ex, stats, region, "clip", iterations=args.iterations, key=1, samples=samples,
                           settings=Settings(rebalance=args.rebalance),
                           progress=lambda stage, f: marks.append(time.perf_counter()))  # fmt: skip
    t3 = time.perf_counter()
    c3 = time.process_time()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    steps = [b - a for a, b in zip(marks, [*marks[1:], t3], strict=True)]
    print(f"| {Path(args.exemplar).stem} | {len(start):,} | {t1 - t0:.1f} | {t2 - t1:.2f} | {t3 - t2:.1f} | "
          f"{min(steps):.1f}–{max(steps):.1f} | {c3 - c2:.1f} | {peak:.0f} | {energies[0]:.3f} → {energies[-1]:.3f} |")
    if spent:
        total = c3 - c2
        print(" · ".join(f"{k} {v:.1f} s ({v / total:.0%})" for k, v in sorted(spent.items(), key=lambda kv: -kv[1])))
    print(f"({platform.machine()}, Python {sys.version.split()[0]}, {args.iterations} iterations)", file=sys.stderr)


def _timed(fn, name: str, spent: dict[str, float]):
    """``fn`` that adds its CPU time to ``spent[name]``."""

    def run(*args, **kwargs):
        t = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            spent[name] = spent.get(name, 0.0) + time.process_time() - t

    return run


if __name__ == "__main__":
    main()
