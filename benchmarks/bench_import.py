"""Issue 12.5: CPU time of ``import_tile`` on a few real tiles, and what stage 7 (the exemplar's
own-overlap check, :mod:`svgtile.tiles.overlaps`) adds to it.

Run from the repository root: ``python benchmarks/bench_import.py [repeats]``.  One line per tile:
the best of ``repeats`` (3) runs of ``import_tile`` and of the stage-7 check alone on its result
(``own_overlaps``: writing is already done; this is the read-back and the overlap query), in
``time.process_time`` seconds.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from svgtile.tiles.importer import import_tile
from svgtile.tiles.overlaps import own_overlaps

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"
FILES = [
    "fgdc-geologic-patterns/lithology/601.svg", "fgdc-geologic-patterns/lithology/603.svg",
    "fgdc-geologic-patterns/lithology/605.svg", "fgdc-geologic-patterns/lithology/681.svg",
    "fgdc-geologic-patterns/lithology/730.svg", "equinor-lithology/svg/30017.svg",
    "osm-carto/generating_patterns/marsh.svg", "osm-carto/symbols/leaftype_mixed.svg",
]  # fmt: skip


def best(f, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        f()
        times.append(time.process_time() - t0)
    return min(times)


repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 3
import_tile(DATA / FILES[0])  # warm up: lazy imports
total = check = 0.0
for name in FILES:
    t = import_tile(DATA / name)
    a = best(lambda name=name: import_tile(DATA / name), repeats)
    b = best(lambda t=t, name=name: own_overlaps(t.text, source=name), repeats)
    total, check = total + a, check + b
    print(f"{name:45s} {len(t):6d} motifs  import {a:6.3f} s  of which own-overlap check {b:6.3f} s")
print(f"{'total':45s} {'':13s} import {total:6.3f} s  of which own-overlap check {check:6.3f} s")
