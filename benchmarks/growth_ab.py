"""The growth engine's CPU time, this checkout against another, alternated (issue 13, the 1k target).

Run: ``python benchmarks/growth_ab.py OTHER EXEMPLAR WxH SEED [--tile] [--pairs N]`` — OTHER is a
directory holding another version's ``svgtile`` package (e.g. ``git archive main svgtile | tar -x
-C /tmp/main``).  N times (default 3) a fresh process of each version, one after the other, loads
the exemplar, grows a 10 × 10 warm-up (numba's cache load), then synthesizes the W × H region
three times and reports the least CPU time (``time.process_time``) and a hash of the arrangement
(kind, xy, angle, scale), which must agree.  On a shared machine only alternated figures compare:
the load changes from minute to minute.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

CHILD = """
import hashlib, sys, time
import numpy as np
import svgtile
from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
path, w, h, seed, tile = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), sys.argv[5] == "1"
ex, st = load_exemplar(path, as_tile=tile, warn=lambda m: None)
synthesize(ex, Region.rectangle(10, 10), "growth", seed=seed, stats=st)
best = float("inf")
for _ in range(3):
    t = time.process_time()
    arr = synthesize(ex, Region.rectangle(w, h), "growth", seed=seed, stats=st).arrangement
    best = min(best, time.process_time() - t)
digest = hashlib.sha256(b"".join(np.ascontiguousarray(a).tobytes() for a in (arr.kind, arr.xy, arr.angle, arr.scale)))
print(len(arr), digest.hexdigest()[:16], f"{best:.3f}")
"""


def main(argv: list[str]) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("other")
    ap.add_argument("exemplar")
    ap.add_argument("size")
    ap.add_argument("seed")
    ap.add_argument("--tile", action="store_true")
    ap.add_argument("--pairs", type=int, default=3)
    a = ap.parse_args(argv)
    w, h = a.size.split("x")
    here = str(Path(__file__).resolve().parents[1])
    cmd = [sys.executable, "-c", CHILD, str(Path(a.exemplar).resolve()), w, h, a.seed, "1" if a.tile else "0"]
    seen: dict[str, list[list[str]]] = {"this": [], "other": []}
    for _ in range(a.pairs):
        for name, root in (("other", str(Path(a.other).resolve())), ("this", here)):
            env = dict(os.environ, PYTHONPATH=root)
            out = subprocess.run(cmd, env=env, check=True, capture_output=True, text=True, cwd="/").stdout.split()
            seen[name].append(out)
            print(name, *out, flush=True)
    for name, runs in seen.items():
        print(f"{name}: motifs {runs[0][0]}, hash {runs[0][1]}, CPU s (least of 3) per process "
              f"{' '.join(r[2] for r in runs)}, best {min(float(r[2]) for r in runs):.3f}")  # fmt: skip
    if {r[1] for r in seen["this"] + seen["other"]} != {seen["this"][0][1]}:
        print("the arrangements DIFFER")


if __name__ == "__main__":
    main(sys.argv[1:])
