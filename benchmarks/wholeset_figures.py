"""The whole-set gates' figures (tests/test_wholeset.py) for some tiles, one JSON line per tile,
and a before → after table of two such runs.

Each tile is imported, synthesized with auto over :func:`test_wholeset.gate_region` (seed 1) and
scored exactly as the gates do (density / ρ, kind-mix TV, overlaps, violators, the exemplar's own
overlaps, repetition, likeness L).  An older package is measured by putting it first on
``PYTHONPATH`` (its own ``tests/`` folder beside it with ``--tests``).

Run by hand (``$SVGTILE_DATA`` or ``../shared/data`` beside the checkout):
    git archive <commit> svgtile tests | tar -x -C /tmp/base
    PYTHONPATH=/tmp/base python benchmarks/wholeset_figures.py --tests /tmp/base/tests fgdc/681 ... > before.jsonl
    python benchmarks/wholeset_figures.py fgdc/681 ... > after.jsonl
    python benchmarks/wholeset_figures.py --compare before.jsonl after.jsonl
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def measure(tiles: list[str], tests: Path) -> None:
    sys.path.insert(0, str(tests))
    import test_wholeset as W

    for tile in tiles:
        t0 = time.perf_counter()
        got = W.figures(tile)
        if got is None or got == "cellular":
            print(json.dumps({"tile": tile, "skip": got or "refused"}), flush=True)
            continue
        s, exemplar_overlaps, L = got
        print(json.dumps({"tile": tile, "density": round(s.density_ratio, 4), "tv": round(s.kind_mix_tv, 4),
                          "ov": int(s.overlaps_total), "viol": int(s.violators_total), "exov": int(exemplar_overlaps),
                          "rep": round(s.repetition, 4), "L": round(float(L), 4),
                          "s": round(time.perf_counter() - t0, 1)}), flush=True)  # fmt: skip


#: The figures of the table, in its column order.
FIGURES = ("density", "tv", "L", "rep")


def _read(path: Path) -> dict[str, dict]:
    """The measured tiles of one run (:func:`measure`'s lines), by tile."""
    lines = map(json.loads, path.read_text().splitlines())
    return {d["tile"]: d for d in lines if "density" in d}


def compare(before: Path, after: Path) -> None:
    runs = [_read(p) for p in (before, after)]
    print("| tile | density/ρ | kind-mix TV | L | repetition | overlaps/violators |")
    print("|---|---|---|---|---|---|")
    for tile in runs[0]:
        b, a = runs[0][tile], runs[1].get(tile)
        if a is None:
            continue
        cells = [f"{b[k]:.3f} → {a[k]:.3f}" if b[k] != a[k] else f"{a[k]:.3f}" for k in FIGURES]
        print(f"| {tile} | {' | '.join(cells)} | {b['ov']}/{b['viol']} → {a['ov']}/{a['viol']} |")
    for name, r in zip(("before", "after"), runs, strict=True):
        v = [r[t] for t in runs[0] if t in runs[1]]
        print(f"\n{name}: {len(v)} tiles, density/ρ in 0.9–1.1: {sum(0.9 <= d['density'] <= 1.1 for d in v)}, "
              f"kind-mix TV > 0.05: {sum(d['tv'] > 0.05 for d in v)}, L mean {sum(d['L'] for d in v) / len(v):.3f}, "
              f"repetition > 0.2: {sum(d['rep'] > 0.2 for d in v)}, "
              f"overlaps + violators: {sum(d['ov'] + d['viol'] for d in v)}")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tiles", nargs="*", help="set/stem, as test_wholeset names them (fgdc/681)")
    parser.add_argument(
        "--tests",
        type=Path,
        default=HERE.parent / "tests",
        help="the tests folder to take the gates from",
    )
    parser.add_argument("--compare", nargs=2, type=Path, metavar=("BEFORE", "AFTER"))
    args = parser.parse_args()
    if args.compare:
        compare(*args.compare)
    else:
        measure(args.tiles, args.tests)


if __name__ == "__main__":
    main()
