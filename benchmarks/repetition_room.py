"""The repetition figure with and without the room rule (step 4 of
:func:`svgtile.metrics.repeats.repetition`): the share ``P_tex(v)`` over the references that have
room for a partner at ``v`` inside the texture's region, against the share over every reference.

For every bundled exemplar (a square of 4 exemplar widths) and every accepted FGDC / osm-carto /
Equinor tile (2 × 2 tiles, seed 1: issue 14's sets, ``benchmarks/optimize_sets.py``), the
``optimize`` engine's texture is scored both ways on the same arrangement; with ``--engine auto``
and ``--gate``, the default engine on the whole-set gate region (tests/test_wholeset.py).  Prints
one line per exemplar whose figure moves by more than 0.01, and per set how many are over 0.2 each
way.

Run by hand:  python benchmarks/repetition_room.py [--sets fgdc,...] [--engine optimize] [--gate]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
sys.path.insert(0, str(REPO / "benchmarks"))
from optimize_sets import cases_all  # noqa: E402

from svgtile import analyze  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402
from svgtile.errors import SvgtileError  # noqa: E402
from svgtile.metrics import interior, repetition  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sets", default="bundled,fgdc,osm-carto,equinor")
    ap.add_argument("--engine", default="optimize")
    ap.add_argument("--gate", action="store_true", help="the whole-set gate region instead of 2 × 2 tiles")
    args = ap.parse_args()
    over: dict[str, list[int]] = {}
    for name, stem, ex, region in cases_all(args.sets.split(","), 0):
        stats = analyze(ex)
        if args.gate and ex.period is not None:
            from test_wholeset import gate_region

            x0, y0, x1, y1 = region.bounds
            region = gate_region((x0, y0, ex.period[0], ex.period[1]), len(ex.motifs))
        try:
            arr = synthesize(ex, region, args.engine, seed=1, stats=stats).arrangement
        except SvgtileError as e:
            print(f"{name} {stem}: not measured ({e})", flush=True)
            continue
        win = interior(ex, region)
        win = region.shape if win.is_empty or win.area <= 0 else win
        old = repetition(arr, ex, stats, win)
        new = repetition(arr, ex, stats, win, room=region.shape)
        a, b = old.repetition or 0.0, new.repetition or 0.0
        n = over.setdefault(name, [0, 0, 0])
        n[0] += 1
        n[1] += a > 0.2
        n[2] += b > 0.2
        if abs(a - b) > 0.01:
            v = new.repetition_vector
            print(f"{name} {stem}: {a:.3f} -> {b:.3f} at {v and (round(v[0], 1), round(v[1], 1))}"
                  f" (period {ex.period})", flush=True)  # fmt: skip
    print(f"\n{args.engine}{' gate region' if args.gate else ''}: | set | measured | over 0.2 every reference | over 0.2 with room |")
    for name, (k, a, b) in over.items():
        print(f"| {name} | {k} | {a} | {b} |")


if __name__ == "__main__":
    main()
