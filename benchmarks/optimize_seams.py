"""Where optimize's likeness is lost on a drawn exemplar: near the start's seams or inside its patches.

Optimize starts from exemplar patches on world-anchored square cells (Ma, Wei & Tong 2011 §4.1,
:func:`svgtile.engines.optimize.init.patch_start`; side ``start_side``, 5 spacings by default).  For
each bundled exemplar named (default: issue 14's four bundled misses) and seeds 1–3, on the square of
4 exemplar widths the optimize benchmarks use, the finished texture's motifs in the score's interior
are split by their distance to the nearest cell edge (under / over one exemplar spacing: the *seam
band* and the *middle*), and the likeness L of each part is measured against the tile and random
baselines of the whole interior (every centre, no sample; L above 1 is nearer the exemplar than the
tile engine's own texture is on average).

Run by hand (about 3 minutes):  python benchmarks/optimize_seams.py [breccia-plain scrub …]
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
sys.path.insert(0, str(REPO / "benchmarks"))
from optimize_bundled_seeds import bundled_squares  # noqa: E402
from optimize_measure import distance  # noqa: E402

from svgtile.analysis.neighbourhood import likeness  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402
from svgtile.engines.optimize.engine import OptimizeParams, start_side  # noqa: E402
from svgtile.metrics.window import in_window, interior, spacing  # noqa: E402

#: Issue 14's bundled misses (tests/test_optimize_sets.py MISSES).
DEFAULT = ["breccia-plain", "chert-nodules", "gravel", "scrub"]
#: The seam band's half-width, exemplar spacings.
BAND = 1.0


def main() -> None:
    names = sys.argv[1:] or DEFAULT
    for path, ex, stats, region in bundled_squares(names):
        s = spacing(stats)
        cell = start_side(ex, OptimizeParams().start_cell, False)
        win = interior(ex, region)

        for seed in (1, 2, 3):
            arrs = {n: synthesize(ex, region, n, seed=seed, stats=stats).arrangement for n in ("optimize", "tile", "random")}
            base = [distance(ex, stats, region, arrs[b], sample=None) for b in ("tile", "random")]
            a = arrs["optimize"]
            inside = in_window(a, win)
            m = np.mod(a.xy, cell)
            edge = np.minimum(m, cell - m).min(axis=1) / s
            band, middle = inside & (edge < BAND), inside & (edge >= BAND)
            figures = [likeness(distance(ex, stats, region, a, centres=np.flatnonzero(part), sample=None), *base)
                       for part in (inside, band, middle)]
            print(f"{path.stem:14s} seed {seed}: cell {cell / s:.1f} spacings;  L all {figures[0]:.3f}   "
                  f"seam band ({band.sum()} motifs) {figures[1]:.3f}   middle ({middle.sum()}) {figures[2]:.3f}")


if __name__ == "__main__":
    main()
