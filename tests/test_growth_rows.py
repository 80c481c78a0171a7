"""Row lines (:mod:`svgtile.engines.growth.rows`): a drawn exemplar's rows, read once and held by
growth and relaxation on world lines, so rows neither climb nor meet out of step at cell seams."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest

from svgtile import analyze, read_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.connectivity import reference_rings
from svgtile.engines.growth.relax import relax
from svgtile.engines.growth.rows import lines_of, row_lines

REPO = Path(__file__).resolve().parents[1]


@cache
def marsh():
    ex = read_exemplar(REPO / "exemplars" / "marsh.svg")
    return ex, analyze(ex)


def hand_rows(pitch: float = 7.0, offset: float = 2.0, tilt: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Five rows of eight points, row 3 missing, each point up to 0.3 off its line: (xy, jitter)."""
    rng = np.random.default_rng(3)
    k = np.array([0, 1, 2, 4, 5])
    x = np.tile(np.arange(8) * 5.0 + 1.0, len(k))
    jitter = rng.uniform(-0.3, 0.3, len(x))
    u = np.repeat(offset + k * pitch, 8) + jitter
    c, s = np.cos(np.radians(tilt)), np.sin(np.radians(tilt))
    return np.c_[c * x - s * u, s * x + c * u], jitter


@pytest.mark.parametrize("tilt", [0.0, 12.0])
def test_lines_of_finds_the_pitch_the_offset_and_each_points_offset_from_its_row(tilt):
    xy, jitter = hand_rows(tilt=tilt)
    step = 5.0 * np.array([np.cos(np.radians(tilt)), np.sin(np.radians(tilt))])
    r = lines_of(xy, step)
    assert r is not None
    assert r.pitch == pytest.approx(7.0, abs=0.15)  # the missing row is numbered, not closed up
    assert r.offset == pytest.approx(2.0, abs=0.3)
    assert np.allclose(r.residual, jitter - jitter.reshape(5, 8).mean(1).repeat(8))
    # a point is put on the nearest line, at its own offset from it; far lines are world lines
    far = xy[:8] + 70.0 * r.across  # ten pitches away
    assert np.allclose(r.target(far, np.arange(8)), r.coordinate(xy[:8]) + 10 * r.pitch, atol=0.5)
    moved = r.onto(xy[:8] + 2.0 * r.across, np.arange(8))
    assert np.allclose(r.coordinate(moved) - r.residual[:8], r.offset + np.round((r.coordinate(moved) - r.residual[:8]
                                                                                 - r.offset) / r.pitch) * r.pitch)  # fmt: skip
    assert np.allclose((moved - xy[:8]) @ r.along, 0.0)  # moved across the rows only


def test_too_few_rows_or_no_rows_give_no_lines():
    xy, _ = hand_rows()
    assert lines_of(xy[:16], np.array([5.0, 0.0])) is None  # two rows
    for name in ("sand", "gravel", "shale"):  # a lattice, scatter, scatter
        assert row_lines(read_exemplar(REPO / "exemplars" / f"{name}.svg")) is None


def test_marsh_has_row_lines_across_its_step():
    ex, _ = marsh()
    r = row_lines(ex)
    assert r is not None
    assert abs(r.along[0]) > 0.999 and r.pitch == pytest.approx(7.66, abs=0.05)
    assert np.abs(r.residual).max() < 1.0  # the hand's jitter, well under the pitch


def test_relaxation_with_row_lines_puts_motifs_on_their_lines_and_keeps_the_rest():
    ex, _ = marsh()
    rings, r = reference_rings(ex), row_lines(ex)
    take = np.arange(0, len(rings), 2)
    sub = rings.element[take]
    # the exemplar's motifs, moved off their lines by up to 1.5 units; the first stays (eq. 6)
    rng = np.random.default_rng(0)
    xy = ex.motifs.xy[sub] + rng.uniform(-1.5, 1.5, (len(sub), 1)) * r.across
    xy[0] = ex.motifs.xy[sub[0]]
    off = lambda p: np.abs(r.coordinate(p) - r.target(p, sub))  # noqa: E731
    plain = relax(rings, xy, take, np.zeros(len(take)), 0)
    held = relax(rings, xy, take, np.zeros(len(take)), 0, rows=r)
    assert np.array_equal(held[0], xy[0])
    assert off(held)[1:].mean() < 0.25 * off(plain)[1:].mean()
    assert off(held)[1:].mean() < 0.25


@cache
def grown(rows: bool):
    ex, st = marsh()
    region = Region.rectangle(180, 180)
    return synthesize(ex, region, "growth", seed=1, stats=st, boundary="centroid", params={"rows": rows}).arrangement


def test_grown_marsh_stays_on_world_row_lines_across_cells():
    """Over 3 × 3 cells (60 units each) every row is on one world line: the motifs' across
    coordinates, less their exemplar offsets, lie near lines ``offset + k · pitch``; without the
    row lines they spread over the whole pitch."""
    ex, _ = marsh()
    r = row_lines(ex)

    def miss(arr):
        u = r.coordinate(arr.xy) - r.offset
        return np.abs(u - np.round(u / r.pitch) * r.pitch)  # ignores the residual (< 1 unit)

    held, free = grown(True), grown(False)
    assert np.quantile(miss(held), 0.95) < 1.2
    assert np.quantile(miss(free), 0.95) > 2.0
    assert len(held) > 0.9 * len(free)


def test_slide_apart_opens_a_row_by_what_the_distance_rule_asks_and_moves_only_the_new():
    """A new tuft too close to one placed before slides away along the row by what the distance
    rule lacks; a run of two new tufts pressed against it opens too (by halves, so not wholly in
    the rounds given)."""
    from svgtile.core.arrangement import Arrangement
    from svgtile.core.conflicts import find_conflicts
    from svgtile.engines.growth.rows import slide_apart

    ex, st = marsh()
    r = row_lines(ex)
    y = r.offset * r.across[1]  # on line 0 (across ≈ −y)

    def lack(arr):  # the distance rule's shortfall over the conflicting pairs, user units
        c = find_conflicts(arr, ex.prototypes, st.distance)
        from svgtile.core.footprint import world_footprints

        g = world_footprints(arr, ex.prototypes)
        return float(sum(st.distance[arr.kind[a], arr.kind[b]] - g[a].distance(g[b]) for a, b in zip(c.i, c.j, strict=True)))

    before = Arrangement(np.array([1]), np.array([[0.0, y]]), np.zeros(1), np.ones(1))
    one = Arrangement(np.array([1]), np.array([[4.0, y]]), np.zeros(1), np.ones(1))
    out = slide_apart(one, before, ex.prototypes, st.distance, r)
    assert lack(Arrangement.concat([before, one])) > 0.4
    assert len(find_conflicts(Arrangement.concat([before, out]), ex.prototypes, st.distance).i) == 0
    assert np.allclose((out.xy - one.xy) @ r.across, 0.0)  # along the row only
    assert 0.4 < out.xy[0, 0] - 4.0 < 0.7  # by about what was lacking
    run = Arrangement(np.array([1, 1]), np.array([[4.0, y], [8.0, y]]), np.zeros(2), np.ones(2))
    opened = slide_apart(run, before, ex.prototypes, st.distance, r)
    assert lack(Arrangement.concat([before, opened])) < 0.2 * lack(Arrangement.concat([before, run]))


def test_row_lines_keep_growth_tile_exact_and_seeded():
    """The lines are world lines (from the exemplar, not the region), and sliding moves only the
    motifs of the cell being grown: growth stays tile-exact with reach 0 — tiles of the region,
    each with a halo of one exemplar width, give together exactly the whole run — and the same
    seed gives the same motifs, another seed others."""
    import shapely

    ex, st = marsh()

    def grow(region, seed=2):
        arr = synthesize(ex, region, "growth", seed=seed, stats=st, boundary="centroid").arrangement
        return arr, np.concatenate([arr.kind[:, None], arr.xy, arr.angle[:, None], arr.scale[:, None]], axis=1)

    whole, rows = grow(Region.rectangle(160, 120))
    tiled = set()
    for tx in (0, 80):
        for ty in (0, 60):
            part = Region(shapely.box(tx, ty, tx + 80, ty + 60).buffer(60, join_style="mitre")
                          .intersection(shapely.box(0, 0, 160, 120)))  # fmt: skip
            arr, cols = grow(part)
            own = (arr.xy[:, 0] >= tx) & (arr.xy[:, 0] < tx + 80) & (arr.xy[:, 1] >= ty) & (arr.xy[:, 1] < ty + 60)
            tiled |= {tuple(r) for r in cols[own]}
    assert len(whole) > 300 and tiled == {tuple(r) for r in rows}
    assert np.array_equal(grow(Region.rectangle(160, 120))[1], rows)
    assert not np.array_equal(grow(Region.rectangle(160, 120), seed=3)[1], rows)


def test_rows_honour_a_barrier_and_a_growth_area():
    """Sliding along a row happens before the exact check, which still removes any motif that
    would cross a barrier or leave the growth area; both sides of the barrier are filled."""
    import shapely
    from test_baselines import brute_force_conflicts

    from svgtile.core.footprint import world_footprints
    from svgtile.engines import Controls

    ex, st = marsh()
    river = shapely.LineString([(70, -10), (95, 130)])
    arr = synthesize(ex, Region.rectangle(160, 120), "growth", seed=5, stats=st,
                     controls=Controls(barriers=river)).arrangement  # fmt: skip
    assert not shapely.intersects(world_footprints(arr, ex.prototypes), river).any()
    side = np.sign((95 - 70) * (arr.xy[:, 1] + 10) - (130 + 10) * (arr.xy[:, 0] - 70))
    assert (side > 0).sum() > 100 and (side < 0).sum() > 100
    assert brute_force_conflicts(arr, ex, st) == (0, 0)
    spray = shapely.Point(80, 60).buffer(40)
    arr = synthesize(ex, Region.rectangle(160, 120), "growth", seed=6, stats=st,
                     controls=Controls(grow_within=spray)).arrangement  # fmt: skip
    assert shapely.contains_xy(spray, arr.xy[:, 0], arr.xy[:, 1]).all()
    assert len(arr) > 0.85 * spray.area * st.count_density  # filled as densely as the exemplar


def test_a_kind_change_does_not_cross_a_barrier_and_a_piece_of_nothing_is_no_error():
    """The final kind passes give a motif another kind's footprint, which may reach across a barrier
    its own did not: the engine's check turns such a change down (before it did not: 8 footprints
    crossed on three such layouts, seeds 1–3).  And where barriers leave a piece no room for any
    motif (lines 3 units apart), there is nothing to re-choose: no error, no motif."""
    import shapely

    from svgtile.core.footprint import world_footprints
    from svgtile.engines import Controls

    ex, st = marsh()
    bend = shapely.LineString([(0, 50), (60, 120), (200, 90)])
    arr = synthesize(ex, Region.rectangle(200, 200), "growth", seed=1, stats=st, boundary="centroid",
                     controls=Controls(barriers=bend)).arrangement  # fmt: skip
    assert len(arr) > 300 and not shapely.intersects(world_footprints(arr, ex.prototypes), bend).any()
    comb = shapely.MultiLineString([[(x, -50), (x, 200)] for x in np.arange(-50, 200, 3.0)])
    arr = synthesize(ex, Region.rectangle(120, 120), "growth", seed=1, stats=st, boundary="centroid",
                     controls=Controls(barriers=comb)).arrangement  # fmt: skip
    assert not shapely.intersects(world_footprints(arr, ex.prototypes), comb).any()
