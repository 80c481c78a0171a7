"""Where growth's likeness is lost on a drawn exemplar of rows (issue 13's gate L ≥ 0.8 on marsh).

Run from the repository root: ``python benchmarks/growth_kinds.py [EXEMPLAR [SEEDS [SIZE]]]`` —
by default marsh, seeds 1,2,3, a 300 × 300 square, scored as tests/test_growth_auto.py scores it
(:func:`svgtile.metrics.score`, centroid boundary).  Four tables:

1. the textures: L, repetition, density ratio, and E (Ma, Wei & Tong 2011 §3.2 eq. 1, the
   figure L is made of) with kinds counted and ignored (α = 0: positions alone);
2. E of the interior motifs by their distance to the nearest edge of a growth cell (growth runs
   per world cell, :mod:`svgtile.engines.growth.engine`), the seeds pooled;
3. the same texture grown as one cell five exemplar widths wide (``cell_widths=5``: no seam
   within 150 units of its start), E by the distance from the cell's start seed (near the cell's
   centre, ``(150, 150)``: :meth:`~svgtile.engines.growth.engine.Growth.start`);
4. L, repetition and density of library variants of the engine (the final kind passes off, cell
   width, relaxation during growth, eq. 2's weights) on the same seeds.

E per group is :func:`svgtile.analysis.neighbourhood.neighbourhood_distance` over that group's
motifs (all of them: no sample).  Seconds are CPU of this process.
"""

from __future__ import annotations

import sys
import time
from itertools import pairwise
from pathlib import Path

import numpy as np

from svgtile import analyze, read_exemplar
from svgtile.analysis.neighbourhood import neighbourhood_distance
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth import GrowthParams, Weights
from svgtile.engines.growth.connectivity import reference_rings
from svgtile.metrics import score
from svgtile.metrics.likeness import ALPHA, K
from svgtile.metrics.window import in_window, interior, spacing

REPO = Path(__file__).resolve().parents[1]
EDGE_BINS = (0, 3, 6, 10, 15, 20, 31)
SEED_BINS = (0, 20, 40, 70, 100, 150)
VARIANTS = {
    "default": {},
    "no kind passes (growth.kinds, growth.neighbourkinds)": {"kind_sweeps": 0},
    "ring pass alone (no growth.neighbourkinds)": {"neighbourhood_sweeps": 0},
    "cells 0.75 wide": {"cell_widths": 0.75},
    "cells 1.5 wide": {"cell_widths": 1.5},
    "cells 2 wide": {"cell_widths": 2.0},
    "relax every 10": {"relax_every": 10},
    "w2 = 3": {"weights": Weights(1.0, 3.0, 0.0)},
    "w3 = 100 (the paper's)": {"weights": Weights(1.0, 1.0, 100.0)},
    "w3 = -1 (coherence)": {"weights": Weights(1.0, 1.0, -1.0)},
}


def grown(ex, st, region, seed, params=None):
    return synthesize(ex, region, "growth", seed=seed, stats=st, boundary="centroid", params=params).arrangement


def distances(ex, st, arr, groups):
    """E with kinds (α as the score's) and without (α = 0) over each group of motif indices."""
    s = spacing(st)
    out = []
    for g in groups:
        e = [neighbourhood_distance(arr.xy, arr.kind, ex.motifs.xy, ex.motifs.kind, spacing=s, k=K, alpha=a,
                                    centres=g, sample=None) if len(g) else np.nan for a in (ALPHA, 0.0)]  # fmt: skip
        out.append(e)
    return out


def main(argv: list[str]) -> None:
    name = argv[0] if argv else "marsh"
    seeds = [int(s) for s in argv[1].split(",")] if len(argv) > 1 else [1, 2, 3]
    size = float(argv[2]) if len(argv) > 2 else 300.0
    ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
    st = analyze(ex)
    region = Region.rectangle(size, size)
    window = interior(ex, region)
    p = GrowthParams()
    x0, y0, x1, y1 = ex.region.bounds
    cell = max(x1 - x0, y1 - y0, 6.0 * reference_rings(ex).mean_length) * p.cell_widths

    print(f"{name}, {size:g} × {size:g}, cells {cell:.2f} wide\n")
    print("| seed | L | repetition | density ratio | E | E, kinds ignored | CPU s |")
    print("|---|---|---|---|---|---|---|")
    textures = {}
    for seed in seeds:
        t = time.process_time()
        arr = textures[seed] = grown(ex, st, region, seed)
        dt = time.process_time() - t
        sc = score(ex, st, arr, region)
        (e, e0), = distances(ex, st, arr, [np.flatnonzero(in_window(arr, window))])
        print(f"| {seed} | {sc.likeness:.3f} | {sc.repetition:.3f} | {sc.density_ratio:.3f} | {e:.3f} | {e0:.3f} "
              f"| {dt:.2f} |", flush=True)  # fmt: skip

    print("\n| distance to a cell edge | motifs | E | E, kinds ignored |")
    print("|---|---|---|---|")
    pooled = {b: [] for b in range(len(EDGE_BINS) - 1)}
    for arr in textures.values():
        c = np.flatnonzero(in_window(arr, window))
        m = arr.xy[c] % cell
        edge = np.minimum(m, cell - m).min(1)
        groups = [c[(edge >= lo) & (edge < hi)] for lo, hi in pairwise(EDGE_BINS)]
        for b, (g, e) in enumerate(zip(groups, distances(ex, st, arr, groups), strict=True)):
            pooled[b].append((len(g), *e))
    for b, rows in pooled.items():
        n = np.array([r[0] for r in rows])
        e, e0 = (np.nansum([r[i] * r[0] for r in rows]) / max(n.sum(), 1) for i in (1, 2))
        print(f"| {EDGE_BINS[b]}–{EDGE_BINS[b + 1]} | {n.sum()} | {e:.3f} | {e0:.3f} |")

    print("\n| distance from the start seed, one cell 5 widths wide | motifs | E | E, kinds ignored |")
    print("|---|---|---|---|")
    pooled = {b: [] for b in range(len(SEED_BINS) - 1)}
    big = GrowthParams(cell_widths=5.0)
    centre = np.full(2, 2.5 * cell)
    for seed in seeds:
        arr = grown(ex, st, region, seed, big)
        c = np.flatnonzero(in_window(arr, window))
        d = np.hypot(*(arr.xy[c] - centre).T)
        groups = [c[(d >= lo) & (d < hi)] for lo, hi in pairwise(SEED_BINS)]
        for b, (g, e) in enumerate(zip(groups, distances(ex, st, arr, groups), strict=True)):
            pooled[b].append((len(g), *e))
    for b, rows in pooled.items():
        n = np.array([r[0] for r in rows])
        e, e0 = (np.nansum([r[i] * r[0] for r in rows]) / max(n.sum(), 1) for i in (1, 2))
        print(f"| {SEED_BINS[b]}–{SEED_BINS[b + 1]} | {n.sum()} | {e:.3f} | {e0:.3f} |")

    print("\n| variant | " + " | ".join(f"seed {s}: L / rep. / dens." for s in seeds) + " | mean L |")
    print("|---|" + "---|" * (len(seeds) + 1))
    for label, params in VARIANTS.items():
        cells, ls = [], []
        for seed in seeds:
            arr = textures[seed] if not params else grown(ex, st, region, seed, params)
            sc = score(ex, st, arr, region)
            ls.append(sc.likeness)
            cells.append(f"{sc.likeness:.3f} / {sc.repetition:.3f} / {sc.density_ratio:.3f}")
        print(f"| {label} | " + " | ".join(cells) + f" | {np.mean(ls):.3f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
