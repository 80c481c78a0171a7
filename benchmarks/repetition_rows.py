"""What the repetition figure reads in FGDC 619, 620 and 670 (issue 13): the tile engine, growth,
and the two probes of tests/row_probes.py (the tile's rows at random phases; rows whose phases
step as the tile's), each with its likeness L, density ratio, conflicts, the figure, and the
figure's next modes with the ones found before left out (:func:`row_probes.successive_modes`).

Run from the repository root: ``python benchmarks/repetition_rows.py [619 620 670]`` (4 × 4
periods, seed 1, as tests/test_growth_regular.py's probes).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from growth_measure import SHARED, baselines, distance
from row_probes import markov_rows, shuffled_rows, successive_modes

from svgtile.analysis.neighbourhood import likeness
from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import score


def main(names: list[str]) -> None:
    print("| tile | texture | L | repetition (vector) | next modes, the ones before left out | density | overlaps / violators |")
    print("|---|---|---|---|---|---|---|")
    for name in names or ["619", "620", "670"]:
        ex, st = load_exemplar(str(SHARED / "fgdc-geologic-patterns" / "lithology" / f"{name}.svg"), as_tile=True,
                               warn=lambda m: None)  # fmt: skip
        w, h = ex.period
        region = Region.rectangle(4 * w, 4 * h)
        ends = baselines(ex, st, region)
        textures = {engine: synthesize(ex, region, engine, seed=1, stats=st, boundary="centroid").arrangement
                    for engine in ("tile", "growth")}  # fmt: skip
        textures["rows at random phases"] = shuffled_rows(ex, st, region, rng=np.random.default_rng(1))
        textures["rows stepping as the tile's"] = markov_rows(ex, st, region, rng=np.random.default_rng(1))
        for label, arr in textures.items():
            s = score(ex, st, arr, region)
            modes = successive_modes(arr, ex, st, region, 6)
            fmt = [f"{v:.3f} ({x:.2f}, {y:.2f})" if vec is not None else f"{v:.3f}" for v, vec in modes
                   for x, y in [vec or (0.0, 0.0)]]  # fmt: skip
            print(f"| {name} | {label} | {likeness(distance(arr, ex, st, region), *ends):.3f} | {fmt[0]} | "
                  f"{'; '.join(fmt[1:])} | {s.density_ratio:.3f} | {s.overlaps_total} / {s.violators_total} |",
                  flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
