"""Where copies meet (issue 3): the junction rule, copies turned rigidly, room for a lacking kind.

Known answers on constructed exemplars, brute force with shapely on random ones, and the patch
engine's copies checked against the exemplar they copy.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely
import shapely.affinity
from conftest import XLINK, random_exemplar
from scipy.spatial import cKDTree

from svgtile import Region, analyze, read_exemplar
from svgtile.analysis.stats import GAP_MIN_SAMPLES, in_arcs, junction_distance
from svgtile.core.arrangement import Arrangement
from svgtile.core.conflicts import find_conflicts
from svgtile.core.footprint import Prototype, world_footprints
from svgtile.engines.patch.density import _rank_within, _roomiest
from svgtile.engines.patch.engine import grid
from svgtile.engines.patch.orientation import turn
from svgtile.svg.reader import parse_exemplar

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"


def row_of_discs(xs: list[float], *, period: str | None = None) -> str:
    """Discs of radius 1 on the line y = 5, in a 22 × 10 region (optionally a repeating tile)."""
    attr = f' svgtile:period="{period}"' if period else ""
    uses = "".join(f'<use xlink:href="#c" transform="translate({x} 5)"/>' for x in xs)
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK}" xmlns:svgtile="urn:svgtile:run:1" '
        f'viewBox="0 0 22 10"><defs><symbol id="c" overflow="visible"><circle r="1"/></symbol></defs>'
        f'<rect id="region" width="22" height="10" fill="none"{attr}/>{uses}</svg>'
    )


# gaps between neighbours 1, 2, 3 and 4: nearest gaps (1, 1, 2, 3, 4); across the tile's edge
# the last disc is 2 from the first, so a repeating tile has nearest gaps (1, 1, 2, 3, 2)
ROW = [1, 4, 8, 13, 19]


def test_junction_is_the_quantile_of_the_nearest_gaps():
    ex = parse_exemplar(row_of_discs(ROW))
    stats = analyze(ex)
    # footprints are covering outlines, a little larger than the circle: every gap shrinks alike
    shrink = 1.0 - stats.distance[0, 0]
    assert 0 <= shrink < 0.1
    assert junction_distance(ex, stats, 0.0)[0, 0] == stats.distance[0, 0]
    assert junction_distance(ex, stats, 0.5)[0, 0] == pytest.approx(2.0 - shrink, abs=1e-6)
    assert junction_distance(ex, stats, 0.9)[0, 0] == pytest.approx(3.6 - shrink, abs=1e-6)


def test_a_repeating_tile_measures_gaps_across_its_edges():
    ex = parse_exemplar(row_of_discs(ROW, period="22 10"))
    assert ex.period == (22.0, 10.0)
    stats = analyze(ex)
    shrink = 1.0 - stats.distance[0, 0]
    assert junction_distance(ex, stats, 0.9)[0, 0] == pytest.approx(2.6 - shrink, abs=1e-6)


def test_too_few_gaps_keep_the_distance_rule():
    ex = parse_exemplar(row_of_discs(ROW[: GAP_MIN_SAMPLES - 1]))
    stats = analyze(ex)
    assert np.array_equal(junction_distance(ex, stats, 0.9), stats.distance)


@pytest.mark.parametrize("seed", [3, 4])
@pytest.mark.parametrize("q", [0.25, 0.6])
def test_junction_equals_brute_force(seed, q):
    ex = parse_exemplar(random_exemplar(np.random.default_rng(seed), 40))
    stats = analyze(ex)
    geoms = world_footprints(ex.motifs, ex.prototypes)
    kind, k = ex.motifs.kind, len(ex.prototypes)
    dist = shapely.distance(geoms[:, None], geoms[None, :])
    np.fill_diagonal(dist, np.inf)
    quant = np.full((k, k), np.nan)
    for i in range(k):
        for j in range(k):
            gaps = dist[np.ix_(kind == i, kind == j)].min(axis=1)
            gaps = gaps[np.isfinite(gaps)]
            if len(gaps) >= GAP_MIN_SAMPLES:
                quant[i, j] = np.quantile(gaps, q)
    expect = np.maximum(stats.distance, np.fmin(quant, quant.T))
    got = junction_distance(ex, stats, q)
    assert np.allclose(got, expect, atol=1e-6)
    assert np.array_equal(got, got.T) and (got >= stats.distance).all()
    assert (junction_distance(ex, stats, min(q + 0.3, 0.99)) >= got).all()  # monotone in q


def discs(xy):
    arr = Arrangement(np.zeros(len(xy), int), np.array(xy, float), np.zeros(len(xy)), np.ones(len(xy)))
    protos = [Prototype.from_geometry(shapely.Point(0, 0).buffer(1.0, 64), tolerance=0.0)]
    return arr, protos


def test_junction_holds_only_between_groups():
    arr, protos = discs([(0, 0), (3.5, 0)])  # gap 1.5
    d, junction = np.array([[1.0]]), np.array([[2.0]])
    assert len(find_conflicts(arr, protos, d)) == 0
    same = find_conflicts(arr, protos, d, group=np.array([4, 4]), junction=junction)
    assert len(same) == 0
    apart = find_conflicts(arr, protos, d, group=np.array([4, 5]), junction=junction)
    assert len(apart) == 1 and apart.violation[0] and not apart.overlap[0]
    with pytest.raises(ValueError):
        find_conflicts(arr, protos, d, junction=junction)


def test_junction_conflicts_are_the_same_band_by_band(monkeypatch):
    rng = np.random.default_rng(5)
    arr, protos = discs(rng.uniform(0, 120, (900, 2)))
    group = rng.integers(0, 4, len(arr))
    d, junction = np.array([[0.5]]), np.array([[2.5]])
    whole = find_conflicts(arr, protos, d, group=group, junction=junction)
    monkeypatch.setattr("svgtile.core.conflicts.BAND_MOTIFS", 100)
    banded = find_conflicts(arr, protos, d, group=group, junction=junction)
    pairs = lambda c: set(zip(c.i.tolist(), c.j.tolist(), strict=True))  # noqa: E731
    assert pairs(whole) == pairs(banded)
    # brute force: centre distance − 2 below the rule of the pair's groups
    gap = np.hypot(*(arr.xy[:, None] - arr.xy[None, :]).transpose(2, 0, 1)) - 2.0
    rule = np.where(group[:, None] == group[None, :], 0.5, 2.5)
    i, j = np.nonzero(np.triu(gap < rule - 1e-3, 1))
    assert pairs(whole) == set(zip(i.tolist(), j.tolist(), strict=True))


def test_turn_keeps_orientations_inside_their_arcs():
    stats = analyze(read_exemplar(EXEMPLARS / "gravel.svg"))
    kind = np.array([0, 0, 1, 1])
    angle = np.array([10.0, 10.0, 20.0, 20.0])
    theta = np.array([5.0, 179.0, 5.0, 140.0])  # 10 + 179 and 20 + 140 fall in the arcs' gaps
    got = turn(kind, angle, theta, stats)
    assert in_arcs(got, kind, stats).all()
    moved = got != angle
    assert moved.tolist() == [True, False, True, False]
    assert np.allclose((got[moved] - angle[moved] - theta[moved] + 180) % 360 - 180, 0)
    assert not in_arcs((angle + theta)[~moved], kind[~moved], stats, tol=0.0).any()
    assert np.array_equal(turn(kind, angle, theta, None), angle)  # the paper's: all turned back


def test_a_copy_of_motifs_drawn_at_all_angles_is_rigid():
    """Breccia's fragments lie at nearly every angle: most turn with their copy, and the footprint
    gaps between turned motifs of a copy are the exemplar's."""
    ex = read_exemplar(EXEMPLARS / "breccia.svg")
    stats = analyze(ex)
    arr, cell = grid(ex, Region.rectangle(200, 200), key=11, grid_kind="square", overlap=0.1, max_rotation=30, stats=stats)
    turned = np.abs((arr.angle - ex.motifs.angle[cell[:, 2]] + 180) % 360 - 180) > 1e-3
    assert turned.mean() > 0.7
    first = (cell[:, 0] == cell[0, 0]) & (cell[:, 1] == cell[0, 1]) & turned
    mine = np.flatnonzero(first)
    assert len(mine) > 20
    copy_geoms = world_footprints(arr.take(mine), ex.prototypes)
    ex_geoms = world_footprints(ex.motifs.take(cell[mine, 2]), ex.prototypes)
    a, b = np.triu_indices(len(mine), 1)
    assert np.allclose(shapely.distance(copy_geoms[a], copy_geoms[b]), shapely.distance(ex_geoms[a], ex_geoms[b]), atol=2e-3)
    # without stats, the paper's: every motif keeps its exemplar orientation
    plain, pcell = grid(ex, Region.rectangle(200, 200), key=11, grid_kind="square", overlap=0.1, max_rotation=30)
    assert np.allclose(plain.angle, ex.motifs.angle[pcell[:, 2]], atol=1e-3)


def test_rank_within():
    assert _rank_within(np.array([2, 0, 2, 2, 0, 1])).tolist() == [0, 0, 1, 2, 1, 0]


def test_roomiest_spot_is_where_a_large_kind_has_most_room():
    """A large disc (kind 0, r = 5, 30 from another large one) and small dots (kind 1, r = 1, no
    extra distance): the roomiest spot is the best of a fine brute-force grid, to within the
    refined sampling step — and is not the largest empty disc, which ignores the wide rule."""
    protos = [Prototype.from_geometry(shapely.Point(0, 0).buffer(r, 64), tolerance=0.0) for r in (5.0, 1.0)]
    xy = np.array([(20.0, 50.0), (80.0, 50.0), (80.0, 60.0), (70.0, 90.0)])
    arr = Arrangement(np.array([0, 1, 1, 1]), xy, np.zeros(4), np.ones(4))
    rule = np.array([[30.0, 0.0], [0.0, 0.0]])
    size, ids = np.array([100.0, 100.0]), np.array([[0, 0]])
    spot, clear = _roomiest(arr, cKDTree(arr.xy), protos, Region.rectangle(100, 100), np.zeros(2), size, ids, np.array([0]), rule, arr)

    def room(p):
        d = np.hypot(*(p[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
        r = np.array([5.0, 1.0, 1.0, 1.0])
        return (d - r - 5.0 - rule[0, arr.kind]).min(axis=1)

    g = (np.arange(400) + 0.5) / 4
    fine = np.stack([v.ravel() for v in np.meshgrid(g, g)], -1)
    best = room(fine).max()
    step = 100 / 12 / 4 * np.sqrt(2)  # the refined grid's diagonal
    assert room(spot)[0] >= best - step
    assert room(spot)[0] > 10  # far from both the large disc and the dots
    # clearance is the plain empty-disc radius at the spot (to footprints and window edges)
    plain = min((np.hypot(*(spot[0] - xy).T) - [5, 1, 1, 1]).min(), *(spot[0]), *(100 - spot[0]))
    assert clear[0] == pytest.approx(plain, abs=1e-6)


def test_roomiest_spot_stays_in_the_region():
    """A window half outside the region: the room outside is large (nothing is there), but the
    spot must be inside, where a motif can go."""
    protos = [Prototype.from_geometry(shapely.Point(0, 0).buffer(1.0, 32), tolerance=0.0)]
    g = np.arange(2.0, 60.0, 4.0)
    xy = np.stack([v.ravel() for v in np.meshgrid(g, np.arange(2.0, 100.0, 4.0))], -1)
    arr = Arrangement(np.zeros(len(xy), int), xy, np.zeros(len(xy)), np.ones(len(xy)))
    region = Region(shapely.box(0, 0, 60, 100))
    size, ids = np.array([100.0, 100.0]), np.array([[0, 0]])
    spot, clear = _roomiest(arr, cKDTree(arr.xy), protos, region, np.zeros(2), size, ids, np.array([0]), np.zeros((1, 1)), arr)
    assert region.shape.contains(shapely.Point(spot[0]))
    assert 0 <= clear[0] < 2.0  # among dots 4 apart, no clearance beyond the gaps between them


def test_junction_below_the_distance_rule_still_keeps_it():
    arr, protos = discs([(0, 0), (2.5, 0)])  # gap 0.5
    found = find_conflicts(arr, protos, np.array([[1.0]]), group=np.array([0, 1]), junction=np.array([[0.2]]))
    assert len(found) == 1 and found.violation[0]


@pytest.mark.parametrize(
    "shape",
    [
        shapely.Polygon([(0, 0), (10, 0), (0, 1)]),  # a sharp triangle: mitred corners reach far
        shapely.Polygon([(np.cos(a) * r, np.sin(a) * r) for a, r in zip(np.linspace(0, 2 * np.pi, 10, endpoint=False), [5, 2] * 5, strict=True)]),
        shapely.Point(0, 0).buffer(3.0, 64),
    ],
)
def test_prototype_excess_bounds_how_far_the_outline_reaches(shape):
    c = shape.centroid
    shape = shapely.affinity.translate(shape, -c.x, -c.y)
    proto = Prototype.from_geometry(shape)
    outline = shapely.segmentize(proto.geometry().boundary, 1e-3)
    reach = float(shapely.distance(shapely.points(shapely.get_coordinates(outline)), shape).max())
    assert 0 < reach <= proto.excess + 1e-9
    assert proto.excess <= reach * 1.5 + 1e-6  # and not much more
