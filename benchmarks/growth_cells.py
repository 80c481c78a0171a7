"""The cells a growth run grows for a region, and the engine's CPU time (issue 13, small regions).

Run: ``python benchmarks/growth_cells.py EXEMPLAR SIDE[@OFFSET] …`` — for each square region of
side SIDE with its lower corner at (OFFSET, OFFSET) (default 0): the cells grown (the closure of
:meth:`svgtile.engines.growth.engine.Growth.cells`), how many meet the region's domain, the area
grown over the region's, and the engine's CPU seconds (best of 3, seed 1, after a warm-up that
loads the compiled kernel).
"""

from __future__ import annotations

import sys
import time

import shapely

from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.engine import Growth


def main(argv: list[str]) -> None:
    ex, st = load_exemplar(argv[0], warn=lambda m: None)
    synthesize(ex, Region.rectangle(10, 10), "growth", seed=1, stats=st)
    seen: dict = {}
    cells = Growth.cells

    def spy(self):
        out = cells(self)
        seen.update(growth=self, cells=out)
        return out

    Growth.cells = spy
    print("| region | cells grown | cells meeting the region | area grown / region area | motifs | engine CPU s |")
    print("|---|---|---|---|---|---|")
    for arg in argv[1:]:
        side, _, off = arg.partition("@")
        side, off = float(side), float(off or 0)
        region = Region.rectangle(side, side, off, off)
        best = float("inf")
        for _ in range(3):
            t = time.process_time()
            n = len(synthesize(ex, region, "growth", seed=1, stats=st).arrangement)
            best = min(best, time.process_time() - t)
        g = seen["growth"]
        w, h = g.cell
        domain = shapely.buffer(region.shape, g.radius + float(g.stats.distance.max()))
        meet = sum(bool(shapely.intersects(shapely.box(a * w, b * h, (a + 1) * w, (b + 1) * h), domain))
                   for a, b in seen["cells"])  # fmt: skip
        grown = len(seen["cells"])
        print(f"| {side:g} × {side:g} at ({off:g}, {off:g}) | {grown} | {meet} | {grown * w * h / side**2:.1f} | {n} | {best:.2f} |",
              flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
