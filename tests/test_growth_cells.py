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

from svgtile import analyze, read_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import Controls, make_params, synthesize
from svgtile.engines.base import Context
from svgtile.engines.growth.engine import Growth, _phase
from svgtile.engines.growth.grow import Grown

REPO = Path(__file__).resolve().parents[1]


def _cells_of(region: Region, monkeypatch: pytest.MonkeyPatch) -> tuple[Growth, list[tuple[int, int]]]:
    """The run's :class:`Growth` and the cells it grew, in order."""
    seen: dict = {}
    grow_cells = Growth.grow_cells

    def spy(self, cells, done):
        seen.setdefault("growth", self)
        seen.setdefault("cells", []).extend(cells)
        return grow_cells(self, cells, done)

    monkeypatch.setattr(Growth, "grow_cells", spy)
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


def _growth(region: Region, **controls) -> Growth:
    ex = read_exemplar(REPO / "exemplars" / "gravel.svg")
    ctx = Context(ex, analyze(ex), region, "clip", 7, lambda stage, fraction: None, Controls(**controls))
    return Growth(ctx, make_params("growth", {}))


def _same(a: Arrangement, b: Arrangement) -> bool:
    return all(np.array_equal(getattr(a, f), getattr(b, f)) for f in ("kind", "xy", "angle", "scale"))


@pytest.mark.parametrize("barrier", [False, True])
def test_cells_of_one_phase_grown_in_step_are_each_as_if_grown_alone(barrier):
    """A phase's cells are grown round by round together, with one exact check a round for all
    of them (:meth:`Growth.grow_cells`); each cell's motifs must be those it gets grown alone."""
    river = shapely.LineString([(-70, 20), (190, 100)]) if barrier else None  # pieces: cells cut in two
    g = _growth(Region(shapely.box(0, 0, 200, 200)), barriers=river)
    done: dict = {}
    g.subs = {}
    order = g.cells()
    for phase in range(4):
        cells = [c for c in order if _phase(c) == phase]
        together = g.grow_cells(cells, done)
        alone = [g.grow_cells([c], done)[0] for c in cells]
        assert len(cells) > 1
        for (arr, sub), (arr1, sub1) in zip(together, alone, strict=True):
            assert _same(arr, arr1) and np.array_equal(sub, sub1)
        for c, (arr, sub) in zip(cells, together, strict=True):
            done[c], g.subs[c] = arr, sub
    assert sum(len(a) for a in done.values()) > 500


def test_one_check_for_several_pieces_is_each_checked_alone():
    """:meth:`Growth.settle_all`: checks that share fixed motifs and whose new motifs clash with
    each other's (as cells of one phase never do) still come out as if made one by one."""
    g = _growth(Region(shapely.box(0, 0, 100, 100)))
    ex = g.ex
    rng = np.random.default_rng(3)

    def make(n: int, x0: float) -> Arrangement:
        return Arrangement(rng.integers(0, len(ex.kinds), n), rng.uniform((x0, 0), (x0 + 30, 30), (n, 2)),
                           rng.uniform(-180, 180, n), np.ones(n))  # fmt: skip

    shared = make(25, 0)
    news = [make(40, 5), make(40, 10), make(0, 0), make(30, 60)]
    befores = [Arrangement.concat([shared, make(10, 0)]), shared, make(5, 0), make(0, 0)]
    supports = [rng.integers(0, 3, len(x)) for x in news]
    together = g.settle_all(news, befores, supports)
    alone = [g.settle(n, b, s) for n, b, s in zip(news, befores, supports, strict=True)]
    assert [len(x) for x in together] == [len(x) for x in news]
    assert all(np.array_equal(t, a) for t, a in zip(together, alone, strict=True))
    assert 0 < sum(a.sum() for a in alone) < sum(len(x) for x in news)  # some stay, some leave
    # pooled as one check, the clashes between the first two would remove more
    assert g.settle(Arrangement.concat(news[:2]), befores[0]).sum() < together[0].sum() + together[1].sum()


def test_a_piece_that_grows_nothing_is_done_while_the_others_go_on(monkeypatch):
    """A round that grows nothing ends its piece (no refill from the same seeds), in step with
    pieces that go on growing."""
    from svgtile.engines.growth import engine

    calls: dict = {}
    real = engine.grow

    def grow(rings, piece, *a, **k):
        key = piece.bounds
        calls[key] = calls.get(key, 0) + 1
        if key == barren:
            return Grown(np.zeros((0, 2)), np.zeros(0, np.int64), np.zeros(0))
        return real(rings, piece, *a, **k)

    monkeypatch.setattr(engine, "grow", grow)
    g = _growth(Region(shapely.box(0, 0, 100, 100)))
    g.subs = {}
    cells = [c for c in g.cells() if _phase(c) == 0]
    w, h = g.cell
    barren = (cells[0][0] * w, cells[0][1] * h, (cells[0][0] + 1) * w, (cells[0][1] + 1) * h)
    out = g.grow_cells(cells, {})
    assert calls[barren] == 1 and len(out[0][0]) == 0
    assert max(calls.values()) > 1 and all(len(arr) for arr, _ in out[1:])


@pytest.mark.parametrize("name, step", [("gravel", 2), ("marsh", 1)])
def test_a_phase_grown_in_steps_of_a_few_cells_is_the_same(monkeypatch, name, step):
    """Growth.run grows a phase IN_STEP cells at a time (memory); any step gives the same texture
    — marsh's too, grown on row lines (growth.rows: the seed on a line, relaxation on the lines,
    slide_apart), which must stay each cell's own business when cells grow in step."""
    from svgtile.engines.growth import engine

    ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
    region = Region(shapely.box(0, 0, 200, 140))
    whole = synthesize(ex, region, "growth", seed=4).arrangement
    monkeypatch.setattr(engine, "IN_STEP", step)
    steps = synthesize(ex, region, "growth", seed=4).arrangement
    assert len(whole) > 300 and _same(whole, steps)
