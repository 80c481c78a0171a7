"""The repetition figure with and without the room rule (step 4 of
:func:`svgtile.metrics.repeats.repetition`): the share ``P_tex(v)`` over the references that have
room for a partner at ``v`` inside the texture's region, against the share over every reference.

For every bundled exemplar (a square of 4 exemplar widths) and every accepted FGDC / osm-carto /
Equinor tile (2 × 2 tiles, seed 1: issue 14's sets, ``benchmarks/optimize_sets.py``), the
``optimize`` engine's texture is scored both ways on the same arrangement; with ``--gate``, on
the whole-set gate region (tests/test_wholeset.py) instead.  Prints one line per exemplar whose
figure moves by more than 0.01, and per set how many are over 0.2 each way.

``--noise``: random placement (30 seeds) over squares 1, 1.5 and 2 bundled exemplar widths
wide, the figure's mean, maximum and seeds over 0.2 each way — what the minimum count of
references with room (``REPEAT_ROOM_MIN``) is set against.

Run by hand:  python benchmarks/repetition_room.py [--sets fgdc,...] [--engine optimize] [--gate] [--noise]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests"))
sys.path.insert(0, str(REPO / "benchmarks"))
from optimize_sets import cases_all  # noqa: E402

from svgtile import analyze, read_exemplar  # noqa: E402
from svgtile.analysis.window import measured_window  # noqa: E402
from svgtile.core.region import Region  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402
from svgtile.errors import SvgtileError  # noqa: E402
from svgtile.metrics import repetition  # noqa: E402


def both(ex, stats, arr, region) -> tuple[float, float, object]:
    """(every reference, with room, the latter's Repetition) of one arrangement."""
    win, _ = measured_window(ex, region)
    old = repetition(arr, ex, stats, win)
    new = repetition(arr, ex, stats, win, room=region.shape)
    return old.repetition or 0.0, new.repetition or 0.0, new


def noise() -> None:
    print("| exemplar | widths | every reference: mean / max / over 0.2 | with room: mean / max / over 0.2 |")
    print("|---|---:|---|---|")
    for name in ("boulders", "gravel", "sand", "marsh", "till"):
        ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
        stats = analyze(ex)
        x0, y0, x1, y1 = ex.region.bounds
        for widths in (1.0, 1.5, 2.0):
            side = widths * max(x1 - x0, y1 - y0)
            region = Region.rectangle(side, side)
            got = np.array([both(ex, stats, synthesize(ex, region, "random", seed=seed, stats=stats).arrangement,
                                 region)[:2] for seed in range(1, 31)])  # fmt: skip
            cols = [f"{c.mean():.3f} / {c.max():.3f} / {int((c > 0.2).sum())}" for c in got.T]
            print(f"| {name} | {widths:g} | {cols[0]} | {cols[1]} |", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sets", default="bundled,fgdc,osm-carto,equinor")
    ap.add_argument("--engine", default="optimize")
    ap.add_argument("--gate", action="store_true", help="the whole-set gate region instead of 2 × 2 tiles")
    ap.add_argument("--noise", action="store_true", help="random placement on small squares instead")
    args = ap.parse_args()
    if args.noise:
        noise()
        return
    over: dict[str, list[int]] = {}
    for name, stem, ex, region in cases_all(args.sets.split(","), 0, cells=True):
        stats = analyze(ex)
        if args.gate and ex.period is not None:
            from test_wholeset import gate_region

            x0, y0, _, _ = ex.region.bounds
            region = gate_region((x0, y0, ex.period[0], ex.period[1]), len(ex.motifs))
        try:
            arr = synthesize(ex, region, args.engine, seed=1, stats=stats).arrangement
        except SvgtileError as e:
            print(f"{name} {stem}: not measured ({e})", flush=True)
            continue
        a, b, new = both(ex, stats, arr, region)
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
