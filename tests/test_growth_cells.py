"""The cells a growth run grows (issue 13, speed of small regions): all that the region needs, no more.

A cell's motifs are a function of the key and the cell alone, grown against its earlier-phase
neighbours (:mod:`svgtile.engines.growth.engine`), so a region needs the cells its domain meets
and, recursively, their earlier-phase neighbours.  That closure is most of a small region's cost
(benchmarks/README.md, "Growth engine: the tiled-run overhead"): these tests pin it down from
both sides — every dependency present (else tiled runs would differ) and every cell grown
either meets the domain or is a dependency (else time is wasted).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile import read_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.engine import Growth, _phase

REPO = Path(__file__).resolve().parents[1]


def _cells_of(region: Region, monkeypatch: pytest.MonkeyPatch) -> tuple[Growth, list[tuple[int, int]]]:
    """The run's :class:`Growth` and the cells it grew, in order."""
    seen: dict = {}
    grow_cell = Growth.grow_cell

    def spy(self, c, done):
        seen.setdefault("growth", self)
        seen.setdefault("cells", []).append(c)
        return grow_cell(self, c, done)

    monkeypatch.setattr(Growth, "grow_cell", spy)
    synthesize(read_exemplar(REPO / "exemplars" / "gravel.svg"), region, "growth", seed=1)
    return seen["growth"], seen["cells"]


@pytest.mark.parametrize("box", [(0, 0, 50, 50), (37, -20, 150, 70), (-130, -130, -10, 5)])
def test_a_run_grows_the_cells_its_region_needs_and_no_others(box, monkeypatch):
    g, cells = _cells_of(Region(shapely.box(*box)), monkeypatch)
    assert len(set(cells)) == len(cells)
    phases = [_phase(c) for c in cells]
    assert phases == sorted(phases)  # earlier phases first: a cell's neighbours are grown before it
    w, h = g.cell
    domain = shapely.buffer(shapely.box(*box), g.radius + float(g.stats.distance.max()))
    meets = {c for c in cells if shapely.intersects(shapely.box(c[0] * w, c[1] * h, (c[0] + 1) * w, (c[1] + 1) * h), domain)}
    # every cell the domain meets is grown (a motif there may reach into the region)
    a0, b0 = np.floor(np.array(domain.bounds[:2]) / (w, h)).astype(int)
    a1, b1 = np.floor(np.array(domain.bounds[2:]) / (w, h)).astype(int)
    for a in range(a0, a1 + 1):
        for b in range(b0, b1 + 1):
            box_ab = shapely.box(a * w, b * h, (a + 1) * w, (b + 1) * h)
            assert (a, b) in cells or not shapely.intersects(box_ab, domain), (a, b)
    grown = set(cells)
    for a, b in cells:
        earlier = {(a + da, b + db) for da in (-1, 0, 1) for db in (-1, 0, 1) if _phase((a + da, b + db)) < _phase((a, b))}
        assert earlier <= grown, (a, b)  # its growth reads them all: a missing one would change its motifs
    # and nothing else: each cell meets the domain or is an earlier-phase neighbour of one grown
    for c in grown - meets:
        later = [(c[0] + da, c[1] + db) for da in (-1, 0, 1) for db in (-1, 0, 1)]
        assert any(q in grown and _phase(q) > _phase(c) for q in later), c
    assert len(meets) < len(cells)  # the closure is real: a small region grows more than it meets
