"""How far an edit of the region reaches into optimize's texture, by distance from the edit.

The engine contract's edit (tests/test_region.py ``edit_stability``: a large polygon, one vertex
moved one exemplar width out; ``boundary="clip"``) on a bundled exemplar, seeds given: for each
variant of the engine's parameters (JSON objects; ``{}`` the defaults), the share of the first
texture's motifs still in the second, byte for byte as written, in bands one exemplar width wide by
distance from the edit, and the contract's figure (the share beyond two widths; 0.95 asked).

Run by hand (about 10 s a texture):
    python benchmarks/optimize_edit_reach.py --exemplars gravel,scrub --seeds 1,2,3 '{"renew": 0}' '{}'
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
import shapely

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
from test_region import _lines, edited_polygons  # noqa: E402

from svgtile import analyze, read_exemplar  # noqa: E402
from svgtile.core.region import Region  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("variants", nargs="*", default=["{}"])
    ap.add_argument("--exemplars", default="gravel")
    ap.add_argument("--seeds", default="3")
    args = ap.parse_args()
    for name in args.exemplars.split(","):
        ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
        stats = analyze(ex)
        x0, y0, x1, y1 = ex.region.bounds
        w = max(x1 - x0, y1 - y0)
        before, after = edited_polygons(w, 4.0)
        edit = shapely.symmetric_difference(before, after)
        for seed in map(int, args.seeds.split(",")):
            for v in args.variants:
                arr = [synthesize(ex, Region(p), "optimize", rng=np.random.default_rng(seed), stats=stats, boundary="clip",
                                  params=json.loads(v)).arrangement for p in (before, after)]  # fmt: skip
                same = np.isin(_lines(arr[0]), _lines(arr[1]))
                d = shapely.distance(edit, shapely.points(arr[0].xy)) / w
                bands = " ".join(f"{lo}–{lo + 1}: {same[(d >= lo) & (d < lo + 1)].mean():.2f}" for lo in range(5))
                print(f"{name} seed {seed} {v}: contract {same[d > 2].mean():.3f}   by widths from the edit  {bands}",
                      flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
