"""Hole filling after the patch engine's density repair, before → after, on whole-set tiles.

For each tile: imported as ``svgtile import`` does, synthesized with ``--engine auto`` (seed 1) on
the whole-set gate's region (tests/test_wholeset.py, :func:`gate_region`), once with hole filling
switched off (the engine as it was) and once with it; printed: auto's choice, density / ρ,
kind-mix TV, repetition, likeness L (against the ``tile`` and ``random`` baselines, as the gate
measures it), overlaps + violators and seconds.

    .venv/bin/python benchmarks/density_holes.py               # the FGDC tiles of the gate's density list
    .venv/bin/python benchmarks/density_holes.py fgdc/606 fgdc/612

Needs ``../shared/data`` beside the checkout (or ``$SVGTILE_DATA``).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from test_wholeset import KNOWN, SETS, gate_region  # noqa: E402

import svgtile.engines.patch.engine as patch_engine  # noqa: E402
from svgtile.analysis.neighbourhood import likeness, neighbourhood_distance  # noqa: E402
from svgtile.analysis.stats import analyze  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402
from svgtile.engines.choose import choose  # noqa: E402
from svgtile.metrics import score, spacing  # noqa: E402
from svgtile.svg.reader import parse_exemplar  # noqa: E402
from svgtile.tiles.importer import import_tile  # noqa: E402

FILL = patch_engine.fill_holes


def off(arr, *args, **kwargs):
    return arr


def measure(ex, stats, region, baselines):
    t0 = time.perf_counter()
    arr = synthesize(ex, region, "auto", seed=1, stats=stats).arrangement
    dt = time.perf_counter() - t0
    s = score(ex, stats, arr, region)
    sp = spacing(stats)
    X0, Y0, X1, Y1 = region.bounds

    def e(a):
        m = 3 * sp
        inside = np.flatnonzero((a.xy[:, 0] > X0 + m) & (a.xy[:, 0] < X1 - m) & (a.xy[:, 1] > Y0 + m) & (a.xy[:, 1] < Y1 - m))
        return neighbourhood_distance(a.xy, a.kind, ex.motifs.xy, ex.motifs.kind, spacing=sp, period=ex.period,
                                      centres=inside, sample=200, rng=np.random.default_rng(0))  # fmt: skip

    L = likeness(e(arr), e(baselines[0]), e(baselines[1]))
    return s, L, dt


def main(tiles: list[str]) -> None:
    print("| tile | engine | density / ρ | kind-mix TV | repetition | L | overlaps + violators | s |")
    print("|---|---|---|---|---|---|---|---|")
    for tile in tiles:
        folder, stem = tile.split("/")
        t = import_tile(SETS[folder] / f"{stem}.svg")
        ex = parse_exemplar(t.text, source=stem)
        stats = analyze(ex)
        region = gate_region(t.box, len(ex.motifs))
        baselines = [synthesize(ex, region, b, seed=1, stats=stats).arrangement for b in ("tile", "random")]
        got = []
        for fill in (off, FILL):
            patch_engine.fill_holes = fill
            got.append(measure(ex, stats, region, baselines))
        patch_engine.fill_holes = FILL
        (a, la, ta), (b, lb, tb) = got

        def pair(x, y, f="{:.3f}"):
            return f"{f.format(x)} → {f.format(y)}"

        print(f"| {tile} | {choose(ex, stats).engine} | {pair(a.density_ratio, b.density_ratio)} | "
              f"{pair(a.kind_mix_tv, b.kind_mix_tv)} | {pair(a.repetition, b.repetition)} | {pair(la, lb, '{:.2f}')} | "
              f"{a.overlaps_total + a.violators_total} → {b.overlaps_total + b.violators_total} | {pair(ta, tb, '{:.1f}')} |",
              flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:] or sorted({t for t, f in KNOWN if f == "density" and t.startswith("fgdc/")}))
