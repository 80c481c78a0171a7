"""Stamp or grow: the whole-set gates' figures of the patch stamp and of the growth engine on every
repeating tile with rows or a lattice (issues 12 and 13, auto's ``tile-order`` rule).

For each gate tile of motifs (tests/test_wholeset.py, :func:`test_wholeset.motif_tiles`) whose
order is rows or a lattice on a period, the tile is synthesized over the gate's region
(:func:`test_wholeset.gate_region`, seed 1) once for each way of ``--ways`` (:data:`WAYS`; by
default the stamp — patch on the period, not turned: ``--grid lattice --max-rotation 0``, what
auto's ``tile-order`` rule picks — and the growth engine with its defaults) and scored exactly as
the gates are (:func:`test_wholeset.figures`: density / ρ, kind-mix TV over shape classes and per
kind with its chance, overlaps, violators, repetition, likeness L, coverage ``cov`` — None for a
tile without holes — and the texture's largest empty disc ``r_tex``).  One JSON line per tile
and way, with the exemplar's order read (:func:`svgtile.analysis.order.stamp_repeats`) and the
engine's wall seconds (synthesis and scoring, as the gate spends them).

Run from the repository root (``$SVGTILE_DATA`` or ``../shared/data`` beside the checkout):
    python benchmarks/stamp_or_grow.py [set/stem …] > stamp_or_grow.jsonl
    python benchmarks/stamp_or_grow.py --table stamp_or_grow.jsonl
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

#: The ways to fill a repeating tile, as (engine, params) for :func:`test_wholeset.figures`.
#: ``redraw``: the tile engine with each copy's row phases and jitter drawn anew (jit12,
#: :mod:`svgtile.engines.jitter`, auto's ``tile-jitter`` rule).
#: ``optimize``: the optimize engine with its defaults (what auto picks for a tile of scattered marks).
WAYS = {"stamp": ("patch", (("grid", "lattice"), ("max_rotation", 0.0))), "growth": ("growth", ()),
        "redraw": ("tile", (("redraw_jitter", True),)), "optimize": ("optimize", ())}


def measure(only: list[str], ways: list[str]) -> None:
    import test_wholeset as W

    from svgtile.analysis.order import read_order, stamp_repeats

    for tile, _t, ex, _st in W.motif_tiles(only):
        o = read_order(ex)
        if o.period is None or o.kind == "scatter":
            continue
        head = {"tile": tile, "order": o.kind, "motifs": len(ex.motifs), "repeats": stamp_repeats(ex, o)}
        for way in ways:
            engine, params = WAYS[way]
            t0 = time.perf_counter()
            s, _exov, L = W.figures(tile, engine, params)
            print(json.dumps({**head, "way": way, "density": round(s.density_ratio, 4), "tv": round(s.kind_mix_tv, 4),
                              "ov": int(s.overlaps_total), "viol": int(s.violators_total),
                              "rep": round(s.repetition, 4), "L": round(float(L), 4),
                              "tvk": s.kind_mix_tv_kinds, "noise": s.kind_mix_noise,
                              "cov": None if s.coverage is None else round(s.coverage, 3),
                              "r_tex": s.empty_disc_radius,
                              "s": round(time.perf_counter() - t0, 1)}), flush=True)  # fmt: skip


def passes(d: dict) -> bool | None:
    """Whether one line meets every whole-set gate but the exemplar's own overlaps
    (:func:`scatter_gates.bounds`, L ≥ 0.8 included); None for a line written before the per-kind
    mix and the coverage were recorded."""
    from scatter_gates import bounds

    if any(f not in d for f in ("tvk", "noise", "cov", "r_tex")):
        return None
    return all(bounds(d).values())


def _cov(d: dict) -> str:
    """The line's coverage, or a dash (lines written before it was recorded, or a tile without holes)."""
    return "–" if d.get("cov") is None else f"{d['cov']:.2f}"


def table(path: Path) -> None:
    rows: dict[str, dict[str, dict]] = {}
    for d in map(json.loads, path.read_text().splitlines()):
        rows.setdefault(d["tile"], {})[d["way"]] = d
    print("| tile | order | stamp repeats | way | density/ρ | TV | L | repetition | coverage | ov/viol | s | all gates |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for tile, ways in rows.items():
        for way, d in ways.items():
            print(f"| {tile} | {d['order']} | {'yes' if d['repeats'] else 'no'} | {way} | {d['density']:.3f} | "
                  f"{d['tv']:.3f} | {d['L']:.2f} | {d['rep']:.3f} | {_cov(d)} | {d['ov']}/{d['viol']} | {d['s']:.1f} | "
                  f"{ {True: 'yes', False: 'no', None: '?'}[passes(d)]} |")  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tiles", nargs="*", help="set/stem prefixes, as test_wholeset names them (fgdc/61)")
    parser.add_argument("--table", type=Path, help="print the markdown table of a run's JSON lines")
    parser.add_argument("--ways", default="stamp,growth", help=f"comma-separated, of {', '.join(WAYS)}")
    args = parser.parse_args()
    if args.table:
        table(args.table)
    else:
        measure(args.tiles, args.ways.split(","))


if __name__ == "__main__":
    main()
