"""Benchmark the patch engine's ``synthesize`` (CPU, wall, peak memory) on the bundled exemplars,
optionally against an older svgtile package, run by run interleaved so both see the same load.

Each case runs in its own process; CPU is ``time.process_time`` of ``synthesize`` alone (all of
the process's threads: scipy's k-d tree queries run with ``workers=-1``), wall is
``time.perf_counter``, peak is the process's maximum resident set.  A hash of the arrangement
(kinds, positions, angles) shows whether the two packages made the same texture.

Run by hand:
    git archive <commit> svgtile | tar -x -C /tmp/base      # the package to compare against
    python benchmarks/patch_speed.py --base /tmp/base --counts 100000 [--exemplars till,gravel]

It prints one Markdown table (to paste into benchmarks/README.md) after the machine's load.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
EXEMPLARS = HERE.parent / "exemplars"


def _child(exemplar: str, count: int) -> None:
    """Run one measured case in this (fresh) process and print JSON."""
    import hashlib
    import math
    import resource
    import time

    import svgtile
    from svgtile import analyze, read_exemplar
    from svgtile.core.region import Region
    from svgtile.engines import synthesize

    ex = read_exemplar(exemplar)
    stats = analyze(ex)
    side = math.sqrt(count / stats.count_density)
    cpu, wall = time.process_time(), time.perf_counter()
    arr = synthesize(ex, Region.rectangle(side, side), "patch", seed=1, stats=stats).arrangement
    cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
    digest = hashlib.sha1(arr.kind.tobytes() + arr.xy.tobytes() + arr.angle.tobytes()).hexdigest()[:10]
    print(json.dumps({"package": str(Path(svgtile.__file__).parent.parent), "motifs": len(arr), "cpu": cpu,
                      "wall": wall, "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                      "hash": digest}))  # fmt: skip


def _run(package: str | None, exemplar: Path, count: int, timeout: float) -> dict | None:
    env = dict(os.environ)
    if package:
        env["PYTHONPATH"] = package + os.pathsep + env.get("PYTHONPATH", "")
    try:
        out = subprocess.run([sys.executable, __file__, "--child", str(exemplar), str(count)], env=env, cwd="/",
                             capture_output=True, text=True, timeout=timeout, check=True)  # fmt: skip
    except (subprocess.TimeoutExpired, subprocess.CalledProcessError) as e:
        print(f"{exemplar.stem} {count}: {type(e).__name__}", file=sys.stderr)
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", help="a folder holding an older svgtile package to compare against")
    parser.add_argument("--counts", default="100000")
    parser.add_argument("--exemplars", default=",".join(sorted(p.stem for p in EXEMPLARS.glob("*.svg"))))
    parser.add_argument("--timeout", type=float, default=900.0, help="seconds per case")
    parser.add_argument("--child", nargs=2, metavar=("EXEMPLAR", "COUNT"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        _child(args.child[0], int(args.child[1]))
        return
    load = os.getloadavg()
    print(f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"load {load[0]:.1f} {load[1]:.1f} {load[2]:.1f} at the start")  # fmt: skip
    print()
    head = "| exemplar | target | motifs | CPU (s) | wall (s) | peak (MiB) |"
    rule = "|---|---:|---:|---:|---:|---:|"
    if args.base:
        head += " base CPU (s) | CPU ratio | same texture |"
        rule += "---:|---:|---|"
    print(head)
    print(rule)
    for name in args.exemplars.split(","):
        for count in (int(c) for c in args.counts.split(",")):
            ex = EXEMPLARS / f"{name}.svg"
            base = _run(args.base, ex, count, args.timeout) if args.base else None
            new = _run(None, ex, count, args.timeout)
            if new is None:
                continue
            row = f"| {name} | {count:,} | {new['motifs']:,} | {new['cpu']:.2f} | {new['wall']:.2f} | {new['peak_mib']:.0f} |"
            if args.base:
                if base is None:
                    row += " – | – | – |"
                else:
                    same = "yes" if base["hash"] == new["hash"] else "no"
                    row += f" {base['cpu']:.2f} | {new['cpu'] / base['cpu']:.2f} | {same} |"
            print(row, flush=True)
    load = os.getloadavg()
    print()
    print(f"load {load[0]:.1f} {load[1]:.1f} {load[2]:.1f} at the end")


if __name__ == "__main__":
    main()
