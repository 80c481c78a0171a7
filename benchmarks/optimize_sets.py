"""Issue 14's bounds over whole data sets: the optimize engine on every accepted tile.

For every accepted FGDC / osm-carto / Equinor tile (imported as ``svgtile import`` does; a
region of 2 × 2 tiles, seed 1) and every bundled exemplar (a square of 4 exemplar widths): L
(tests/optimize_measure.py), repetition, overlaps, violators and density / ρ, and which bound
each misses.  Prints one line per exemplar and a summary per set.

Run by hand:  python benchmarks/optimize_sets.py [--sets fgdc,osm-carto,equinor,bundled] [--limit N] [--cells]
(the whole of it takes several minutes on the 2-core machine; ``--limit`` measures the first N
accepted tiles of each set).  Patterns the importer reads as cells (bricks, bedding: the cellular
engine's) are left out, as tests/test_optimize_sets.py leaves them out; ``--cells`` measures those
of them that have motifs besides their cells too (the figures of this benchmark before
2026-12-08: FGDC's 90 tiles, 61 of motifs and 29 of cells with motifs).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
from optimize_measure import measure  # noqa: E402
from test_optimize_sets import EXEMPLARS, SETS, misses  # noqa: E402

from svgtile import analyze, read_exemplar  # noqa: E402
from svgtile.core.region import Region  # noqa: E402
from svgtile.errors import SvgtileError  # noqa: E402
from svgtile.svg.reader import parse_exemplar  # noqa: E402
from svgtile.tiles.importer import TileRefused, import_tile  # noqa: E402


def cases_all(wanted: list[str], limit: int, cells: bool = False):
    """(set, name, exemplar, region): the bundled exemplars and every accepted tile of each set
    (of motifs; with ``cells``, patterns of cells too)."""
    if "bundled" in wanted:
        for path in sorted(EXEMPLARS.glob("*.svg")):
            ex = read_exemplar(path)
            x0, y0, x1, y1 = ex.region.bounds
            side = 4 * max(x1 - x0, y1 - y0)
            yield "bundled", path.stem, ex, Region.rectangle(side, side)
    for name, folder in SETS.items():
        if name not in wanted or not folder.is_dir():
            continue
        done = 0
        for path in sorted(folder.glob("*.svg")):
            if limit and done >= limit:
                break
            try:
                t = import_tile(path)
            except TileRefused:
                continue
            x0, y0, w, h = t.box
            ex = parse_exemplar(t.text, source=str(path))
            if ex.cellular is not None and not cells:
                continue
            yield name, path.stem, ex, Region.rectangle(2 * w, 2 * h, x0, y0)
            done += 1


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sets", default="bundled,fgdc,osm-carto,equinor")
    ap.add_argument("--limit", type=int, default=0)
    ap.add_argument("--cells", action="store_true", help="measure patterns of cells that have motifs too")
    args = ap.parse_args()
    wanted = args.sets.split(",")
    rows: dict[str, list] = {}
    for name, stem, ex, region in cases_all(wanted, args.limit, args.cells):
        t = time.perf_counter()
        try:
            m = measure(ex, analyze(ex), region)
        except SvgtileError as e:  # a pattern of cells: the cellular engine's, not this one's
            print(f"{name} {stem}: not measured ({e})", flush=True)
            continue
        miss = misses(m)
        rows.setdefault(name, []).append((stem, m, miss))
        print(f"{name} {stem}: L {m.likeness:.2f} rep {m.repetition:.2f} overlaps {m.overlaps} violators "
              f"{m.violators} density {m.density_ratio:.2f} {'ok' if not miss else 'MISS ' + ' '.join(miss)} "
              f"({time.perf_counter() - t:.1f} s)", flush=True)  # fmt: skip
    print("\n| set | exemplars | meet every bound | median L | L ≥ 0.85 | rep ≤ 0.2 | density in 0.9–1.1 | conflicts |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, rs in rows.items():
        ms = [m for _, m, _ in rs]
        print(f"| {name} | {len(rs)} | {sum(not x for *_, x in rs)} | {np.median([m.likeness for m in ms]):.2f} | "
              f"{sum(m.likeness >= 0.85 for m in ms)} | {sum(m.repetition <= 0.2 for m in ms)} | "
              f"{sum(0.9 <= m.density_ratio <= 1.1 for m in ms)} | {sum(m.overlaps + m.violators for m in ms)} |")


if __name__ == "__main__":
    main()
