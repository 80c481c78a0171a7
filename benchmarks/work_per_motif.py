"""CPU seconds per motif of ``svgtile synth`` for each engine: the figures behind the work guard.

    python benchmarks/work_per_motif.py [--only ENGINE] [EXEMPLAR]
    python benchmarks/work_per_motif.py --only cellular TILE.svg   # an exemplar `svgtile import` made cellular

Runs ``svgtile synth`` end to end (read, analyse, synthesise, write the SVG) in a child process
per engine at two sizes, and reports the child's CPU time (user + system), which a shared
machine inflates less than wall time.  The slope between the two sizes is the engine's cost per
motif; ``svgtile.apps.load.SECONDS_PER_MOTIF`` holds rounded-up values of it (benchmarks/
README.md has the run they come from).  ``--refine 1`` is measured as its own line: the cost of
one refinement iteration per motif.
"""

from __future__ import annotations

import math
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

#: engine → the two motif counts it is measured at (the slow engines at fewer)
RUNS = {"patch": (20_000, 200_000), "tile": (20_000, 200_000), "random": (20_000, 200_000),
        "growth": (2_000, 10_000), "optimize": (2_000, 10_000), "patch --refine 1": (2_000, 20_000),
        "patch --refine 5": (2_000, 20_000), "cellular": (1_000, 10_000)}  # fmt: skip


def cpu_of(args: list[str]) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-m", "svgtile", *args], check=True, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    args = sys.argv[1:]
    only = None
    if args[:1] == ["--only"]:
        only, args = args[1], args[2:]
    exemplar = args[0] if args else str(REPO / "exemplars" / "gravel.svg")
    sys.path.insert(0, str(REPO))
    from svgtile.apps.load import load_exemplar

    _, stats = load_exemplar(exemplar)
    out = Path(tempfile.mkdtemp()) / "t.svg"
    print(f"{exemplar}: {stats.count_density:.4f} motifs per unit²\n")
    print("| engine | motifs | CPU s | motifs | CPU s | CPU s per motif |")
    print("|---|---:|---:|---:|---:|---:|")
    for engine, counts in RUNS.items():
        if (only is None and engine == "cellular") or (only is not None and only not in engine):
            continue  # the cellular engine needs a cellular exemplar
        name, *extra = engine.split()
        row = []
        for n in counts:
            side = math.sqrt(n / stats.count_density)
            args = ["synth", exemplar, "--engine", name, *extra, "--size", f"{side:.0f}x{side:.0f}", "--seed", "1",
                    "-o", str(out), "--force"]  # fmt: skip
            row.append((n, cpu_of(args)))
        (n0, t0), (n1, t1) = row
        print(f"| {engine} | {n0:,} | {t0:.1f} | {n1:,} | {t1:.1f} | {(t1 - t0) / (n1 - n0):.2e} |", flush=True)


if __name__ == "__main__":
    main()
