"""Growth's repetition on marsh (issue 13's gate: repetition ≤ 0.2 with L ≥ 0.8, seeds 1–7).

Run from the repository root::

    python benchmarks/marsh_repetition.py seeds [SEEDS [PARAMS]]   # table 1
    python benchmarks/marsh_repetition.py windows [SEEDS]           # table 2
    python benchmarks/marsh_repetition.py probes [SEEDS]            # table 3

Marsh (``exemplars/marsh.svg``), growth, centroid boundary, scored by
:func:`svgtile.metrics.score` as tests/test_growth_kinds.py scores it.

1. ``seeds``: the 300 × 300 square at the origin: L, repetition (its vector and the exemplar's
   share P_ex there), density ratio, overlaps, violators, motifs and the synthesis's CPU seconds;
   ``PARAMS`` is a JSON object of :class:`~svgtile.engines.growth.GrowthParams` fields (library
   variants, e.g. ``'{"kind_sweeps": 0}'``).
2. ``windows``: the same world texture (growth is world-anchored: a region only chooses which
   motifs are kept) scored in 300 × 300 regions at five offsets — how much the figure moves with
   the window alone.
3. ``probes``: each growth texture's rows (the exemplar's row lines, :mod:`svgtile.engines.growth.rows`)
   rearranged, motifs not checked for conflicts: *random row phases* — every row moved along
   itself by its own random shift (the rows' own spacing kept, the relations between rows gone);
   *uniform along rows* — every motif at a uniform random place along its row.  Repetition of
   three draws, and L of the first.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np
import shapely

from svgtile import analyze, read_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.rows import row_lines
from svgtile.metrics import score

REPO = Path(__file__).resolve().parents[1]
OFFSETS = ((0, 0), (90, 0), (0, 90), (90, 90), (-150, 40))


def grown(ex, st, region, seed, params=None):
    return synthesize(ex, region, "growth", seed=seed, stats=st, boundary="centroid", params=params).arrangement


def seeds_table(ex, st, seeds, params):
    region = Region.rectangle(300, 300)
    print("| seed | L | repetition | vector | P_ex | density | overlaps / violators | motifs | CPU s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for seed in seeds:
        t = time.process_time()
        arr = grown(ex, st, region, seed, params)
        cpu = time.process_time() - t
        s = score(ex, st, arr, region)
        vx, vy = s.repetition_vector
        print(f"| {seed} | {s.likeness:.3f} | {s.repetition:.3f} | ({vx:.1f}, {vy:.1f}) | "
              f"{s.repetition_exemplar:.3f} | {s.density_ratio:.3f} | {s.overlaps_total} / {s.violators_total} | "
              f"{len(arr)} | {cpu:.2f} |", flush=True)  # fmt: skip


def windows_table(ex, st, seeds):
    print("| seed | " + " | ".join(f"at {o}" for o in OFFSETS) + " | mean |")
    print("|---" * (len(OFFSETS) + 2) + "|")
    for seed in seeds:
        rep, like = [], []
        for ox, oy in OFFSETS:
            region = Region(shapely.box(ox, oy, ox + 300, oy + 300))
            s = score(ex, st, grown(ex, st, region, seed), region)
            rep.append(s.repetition)
            like.append(s.likeness)
        cells = " | ".join(f"{r:.3f} (L {v:.3f})" for r, v in zip(rep, like, strict=True))
        print(f"| {seed} | {cells} | {np.mean(rep):.3f} |", flush=True)


def probes_table(ex, st, seeds):
    rows = row_lines(ex)
    region = Region.rectangle(300, 300)
    print("| seed | growth: repetition / L | random row phases: repetition ×3 / L | uniform along rows: repetition ×3 / L |")
    print("|---|---|---|---|")
    for seed in seeds:
        arr = grown(ex, st, region, seed)
        row = np.round((arr.xy @ rows.across - rows.offset) / rows.pitch).astype(np.int64)
        rng = np.random.default_rng(seed)
        shifted, uniform = [], []
        for _ in range(3):
            xy = arr.xy.copy()
            for r in np.unique(row):
                sel = row == r
                xy[sel, 0] = (xy[sel, 0] + rng.uniform(0, 300)) % 300  # marsh's rows run along x
            shifted.append(score(ex, st, Arrangement(arr.kind, xy, arr.angle, arr.scale), region))
            xy = arr.xy.copy()
            xy[:, 0] = rng.uniform(0, 300, len(xy))
            uniform.append(score(ex, st, Arrangement(arr.kind, xy, arr.angle, arr.scale), region))
        s = score(ex, st, arr, region)

        def cell(group):
            return " ".join(f"{g.repetition:.3f}" for g in group) + f" / {group[0].likeness:.3f}"

        print(f"| {seed} | {s.repetition:.3f} / {s.likeness:.3f} | {cell(shifted)} | {cell(uniform)} |", flush=True)


def main() -> None:
    what = sys.argv[1] if len(sys.argv) > 1 else "seeds"
    seeds = [int(s) for s in (sys.argv[2] if len(sys.argv) > 2 else "1,2,3,4,5,6,7").split(",")]
    ex = read_exemplar(REPO / "exemplars" / "marsh.svg")
    st = analyze(ex)
    if what == "seeds":
        seeds_table(ex, st, seeds, json.loads(sys.argv[3]) if len(sys.argv) > 3 else None)
    elif what == "windows":
        windows_table(ex, st, seeds)
    elif what == "probes":
        probes_table(ex, st, seeds)
    else:
        raise SystemExit(f"marsh_repetition.py: unknown table {what!r} (seeds, windows, probes)")


if __name__ == "__main__":
    main()
