"""Inscribed discs per kind (svgtile.core.discs) decide pairs of motifs before GEOS: they must
lie inside the footprints, and the conflicts found with them must be exactly those GEOS finds
on every pair (issue 12's speed target: the marsh and scrub tufts, thin and concave)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile import read_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.conflicts import (
    RULE_SLACK,
    cross_conflicts,
    cross_pairs,
    discs_close,
    find_conflicts,
    slack,
)
from svgtile.core.discs import inscribed_discs
from svgtile.core.footprint import Prototype, world_footprints

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"


@pytest.mark.parametrize("name", sorted(p.stem for p in EXEMPLARS.glob("*.svg")))
def test_discs_lie_inside_the_outline(name):
    for proto in read_exemplar(EXEMPLARS / f"{name}.svg").prototypes:
        centre, radius = inscribed_discs(proto)
        assert len(radius) and (radius > 0).all()
        outline = proto.geometry()
        disc = shapely.buffer(shapely.points(centre), radius, quad_segs=32)
        # each disc is in one part of the outline (the parts are tested alone, as GEOS does)
        assert all(shapely.covers(outline, d) or any(shapely.covers(shapely.polygons(r), d) for r in proto.rings)
                   for d in disc)  # fmt: skip
        gap = shapely.distance(shapely.points(centre), shapely.MultiLineString(list(proto.rings)))
        assert (gap >= radius).all()


def _tufts():
    """Thin and concave motifs whose centroids lie outside them or in a thin stroke."""
    vee = shapely.union_all([
        shapely.LineString([(-2, 2), (0, -2), (2, 2)]).buffer(0.2),
        shapely.LineString([(0, -2), (0, 1.5)]).buffer(0.15),
    ])  # fmt: skip
    ell = shapely.LineString([(-2, 2), (-2, -2), (2, -2)]).buffer(0.25)
    bar = shapely.box(-3, -0.3, 3, 0.3)
    out = []
    for g in (vee, ell, bar):
        c = g.centroid
        out.append(
            Prototype.from_geometry(shapely.affinity.translate(g, -c.x, -c.y), tolerance=0.0)
        )
    return out


def _scatter(rng, n, k, side):
    return Arrangement(rng.integers(0, k, n), rng.uniform(0, side, (n, 2)), rng.uniform(-180, 180, n),
                       rng.uniform(0.8, 1.2, n))  # fmt: skip


def _plain_cross(new, old, protos, rule):
    """(a, b) of every conflicting pair, by GEOS on every pair."""
    eps = slack(protos)
    ga, gb = world_footprints(new, protos), world_footprints(old, protos)
    a, b = (v.ravel() for v in np.meshgrid(np.arange(len(new)), np.arange(len(old)), indexing="ij"))
    reach = rule[new.kind[a], old.kind[b]] - eps
    close = (reach > 0) & shapely.dwithin(ga[a], gb[b], np.maximum(reach, 0))
    share = shapely.intersects(ga[a], gb[b]) & ~shapely.touches(ga[a], gb[b])
    hit = close | share
    return a[hit], b[hit]


@pytest.mark.parametrize("seed", range(3))
def test_cross_pairs_with_discs_find_what_geos_finds(seed):
    rng = np.random.default_rng(seed)
    protos = _tufts()
    old, new = _scatter(rng, 150, 3, 50), _scatter(rng, 150, 3, 50)
    rule = np.array([[1.0, 0.5, 0.8], [0.5, 0.3, 0.6], [0.8, 0.6, 0.0]])
    pa, pb = _plain_cross(new, old, protos, rule)
    a, b = cross_pairs(new, old, protos, rule, complete=True)
    assert set(zip(a.tolist(), b.tolist(), strict=True)) == set(
        zip(pa.tolist(), pb.tolist(), strict=True)
    )
    bad = np.zeros(len(new), dtype=bool)
    bad[pa] = True
    assert 0 < bad.sum() < len(new)
    assert np.array_equal(cross_conflicts(new, old, protos, rule), bad)
    # the discs decide many of those pairs alone (else this test would not exercise them)
    reach = np.maximum(rule[new.kind[pa], old.kind[pb]] - slack(protos), 0)
    assert discs_close(new, old, protos, pa, pb, reach).mean() > 0.3


def _geos_conflicts(arr, protos, rule):
    """{(i, j): (overlap, violation)} of every conflicting pair i < j, by GEOS on every pair."""
    g = world_footprints(arr, protos)
    i, j = np.triu_indices(len(arr), 1)
    reach = rule[arr.kind[i], arr.kind[j]] - (RULE_SLACK + 1e-6 * max(p.radius for p in protos))
    violation = shapely.dwithin(g[i], g[j], reach)  # a rule ≤ 0: reach < 0, never
    overlap = shapely.intersects(g[i], g[j]) & ~shapely.touches(g[i], g[j])
    keep = violation | overlap
    return dict(zip(zip(i[keep].tolist(), j[keep].tolist(), strict=True),
                    zip(overlap[keep].tolist(), violation[keep].tolist(), strict=True), strict=True))  # fmt: skip


def _found(c):
    """find_conflicts' answer in :func:`_geos_conflicts`' form."""
    return dict(zip(zip(c.i.tolist(), c.j.tolist(), strict=True),
                    zip(c.overlap.tolist(), c.violation.tolist(), strict=True), strict=True))  # fmt: skip


@pytest.mark.parametrize("seed", range(3))
def test_find_conflicts_with_discs_find_what_geos_finds(seed):
    rng = np.random.default_rng(seed)
    protos = _tufts()
    arr = _scatter(rng, 250, 3, 60)
    rule = np.array([[1.0, 0.5, 0.8], [0.5, 0.3, 0.6], [0.8, 0.6, 0.4]])
    plain = _geos_conflicts(arr, protos, rule)
    assert _found(find_conflicts(arr, protos, rule)) == plain
    assert sum(o for o, _ in plain.values()) > 10


def test_a_kind_of_many_parts_gets_no_discs_and_geos_decides():
    """A kind whose greedy cover would weigh more than MAX_PAIRS (candidate, outline point)
    pairs — a path of many dots — gets no discs (reviewer: ≈ 5 GB for 95 dots), and its pairs'
    conflicts are still exactly GEOS's (a rule of 0 included: overlaps only)."""
    def dots(n):
        g = shapely.union_all([shapely.Point(x, y).buffer(0.3) for x in range(n) for y in range(n)])
        return Prototype.from_geometry(shapely.affinity.translate(g, -g.centroid.x, -g.centroid.y), tolerance=0.0)

    assert len(inscribed_discs(dots(3))[1])  # 9 dots: under the cap, discs
    protos = [dots(6), *_tufts()[:1]]  # 36 dots: ≈ 5 × 10⁴ candidates against ≈ 10³ outline points
    centre, radius = inscribed_discs(protos[0])
    assert centre.shape == (0, 2) and radius.shape == (0,)
    assert len(inscribed_discs(protos[1])[1])  # the small kind keeps its discs
    rng = np.random.default_rng(5)
    arr = _scatter(rng, 120, 2, 40)
    rule = np.array([[0.0, 0.5], [0.5, 0.3]])
    plain = _geos_conflicts(arr, protos, rule)
    assert _found(find_conflicts(arr, protos, rule)) == plain
    assert sum(o for o, _ in plain.values()) > 5


@pytest.mark.parametrize("seed", range(2))
def test_cross_pairs_skips_only_the_motifs_the_caller_gives_up(seed):
    """``hopeless`` (the patch engine's displacement tests): a new motif the pairs known so far
    rule out (here: two or more) is not tested further; every other motif's pairs are exactly
    those found without it, in the same order."""
    rng = np.random.default_rng(seed)
    protos = _tufts()
    old, new = _scatter(rng, 200, 3, 40), _scatter(rng, 200, 3, 40)
    rule = np.array([[1.0, 0.5, 0.8], [0.5, 0.3, 0.6], [0.8, 0.6, 0.0]])
    a, b = cross_pairs(new, old, protos, rule)
    dead = np.zeros(len(new), dtype=bool)
    asked = []

    def hopeless(ha, hb):
        asked.append(len(ha))
        dead[:] |= np.bincount(ha, minlength=len(new)) >= 2
        return dead

    ha, hb = cross_pairs(new, old, protos, rule, hopeless=hopeless)
    assert len(asked) == 2 and 0 < dead.sum() < len(new)
    live, hlive = ~dead[a], ~dead[ha]
    assert np.array_equal(a[live], ha[hlive]) and np.array_equal(b[live], hb[hlive])
    # the motifs given up on did conflict that much, and some of their pairs went untested
    assert (np.bincount(a, minlength=len(new))[dead] >= 2).all()
    assert len(ha) < len(a)


def test_world_footprints_from_coordinates_are_the_rings_footprints():
    """Footprints built straight from coordinates (closed rings) are those of the outline
    turned, scaled and moved; a two-part kind gives MultiPolygons, an open ring still works."""
    vee, ell, bar = _tufts()
    two = Prototype(rings=(vee.rings[0], ell.rings[0] + np.array([6.0, 0.0])), area=vee.area + ell.area,
                    radius=vee.radius + 6.0, inner=0.0, excess=0.0)  # fmt: skip
    open_ = Prototype(rings=(bar.rings[0][:-1],), area=bar.area, radius=bar.radius, inner=bar.inner, excess=0.0)
    protos = [vee, two, open_]
    rng = np.random.default_rng(3)
    arr = _scatter(rng, 60, 3, 30)
    got = world_footprints(arr, protos)
    for g, k, xy, angle, scale in zip(got, arr.kind, arr.xy, arr.angle, arr.scale, strict=True):
        a = np.radians(angle)
        c, s = np.cos(a) * scale, np.sin(a) * scale
        parts = [shapely.polygons(np.c_[c * r[:, 0] - s * r[:, 1] + xy[0], s * r[:, 0] + c * r[:, 1] + xy[1]])
                 for r in protos[k].rings]  # fmt: skip
        want = parts[0] if len(parts) == 1 else shapely.multipolygons(parts)
        assert shapely.get_type_id(g) == shapely.get_type_id(want)
        assert shapely.equals_exact(g, want, tolerance=1e-12)
