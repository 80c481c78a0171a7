"""Exemplar statistics (svgtile/analysis/) against brute force.

``d_ij`` is checked against every pair of motifs measured with shapely, on random arrangements
built here (own rotation and translation, exact prototypes) and on a random exemplar read from
SVG; orientation arcs against an exhaustive search over arc starts.
"""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np
import pytest
import shapely
import shapely.affinity
from conftest import XLINK, random_exemplar

from svgtile.analysis.stats import (
    analyze,
    distance_matrix,
    in_arcs,
    motif_estimate,
    orientation_arcs,
)
from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import Prototype, world_footprints
from svgtile.svg.reader import parse_exemplar

SHAPES = [
    shapely.Polygon([(0, 0), (6, 0), (6, 2), (2, 2), (2, 8), (0, 8)]),  # an L
    shapely.Point(0, 0).buffer(1.5, 16),
    shapely.box(0, 0, 5, 1),
    shapely.Polygon([(0, 0), (4, 0), (0, 3)]),
    shapely.box(0, 0, 20, 1),  # long and thin: bounding discs say little
]


def centred(geom: shapely.Geometry) -> shapely.Geometry:
    c = geom.centroid
    return shapely.affinity.translate(geom, -c.x, -c.y)


def exact_prototypes(shapes: list[shapely.Geometry]) -> list[Prototype]:
    return [Prototype.from_geometry(centred(g), tolerance=0.0) for g in shapes]


def placed(shapes: list[shapely.Geometry], arr: Arrangement) -> list[shapely.Geometry]:
    """Each motif built with shapely.affinity: scale, rotate about the centroid, move."""
    out = []
    for k, (x, y), a, s in zip(arr.kind, arr.xy, arr.angle, arr.scale, strict=True):
        g = shapely.affinity.scale(centred(shapes[k]), s, s, origin=(0, 0))
        g = shapely.affinity.rotate(g, a, origin=(0, 0))
        out.append(shapely.affinity.translate(g, x, y))
    return out


def brute_force(geoms: list[shapely.Geometry], kind: np.ndarray, k: int) -> tuple[np.ndarray, int]:
    """(k, k) minimum distance per kind pair (inf where no pair) and the overlap count."""
    d = np.full((k, k), np.inf)
    overlaps = 0
    for i, j in itertools.combinations(range(len(geoms)), 2):
        dist = geoms[i].distance(geoms[j])
        a, b = kind[i], kind[j]
        d[a, b] = d[b, a] = min(d[a, b], dist)
        overlaps += geoms[i].intersection(geoms[j]).area > 1e-9
    return d, overlaps


def random_arrangement(rng: np.random.Generator, n: int, k: int, size: float, *, clustered: bool) -> Arrangement:
    kind = rng.integers(0, k, n)
    xy = rng.uniform(0, size, (n, 2))
    if clustered:  # each kind in its own corner of a large field: far kind pairs
        xy = xy * 0.2 + (kind[:, None] * [0.23, 0.31] % 1.0) * size
    return Arrangement(kind, xy, rng.uniform(-180, 180, n), rng.uniform(0.5, 2.0, n))


@pytest.mark.parametrize(
    ("seed", "n", "k", "size", "clustered"),
    [(1, 40, 4, 60, False), (2, 80, 4, 200, False), (3, 60, 4, 400, True), (4, 25, 4, 1000, False),
     (5, 120, 4, 120, False), (6, 12, 4, 300, True), (8, 30, 5, 150, False), (9, 60, 5, 300, True)],
)  # fmt: skip
def test_distance_matrix_equals_brute_force(seed, n, k, size, clustered):
    rng = np.random.default_rng(seed)
    arr = random_arrangement(rng, n, k, size, clustered=clustered)
    shapes = [SHAPES[i % len(SHAPES)] for i in range(k)]
    protos = exact_prototypes(shapes)
    expect, overlaps = brute_force(placed(shapes, arr), arr.kind, k)
    distance, measured, counted = distance_matrix(arr, protos)
    assert np.array_equal(measured, np.isfinite(expect))
    assert np.allclose(distance[measured], expect[measured], rtol=1e-9, atol=1e-9)
    assert np.allclose(distance, distance.T)
    assert counted == overlaps


def test_many_sparse_kinds_equal_brute_force():
    """Many kinds with a few motifs each: most kind pairs are far apart (the branch and bound)."""
    rng = np.random.default_rng(7)
    k = 30
    shapes = [shapely.affinity.scale(SHAPES[i % 4], 1 + 0.1 * i, 1, origin=(0, 0)) for i in range(k)]
    kind = np.repeat(np.arange(k), rng.integers(1, 5, k))
    arr = Arrangement(kind, rng.uniform(0, 500, (len(kind), 2)), rng.uniform(-180, 180, len(kind)), np.ones(len(kind)))
    expect, _ = brute_force(placed(shapes, arr), arr.kind, k)
    distance, measured, _ = distance_matrix(arr, exact_prototypes(shapes))
    assert np.array_equal(measured, np.isfinite(expect))
    assert np.allclose(distance[measured], expect[measured], rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_analysis_of_a_random_exemplar_equals_brute_force(seed):
    ex = parse_exemplar(random_exemplar(np.random.default_rng(seed), 60))
    stats = analyze(ex)
    geoms = list(world_footprints(ex.motifs, ex.prototypes))
    k = len(ex.kinds)
    expect, overlaps = brute_force(geoms, ex.motifs.kind, k)
    assert np.allclose(stats.distance[np.isfinite(expect)], expect[np.isfinite(expect)], atol=1e-9)
    assert stats.overlaps == overlaps
    # density counts the exact footprints (Kind.footprint), not the engine's covering outlines
    exact = sum(ex.kinds[k].footprint.area * s**2 for k, s in zip(ex.motifs.kind, ex.motifs.scale, strict=True))
    assert stats.density == pytest.approx(exact / ex.region.area, rel=1e-6)
    assert stats.count_density == pytest.approx(len(ex.motifs) / 10000)
    counts = np.array([np.sum(ex.motifs.kind == i) for i in range(k)])
    assert np.allclose(stats.frequency, counts / counts.sum())
    assert in_arcs(ex.motifs.angle, ex.motifs.kind, stats).all()


def test_a_near_pair_that_is_not_the_nearest():
    """Bars 20 long: side by side their discs overlap but they are 21 apart; end to end their
    discs are 12 apart, and so are they.  The minimum is the second pair's."""
    shapes = [shapely.box(0, 0, 20, 1)]
    arr = Arrangement([0, 0, 0, 0], [(0, 0), (0, 22), (100, 0), (132, 0)], [0, 0, 0, 0], [1, 1, 1, 1])
    distance, measured, _ = distance_matrix(arr, exact_prototypes(shapes))
    assert measured[0, 0] and distance[0, 0] == pytest.approx(12.0)


def test_fallback_for_kind_pairs_without_instances():
    """Kinds 0-2 have one square each on a line (gaps 8, 28, 18); kind 3 has none."""
    shapes = [shapely.box(0, 0, 2, 2)] * 4
    arr = Arrangement([0, 1, 2], [(0, 0), (10, 0), (30, 0)], [0, 0, 0], [1, 1, 1])
    distance, measured, overlaps = distance_matrix(arr, exact_prototypes(shapes))
    expect_measured = np.zeros((4, 4), bool)
    for a, b in [(0, 1), (0, 2), (1, 2)]:
        expect_measured[a, b] = expect_measured[b, a] = True
    assert np.array_equal(measured, expect_measured)
    # measured: the gaps; unmeasured: the smaller of the two kinds' smallest measured distances,
    # and 0 where neither kind has one
    expect = np.array([[8, 8, 28, 8], [8, 8, 18, 8], [28, 18, 18, 18], [8, 8, 18, 0]], dtype=float)
    assert np.allclose(distance, expect)
    assert overlaps == 0


def test_overlapping_motifs_are_counted_and_do_not_crash():
    text = (
        f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK}" viewBox="0 0 40 40">'
        '<defs><symbol id="sq" overflow="visible"><rect x="-1" y="-1" width="2" height="2"/></symbol></defs>'
        '<use xlink:href="#sq" x="5" y="5"/><use xlink:href="#sq" x="6" y="5"/>'  # overlap
        '<use xlink:href="#sq" x="5" y="5.5"/>'  # overlaps both
        '<use xlink:href="#sq" x="20" y="20"/><use xlink:href="#sq" x="20" y="20"/>'  # exact duplicate
        '<use xlink:href="#sq" x="30" y="30"/><use xlink:href="#sq" x="30" y="34"/>'  # apart
        "</svg>"
    )
    ex = parse_exemplar(text)
    stats = analyze(ex)
    _, overlaps = brute_force(list(world_footprints(ex.motifs, ex.prototypes)), ex.motifs.kind, 1)
    assert stats.overlaps == overlaps == 4
    assert stats.distance[0, 0] == 0.0 and stats.measured[0, 0]


def test_touching_motifs_are_not_overlaps():
    shapes = [shapely.box(0, 0, 2, 2)]
    arr = Arrangement([0, 0, 0], [(0, 0), (2, 0), (2, 2)], [0, 0, 0], [1, 1, 1])
    distance, _, overlaps = distance_matrix(arr, exact_prototypes(shapes))
    assert overlaps == 0 and distance[0, 0] == 0.0


def test_density_is_footprint_area_over_region_area():
    squares = "".join(f'<rect x="{x}" y="{y}" width="4" height="4"/>' for x in (20, 35, 50, 65) for y in (30, 60))
    text = (
        '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">'
        f'<circle id="region" cx="50" cy="50" r="45" fill="none"/>{squares}</svg>'
    )
    ex = parse_exemplar(text)
    stats = analyze(ex)
    exact = 8 * 16 / (np.pi * 45**2)
    assert ex.region.area == pytest.approx(np.pi * 45**2, rel=1e-4)
    # density counts exact footprints, not the engine's slightly larger covering outlines
    assert stats.density == pytest.approx(exact, rel=1e-3)
    areas = [g.area for g in world_footprints(ex.motifs, ex.prototypes)]
    assert sum(areas) / ex.region.area > stats.density


# ----------------------------------------------------------------------------- orientation arcs


def brute_arc(angles: list[float]) -> float:
    """Width of the smallest arc holding every angle: try each angle as the arc's start."""
    a = np.mod(angles, 360.0)
    return min(float(np.max(np.mod(a - s, 360.0))) for s in a)


@pytest.mark.parametrize(
    ("angles", "start", "width"),
    [([170, -170], 170, 20), ([0, 90], 0, 90), ([10], 10, 0), ([0, 120, 240], 0, 240),
     ([-179, 179], 179, 2), ([350, 10, 20], -10, 30), ([45, 45, 45], 45, 0), ([-90, 0, 90, 180], -90, 270)],
)  # fmt: skip
def test_orientation_arcs_table(angles, start, width):
    got_start, got_width = orientation_arcs(np.array(angles, float), np.zeros(len(angles), int), 1)
    assert got_width[0] == pytest.approx(width)
    assert got_width[0] == pytest.approx(brute_arc(angles))
    if width < 180:  # a wider arc's start is not unique for symmetric inputs
        assert (got_start[0] - start) % 360 == pytest.approx(0, abs=1e-9)


@pytest.mark.parametrize("seed", range(5))
def test_orientation_arcs_random(seed):
    rng = np.random.default_rng(seed)
    k = 4
    kind = rng.integers(0, k - 1, 40)  # the last kind has no instances
    centre = rng.uniform(-180, 180, k)
    angle = centre[kind] + rng.uniform(-1, 1, 40) * rng.uniform(0, 170, k)[kind]
    start, width = orientation_arcs(angle, kind, k)
    for c in range(k - 1):
        assert width[c] == pytest.approx(brute_arc(angle[kind == c]), abs=1e-9)
        assert -180 <= start[c] < 180
    assert width[k - 1] == 0
    stats = SimpleNamespace(arc_start=start, arc_width=width)
    assert in_arcs(angle, kind, stats).all()
    # just outside each arc is out; rounding to the 4 decimals of the output keeps in
    narrow = width[kind] < 359
    assert not in_arcs((start[kind] - 0.01)[narrow], kind[narrow], stats).any()
    assert not in_arcs((start[kind] + width[kind] + 0.01)[narrow], kind[narrow], stats).any()
    assert in_arcs(np.round(angle, 4), kind, stats).all()


def test_motif_estimate_is_area_times_density_but_a_thin_strip_costs_whole_copies():
    from svgtile.core.region import Region

    ex = parse_exemplar('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 20">'
                        + "".join(f'<circle cx="{x}" cy="{y}" r="1"/>' for x in (2, 7) for y in (3, 9, 15)) + "</svg>")  # fmt: skip
    stats = analyze(ex)
    assert stats.count_density == pytest.approx(6 / 200)
    assert motif_estimate(ex, stats, Region.rectangle(100, 50)) == pytest.approx(6 / 200 * 5000)
    # 0.01 wide: the copies laid along it are 10 wide
    assert motif_estimate(ex, stats, Region.rectangle(0.01, 1000)) == pytest.approx(6 / 200 * 10 * 1000)
