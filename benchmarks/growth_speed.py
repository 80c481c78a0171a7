"""Growth engine timings (issue 13): motifs per second with and without relaxation, peak memory.

Run: ``python benchmarks/growth_speed.py EXEMPLAR SIDE [SIDE …]`` — one square region per SIDE
(user units), seed 1, boundary clip; prints motifs, seconds and peak RSS.
"""

from __future__ import annotations

import resource
import sys
import time

from svgtile import analyze, read_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize


def main(argv: list[str]) -> None:
    ex = read_exemplar(argv[0])
    st = analyze(ex)
    for side in map(float, argv[1:]):
        for relaxation in (True, False):
            t = time.perf_counter()
            r = synthesize(ex, Region.rectangle(side, side), "growth", seed=1, stats=st, params={"relaxation": relaxation})
            dt = time.perf_counter() - t
            rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
            print(f"{argv[0]} side={side:g} relaxation={relaxation} motifs={len(r)} seconds={dt:.2f} "
                  f"peak_rss_mb={rss:.0f}", flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
