"""Growth on hand-drawn repeating tiles (issue 13): the tile's sites and the gap fill.

A hand-drawn tile's rings are near duplicates, so growth's best match is often another motif's
ring and each front drifts off the tile's lattice (FGDC 619 and 670 grew at density 0.77 and
0.67).  On a tile grown unturned every grown motif is moved to the nearest site of its kind in
the tile's pattern (:meth:`svgtile.engines.growth.engine.Growth.on_sites`), and the gaps left are
filled with what the placed motifs predict (:mod:`svgtile.engines.growth.gapfill`).  The figures
on the real tiles are in tests/test_growth_regular.py.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
import shapely
from test_baselines import brute_force_conflicts
from test_growth import lattice_tile

from svgtile import analyze
from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import world_footprints
from svgtile.core.region import Region
from svgtile.engines import Controls, make_params, synthesize
from svgtile.engines.base import Context
from svgtile.engines.growth.connectivity import reference_rings
from svgtile.engines.growth.engine import Growth
from svgtile.engines.growth.gapfill import candidates, predictions
from svgtile.metrics import score
from svgtile.svg.reader import parse_exemplar


def jittered_tile(rows: int, cols: int, dx: float, dy: float, jitter: float, r: float = 0.6) -> str:
    """Rows of dots, each moved by up to ``jitter`` units (fixed draws): a hand-drawn tile."""
    j = np.random.default_rng(0).uniform(-jitter, jitter, (rows, cols, 2))
    dots = "".join(f'<circle cx="{(i + 0.5) * dx + j[a, i, 0]:.4f}" cy="{(a + 0.5) * dy + j[a, i, 1]:.4f}" r="{r}"/>'
                   for a in range(rows) for i in range(cols))  # fmt: skip
    w, h = cols * dx, rows * dy
    return (f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:svgtile="urn:svgtile:run:1" viewBox="0 0 {w} {h}">'
            f'<rect id="region" width="{w}" height="{h}" fill="none" svgtile:period="{w} {h}"/>{dots}</svg>')  # fmt: skip


@cache
def jittered():
    ex = parse_exemplar(jittered_tile(5, 8, 3.0, 5.0, 1.0))
    return ex, analyze(ex)


def off_site(arr: Arrangement, ex) -> np.ndarray:
    """(n,) float: each motif's distance to the nearest site of its kind in the tile's pattern."""
    period = np.asarray(ex.period)
    rel = arr.xy[:, None] - ex.motifs.xy[None]
    d = np.hypot(*(rel - np.round(rel / period) * period).transpose(2, 0, 1))
    d[arr.kind[:, None] != ex.motifs.kind[None]] = np.inf
    return d.min(1)


def test_predictions_of_a_lattice_tile_are_its_lattice_steps():
    ex = parse_exemplar(lattice_tile(4, 4, 5.0, 4.0))
    pred = predictions(ex, reference_rings(ex))
    assert np.array_equal(np.diff(pred.start), np.full(16, 4))  # every motif: its four lattice neighbours
    for s in range(16):
        rows = slice(pred.start[s], pred.start[s + 1])
        assert sorted(map(tuple, np.round(pred.offset[rows], 9))) == [(-5, 0), (0, -4), (0, 4), (5, 0)]
        # each predicted motif is the tile's motif at that offset, whole periods away
        at = ex.motifs.xy[s] + pred.offset[rows]
        rel = at - ex.motifs.xy[pred.sub[rows]]
        assert np.allclose(rel / (20.0, 16.0), np.round(rel / (20.0, 16.0)))


def test_predictions_need_a_tile():
    ex = parse_exemplar(lattice_tile(4, 4, 5.0, 4.0).replace('svgtile:period="20.0 16.0"', ""))
    assert ex.period is None
    with pytest.raises(ValueError, match="repeating tile only"):
        predictions(ex, reference_rings(ex))


def test_candidates_merge_coincident_predictions_and_count_them():
    ex = parse_exemplar(lattice_tile(4, 4, 5.0, 5.0))
    pred = predictions(ex, reference_rings(ex))
    # motifs 0 at (2.5, 2.5) and 5 at (7.5, 7.5): both predict (7.5, 2.5) and (2.5, 7.5)
    placed = ex.motifs.take(np.array([0, 5]))
    cand, sub, support = candidates(pred, ex, placed, np.array([0, 5]))
    assert len(cand) == 6 and support.sum() == 8
    two = {tuple(p) for p in cand.xy[support == 2]}
    assert two == {(7.5, 2.5), (2.5, 7.5)}
    assert np.array_equal(ex.motifs.xy[sub][support == 2], cand.xy[support == 2])  # inside the tile: sub is the site


def test_a_hand_drawn_tile_grows_on_its_own_sites_at_its_density():
    ex, st = jittered()
    region = Region.rectangle(96, 100)
    arr = synthesize(ex, region, "growth", seed=2, stats=st, boundary="centroid").arrangement
    assert (off_site(arr, ex) < 1e-3).all()
    sc = score(ex, st, arr, region)
    assert 0.9 <= sc.density_ratio <= 1.1 and sc.likeness >= 0.99
    assert brute_force_conflicts(arr, ex, st) == (0, 0)
    # without the sites and the fill the fronts drift (the check can fail)
    free = synthesize(ex, region, "growth", seed=2, stats=st, boundary="centroid",
                      params={"snap": False, "gap_fill": False}).arrangement  # fmt: skip
    assert (off_site(free, ex) > 1e-3).mean() > 0.5
    assert not 0.9 <= score(ex, st, free, region).density_ratio <= 1.1


def test_a_turned_tile_keeps_its_rotation_and_is_not_moved_to_sites():
    ex, st = jittered()
    arr = synthesize(ex, Region.rectangle(60, 60), "growth", seed=2, stats=st,
                     params={"rotation": "fit"}).arrangement  # fmt: skip
    assert len(arr) and brute_force_conflicts(arr, ex, st) == (0, 0)
    assert (off_site(arr, ex) > 1e-3).mean() > 0.5
    assert make_params("growth", {"rotation": "fit"}).snap  # the setting stays; the rotation decides


def test_the_gap_fill_refills_a_hole_with_the_tiles_own_motifs():
    ex, st = jittered()
    region = Region.rectangle(96, 100)
    full = synthesize(ex, region, "growth", seed=2, stats=st, boundary="centroid").arrangement
    ctx = Context(ex, st, region, "centroid", 7, lambda stage, fraction: None)
    g = Growth(ctx, make_params("growth", {}))
    hole = shapely.box(30, 30, 60, 65)
    out = shapely.contains_xy(hole, full.xy[:, 0], full.xy[:, 1])
    rest = full.take(~out)
    _, sub = g.on_sites(rest.xy, rest.kind)
    kept: list[Arrangement] = []
    ksub: list[np.ndarray] = []
    g.fill_gaps(hole, [rest], [sub], kept, ksub)
    filled = Arrangement.concat(kept)
    assert out.sum() > 20 and len(filled) == out.sum()
    order = np.lexsort(filled.xy.T), np.lexsort(full.xy[out].T)
    assert np.allclose(filled.xy[order[0]], full.xy[out][order[1]], atol=1e-3)
    assert np.array_equal(ex.motifs.kind[np.concatenate(ksub)], filled.kind)


def test_on_a_tile_a_barrier_is_never_crossed_and_both_sides_keep_to_the_sites():
    ex, st = jittered()
    river = shapely.LineString([(40, -5), (55, 105)])
    arr = synthesize(ex, Region.rectangle(96, 100), "growth", seed=3, stats=st,
                     controls=Controls(barriers=river)).arrangement  # fmt: skip
    assert not shapely.intersects(world_footprints(arr, ex.prototypes), river).any()
    side = np.sign((55 - 40) * (arr.xy[:, 1] + 5) - (105 + 5) * (arr.xy[:, 0] - 40))
    assert (side > 0).sum() > 150 and (side < 0).sum() > 150
    assert (off_site(arr, ex) < 1e-3).all() and brute_force_conflicts(arr, ex, st) == (0, 0)
