"""Row phases (:mod:`svgtile.engines.growth.phases`): growth on a tile of rows exact along x whose
phases repeat only at the tile's height (FGDC 619, 620) keeps the tile's rows but not its period."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely
from growth_measure import baselines, distance
from test_baselines import brute_force_conflicts
from test_growth_gaps import jittered_tile
from test_growth_regular import REGULAR_TILES, at_step, needs_data

from svgtile import analyze, read_exemplar
from svgtile.analysis.neighbourhood import likeness
from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.phases import QUANTUM, row_phases
from svgtile.metrics import score
from svgtile.metrics.window import spacing
from svgtile.svg.reader import parse_exemplar

REPO = Path(__file__).resolve().parents[1]

#: Hand-drawn phases of the synthetic tile's six rows (user units, in [0, 4)).
PHASES = (0.3, 2.9, 1.1, 3.6, 0.8, 2.2)


def phased_tile(phases=PHASES, step: float = 4.0, cols: int = 6, dy: float = 3.0, squares: bool = False,
                ys=None) -> str:  # fmt: skip
    """Rows of dots ``dy`` apart (or at heights ``ys``, the tile ``dy`` per row high), each exact
    along x at ``step`` from its own hand-drawn phase; with ``squares`` every other dot is a square
    (a second kind: the exact step is ``2 · step``)."""
    marks = []
    for a, ph in enumerate(phases):
        for i in range(cols):
            x, y = ph + i * step, (a + 0.5) * dy if ys is None else ys[a]
            marks.append(f'<rect x="{x - 0.4:.4f}" y="{y - 0.4:.4f}" width="0.8" height="0.8"/>' if squares and i % 2
                         else f'<circle cx="{x:.4f}" cy="{y:.4f}" r="0.5"/>')  # fmt: skip
    w, h = cols * step, len(phases) * dy
    return (f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:svgtile="urn:svgtile:run:1" viewBox="0 0 {w} {h}">'
            f'<rect id="region" width="{w}" height="{h}" fill="none" svgtile:period="{w} {h}"/>{"".join(marks)}</svg>')  # fmt: skip


def phases_of(ex, key: int = 7):
    """:func:`row_phases` of ``ex`` with its own distance rule."""
    return row_phases(ex, key, analyze(ex).distance)


def test_a_tile_of_exact_rows_at_hand_drawn_phases_has_row_phases():
    ex = parse_exemplar(phased_tile())  # one kind: dots
    r = phases_of(ex)
    assert r is not None
    assert r.step == pytest.approx(4.0) and r.rows == 6
    assert np.allclose(r.phase * QUANTUM, PHASES, atol=1e-4)
    # the steps from each row to the next (the last to the first's copy above) close over the height
    assert np.allclose(r.steps * QUANTUM, np.diff(np.r_[PHASES, PHASES[0]]) % 4.0, atol=1e-4)
    assert np.array_equal(np.bincount(r.row), np.full(6, 6))


@pytest.mark.parametrize("svg, why", [
    (phased_tile(phases=(0.0, 2.0) * 3), "an exact brick: its rows repeat at a step across them"),
    (jittered_tile(5, 8, 3.0, 5.0, 0.3), "rows jittered along x: no exact step along them"),
    (phased_tile(dy=3.0, cols=1), "one motif a row: the step is the width"),
    (phased_tile(phases=(0.3, 2.9)), "two rows are too few"),
])  # fmt: skip
def test_other_tiles_have_no_row_phases(svg, why):
    assert phases_of(parse_exemplar(svg)) is None, why


def test_drawn_exemplars_have_no_row_phases():
    for path in sorted((REPO / "exemplars").glob("*.svg")):
        assert phases_of(read_exemplar(path)) is None, path.name


def test_the_walk_is_a_chain_of_the_tiles_own_steps_anchored_at_row_zero():
    ex = parse_exemplar(phased_tile())
    r = phases_of(ex)
    q = round(r.step / QUANTUM)
    k = np.arange(-200, 201)
    walk = r.walk(k)
    assert walk[200] == r.phase[0]  # world row 0 has tile row 0's phase
    assert set(np.diff(walk) % q) <= set(r.steps)  # every step is one of the tile's
    assert len(set(np.diff(walk) % q)) == r.rows  # … and every one of them is drawn
    # a row's phase is the same whatever rows are asked for with it (a region's extent)
    assert np.array_equal(r.walk(np.array([-150, 3, 180])), walk[[50, 203, 380]])
    assert np.array_equal(r.walk(np.array([5])), walk[[205]])
    assert not np.array_equal(phases_of(ex, 8).walk(k), walk)  # another key, another walk
    shift = r.shift(np.arange(-30, 30)[:, None], np.arange(6)[None])
    assert shift.min() >= 0 and shift.max() < r.step
    # not the tile's own phases repeated: rows one tile height apart move by different amounts
    assert np.ptp(shift, axis=0).min() > 1.0


def test_a_row_follows_the_one_below_only_by_steps_that_keep_the_distance_rule():
    """Rows 1.6 and 2.4 apart by turns (dots of radius 0.5), the wider pairs nearly above each
    other: their phase steps break the distance rule between a narrower pair.  The steps kept are
    exactly those that keep it (checked pair by pair on footprints), and the walk draws no other."""
    from svgtile.core.arrangement import Arrangement
    from svgtile.core.footprint import world_footprints

    ex = parse_exemplar(phased_tile((0.3, 1.6, 1.9, 3.8, 0.3, 1.9), dy=2.0, ys=(0.8, 2.4, 4.8, 6.4, 8.8, 10.4)))
    st = analyze(ex)
    r = row_phases(ex, 5, st.distance)
    assert r is not None
    n, m = r.rows, ex.motifs
    w, h = ex.period
    fits = np.zeros((n, n), bool)
    for a in range(n):
        for j in range(n):
            moved = ((r.steps[j] - r.steps[a]) * QUANTUM) % r.step
            lo = np.flatnonzero(r.row == a)
            hi = np.flatnonzero(r.row == (a + 1) % n)
            up = np.c_[moved + np.array([-w, 0.0, w])[:, None].repeat(len(hi), 1).ravel(),
                       np.full(3 * len(hi), h if a == n - 1 else 0.0)]  # fmt: skip
            other = Arrangement(m.kind[np.tile(hi, 3)], m.xy[np.tile(hi, 3)] + up, m.angle[np.tile(hi, 3)],
                                m.scale[np.tile(hi, 3)])  # fmt: skip
            g1 = world_footprints(m.take(lo), ex.prototypes)
            g2 = world_footprints(other, ex.prototypes)
            gap = shapely.distance(g1[:, None], g2[None])
            need = st.distance[m.kind[lo][:, None], other.kind[None]]
            fits[a, j] = bool((gap >= need - 1e-9).all())
    fits[np.arange(n), np.arange(n)] = True
    kept = np.zeros((n, n), bool)
    for a in range(n):
        kept[a, r.choices[a, : r.count[a]]] = True
    assert 0 < (~fits).sum() and fits.sum() > n  # some steps refused, some besides the tile's own kept
    assert np.array_equal(kept, fits)
    q = round(r.step / QUANTUM)
    k = np.arange(-100, 100)
    drawn = np.diff(r.walk(k)) % q
    assert all(d in r.steps[r.choices[a, : r.count[a]]] for d, a in zip(drawn, k[:-1] % n, strict=True))


def test_sites_are_the_tiles_rows_moved_along_x():
    ex = parse_exemplar(phased_tile(squares=True))
    r = phases_of(ex, 3)
    assert r.step == pytest.approx(8.0) and len(ex.kinds) == 2
    rng = np.random.default_rng(0)
    xy = rng.uniform(-60, 60, (400, 2))
    kind = rng.integers(0, 2, 400)
    site, sub = r.sites(ex, xy, kind)
    assert np.array_equal(ex.motifs.kind[sub], kind)
    w, h = r.period
    b = np.round((site[:, 1] - ex.motifs.xy[sub, 1]) / h).astype(np.int64)
    assert np.allclose(site[:, 1], ex.motifs.xy[sub, 1] + b * h)  # the tile row's height, kept
    dx = site[:, 0] - ex.motifs.xy[sub, 0] - r.shift(b, r.row[sub])
    assert np.allclose(dx, np.round(dx / w) * w)  # the row copy's own phase, whole widths away
    # onto its own row or the next (rows 3 apart; a point between two rows, up to 4 units off the
    # phase of the nearer, may go to the other: 4·|dy| ≤ √(4² + (4·1.5)²) ⇒ |dy| ≤ 1.8)
    assert np.abs(site[:, 1] - xy[:, 1]).max() <= 1.81


# -- growth on FGDC 619 and 620 ------------------------------------------------------------------

@cache
def grown(name: str, seed: int = 1, **params):
    ex, st = load_exemplar(str(REGULAR_TILES[name]), as_tile=True, warn=lambda m: None)
    w, h = ex.period
    region = Region.rectangle(5 * w, 5 * h)  # its interior (one tile in from the edge) holds 9 tiles
    arr = synthesize(ex, region, "growth", seed=seed, stats=st, boundary="centroid", params=params or None).arrangement
    return ex, st, region, arr


@needs_data
def test_only_619_and_620_of_the_regular_tiles_have_row_phases():
    found = set()
    for name, path in REGULAR_TILES.items():
        ex, st = load_exemplar(str(path), as_tile=True, warn=lambda m: None)
        if row_phases(ex, 1, st.distance) is not None:
            found.add(name)
    assert found == {"619", "620"}


@needs_data
@pytest.mark.parametrize("name", ["619", "620"])
def test_growth_on_hand_phased_rows_does_not_repeat_at_the_tiles_period(name):
    ex, st, region, arr = grown(name)
    _, _, _, old = grown(name, row_phases=False)
    tol = 0.01 * spacing(st)
    r = row_phases(ex, 1, st.distance)
    # a motif's same-kind partners one tile height up lie every ``step`` along that row: by chance,
    # one within ``tol`` of x ± 0 for a share 4·tol / step of the motifs
    chance = 4 * tol / r.step
    h = ex.period[1]
    assert at_step(old, (0.0, h), tol) > 0.95  # snapped to the tile's sites: its period, everywhere
    assert at_step(arr, (0.0, h), tol) <= chance + 0.1
    assert at_step(arr, (ex.period[0], h), tol) <= chance + 0.1
    s = score(ex, st, arr, region)
    _vx, vy = s.repetition_vector
    assert abs(vy) < 0.1 * spacing(st), s.repetition_vector  # the mode is along a row, not the period across


@needs_data
@pytest.mark.parametrize("name", ["619", "620"])
def test_growth_on_hand_phased_rows_keeps_the_tiles_rows(name):
    """Every motif lies at the height of its tile row (whole tile heights away), and every world
    row is one copy of its tile row moved along x as a whole: the hand's jitter within the row kept."""
    ex, st, _region, arr = grown(name)
    m = ex.motifs
    w, h = ex.period
    r = row_phases(ex, 1, st.distance)
    # each motif's tile row: the tile motif of its kind whose height (mod h) is nearest
    dy = arr.xy[:, None, 1] - m.xy[None, :, 1]
    miss = np.abs(dy - np.round(dy / h) * h) + np.where(arr.kind[:, None] == m.kind[None], 0.0, np.inf)
    s = np.argmin(miss, axis=1)
    assert miss[np.arange(len(arr)), s].max() < 1e-3
    b = np.round(dy[np.arange(len(arr)), s] / h).astype(np.int64)
    row = r.row[s]
    worlds = b * r.rows + row
    for k in np.unique(worlds):
        mine = np.flatnonzero(worlds == k)
        tile = np.flatnonzero(r.row == row[mine[0]])
        # the shift that puts this world row's first motif on a tile motif of its kind …
        first = mine[np.argmin(arr.xy[mine, 0])]
        cands = [arr.xy[first, 0] - m.xy[t, 0] for t in tile if m.kind[t] == arr.kind[first]]
        best = 0
        for c in cands:  # … puts all of them on the tile's row copies (whole widths apart)
            rel = arr.xy[mine, 0, None] - c - m.xy[tile, 0][None]
            hit = (np.abs(rel - np.round(rel / w) * w) < 1e-3) & (arr.kind[mine, None] == m.kind[tile][None])
            best = max(best, int(hit.any(1).sum()))
        assert best == len(mine), (k, best, len(mine))
    # and the rows do not all sit at the tile's phases (that is stamping)
    assert at_step(arr, (0.0, h), 0.01 * spacing(st)) < 0.5


@needs_data
@pytest.mark.parametrize("name", ["619", "620"])
def test_growth_on_hand_phased_rows_is_dense_like_and_clean(name):
    ex, st, region, arr = grown(name)
    assert brute_force_conflicts(arr, ex, st) == (0, 0)
    s = score(ex, st, arr, region)
    assert s.overlaps_total == 0 and s.violators_total == 0
    assert 0.9 <= s.density_ratio <= 1.1, s.density_ratio
    assert likeness(distance(arr, ex, st, region), *baselines(ex, st, region)) >= 0.8


@needs_data
def test_growth_on_hand_phased_rows_is_seeded_and_a_cells_content_is_independent_of_the_region():
    from svgtile.svg.writer import result_document

    ex, st, _region, _arr = grown("620")
    w, h = ex.period

    def svg(seed):
        return result_document(synthesize(ex, Region.rectangle(2 * w, 2 * h), "growth", seed=seed, stats=st))

    first = svg(1)
    assert svg(1) == first and svg(2) != first  # same seed, same bytes; another seed, other phases
    # a smaller region, across the origin (negative world rows), gives the same motifs where both reach
    part = Region(shapely.box(-0.7 * w, -0.4 * h, 1.3 * w, 1.6 * h))
    small = synthesize(ex, part, "growth", seed=1, stats=st, boundary="centroid").arrangement
    big = synthesize(ex, Region(shapely.box(-w, -h, 2 * w, 2 * h)), "growth", seed=1, stats=st,
                     boundary="centroid").arrangement  # fmt: skip
    inside = shapely.contains_xy(part.shape, big.xy[:, 0], big.xy[:, 1])
    key = lambda a: {(int(k), float(x), float(y)) for k, (x, y) in zip(a.kind, a.xy, strict=True)}  # noqa: E731
    assert len(small) > 100 and key(small) == key(big.take(np.flatnonzero(inside)))
    assert (small.xy[:, 1] < 0).sum() > 20  # rows below world row 0 were grown


@needs_data
def test_growth_on_hand_phased_rows_honours_a_barrier_a_growth_area_and_avoid_zones():
    """Sites move before the exact check, which still removes a motif that would cross a barrier
    or leave the growth area; both sides of the barrier are filled, and avoid zones stay empty."""
    from svgtile.core.footprint import world_footprints
    from svgtile.engines import Controls

    ex, st = load_exemplar(str(REGULAR_TILES["619"]), as_tile=True, warn=lambda m: None)
    w, h = ex.period
    region = Region.rectangle(2 * w, 2 * h)
    river = shapely.LineString([(0.3 * w, -5), (1.6 * w, 2 * h + 5)])
    arr = synthesize(ex, region, "growth", seed=4, stats=st, controls=Controls(barriers=river)).arrangement
    assert not shapely.intersects(world_footprints(arr, ex.prototypes), river).any()
    side = shapely.contains_xy(shapely.Polygon([(0.3 * w, -5), (1.6 * w, 2 * h + 5), (-10, 2 * h + 5), (-10, -5)]),
                               arr.xy[:, 0], arr.xy[:, 1])  # fmt: skip
    assert side.sum() > 0.3 * len(arr) and (~side).sum() > 0.3 * len(arr)
    assert brute_force_conflicts(arr, ex, st) == (0, 0)
    spray = shapely.Point(w, h).buffer(0.7 * w)
    arr = synthesize(ex, region, "growth", seed=6, stats=st, controls=Controls(grow_within=spray)).arrangement
    assert shapely.contains_xy(spray, arr.xy[:, 0], arr.xy[:, 1]).all()
    assert len(arr) > 0.85 * spray.area * st.count_density
    hole = shapely.box(0.8 * w, 0.8 * h, 1.2 * w, 1.2 * h)
    arr = synthesize(ex, Region(region.shape, avoid=hole), "growth", seed=6, stats=st, boundary="inside").arrangement
    feet = world_footprints(arr, ex.prototypes)
    assert not shapely.intersects(feet, hole).any() and shapely.within(feet, region.shape).all()
    assert brute_force_conflicts(arr, ex, st) == (0, 0)
    assert row_phases(ex, 1, st.distance) is not None  # all this on row phases
