"""Cellular engine timing (issue 15): bricks 6 × 14 on a square unit with a round hole, synthesis
and SVG writing separately.  Run by hand: python benchmarks/bench_cellular.py"""

from __future__ import annotations

import json
import time

import shapely

from svgtile import analyze, read_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.svg.writer import result_document

ex = read_exemplar("exemplars/gravel.svg")
st = analyze(ex)
TREE = "/tmp/svgtile-bench-cellular.json"
with open(TREE, "w") as fh:
    json.dump({"course": 6, "length": 14}, fh)
for size in (300, 1000):
    unit = shapely.box(0, 0, size, size).difference(shapely.Point(size/2, size/2).buffer(size/5))
    t = time.perf_counter()
    r = synthesize(ex, Region(unit), "cellular", seed=1, stats=st, params={"tree": TREE})
    t1 = time.perf_counter()
    result_document(r)
    t2 = time.perf_counter()
    print(f"| {size}x{size} with a hole | {len(r.cells)} | {len(r.arrangement)} | {t1-t:.2f} | {t2-t1:.2f} |", flush=True)
