#!/usr/bin/env python3
"""Choose α, the kind-mismatch cost of the neighbourhood distance, on the whole data sets.

For every bundled exemplar and every tile of FGDC lithology, osm-carto (patterns, symbols) and
Equinor that ``svgtile import`` accepts: the ``tile`` and ``random`` engines (and ``patch``) fill the
baselines' square (:func:`svgtile.metrics.likeness.baseline_region`, seed 1), and the
neighbourhood distance E of each is measured as :func:`svgtile.metrics.score` measures it, for
each α of ALPHAS.  Prints one line per exemplar and, per α, over the exemplars whose baselines
differ: the median *contrast* ``(E_random − E_tile) / E_random`` (how far apart order and
disorder lie: the larger, the less L is at the mercy of sampling noise), the number of
exemplars where E_random ≤ E_tile (the figure cannot tell them apart), and patch's median L.

Needs ``../shared/data`` beside the repository.  Usage, from the repository root::

    python benchmarks/choose_alpha.py [--limit N] [--data ../shared/data] [--patch]   # N files per set
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from svgtile import analyze, read_exemplar
from svgtile.analysis.neighbourhood import likeness, neighbourhood_distance
from svgtile.engines import synthesize
from svgtile.errors import SvgtileError
from svgtile.metrics import likeness as order
from svgtile.metrics.window import in_window, interior, spacing
from svgtile.svg.reader import parse_exemplar
from svgtile.tiles.importer import import_tile

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data"
SETS = [
    ("fgdc", "fgdc-geologic-patterns/lithology"),
    ("osm-patterns", "osm-carto/patterns"),
    ("osm-symbols", "osm-carto/symbols"),
    ("equinor", "equinor-lithology/svg"),
]
ALPHAS = (0.25, 0.5, 1.0, 2.0, 4.0)


def exemplars(limit: int | None, data: Path = DATA):
    for path in sorted((ROOT / "exemplars").glob("*.svg")):
        yield "bundled", path.stem, read_exemplar(path)
    for name, folder in SETS:
        for path in sorted((data / folder).glob("*.svg"))[:limit]:
            try:
                tile = import_tile(path)
                yield name, path.stem, parse_exemplar(tile.text, source=str(path))
            except SvgtileError:
                continue


def distances(ex, stats, engines) -> dict[str, list[float]]:
    region = order.baseline_region(ex, stats)
    window = interior(ex, region)
    out = {"patch": [math.nan] * len(ALPHAS)}
    for engine in engines:
        arr = synthesize(ex, region, engine, seed=order.BASELINE_SEED, stats=stats).arrangement
        centres = np.flatnonzero(in_window(arr, window))
        out[engine] = [
            neighbourhood_distance(
                arr.xy, arr.kind, ex.motifs.xy, ex.motifs.kind, spacing=spacing(stats), k=order.K,
                alpha=a, period=ex.period, rotate=order.turns_allowed(stats), centres=centres,
                sample=order.SAMPLE, rng=np.random.default_rng(order.SAMPLE_SEED),
            ) if len(centres) else math.nan
            for a in ALPHAS
        ]  # fmt: skip
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=None)
    parser.add_argument("--data", type=Path, default=DATA, help="the shared data folder")
    parser.add_argument("--patch", action="store_true", help="also the patch engine (slow), for its L")
    args = parser.parse_args()
    rows = []
    for group, name, ex in exemplars(args.limit, args.data):
        stats = analyze(ex)
        if stats.count_density <= 0 or order.baseline_region(ex, stats).area * stats.count_density > 20000:
            continue
        e = distances(ex, stats, ("tile", "random", "patch") if args.patch else ("tile", "random"))
        rows.append(e)
        cells = "  ".join(f"{t:.3f}/{r:.3f}/{p:.3f}" for t, r, p in zip(e["tile"], e["random"], e["patch"], strict=True))
        print(f"{group:12s} {name:24s} {len(ex.motifs):4d} tile/random/patch per α: {cells}", flush=True)
    print(f"\n{len(rows)} exemplars")
    for i, a in enumerate(ALPHAS):
        t = np.array([r["tile"][i] for r in rows])
        rnd = np.array([r["random"][i] for r in rows])
        p = np.array([r["patch"][i] for r in rows])
        ok = np.isfinite(t) & np.isfinite(rnd) & (rnd > 0)
        contrast = (rnd[ok] - t[ok]) / rnd[ok]
        ls = np.array([likeness(pp, tt, rr) for pp, tt, rr in zip(p[ok], t[ok], rnd[ok], strict=True)] + [math.nan])
        patch = f", patch L median {np.nanmedian(ls):.2f}" if args.patch else ""
        print(f"α = {a:4}: median contrast {np.median(contrast):.3f}, 10th percentile {np.percentile(contrast, 10):.3f}, "
              f"E_random ≤ E_tile on {int((contrast <= 0).sum())}{patch}")  # fmt: skip


if __name__ == "__main__":
    main()
