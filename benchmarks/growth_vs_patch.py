"""Growth against auto's previous choice for rows and lattices (issue 13, ``--engine auto``).

Run from the repository root: ``python benchmarks/growth_vs_patch.py [NAME …]`` — on each regular
tile of tests/test_growth_regular.py (all of them by default), the growth engine and the patch
engine with ``--grid lattice --max-rotation 0`` (what auto chose for a tile with rows or a lattice
before growth), with the figures of tests/growth_measure.py (4 periods, ≥ 200 units a side, seed 1)
and the seconds of the engine's own synthesis.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import numpy as np
from growth_measure import measure
from test_growth_regular import REGULAR_TILES

from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize

ENGINES = {"growth": {}, "patch": {"grid": "lattice", "max_rotation": 0.0}}


def main(argv: list[str]) -> None:
    print("| tile | engine | L | repetition | density ratio | overlaps / violators | seconds |")
    print("|---|---|---|---|---|---|---|")
    for name in argv or sorted(REGULAR_TILES):
        path = REGULAR_TILES[name]
        ex, st = load_exemplar(str(path), as_tile=True, warn=lambda m: None)
        w, h = ex.period
        n = max(4, int(np.ceil(200 / min(w, h))))
        for engine, params in ENGINES.items():
            t = time.perf_counter()
            synthesize(ex, Region.rectangle(n * w, n * h), engine, seed=1, stats=st, boundary="centroid", params=params)
            dt = time.perf_counter() - t
            f = measure(path, engine=engine, **params)
            print(f"| {name} | {engine} | {f.likeness:.3f} | {f.repetition:.3f} | {f.density_ratio:.3f} | "
                  f"{f.overlaps} / {f.violators} | {dt:.2f} |", flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
