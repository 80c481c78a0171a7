"""Optimize's kind mix on the bundled exemplars, with its L and the other bounds (omix14).

Each bundled exemplar over a square of 4 exemplar widths (as benchmarks/optimize_bundled_seeds.py),
``--engine optimize``, seeds 1–3: the start's kind-mix TV (:func:`svgtile.engines.optimize.init.patch_start`,
counted over every start motif) and the texture's, ``svgtile score``'s ``kind mix TV`` (shape
classes, the score's window), with L (tests/optimize_measure.py), repetition, density / ρ and the
conflicts.  One line per exemplar and seed, then the count of runs over TV 0.05 and issue 14's
misses.  ``--set MODULE:NAME=VALUE`` overrides a module constant first.

Run by hand (about 4 minutes):
    python benchmarks/optimize_kind_mix.py
    python benchmarks/optimize_kind_mix.py --set svgtile.engines.optimize.assign:MIX_WINDOW=12.0 gravel shale
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
from optimize_bundled_seeds import bundled_squares  # noqa: E402
from optimize_measure import distance  # noqa: E402
from scatter_gates import apply_sets  # noqa: E402
from test_optimize_sets import misses  # noqa: E402

from svgtile.analysis.neighbourhood import likeness  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402
from svgtile.metrics import kind_mix_tv, score  # noqa: E402

SEEDS = (1, 2, 3)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--set", action="append", default=[], metavar="MODULE:NAME=VALUE")
    parser.add_argument("names", nargs="*", help="bundled exemplars (default: all)")
    args = parser.parse_args()
    apply_sets(parser, args.set)
    from svgtile.engines.optimize import init

    starts = []
    original = init.patch_start

    def recording(*a, **k):
        out = original(*a, **k)
        starts.append(out[0] if isinstance(out, tuple) else out)
        return out

    init.patch_start = recording
    over, missed, Ls = 0, 0, []
    for path, ex, stats, region in bundled_squares(args.names):
        for seed in SEEDS:
            base = tuple(distance(ex, stats, region, synthesize(ex, region, b, seed=seed, stats=stats).arrangement)
                         for b in ("tile", "random"))  # fmt: skip
            starts.clear()
            arr = synthesize(ex, region, "optimize", seed=seed, stats=stats).arrangement
            s = score(ex, stats, arr, region)
            L = likeness(distance(ex, stats, region, arr), *base)

            class M:  # what misses() reads
                likeness, repetition = L, s.repetition
                overlaps, violators, density_ratio = s.overlaps_total, s.violators_total, s.density_ratio

            miss = misses(M)
            over += s.kind_mix_tv > 0.05
            missed += bool(miss)
            Ls.append(L)
            start_tv = kind_mix_tv(starts[0], stats) if starts else float("nan")
            print(f"{path.stem:14s} seed {seed}: start TV {start_tv:.3f}  TV {s.kind_mix_tv:.3f}  L {L:.3f}  "
                  f"rep {s.repetition:.3f}  density {s.density_ratio:.3f}  {' '.join(miss)}", flush=True)
    print(f"runs with TV > 0.05: {over}; runs missing issue 14's bounds: {missed}; mean L {np.mean(Ls):.3f}")


if __name__ == "__main__":
    main()
