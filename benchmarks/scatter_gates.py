"""The whole-set gates' figures on the tiles auto sends to the optimize engine (``tile-scatter``).

For every gate tile (tests/test_wholeset.py's ``TILES``) that :func:`svgtile.engines.choose.choose`
sends to optimize: density / ρ, kind-mix TV (over shape classes, and per kind with its chance where
kinds pool), repetition, coverage, L, overlaps and violators, as ``test_wholeset.figures`` measures them (gate
region, seed 1; overlaps and violators over the whole texture and the exemplar's own overlaps, as the
gates count them); one JSON line per tile.  ``--set MODULE:NAME=VALUE`` overrides a module constant
first (an experiment without a branch); ``--compare BASE.jsonl HEAD.jsonl`` prints the tiles whose
figures changed, which bounds they gained (+) or lost (−), and a summary of both.

Run by hand (``$SVGTILE_DATA`` or ``../shared/data`` beside the checkout; about 4 minutes):
    python benchmarks/scatter_gates.py > base.jsonl
    python benchmarks/scatter_gates.py --set svgtile.engines.optimize.engine:TILE_CELL=0.58 > head.jsonl
    python benchmarks/scatter_gates.py --compare base.jsonl head.jsonl
"""

from __future__ import annotations

import argparse
import ast
import importlib
import json
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

#: The gates' bounds (tests/test_wholeset.py): L ≥ 0.6 for every tile, and L ≥ 0.8 (issue 12.6, since
#: growth and optimize exist; 2026-12-07) with the tiles under it listed there as known misses.
TV, REPETITION, LIKENESS, LIKENESS_NOW, COVERAGE, DENSITY = 0.05, 0.2, 0.6, 0.8, 1.3, (0.9, 1.1)


def bounds(row: dict) -> dict[str, bool]:
    """Which of the gates' bounds a tile's figures meet."""
    per_kind = row["tvk"] is None or row["tvk"] <= max(TV, row["noise"] or 0.0)
    return {
        "density": DENSITY[0] <= row["density"] <= DENSITY[1],
        "kind mix": row["tv"] <= TV and per_kind,
        "repetition": row["rep"] <= REPETITION,
        "likeness": row["L"] >= LIKENESS,
        "likeness 0.8": row["L"] >= LIKENESS_NOW,
        # a tile without holes passes only with a texture without (as the gate reads it)
        "coverage": row["cov"] <= COVERAGE if row.get("cov") is not None else row.get("r_tex", 0) == 0,
        "conflicts": row["ov"] == 0 and row["viol"] == 0 and row.get("exemplar_ov", 0) == 0,
    }


def compare(base_path: str, head_path: str) -> None:
    base = {r["tile"]: r for r in map(json.loads, open(base_path))}
    head = {r["tile"]: r for r in map(json.loads, open(head_path))}
    both = [t for t in base if t in head]
    for t in sorted(set(base) ^ set(head)):
        print(f"{t:34s} only in {'base' if t in base else 'head'}")
    for t in both:
        a, b = base[t], head[t]
        ma, mb = bounds(a), bounds(b)
        if ma == mb and all(a.get(f) == b.get(f) for f in ("density", "tv", "tvk", "rep", "cov", "L", "ov", "viol")):
            continue
        moved = " ".join(f"{f} {'+' if mb[f] else '−'}" for f in ma if ma[f] != mb[f])
        print(f"{t:34s} density {a['density']:.3f} → {b['density']:.3f}  TV {a['tv']:.3f} → {b['tv']:.3f}  "
              f"rep {a['rep']:.3f} → {b['rep']:.3f}  L {a['L']:.3f} → {b['L']:.3f}  {moved}")
    for name, rows in (("base", base), ("head", head)):
        met = [bounds(rows[t]) for t in both]
        missed = {f: sum(not m[f] for m in met) for f in met[0]} if met else {}
        print(f"{name}: {len(both)} tiles, every bound {sum(all(m.values()) for m in met)}, misses {missed}, "
              f"mean L {np.mean([rows[t]['L'] for t in both]):.4f}")


def apply_sets(parser: argparse.ArgumentParser, specs: list[str]) -> None:
    """Override module constants from ``--set MODULE:NAME=VALUE`` options (an experiment without a branch)."""
    for spec in specs:
        module, assignment = spec.split(":", 1)
        name, value = assignment.split("=", 1)
        target = importlib.import_module(module)
        # a typo would run the defaults; a name another module imported by value is not reached
        if not hasattr(target, name):
            parser.error(f"--set {spec}: {module} has no {name}")
        setattr(target, name, ast.literal_eval(value))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tiles", nargs="*", help="set/stem (fgdc/605); default: every gate tile")
    parser.add_argument("--set", action="append", default=[], metavar="MODULE:NAME=VALUE")
    parser.add_argument("--compare", nargs=2, metavar=("BASE", "HEAD"))
    args = parser.parse_args()
    if args.compare:
        if args.set or args.tiles:
            parser.error("--compare reads two JSONL files; it takes no tiles and no --set")
        compare(*args.compare)
        return
    apply_sets(parser, args.set)
    sys.path.insert(0, str(HERE.parent / "tests"))
    import test_wholeset as W

    from svgtile.engines.choose import choose

    if not (args.tiles or W.TILES):
        parser.error(f"no gate tiles: {W.DATA} is not there (set SVGTILE_DATA)")
    for tile in args.tiles or W.TILES:
        loaded = W.motif_tile(tile)
        if not isinstance(loaded, tuple) or choose(loaded[1], loaded[2]).engine != "optimize":
            continue
        cpu = time.process_time()
        s, exemplar_overlaps, L = W.figures(tile)
        print(json.dumps({"tile": tile, "density": s.density_ratio, "tv": s.kind_mix_tv, "tvk": s.kind_mix_tv_kinds,
                          "noise": s.kind_mix_noise, "rep": s.repetition, "cov": s.coverage,
                          "r_tex": s.empty_disc_radius, "L": L, "ov": s.overlaps_total,
                          "viol": s.violators_total, "exemplar_ov": exemplar_overlaps,
                          "cpu": round(time.process_time() - cpu, 2)}), flush=True)


if __name__ == "__main__":
    main()
