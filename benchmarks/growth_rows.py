"""Growth on a drawn exemplar of rows with and without its row lines (issue 13's likeness gate).

Run from the repository root: ``python benchmarks/growth_rows.py [SIZE [SEEDS [EXEMPLAR …]]]`` —
by default a 300 × 300 square, seeds 1,2,3, marsh and sand (the bundled exemplars whose order is
rows or a lattice; only marsh has row lines, :func:`svgtile.engines.growth.rows.row_lines`).  Each
texture is scored as tests/test_growth_auto.py scores it (:func:`svgtile.metrics.score`, centroid
boundary): likeness L, repetition, density ratio, overlaps and violators.  Variants: growth
without row lines (``rows=False``: the engine before them), growth with them (the default), and
the default followed by one iteration of ``--refine`` (Ma, Wei & Tong 2011's optimisation).
Seconds: synthesis, CPU of this process.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from svgtile import analyze, read_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import score

REPO = Path(__file__).resolve().parents[1]
VARIANTS = {"growth, no row lines": ({"rows": False}, 0), "growth": ({}, 0), "growth --refine 1": ({}, 1)}


def main(argv: list[str]) -> None:
    size = float(argv[0]) if argv else 300.0
    seeds = [int(s) for s in argv[1].split(",")] if len(argv) > 1 else [1, 2, 3]
    names = argv[2:] or ["marsh", "sand"]
    print("| exemplar | seed | variant | L | repetition | density ratio | overlaps / violators | CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    for name in names:
        ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
        st = analyze(ex)
        region = Region.rectangle(size, size)
        for seed in seeds:
            for label, (params, refine) in VARIANTS.items():
                t = time.process_time()
                arr = synthesize(ex, region, "growth", seed=seed, stats=st, boundary="centroid", params=params,
                                 refine=refine).arrangement  # fmt: skip
                dt = time.process_time() - t
                sc = score(ex, st, arr, region)
                print(f"| {name} | {seed} | {label} | {sc.likeness:.3f} | {sc.repetition:.3f} | {sc.density_ratio:.3f} | "
                      f"{sc.overlaps_total} / {sc.violators_total} | {dt:.2f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
