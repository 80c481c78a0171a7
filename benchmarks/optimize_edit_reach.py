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

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
from test_region import edit_comparison  # noqa: E402

from svgtile import analyze, read_exemplar  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("variants", nargs="*", default=["{}"])
    ap.add_argument("--exemplars", default="gravel")
    ap.add_argument("--seeds", default="3")
    args = ap.parse_args()
    for name in args.exemplars.split(","):
        ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
        stats = analyze(ex)
        for seed in map(int, args.seeds.split(",")):
            for v in args.variants:
                same, distance, w = edit_comparison(ex, stats, radius_widths=4.0, seed=seed, engine="optimize",
                                                    **json.loads(v))  # fmt: skip
                d = distance / w
                bands = " ".join(f"{lo}–{lo + 1}: {same[(d >= lo) & (d < lo + 1)].mean():.2f}" for lo in range(5))
                print(f"{name} seed {seed} {v}: contract {same[distance > 2 * w].mean():.3f}   by widths from the edit  {bands}",
                      flush=True)  # fmt: skip


if __name__ == "__main__":
    main()
