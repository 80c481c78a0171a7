"""Issue 13 (rep13): repetition (new: over what the exemplar shows) and repetition_order (the
figure before) of the auto, tile and random engines on every accepted tile of the whole sets,
with tests/test_wholeset.py's regions (gate_region), window (the interior) and seed 1.

Run from the repository root: ``SVGTILE_DATA=… python benchmarks/repetition_exemplar_sets.py
[engines] [-- prefixes]``; one line per tile and engine: ``engine new/old``.
"""

from __future__ import annotations

import sys

sys.path.insert(0, "tests")
from test_wholeset import gate_region, motif_tiles, scored_window

from svgtile.engines import synthesize
from svgtile.metrics import repetition

args = sys.argv[1:]
engines = args[: args.index("--")] if "--" in args else args
only = args[args.index("--") + 1 :] if "--" in args else []
engines = engines or ["auto", "tile", "random"]
for tile, t, ex, stats in motif_tiles(only):
    region = gate_region(t.box, len(ex.motifs))
    win = scored_window(ex, region)
    out = []
    for eng in engines:
        arr = synthesize(ex, region, eng, seed=1, stats=stats).arrangement
        s = repetition(arr, ex, stats, win)
        out.append(f"{eng} {s.repetition:.3f}/{s.repetition_order:.3f}")
    print(f"{tile:36s} " + "  ".join(out), flush=True)
