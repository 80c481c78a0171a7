"""How far ``svgtile score``'s sampled figures lie from the exact ones, on large textures.

    python benchmarks/score_sample_deviation.py [MOTIFS] [SEEDS] [EXEMPLAR …]

For each bundled exemplar (default: gravel till breccia sand shale marsh) and seed (default
1 2), the patch engine fills a square whose interior holds about MOTIFS motifs (default
120,000); the texture is scored twice (:func:`svgtile.metrics.score`, sampled and ``exact=True``)
and one Markdown row per texture gives sampled − exact for each sampled figure, with the CPU
time of each score (baselines computed before, so both pay the same).  The largest deviation
per figure over all rows is the bound written in :mod:`svgtile.metrics.scoring` and
benchmarks/README.md.  Run from the repository root.
"""

from __future__ import annotations

import gc
import math
import sys
import time
from pathlib import Path

from svgtile.analysis.stats import analyze
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import likeness, score
from svgtile.metrics.window import exemplar_size
from svgtile.svg.reader import read_exemplar

FIGURES = ("gap_distance", "gap_noise", "pair_correlation_distance", "repetition", "neighbourhood_distance",
           "likeness", "empty_disc_radius")  # fmt: skip


def main(argv: list[str]) -> None:
    motifs = int(argv[0]) if argv else 120_000
    seeds = [int(s) for s in argv[1].split(",")] if len(argv) > 1 else [1, 2]
    names = argv[2:] or ["gravel", "till", "breccia", "sand", "shale", "marsh"]
    gc.disable()
    print("| texture | motifs (sampled) | " + " | ".join(FIGURES) + " | CPU sampled · exact |")
    print("|---|---:|" + "---:|" * len(FIGURES) + "---:|")
    worst = dict.fromkeys(FIGURES, 0.0)
    for name in names:
        ex = read_exemplar(Path("exemplars") / f"{name}.svg")
        stats = analyze(ex)
        likeness.baseline_distances(ex, stats)
        width = max(exemplar_size(ex))
        side = math.sqrt(motifs / stats.count_density) + 2 * width
        for seed in seeds:
            arr = synthesize(ex, Region.rectangle(side, side), "patch", seed=seed, stats=stats).arrangement
            region = Region.rectangle(side, side)
            t = time.process_time()
            a = score(ex, stats, arr, region)
            t_a = time.process_time() - t
            b = score(ex, stats, arr, region, exact=True)
            t_b = time.process_time() - t - t_a
            cells = []
            for f in FIGURES:
                x, y = getattr(a, f), getattr(b, f)
                if x is None or y is None:
                    cells.append("—")
                    continue
                rel = f == "empty_disc_radius"  # a length: relative to the exact radius
                worst[f] = max(worst[f], abs(x - y) / (y if rel else 1.0))
                cells.append(f"{(x - y) / y:+.2%}" if rel else f"{x - y:+.3f}")
            sampled = f"{a.sample.motifs:,}" if a.sample else "not sampled"
            print(f"| {name} {side:.0f}², seed {seed} | {b.motifs:,} ({sampled}) | " + " | ".join(cells)
                  + f" | {t_a:.2f} · {t_b:.2f} s |", flush=True)  # fmt: skip
    print("\nlargest |sampled − exact| (empty disc: relative): " + ", ".join(f"{f} {v:.3f}" for f, v in worst.items()))


if __name__ == "__main__":
    main(sys.argv[1:])
