"""Growth against patch on the bundled exemplars with rows or a lattice (issue 13, ``--engine auto``).

Run from the repository root: ``python benchmarks/growth_auto.py [SIZE [SEEDS [EXEMPLAR …]]]`` —
by default a 300 × 300 square, seeds 1,2,3, and every bundled exemplar whose order
(:func:`svgtile.analysis.order.read_order`) is rows or a lattice.  Each engine runs with its
defaults (patch's are what ``--engine auto`` chose for these before growth) and the texture is
scored by :func:`svgtile.metrics.score` (likeness L against the tile and random engines,
repetition, density ratio, overlaps and violators over the whole texture).  Seconds: the
engine's synthesis, CPU of this process.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from svgtile import analyze, read_exemplar
from svgtile.analysis.order import read_order
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import score

REPO = Path(__file__).resolve().parents[1]
ENGINES = {"growth": ("growth", {}), "patch": ("patch", {})}


def main(argv: list[str]) -> None:
    size = float(argv[0]) if argv else 300.0
    seeds = [int(s) for s in argv[1].split(",")] if len(argv) > 1 else [1, 2, 3]
    paths = [REPO / "exemplars" / f"{n}.svg" for n in argv[2:]] or sorted((REPO / "exemplars").glob("*.svg"))
    print("| exemplar (order) | seed | engine | L | repetition | density ratio | overlaps / violators | CPU s |")
    print("|---|---|---|---|---|---|---|---|")
    for path in paths:
        ex = read_exemplar(path)
        order = read_order(ex)
        if order.kind not in ("rows", "lattice") and not argv[2:]:
            continue
        st = analyze(ex)
        region = Region.rectangle(size, size)
        for seed in seeds:
            for label, (engine, params) in ENGINES.items():
                t = time.process_time()
                arr = synthesize(ex, region, engine, seed=seed, stats=st, boundary="centroid",
                                 params=params).arrangement  # fmt: skip
                dt = time.process_time() - t
                sc = score(ex, st, arr, region)
                print(f"| {path.stem} ({order.kind}) | {seed} | {label} | {sc.likeness:.3f} | {sc.repetition:.3f} | "
                      f"{sc.density_ratio:.3f} | {sc.overlaps_total} / {sc.violators_total} | {dt:.2f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
