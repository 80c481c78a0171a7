"""CPU of ``svgtile score`` in each of its two processes, this package against another, alternated (issue 11).

    python benchmarks/score_cpu.py EXEMPLAR TEXTURE BASE_PKG_DIR [ROUNDS]

Each round runs, for the base (``BASE_PKG_DIR``: a ``git archive`` of another commit, unpacked)
and then for this package: ``score EXEMPLAR TEXTURE --jobs 2`` in a child whose command, once
its figures are printed, reports its own CPU (user + sys, ``os.times``) and its worker's (the
worker joined first, so that it is counted among the reaped children); then ``score --jobs 1``
under ``/usr/bin/time`` (the whole work in one process).  ``/usr/bin/time`` alone cannot split
``--jobs 2``: the command ends without waiting for its worker (``Ending``), and whether the
worker was reaped by then, and so counted, is a race (score11e saw both, 1.3 s and 2.3 s of
the same run).  One Markdown row per run.  Run from the root of this package.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

#: The child: the command line of ``python -m svgtile``, with ``Ending.end`` reporting the CPU.
_CHILD = """
import multiprocessing, os, sys
import svgtile.cli.output as out
end = out.Ending.end
def report(code):
    me = os.times()
    for p in multiprocessing.active_children():
        p.join(30)
    ch = os.times()
    print(f"@cpu {me.user + me.system:.2f} {ch.children_user + ch.children_system:.2f}", file=sys.stderr)
    end(code)
out.Ending.end = report
from svgtile.cli.main import main
sys.argv = ["svgtile", *sys.argv[1:]]  # as the command line: main() reads sys.argv, and ends
sys.exit(main())
"""


def _run(pkg: Path, args: list[str]) -> tuple[str, str]:
    env = {**os.environ, "PYTHONPATH": str(pkg)}
    two = subprocess.run([sys.executable, "-c", _CHILD, "score", *args, "--jobs", "2"], cwd=pkg, env=env,
                         capture_output=True, text=True, check=True)  # fmt: skip
    main, worker = next(ln for ln in two.stderr.splitlines() if ln.startswith("@cpu ")).split()[1:]
    one = subprocess.run(["/usr/bin/time", "-f", "@time %e %U %S", sys.executable, "-m", "svgtile", "score", *args,
                          "--jobs", "1"], cwd=pkg, env=env, capture_output=True, text=True, check=True)  # fmt: skip
    wall, user, sys_ = next(ln for ln in one.stderr.splitlines() if ln.startswith("@time ")).split()[1:]
    return f"{main} s | {worker} s | {float(main) + float(worker):.2f} s", f"{float(user) + float(sys_):.2f} s | {wall} s"


def main() -> None:
    exemplar, texture, base = (str(Path(a).resolve()) for a in sys.argv[1:4])
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    here = Path(__file__).resolve().parents[1]
    print("| round | package | load | --jobs 2: command CPU | worker CPU | both | --jobs 1: CPU | wall |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for r in range(1, rounds + 1):
        for name, pkg in (("base", Path(base)), ("this", here)):
            load = os.getloadavg()[0]
            two, one = _run(pkg, [exemplar, texture])
            print(f"| {r} | {name} | {load:.2f} | {two} | {one} |", flush=True)


if __name__ == "__main__":
    main()
