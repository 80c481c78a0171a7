"""Reading exemplars (svgtile/svg/): kinds, instances, footprints, regions, errors.

Expectations are computed here, independently of the reader: transforms are composed with
hand-written numpy matrices, footprints are built with shapely from the analytic shape, areas are
formulas.  Kind prototypes are simplified covers of the exact footprint (see
``Prototype.from_geometry``), so exact comparisons use ``Kind.footprint`` and prototype-based
ones (``world_footprints``) allow the prototype's tolerance.
"""

from __future__ import annotations

import math
import re
import socket
import time
import urllib.request
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely
import shapely.affinity

from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import SIMPLIFY, world_footprints
from svgtile.errors import ExemplarError
from svgtile.svg.reader import parse_exemplar, read_exemplar

SHARED = Path(__file__).resolve().parents[2] / "shared"
DATA = SHARED / "data"

XLINK = "http://www.w3.org/1999/xlink"
SVG = "http://www.w3.org/2000/svg"
L_POINTS = [(0, 0), (6, 0), (6, 2), (2, 2), (2, 8), (0, 8)]  # no rotational or mirror symmetry
L_ATTR = " ".join(f"{x},{y}" for x, y in L_POINTS)
L_SYMBOL = f'<defs><symbol id="L" overflow="visible"><polygon points="{L_ATTR}"/></symbol></defs>'


def svg(body: str, attrs: str = 'viewBox="0 0 100 100"') -> str:
    return f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK}" {attrs}>{body}</svg>'


# ----------------------------------------------------------------------------- hand-made matrices


def T(x: float, y: float) -> np.ndarray:
    return np.array([[1.0, 0, x], [0, 1, y], [0, 0, 1]])


def R(deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def S(sx: float, sy: float | None = None) -> np.ndarray:
    return np.diag([sx, sx if sy is None else sy, 1.0])


def SKX(deg: float) -> np.ndarray:
    return np.array([[1.0, math.tan(math.radians(deg)), 0], [0, 1, 0], [0, 0, 1]])


def M(a: float, b: float, c: float, d: float, e: float, f: float) -> np.ndarray:
    return np.array([[a, c, e], [b, d, f], [0, 0, 1.0]])


def mapped(m: np.ndarray, geom: shapely.Geometry) -> shapely.Geometry:
    return shapely.affinity.affine_transform(geom, [m[0, 0], m[0, 1], m[1, 0], m[1, 1], m[0, 2], m[1, 2]])


def exact_world(ex: Exemplar, i: int) -> shapely.Geometry:
    """Motif i rebuilt from the arrangement and its kind's exact footprint."""
    arr = ex.motifs
    m = T(*arr.xy[i]) @ R(arr.angle[i]) @ S(arr.scale[i])
    return mapped(m, ex.kinds[arr.kind[i]].footprint)


def same_shape(a: shapely.Geometry, b: shapely.Geometry, rel: float = 1e-6) -> bool:
    return shapely.symmetric_difference(a, b).area <= rel * max(a.area, b.area)


def radius_of(geom: shapely.Geometry) -> float:
    c = np.array(geom.centroid.coords[0])
    return float(np.hypot(*(shapely.get_coordinates(geom) - c).T).max())


def covers_loosely(proto_world: shapely.Geometry, exact: shapely.Geometry) -> bool:
    """The prototype covers the exact footprint and stays within its tolerance band of it."""
    band = 4 * SIMPLIFY * radius_of(exact)
    return (
        shapely.difference(exact, proto_world).area <= 1e-6 * exact.area
        and shapely.hausdorff_distance(proto_world, exact) <= band
    )


def angle_diff(a: float, b: float) -> float:
    return abs((a - b + 180.0) % 360.0 - 180.0)


L_POLY = shapely.Polygon(L_POINTS)


# ----------------------------------------------------------------------------- 1. symbol / use


@pytest.mark.parametrize(
    "use",
    [
        '<use href="#L" transform="translate(30 40)"/>',
        '<use xlink:href="#L" transform="translate(30 40)"/>',
        f'<use NS1:href="#L" xmlns:NS1="{XLINK}" x="30" y="40"/>',
        f'<use a7:href="#L" xmlns:a7="{XLINK}" transform="translate(10 10)" x="20" y="30"/>',
    ],
    ids=["href", "xlink-href", "ad-hoc-prefix", "ad-hoc-prefix-with-transform"],
)
def test_use_href_forms(use):
    ex = parse_exemplar(svg(L_SYMBOL + use))
    assert [k.href for k in ex.kinds] == ["L"]
    assert len(ex.motifs) == 1
    expect = mapped(T(30, 40), L_POLY).centroid
    assert np.allclose(ex.motifs.xy[0], [expect.x, expect.y], atol=1e-3)
    assert angle_diff(ex.motifs.angle[0], 0.0) < 1e-6 and ex.motifs.scale[0] == pytest.approx(1.0)


def test_href_in_a_foreign_namespace_is_not_a_reference():
    text = svg(L_SYMBOL + '<use xmlns:x="urn:other" x:href="#L"/>')
    with pytest.raises(ExemplarError, match="has no href"):
        parse_exemplar(text)


def test_svg2_href_wins_over_xlink_href():
    defs = f'<defs><symbol id="A" overflow="visible"><polygon points="{L_ATTR}"/></symbol>' \
           '<symbol id="B" overflow="visible"><circle r="3"/></symbol></defs>'  # fmt: skip
    ex = parse_exemplar(svg(defs + '<use href="#B" xlink:href="#A" x="50" y="50"/>'))
    assert [k.href for k in ex.kinds] == ["B"]


NESTED = [
    # (group transforms, use transform, use x/y, expected matrix, expected angle, expected scale)
    (["translate(10 20)"], "rotate(30)", (0, 0), T(10, 20) @ R(30), 30.0, 1.0),
    (["matrix(0 1 -1 0 50 10)", "translate(5 5)"], "scale(2)", (3, 4),
     M(0, 1, -1, 0, 50, 10) @ T(5, 5) @ S(2) @ T(3, 4), 90.0, 2.0),
    (["rotate(-45 50 50)", "scale(1.5)"], "translate(4 6) rotate(100)", (1, -2),
     T(50, 50) @ R(-45) @ T(-50, -50) @ S(1.5) @ T(4, 6) @ R(100) @ T(1, -2), 55.0, 1.5),
    (["scale(0.5)", "rotate(170)", "translate(-20 -30)"], "rotate(20) scale(3)", (0, 0),
     S(0.5) @ R(170) @ T(-20, -30) @ R(20) @ S(3), -170.0, 1.5),
]  # fmt: skip


@pytest.mark.parametrize(("groups", "use_tf", "xy", "matrix", "angle", "scale"), NESTED)
def test_nested_group_transforms_compose_with_the_use(groups, use_tf, xy, matrix, angle, scale):
    body = "".join(f'<g transform="{g}">' for g in groups)
    body += f'<use xlink:href="#L" transform="{use_tf}" x="{xy[0]}" y="{xy[1]}"/>' + "</g>" * len(groups)
    ex = parse_exemplar(svg(L_SYMBOL + body, 'viewBox="-200 -200 400 400"'))
    assert len(ex.kinds) == 1 and len(ex.motifs) == 1
    world = mapped(matrix, L_POLY)
    assert np.allclose(ex.motifs.xy[0], world.centroid.coords[0], atol=1e-3)
    assert angle_diff(ex.motifs.angle[0], angle) < 1e-6
    assert ex.motifs.scale[0] == pytest.approx(scale)
    assert np.allclose(ex.kinds[0].residual, np.eye(2))
    assert same_shape(exact_world(ex, 0), world)
    assert covers_loosely(world_footprints(ex.motifs, ex.prototypes)[0], world)


def test_instances_of_one_symbol_share_a_kind_and_keep_their_own_pose():
    uses = [("translate(20 20)", T(20, 20), 0, 1), ("translate(60 20) rotate(45)", T(60, 20) @ R(45), 45, 1),
            ("translate(20 70) rotate(-120) scale(0.5)", T(20, 70) @ R(-120) @ S(0.5), -120, 0.5)]  # fmt: skip
    body = "".join(f'<use xlink:href="#L" transform="{tf}"/>' for tf, *_ in uses)
    ex = parse_exemplar(svg(L_SYMBOL + body))
    assert len(ex.kinds) == 1 and list(ex.motifs.kind) == [0, 0, 0]
    for i, (_, m, angle, scale) in enumerate(uses):
        assert np.allclose(ex.motifs.xy[i], mapped(m, L_POLY).centroid.coords[0], atol=1e-3)
        assert angle_diff(ex.motifs.angle[i], angle) < 1e-6
        assert ex.motifs.scale[i] == pytest.approx(scale)


@pytest.mark.parametrize(
    ("view", "par", "bounds"),
    [
        ("0 0 10 10", "", (20, 30, 60, 70)),  # scale 4
        ("0 0 10 5", "", (20, 40, 60, 60)),  # meet: scale 4, centred vertically
        ("0 0 10 5", 'preserveAspectRatio="xMinYMin meet"', (20, 30, 60, 50)),
        ("0 0 10 5", 'preserveAspectRatio="none"', (20, 30, 60, 70)),  # scale 4 × 8
        ("-5 -5 10 10", "", (20, 30, 60, 70)),
    ],
)
def test_symbol_viewbox_is_honoured_with_use_width_height(view, par, bounds):
    x0, y0, w, h = (float(v) for v in view.split())
    sym = f'<defs><symbol id="box" viewBox="{view}" {par}><rect x="{x0}" y="{y0}" width="{w}" height="{h}"/></symbol></defs>'
    ex = parse_exemplar(svg(sym + '<use xlink:href="#box" x="20" y="30" width="40" height="40"/>'))
    assert np.allclose(exact_world(ex, 0).bounds, bounds, atol=1e-3)
    expect = shapely.box(*bounds)
    assert covers_loosely(world_footprints(ex.motifs, ex.prototypes)[0], expect)
    assert dict(ex.kinds[0].use_attrs) == {"width": "40", "height": "40"}


def test_symbol_viewbox_without_width_height_is_refused_naming_the_symbol():
    sym = '<defs><symbol id="star" viewBox="0 0 10 10"><rect width="10" height="10"/></symbol></defs>'
    with pytest.raises(ExemplarError, match=r"symbol id='star'.*width and height"):
        parse_exemplar(svg(sym + '<use xlink:href="#star" x="20" y="30"/>'))


@pytest.mark.parametrize(
    ("view", "size", "message"),
    [
        ("0 0 0 0", "", "empty or unbounded viewBox '0 0 0 0'"),
        ("0 0 -5 nan", "", "empty or unbounded viewBox"),
        ("0 0 1e308 1e-308", 'width="1e308" height="1e308"', "empty or unbounded viewBox"),
        ("0 0 10 10", 'width="0" height="4"', "empty or unbounded viewport"),
        ("0 0 1e-300 1e-300", 'width="2" height="2"', "scales by more than"),
    ],
)
def test_degenerate_symbol_viewbox_is_refused_naming_it(view, size, message):
    sym = f'<defs><symbol id="star" viewBox="{view}"><rect width="10" height="10"/></symbol></defs>'
    with pytest.raises(ExemplarError, match=r"symbol id='star'.*" + re.escape(message)):
        parse_exemplar(svg(sym + f'<use xlink:href="#star" x="20" y="30" {size}/>'))


@pytest.mark.parametrize(
    ("tf", "m"),
    [("skewX(30)", SKX(30)), ("scale(-1 1)", S(-1, 1)), ("scale(2 1)", S(2, 1)),
     ("rotate(30) scale(1 -2)", R(30) @ S(1, -2)), ("matrix(1 0.5 0.2 1 0 0)", M(1, 0.5, 0.2, 1, 0, 0))],
)  # fmt: skip
def test_skew_and_mirror_make_a_residual_kind_with_the_right_world_footprint(tf, m):
    body = '<use xlink:href="#L" transform="translate(20 20)"/>'
    body += f'<g transform="translate(60 60)"><use xlink:href="#L" transform="{tf}"/></g>'
    ex = parse_exemplar(svg(L_SYMBOL + body))
    assert len(ex.kinds) == 2
    plain, odd = ex.kinds[ex.motifs.kind[0]], ex.kinds[ex.motifs.kind[1]]
    assert np.allclose(plain.residual, np.eye(2))
    assert not np.allclose(odd.residual, np.eye(2), atol=1e-3)
    assert odd.href == "L"
    expect = mapped(T(60, 60) @ m, L_POLY)
    assert np.allclose(ex.motifs.xy[1], expect.centroid.coords[0], atol=1e-3)
    assert same_shape(exact_world(ex, 1), expect)
    proto_world = world_footprints(ex.motifs, ex.prototypes)[1]
    assert covers_loosely(proto_world, expect)
    # the plain instance next to it is not mirrored or skewed
    assert same_shape(exact_world(ex, 0), mapped(T(20, 20), L_POLY))


# ----------------------------------------------------------------------------- 2. plain drawings


def l_at(angle: float, x: float, y: float) -> np.ndarray:
    pts = np.array(L_POINTS, dtype=float) @ R(angle)[:2, :2].T
    return pts + np.array([x, y])


def poly(pts: np.ndarray, extra: str = "") -> str:
    return f'<polygon points="{" ".join(f"{x:.6f},{y:.6f}" for x, y in pts)}" {extra}/>'


def test_plain_shapes_identical_up_to_rotation_share_a_kind_with_the_right_angle():
    poses = [(0, 15, 15), (37, 60, 20), (-100, 30, 70), (180, 75, 75), (90, 45, 45)]
    ex = parse_exemplar(svg("".join(poly(l_at(a, x, y)) for a, x, y in poses)))
    assert len(ex.kinds) == 1 and len(ex.motifs) == len(poses)
    for i, (a, x, y) in enumerate(poses):
        assert angle_diff(ex.motifs.angle[i], a - poses[0][0]) < 0.01
        assert np.allclose(ex.motifs.xy[i], shapely.Polygon(l_at(a, x, y)).centroid.coords[0], atol=1e-3)
        assert same_shape(exact_world(ex, i), shapely.Polygon(l_at(a, x, y)), rel=1e-4)


def test_mirrored_and_other_shapes_are_other_kinds():
    mirrored = l_at(0, 0, 0) * [-1, 1] + [80, 20]
    ex = parse_exemplar(svg(poly(l_at(0, 10, 10)) + poly(mirrored) + poly(l_at(0, 10, 60) * [1, 1.3] - [0, 20])))
    assert len(ex.kinds) == 3


def test_differently_coloured_identical_shapes_are_different_kinds():
    body = poly(l_at(0, 10, 10), 'fill="red"') + poly(l_at(45, 50, 50), 'fill="red"')
    body += poly(l_at(0, 70, 10), 'fill="blue"')
    # colour inherited from a group counts too
    body += f'<g fill="blue">{poly(l_at(90, 20, 70))}</g><g fill="green">{poly(l_at(90, 70, 70))}</g>'
    ex = parse_exemplar(svg(body))
    assert list(ex.motifs.kind) == [0, 0, 1, 1, 2]
    assert angle_diff(ex.motifs.angle[1], 45) < 0.01 and angle_diff(ex.motifs.angle[3], 90) < 0.01


def test_a_top_level_group_is_one_motif():
    body = f'<g>{poly(l_at(0, 10, 10))}<circle cx="20" cy="30" r="2"/></g>{poly(l_at(0, 60, 60))}'
    ex = parse_exemplar(svg(body))
    assert len(ex.motifs) == 2 and len(ex.kinds) == 2
    expect = shapely.union_all([shapely.Polygon(l_at(0, 10, 10)), shapely.Point(20, 30).buffer(2, 64)])
    assert shapely.symmetric_difference(exact_world(ex, 0), expect).area < 0.01 * expect.area


INKSCAPE = 'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"'


@pytest.mark.parametrize(
    ("wrap", "shift"),
    [
        (lambda s: f'<g inkscape:groupmode="layer" {INKSCAPE} transform="translate(5 -3)">{s}</g>', (5, -3)),
        (lambda s: f'<g transform="translate(-4 2)">{s}</g>', (-4, 2)),  # a lone wrapper
        (lambda s: f'<g><g transform="translate(1 1)">{s}</g></g>', (1, 1)),  # nested lone wrappers
        (lambda s: f'<g inkscape:groupmode="layer" {INKSCAPE}>{s}</g><g inkscape:groupmode="layer" {INKSCAPE}/>', (0, 0)),
    ],
    ids=["layer", "wrapper", "nested-wrappers", "two-layers"],
)
def test_layers_and_lone_wrappers_are_descended_into(wrap, shift):
    poses = [(0, 20, 20), (30, 60, 30), (200, 40, 70)]
    ex = parse_exemplar(svg(wrap("".join(poly(l_at(a, x, y)) for a, x, y in poses))))
    assert len(ex.motifs) == 3 and len(ex.kinds) == 1
    for i, (a, x, y) in enumerate(poses):
        expect = shapely.Polygon(l_at(a, x + shift[0], y + shift[1])).centroid
        assert np.allclose(ex.motifs.xy[i], [expect.x, expect.y], atol=1e-3)


# ----------------------------------------------------------------------------- 3. footprints


def footprint_area(shape: str) -> float:
    """Area of the exact footprint of ``shape``, 0 if it draws nothing.

    A reference dot is drawn last, so that the exemplar is valid even then; it is the last motif.
    """
    ex = parse_exemplar(svg(f'<g transform="translate(20 20)">{shape}</g><circle cx="90" cy="90" r="1"/>'))
    assert len(ex.motifs) in (1, 2)
    return ex.kinds[ex.motifs.kind[0]].footprint.area if len(ex.motifs) == 2 else 0.0


DISC = math.pi  # a unit disc; footprints flatten arcs with at least 32 chords per circle
STROKE = 'fill="none" stroke="black" stroke-width="2"'


@pytest.mark.parametrize(
    ("shape", "area"),
    [
        (f'<line x1="0" y1="0" x2="10" y2="0" {STROKE}/>', 20),  # butt caps by default
        (f'<line x1="0" y1="0" x2="10" y2="0" {STROKE} stroke-linecap="round"/>', 20 + DISC),
        (f'<line x1="0" y1="0" x2="10" y2="0" {STROKE} stroke-linecap="square"/>', 24),
        (f'<polyline points="0,0 10,0 10,10" {STROKE} stroke-linecap="square" stroke-linejoin="miter"/>', 24 + 20),  # open: no interior
        (f'<rect width="10" height="10" {STROKE}/>', 144),  # a closed outline: interior included
        (f'<path d="M0 0 H10 V10 H0 V0" {STROKE} stroke-linecap="square"/>', 144),  # closed by returning
        ('<rect width="10" height="6"/>', 60),  # filled, no stroke
        ('<circle r="5"/>', 25 * math.pi),
        ('<ellipse rx="6" ry="2" fill="red"/>', 12 * math.pi),
        ('<circle r="5" fill="none" stroke="black" stroke-width="1"/>', 5.5**2 * math.pi),  # a ring: hole filled
        ('<path d="M-5 0 A5 5 0 1 0 5 0 A5 5 0 1 0 -5 0 Z M-3 0 A3 3 0 1 0 3 0 A3 3 0 1 0 -3 0 Z" fill-rule="evenodd"/>', 25 * math.pi),
        ('<line x1="3" y1="3" x2="3" y2="3" stroke="black" stroke-width="0.7" stroke-linecap="round"/>', 0.35**2 * math.pi),
        ('<path d="M3 3 Z" stroke="black" stroke-width="2" stroke-linecap="round"/>', DISC),
        ('<line x1="3" y1="3" x2="3" y2="3" stroke="black" stroke-width="0.7" stroke-linecap="square"/>', 0.49),
        ('<line x1="3" y1="3" x2="3" y2="3" stroke="black" stroke-width="0.7" stroke-linecap="butt"/>', 0),
        ('<path d="M9 9 M0 0 L10 0" stroke="black" stroke-width="2" stroke-linecap="round"/>', 20 + DISC),  # a lone moveto draws nothing
        (f'<line x1="0" y1="0" x2="10" y2="0" {STROKE} transform="scale(2)"/>', 80),  # 20 long, 4 wide
        ('<g transform="scale(2)"><line x1="0" y1="0" x2="10" y2="0" fill="none" stroke="black" stroke-width="1"/></g>', 40),
        (f'<line x1="0" y1="0" x2="10" y2="0" {STROKE} transform="scale(1 3)"/>', 60),  # 10 long, 6 wide
        ('<rect width="10mm" height="1in"/>', 10 * 96 / 25.4 * 96),
    ],
    ids=lambda v: v if isinstance(v, str) and len(v) < 20 else None,
)
def test_footprint_area(shape, area):
    assert footprint_area(shape) == pytest.approx(area, rel=0.01, abs=1e-9)


def test_prototype_covers_the_exact_footprint():
    ex = parse_exemplar(svg(poly(l_at(10, 30, 30)) + f'<line x1="60" y1="60" x2="80" y2="70" {STROKE}/>'))
    for kind in ex.kinds:
        proto = kind.prototype.geometry()
        assert shapely.difference(kind.footprint, proto).area <= 1e-6 * kind.footprint.area
        assert kind.prototype.area == pytest.approx(kind.footprint.area)
        assert proto.area < 1.2 * kind.footprint.area  # a cover, not a fattening


# ----------------------------------------------------------------------------- 4. input region

DOTS = "".join(f'<circle cx="{x}" cy="{y}" r="1"/>' for x, y in [(20, 20), (40, 30), (30, 50)])


@pytest.mark.parametrize(
    ("region", "expect"),
    [
        ('<rect id="region" x="10" y="5" width="50" height="60" fill="none"/>', shapely.box(10, 5, 60, 65)),
        ('<circle id="region" cx="35" cy="35" r="30"/>', shapely.Point(35, 35).buffer(30, 1024)),
        ('<ellipse id="region" cx="35" cy="35" rx="34" ry="25"/>',
         shapely.affinity.scale(shapely.Point(35, 35).buffer(1, 1024), 34, 25)),
        ('<polygon id="region" points="0,0 80,0 60,70 5,60"/>', shapely.Polygon([(0, 0), (80, 0), (60, 70), (5, 60)])),
        ('<path id="region" d="M0 0 h70 v70 h-70 z M50 50"/>', shapely.box(0, 0, 70, 70)),
        ('<g transform="translate(10 20) scale(2)"><g transform="translate(-10 -10)">'
         '<rect id="region" x="5" y="0" width="30" height="26"/></g></g>', shapely.box(0, 0, 60, 52)),
    ],
    ids=["rect", "circle", "ellipse", "polygon", "path", "transformed"],
)  # fmt: skip
def test_region_element(region, expect):
    ex = parse_exemplar(svg(region + DOTS))
    assert ex.region.area == pytest.approx(expect.area, rel=2e-3)
    assert shapely.symmetric_difference(ex.region, expect).area <= 2e-3 * expect.area
    assert len(ex.motifs) == 3  # the region is not a motif


def test_region_falls_back_to_viewbox_then_size_then_motif_bounds():
    assert ex_region('viewBox="5 6 70 80" width="10" height="10"').equals(shapely.box(5, 6, 75, 86))
    assert np.allclose(ex_region('width="70mm" height="80"').bounds, (0, 0, 70 * 96 / 25.4, 80))
    bounds = ex_region("").bounds
    assert np.allclose(bounds, (19, 19, 41, 51), atol=1e-6)  # motif centres ± radius


def ex_region(attrs: str) -> shapely.Geometry:
    return parse_exemplar(svg(DOTS, attrs)).region


@pytest.mark.parametrize(
    "region",
    ['<rect id="region" x="10" y="10" width="50" height="0"/>', '<polygon id="region" points="0,0 10,10 20,20"/>',
     '<circle id="region" cx="5" cy="5" r="0"/>'],
)  # fmt: skip
def test_degenerate_region_is_an_error(region):
    with pytest.raises(ExemplarError, match="no area"):
        parse_exemplar(svg(region + DOTS))


def test_motifs_outside_the_region_are_dropped_with_a_warning():
    ex = parse_exemplar(svg('<rect id="region" x="0" y="0" width="35" height="100"/>' + DOTS))
    assert sorted(map(tuple, np.round(ex.motifs.xy, 6))) == [(20, 20), (30, 50)]
    assert any("1 motif(s) outside" in w for w in ex.warnings)


# ----------------------------------------------------------------------------- 5. bad input

BAD = {
    "not-xml": ("this is <not xml", "not a well-formed XML"),
    "not-svg": ('<html xmlns="http://www.w3.org/1999/xhtml"/>', "not an SVG"),
    "svg-in-other-namespace": ('<svg xmlns="urn:not-svg"><circle r="1"/></svg>', "not an SVG"),
    "no-motifs": (svg("<defs><circle id='c' r='1'/></defs><text>hi</text>"), "no motifs"),
    "missing-id": (svg('<use xlink:href="#nowhere"/>'), "'#nowhere', which is not in the file"),
    "external-file": (svg('<use xlink:href="other.svg#dot"/>'), "other.svg"),
    "external-url": (svg('<use href="https://example.com/motifs.svg#dot"/>'), "never fetches"),
    "self-recursive": (svg('<use id="u" xlink:href="#u"/>'), "recursively"),
    "indirect-recursive": (
        svg('<defs><g id="a"><use xlink:href="#b"/></g><g id="b"><use xlink:href="#a"/></g></defs><use xlink:href="#a"/>'),
        "recursively",
    ),
    "recursive-ancestor": (svg('<g id="g"><circle r="1"/><use xlink:href="#g"/></g>'), "recursively"),
    "malformed-path": (svg('<path d="M 10 10 L 20 20 L 30#40" stroke="black"/>'), "malformed path data"),
    "path-without-moveto": (svg('<path d="L 10 10 20 20 Z"/>'), "path"),
    "relative-length": (svg('<rect width="10%" height="5"/>'), "relative"),
    "use-without-href": (svg("<use/>"), "has no href"),
}


@pytest.mark.parametrize(("text", "fragment"), BAD.values(), ids=BAD.keys())
def test_bad_input_is_one_line_naming_the_source(text, fragment, monkeypatch):
    def no_network(*args, **kwargs):
        raise AssertionError("the reader tried to fetch something")

    monkeypatch.setattr(socket.socket, "connect", no_network)
    monkeypatch.setattr(urllib.request, "urlopen", no_network)
    with pytest.raises(ExemplarError) as info:
        parse_exemplar(text, source="bad.svg")
    message = str(info.value)
    assert message.startswith("bad.svg: ") and "\n" not in message
    assert fragment in message


def test_deep_nesting_is_an_error_not_a_crash():
    depth = 5000
    text = svg("<g>" * depth + '<circle r="1"/>' + "</g>" * depth)
    with pytest.raises(ExemplarError, match="nested too deeply"):
        parse_exemplar(text)


def test_use_fan_out_is_bounded():
    levels = ['<g id="l0"><circle r="1"/></g>']
    for n in range(1, 9):
        uses = "".join(f'<use xlink:href="#l{n - 1}" x="{3 * i * 10 ** (n - 1)}"/>' for i in range(10))
        levels.append(f'<g id="l{n}">{uses}</g>')
    text = svg("<defs>" + "".join(levels) + '</defs><use xlink:href="#l8"/>')
    start = time.perf_counter()
    with pytest.raises(ExemplarError, match="too complex"):
        parse_exemplar(text)
    assert time.perf_counter() - start < 30  # a guard against a hang, not a benchmark


def test_unreadable_file():
    with pytest.raises(ExemplarError, match=r"nope\.svg: cannot read file"):
        read_exemplar("nope.svg")


def test_real_malformed_file():
    path = DATA / "usgs-fgdc-cecgeology" / "SED_fixedcolor" / "sed663.svg"
    if not path.exists():
        pytest.skip("shared data not available")
    with pytest.raises(ExemplarError) as info:
        read_exemplar(path)
    assert str(info.value).startswith(f"{path}: not a well-formed XML file") and "\n" not in str(info.value)


def test_use_of_something_that_draws_nothing_is_ignored_with_a_warning():
    ex = parse_exemplar(svg('<defs><text id="t">A</text></defs><use xlink:href="#t"/>' + DOTS))
    assert len(ex.motifs) == 3
    assert any("'#t'" in w and "ignored" in w for w in ex.warnings)


def test_symbol_clipped_by_default_overflow_is_warned():
    sym = '<defs><symbol id="dot"><circle r="2"/></symbol></defs><use xlink:href="#dot" x="50" y="50"/>'
    assert any("overflow" in w for w in parse_exemplar(svg(sym)).warnings)
    visible = sym.replace('<symbol id="dot">', '<symbol id="dot" overflow="visible">')
    assert not any("overflow" in w for w in parse_exemplar(svg(visible)).warnings)


def test_links_and_images_elsewhere_are_not_refused():
    body = '<a href="https://example.com"><circle cx="20" cy="20" r="2"/></a><image href="photo.png"/>'
    ex = parse_exemplar(svg(body + DOTS))
    assert len(ex.motifs) == 4


# ----------------------------------------------------------------------------- real files


def real_files(*folders: str) -> list[Path]:
    return sorted(p for f in folders for p in (DATA / f).glob("*.svg"))


@pytest.mark.skipif(not (DATA / "resvg-tests").exists(), reason="shared data not available")
@pytest.mark.parametrize(
    "path",
    real_files("resvg-tests/structure/symbol", "resvg-tests/structure/use"),
    ids=lambda p: f"{p.parent.name}/{p.name}",
)
def test_resvg_symbol_and_use_files_parse_or_raise_exemplar_error(path):
    try:
        ex = read_exemplar(path)
    except ExemplarError as exc:
        assert str(exc).startswith(str(path)) and "\n" not in str(exc)
    else:
        assert len(ex.motifs) >= 1 and ex.motifs.kind.max() < len(ex.kinds)
        assert np.isfinite(ex.motifs.xy).all()


@pytest.mark.skipif(not (DATA / "osm-carto").exists(), reason="shared data not available")
@pytest.mark.parametrize(
    ("name", "kinds", "instances"),
    [("scrub", ["gSjorsa39f3u43"], 441), ("marsh", ["Si5y5ofczdv2", "Si5y5ofczdv3"], 484)],
)
def test_osm_carto_defs_use_patterns(name, kinds, instances):
    """jsdotpattern output: ``<g>`` defs used through ad-hoc xlink prefixes (shared/notes/data.md §3):
    the referenced ids are the kinds, and the uses inside the 512-px tile are the unique instances."""
    path = DATA / "osm-carto" / "generating_patterns" / f"{name}.svg"
    ex = read_exemplar(path)
    assert [k.href for k in ex.kinds] == kinds
    assert len(ex.motifs) == instances
    assert ex.region.equals(shapely.box(0, 0, 512, 512))
    # the motifs are the <use> positions of their kind moved by one offset (the def's drawing
    # relative to its origin), kept where they land in the tile: find that offset by brute force
    root = ET.parse(path).getroot()
    uses = [(u.get(f"{{{XLINK}}}href")[1:], float(u.get("x")), float(u.get("y"))) for u in root.iter(f"{{{SVG}}}use")]
    for k, href in enumerate(kinds):
        placed = np.array([u[1:] for u in uses if u[0] == href])
        got = ex.motifs.xy[ex.motifs.kind == k]
        matches = []
        for start in placed:
            moved = placed + (got[0] - start)
            kept = moved[((moved > 0) & (moved < 512)).all(axis=1)]
            if len(kept) == len(got) and np.allclose(kept[np.lexsort(kept.T)], got[np.lexsort(got.T)], atol=1e-6):
                matches.append(got[0] - start)
        assert matches and np.all(np.abs(matches[0]) < 6)  # the defs draw within a few px of their origin
    assert np.allclose(ex.motifs.angle, 0) and np.allclose(ex.motifs.scale, 1)


@pytest.mark.parametrize(
    ("head", "message"),
    [
        ('viewBox="0 0 1e308 1e308"', "beyond ±1e\\+100"),
        ('viewBox="nan nan inf inf"', "is not finite"),
        ('viewBox="0 0 1e200 5"', "beyond ±1e\\+100"),
    ],
)
def test_region_with_overflowing_or_non_finite_coordinates_is_refused(head, message):
    svg = f'<svg xmlns="http://www.w3.org/2000/svg" {head}><circle cx="5" cy="5" r="1"/><circle cx="15" cy="5" r="1"/></svg>'
    with pytest.raises(ExemplarError, match=message):
        parse_exemplar(svg, source="big.svg")


# ----------------------------------------------------------------------------- prototypes kept apart


def _circles(xs: list[float], r: float = 10.0, extra: str = "", region: str = "") -> str:
    uses = "".join(f'<use xlink:href="#c" x="{x}" y="50"/>' for x in xs)
    return svg(f'<defs><symbol id="c" overflow="visible"><circle r="{r}"/></symbol>'
               f'<symbol id="s" overflow="visible"><rect x="-8" y="-8" width="16" height="16"/></symbol></defs>'
               f"{region}{uses}{extra}", 'xmlns:svgtile="urn:svgtile:run:1" viewBox="0 0 100 100"')  # fmt: skip


def _same_rings(a, b) -> bool:
    return len(a.rings) == len(b.rings) and all(np.array_equal(x, y) for x, y in zip(a.rings, b.rings, strict=True))


def _gap(ex, a: int, b: int) -> float:
    g = world_footprints(ex.motifs, [k.prototype for k in ex.kinds])
    return float(shapely.distance(g[a], g[b]))


def test_motifs_drawn_a_hair_apart_do_not_overlap_in_the_analysis():
    """Two circles of radius 10 drawn 0.2 apart: the default outline (grown by a fortieth of the
    radius, 0.25) would make them share area; the exemplar's prototype keeps them apart, each
    reaching at most GAP_SHARE of the gap beyond its footprint, so the analysis counts no overlap
    and its rule is the drawn gap, give or take that."""
    from svgtile.analysis.stats import analyze
    from svgtile.core.footprint import GAP_SHARE, Prototype

    ex = parse_exemplar(_circles([20.0, 40.2], extra='<use xlink:href="#s" x="80" y="20"/>'))
    circle, square = ex.kinds
    default = Prototype.from_geometry(circle.footprint)
    two = ex.motifs.take(ex.motifs.kind == 0)
    assert shapely.intersection(*world_footprints(two, [default, square.prototype])).area > 0  # the case is real
    assert circle.prototype.excess <= GAP_SHARE * 0.2 + 1e-9
    assert 0.2 * (1 - 2 * GAP_SHARE) - 1e-9 <= _gap(ex, 0, 1) <= 0.2 + 1e-9
    stats = analyze(ex)
    assert stats.overlaps == 0 and 0 < stats.distance[0, 0] <= 0.2 + 1e-9
    # the outline still covers the exact footprint
    assert shapely.difference(circle.footprint, circle.prototype.geometry()).area < 1e-9
    # a kind in no such pair keeps the prototype built the usual way
    assert _same_rings(square.prototype, Prototype.from_geometry(square.footprint))


def test_both_kinds_of_a_pair_a_hair_apart_are_drawn_finer():
    """A circle and a square 0.2 apart: each outline alone, grown as usual, would reach into the
    gap far enough to meet the other's; both are drawn finer."""
    from svgtile.analysis.stats import analyze
    from svgtile.core.footprint import GAP_SHARE, Prototype

    ex = parse_exemplar(_circles([20.0], extra='<use xlink:href="#s" x="38.2" y="50"/>'))
    for k in ex.kinds:
        assert not _same_rings(k.prototype, Prototype.from_geometry(k.footprint))
        assert k.prototype.excess <= GAP_SHARE * 0.2 + 1e-9
    assert _gap(ex, 0, 1) > 0 and analyze(ex).overlaps == 0


def test_sharp_corners_a_hair_apart_stay_apart():
    """Two five-pointed stars tip to tip 0.2 apart: a mitred outline reaches up to four times its
    tolerance beyond a sharp tip (0.40 here for a tolerance of 0.12), so the tolerance is cut by
    how far the outline reaches, not by the tolerance itself."""
    from svgtile.analysis.stats import analyze

    pts = " ".join(f"{(10 if k % 2 == 0 else 3.82) * math.cos(math.pi * k / 5):.6f},"
                   f"{(10 if k % 2 == 0 else 3.82) * math.sin(math.pi * k / 5):.6f}" for k in range(10))  # fmt: skip
    body = (f'<defs><symbol id="st" overflow="visible"><polygon points="{pts}"/></symbol></defs>'
            '<use xlink:href="#st" x="20" y="50"/><use xlink:href="#st" transform="translate(40.2 50) rotate(180)"/>')  # fmt: skip
    ex = parse_exemplar(svg(body))
    assert _gap(ex, 0, 1) > 0 and analyze(ex).overlaps == 0


def test_motifs_that_do_overlap_as_drawn_still_do():
    """Two circles drawn overlapping: nothing to keep apart, the prototype is the usual one and
    the analysis counts the overlap."""
    from svgtile.analysis.stats import analyze
    from svgtile.core.footprint import Prototype

    ex = parse_exemplar(_circles([20.0, 39.0]))
    assert _same_rings(ex.kinds[0].prototype, Prototype.from_geometry(ex.kinds[0].footprint))
    assert analyze(ex).overlaps == 1


def test_a_tile_whose_motif_comes_a_hair_from_its_own_repeat():
    """Across a repeating tile's edge: a circle of radius 10 in a tile 20.2 wide is 0.2 from its
    own copy; the pattern does not overlap, and neither does its analysis."""
    from svgtile.analysis.stats import analyze

    region = '<rect id="region" x="0" y="30" width="20.2" height="40" svgtile:period="20.2 40"/>'
    ex = parse_exemplar(_circles([10.1], region=region))
    assert ex.period == (20.2, 40.0)
    stats = analyze(ex)
    assert stats.overlaps == 0 and 0 < stats.distance[0, 0] <= 0.2 + 1e-9


def test_a_motif_drawn_larger_is_drawn_finer_by_its_scale():
    """The same circle at scale 2 beside one at scale 1, 0.2 apart: its outline, grown in its own
    frame, reaches twice as far in the world at scale 2, so the kind is drawn finer by that scale:
    in the world neither reaches more than GAP_SHARE of the gap."""
    from svgtile.analysis.stats import analyze
    from svgtile.core.footprint import GAP_SHARE

    body = ('<defs><symbol id="c" overflow="visible"><circle r="5"/></symbol></defs>'
            '<use xlink:href="#c" transform="translate(20 50) scale(2)"/><use xlink:href="#c" x="35.2" y="50"/>')  # fmt: skip
    ex = parse_exemplar(svg(body))
    assert len(ex.kinds) == 1 and sorted(ex.motifs.scale.tolist()) == [1.0, 2.0]
    assert 2 * ex.kinds[0].prototype.excess <= GAP_SHARE * 0.2 + 1e-9
    assert _gap(ex, 0, 1) > 0 and analyze(ex).overlaps == 0


def test_a_crowded_exemplar_is_left_to_the_crowding_check(monkeypatch):
    """Over MAX_NEAR_PAIRS pairs of motifs lying on each other: the prototypes are not measured
    pair by pair (the crowding check refuses such an exemplar, quickly)."""
    import svgtile.core.footprint as footprint

    monkeypatch.setattr(footprint, "MAX_NEAR_PAIRS", 0)
    ex = parse_exemplar(_circles([20.0, 40.2]))
    assert _same_rings(ex.kinds[0].prototype, footprint.Prototype.from_geometry(ex.kinds[0].footprint))
