"""Issue 12: repetition (beyond the exemplar's order) and repetition_total (every displacement,
the figure before issue 12) of the auto and tile engines on every accepted tile of the whole
sets, with tests/test_wholeset.py's regions and seed.

Run from the repository root: ``python benchmarks/repetition_sets.py [fgdc equinor …]`` (prefixes
of the tiles to measure; all by default).  One line per tile: ``steps`` is how many exact order
steps were left out, then ``engine repetition/repetition_total``.
"""
from __future__ import annotations

import math
import sys

sys.path.insert(0, "tests")
from test_wholeset import motif_tiles, scored_window

from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import repetition

only = sys.argv[1:]
for tile, t, ex, stats in motif_tiles(only):
    x0, y0, w, h = t.box
    k = max(3.0, math.sqrt(600 / len(ex.motifs)))
    region = Region.rectangle(k * w, k * h * 0.75, x0, y0)
    out = []
    for eng in ("auto", "tile"):
        win = scored_window(ex, region)
        s = repetition(synthesize(ex, region, eng, seed=1, stats=stats).arrangement, ex, stats, win)
        out.append(f"{eng} {s.repetition:.3f}/{s.repetition_total:.3f}")
    print(f"{tile:36s} steps={len(s.order_steps)} " + "  ".join(out), flush=True)
