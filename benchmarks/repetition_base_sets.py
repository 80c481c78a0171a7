"""rep13e: the repetition figure of this checkout beside a base checkout's, on the same textures:
the auto, tile and random engines on every accepted tile of the whole sets, with
tests/test_wholeset.py's regions (gate_region), window (the interior) and seed 1.

Run from the repository root::

    SVGTILE_DATA=… python benchmarks/repetition_base_sets.py BASE [--ordered] [engines] [-- prefixes]

``BASE`` a directory holding a base checkout's ``svgtile/metrics/repeats.py`` (e.g. ``git archive
a7ae804 svgtile | tar -x -C /tmp/base``); only that module is taken from it, with its
``svgtile/metrics/shown.py`` where it has one (the rest of svgtile is this checkout's), so each texture is synthesized once and scored by both figures.  Prefixes
are run in the order given (``equinor osm fgdc``).  One line per tile: ``engine base→head``.
``--ordered``: only the tiles whose exemplar has an exact order
(:func:`svgtile.metrics.order.order_steps`): rep13e's change reads nothing else on a repeating
tile, so every other tile's figures are the base's by construction (a saving under load).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

sys.path.insert(0, "tests")
from test_wholeset import gate_region, motif_tiles, scored_window

from svgtile.engines import synthesize
from svgtile.metrics import repetition
from svgtile.metrics.order import order_steps
from svgtile.metrics.repeats import REPEAT_MIN
from svgtile.metrics.window import spacing

args = sys.argv[1:]
base_dir, args = Path(args[0]), args[1:]
ordered = "--ordered" in args
args = [a for a in args if a != "--ordered"]
engines = args[: args.index("--")] if "--" in args else args
only = args[args.index("--") + 1 :] if "--" in args else [""]
engines = engines or ["auto", "tile", "random"]
spec = importlib.util.spec_from_file_location("base_repeats", base_dir / "svgtile/metrics/repeats.py")
base = importlib.util.module_from_spec(spec)
sys.modules["base_repeats"] = base  # dataclasses look their module up
# since room07 the exemplar's side lives in svgtile/metrics/shown.py: the base's own, while its
# repeats.py is loaded (this checkout's stays bound to this checkout's repeats)
own_shown = sys.modules.get("svgtile.metrics.shown")
if (base_dir / "svgtile/metrics/shown.py").is_file():
    shown_spec = importlib.util.spec_from_file_location("svgtile.metrics.shown", base_dir / "svgtile/metrics/shown.py")
    sys.modules["svgtile.metrics.shown"] = importlib.util.module_from_spec(shown_spec)
    shown_spec.loader.exec_module(sys.modules["svgtile.metrics.shown"])
try:
    spec.loader.exec_module(base)
finally:
    if own_shown is not None:
        sys.modules["svgtile.metrics.shown"] = own_shown
for prefix in only:
    for tile, t, ex, stats in motif_tiles([prefix]):
        if ordered and not len(order_steps(ex, spacing(stats), REPEAT_MIN * spacing(stats))):
            continue
        region = gate_region(t.box, len(ex.motifs))
        win = scored_window(ex, region)
        out = []
        for eng in engines:
            arr = synthesize(ex, region, eng, seed=1, stats=stats).arrangement
            old, new = base.repetition(arr, ex, stats, win), repetition(arr, ex, stats, win)
            out.append(f"{eng} {old.repetition:.3f}→{new.repetition:.3f}")
        print(f"{tile:36s} " + "  ".join(out), flush=True)
