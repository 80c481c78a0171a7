"""How much ``--refine 10`` raises the patch engine's likeness L, per data set (issue 14).

For each bundled exemplar (a square of 4 exemplar widths) and a sample of accepted FGDC /
osm-carto / Equinor tiles (imported as ``svgtile import`` does; 2 x 2 tiles), seed 1: L of
``--engine patch`` and of ``--engine patch --refine 10`` (tests/optimize_measure.py: 0 at the
``random`` engine, 1 at ``tile``), and of ``--engine optimize``.

Run by hand:  python benchmarks/refine_likeness.py [--per-set 5]
It prints one Markdown table row per exemplar and a mean per set.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(REPO / "tests"))
DATA = Path(os.environ.get("SVGTILE_SHARED_DATA", REPO.parent / "shared" / "data"))
SETS = {
    "fgdc": DATA / "fgdc-geologic-patterns" / "lithology",
    "osm-carto": DATA / "osm-carto" / "patterns",
    "equinor": DATA / "equinor-lithology" / "svg",
}


def cases(per_set: int, bundled: bool = True):
    """(set, name, exemplar, region) for the bundled exemplars and ``per_set`` tiles of each set,
    spread evenly over the set's accepted tiles in name order."""
    from svgtile import read_exemplar
    from svgtile.core.region import Region
    from svgtile.svg.reader import parse_exemplar
    from svgtile.tiles.importer import TileRefused, import_tile

    for path in sorted((REPO / "exemplars").glob("*.svg")) if bundled else ():
        ex = read_exemplar(path)
        x0, y0, x1, y1 = ex.region.bounds
        side = 4 * max(x1 - x0, y1 - y0)
        yield "bundled", path.stem, ex, Region.rectangle(side, side)
    for name, folder in SETS.items():
        if not folder.is_dir():
            continue
        paths = sorted(folder.glob("*.svg"))
        left = per_set
        for path in paths[:: max(1, len(paths) // (3 * per_set))] if per_set > 0 else ():
            if left == 0:
                break
            try:
                t = import_tile(path)
            except TileRefused:
                continue
            x0, y0, w, h = t.box
            yield name, path.stem, parse_exemplar(t.text, source=str(path)), Region.rectangle(2 * w, 2 * h, x0, y0)
            left -= 1


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--per-set", type=int, default=5)
    ap.add_argument("--no-bundled", action="store_true", help="only the tile sets")
    args = ap.parse_args()
    from optimize_measure import distance, measure

    from svgtile import analyze
    from svgtile.engines import synthesize

    rows: dict[str, list[tuple[float, float, float]]] = {}
    print("| set | exemplar | patch L | patch --refine 10 L | gain | optimize L |")
    print("|---|---|---:|---:|---:|---:|")
    for group, name, ex, region in cases(args.per_set, not args.no_bundled):
        stats = analyze(ex)
        base = tuple(distance(ex, stats, region, synthesize(ex, region, b, seed=1, stats=stats).arrangement)
                     for b in ("tile", "random"))  # fmt: skip
        plain = measure(ex, stats, region, "patch", baselines=base).likeness
        refined = measure(ex, stats, region, "patch", refine=10, baselines=base).likeness
        opt = measure(ex, stats, region, "optimize", baselines=base).likeness
        rows.setdefault(group, []).append((plain, refined, opt))
        print(f"| {group} | {name} | {plain:.2f} | {refined:.2f} | {refined - plain:+.2f} | {opt:.2f} |", flush=True)
    for group, r in rows.items():
        a = np.array(r)
        print(f"| {group} | mean of {len(a)} | {a[:, 0].mean():.2f} | {a[:, 1].mean():.2f} | "
              f"{(a[:, 1] - a[:, 0]).mean():+.2f} (min {(a[:, 1] - a[:, 0]).min():+.2f}) | {a[:, 2].mean():.2f} |")  # fmt: skip


if __name__ == "__main__":
    main()
