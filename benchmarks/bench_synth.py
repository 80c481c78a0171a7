"""Benchmark ``svgtile synth``: wall time and peak memory at about 1k, 10k, 100k and 1M motifs.

Each case runs in its own process (so peak RSS is that case's own) beside two references filling
the same area:

* floor — only writing the same number of ``<use>`` elements with svgtile's output code;
* poisson — scipy's ``qmc.PoissonDisk`` placing the same number of points (the point-only peer:
  no shapes, no overlaps, no exemplar).

Run by hand:  python benchmarks/bench_synth.py [EXEMPLAR] [--counts 1000,10000,100000,1000000]
It prints a Markdown table to paste into benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_EXEMPLAR = HERE.parent / "exemplars" / "gravel.svg"


def _child(case: str, exemplar: str, count: int, out: str) -> None:
    """Run one measured case in this (fresh) process and print JSON."""
    import numpy as np

    from svgtile import analyze, read_exemplar
    from svgtile.svg.writer import use_elements, write_text

    ex = read_exemplar(exemplar)
    stats = analyze(ex)
    side = math.sqrt(count / stats.count_density)
    start = time.perf_counter()
    if case == "synth":
        from svgtile.cli.main import main

        code = main(["synth", exemplar, "-o", out, "--size", f"{side:.3f}x{side:.3f}", "--seed", "1", "--force"])
        assert code == 0
        motifs = Path(out).read_text().count("<use ")
    elif case == "floor":
        from svgtile.core.arrangement import Arrangement

        rng = np.random.default_rng(1)
        kinds = rng.integers(0, len(ex.kinds), count)
        arr = Arrangement(kinds, np.round(rng.uniform(0, side, (count, 2)), 4),
                          np.round(rng.uniform(-180, 180, count), 4), np.ones(count))  # fmt: skip
        write_text("\n".join(use_elements(arr, ex.kinds)), out)
        motifs = count
    elif case == "poisson":
        from scipy.stats import qmc

        # a Poisson-disk radius that gives about `count` points in the unit square
        radius = math.sqrt(0.68 / count)
        pts = qmc.PoissonDisk(d=2, radius=radius, seed=1).fill_space()
        motifs = len(pts)
    else:
        raise ValueError(case)
    wall = time.perf_counter() - start
    peak_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(json.dumps({"case": case, "count": count, "motifs": motifs, "wall": wall, "peak_mib": peak_mib}))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("exemplar", nargs="?", default=str(DEFAULT_EXEMPLAR))
    parser.add_argument("--counts", default="1000,10000,100000,1000000")
    parser.add_argument("--cases", default="synth,floor,poisson")
    parser.add_argument("--child", nargs=3, metavar=("CASE", "COUNT", "OUT"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        _child(args.child[0], args.exemplar, int(args.child[1]), args.child[2])
        return
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for count in (int(c) for c in args.counts.split(",")):
            for case in args.cases.split(","):
                if case == "poisson" and count > 100_000:
                    rows.append({"case": case, "count": count, "motifs": None, "wall": None, "peak_mib": None})
                    continue
                out = os.path.join(tmp, f"{case}-{count}.svg")
                cmd = [sys.executable, __file__, args.exemplar, "--child", case, str(count), out]
                res = subprocess.run(cmd, capture_output=True, text=True, check=True)
                rows.append(json.loads(res.stdout.strip().splitlines()[-1]))
                print(rows[-1], file=sys.stderr)
    print(f"exemplar `{Path(args.exemplar).name}`; {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, Python {platform.python_version()}\n")  # fmt: skip
    print("| target motifs | synth motifs | synth wall (s) | synth peak (MiB) | floor: write uses (s) | scipy PoissonDisk (s) |")
    print("|---:|---:|---:|---:|---:|---:|")
    by = {(r["case"], r["count"]): r for r in rows}
    for count in sorted({r["count"] for r in rows}):
        s, f, p = by.get(("synth", count)), by.get(("floor", count)), by.get(("poisson", count))
        cell = lambda r, k, fmt: (fmt.format(r[k]) if r and r.get(k) is not None else "—")  # noqa: E731
        print(f"| {count:,} | {cell(s, 'motifs', '{:,}')} | {cell(s, 'wall', '{:.2f}')} | {cell(s, 'peak_mib', '{:.0f}')} "
              f"| {cell(f, 'wall', '{:.2f}')} | {cell(p, 'wall', '{:.2f}')} |")  # fmt: skip


if __name__ == "__main__":
    main()
