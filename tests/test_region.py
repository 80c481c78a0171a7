"""Regions beyond a rectangle: holes, several parts, avoid zones, fill rules, edit stability.

Invariants checked on real syntheses, per boundary mode and engine: no motif footprint in a hole
or an avoid zone as each mode promises it, and the fraction of motifs far from a one-vertex edit
that stay byte-identical (issue 5, item 5).
"""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import TINY, arrange, fake_engine

from svgtile import analyze
from svgtile.apps.mapread import read_avoid_shape, read_region_shape, synth_region
from svgtile.core.footprint import world_footprints
from svgtile.core.region import BOUNDARY_MODES, Region, winding_fill, winding_numbers
from svgtile.engines import ENGINES
from svgtile.errors import RegionError, SvgtileError
from svgtile.svg.mapdoc import SvgShapes
from svgtile.svg.reader import parse_exemplar, read_exemplar
from svgtile.svg.writer import fmt_array, svg_document

REPO = Path(__file__).parents[1]

SQUARE = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
INNER = np.array([[2, 2], [8, 2], [8, 8], [2, 8]], float)  # same direction as SQUARE
CORE = np.array([[4, 4], [6, 4], [6, 6], [4, 6]], float)  # same direction, inside INNER
HOLE_CW = np.array([[3, 3], [3, 7], [7, 7], [7, 3]], float)  # against SQUARE
FAR = np.array([[20, 0], [24, 0], [24, 4], [20, 4]], float)
TRIANGLE_CW = np.array([[2, 2], [2, 6], [6, 2]], float)  # 3 vertices against SQUARE's 4
BOWTIE = np.array([[0, 0], [10, 10], [10, 0], [0, 10]], float)  # crosses itself: two triangles


@pytest.mark.parametrize(
    ("rings", "rule", "area"),
    [
        ([SQUARE], "nonzero", 100.0),
        ([SQUARE, INNER], "nonzero", 100.0),  # same direction: winding 2, painted
        ([SQUARE, INNER[::-1]], "nonzero", 64.0),  # opposite direction: a hole
        ([SQUARE, INNER], "evenodd", 64.0),
        ([SQUARE, INNER[::-1]], "evenodd", 64.0),
        ([SQUARE, INNER + 20], "evenodd", 136.0),  # two separate parts
        ([SQUARE, HOLE_CW], "nonzero", 84.0),
        ([SQUARE, HOLE_CW], "evenodd", 84.0),
        ([SQUARE, FAR], "nonzero", 116.0),
        ([SQUARE, INNER, CORE], "nonzero", 100.0),  # nested, all one direction: winding 1, 2, 3
        ([SQUARE, INNER, CORE], "evenodd", 68.0),  # 1, 2, 3: the ring between INNER and CORE is out
        ([SQUARE, INNER[::-1], CORE], "nonzero", 68.0),  # 1, 0, 1
        ([SQUARE, TRIANGLE_CW], "nonzero", 92.0),  # rings of different lengths
        ([SQUARE, TRIANGLE_CW[::-1]], "evenodd", 92.0),
        ([SQUARE, TRIANGLE_CW[::-1]], "nonzero", 100.0),
        ([BOWTIE], "nonzero", 50.0),
        ([BOWTIE], "evenodd", 50.0),
        ([SQUARE, SQUARE], "evenodd", 0.0),  # drawn twice: even
        ([SQUARE, SQUARE], "nonzero", 100.0),
        ([np.vstack([SQUARE, SQUARE[:1]]), HOLE_CW], "nonzero", 84.0),  # an explicit closing point
        ([SQUARE[:2]], "nonzero", 0.0),  # two points enclose nothing
        ([np.array([[0, 0], [5, 0], [9, 0]], float)], "nonzero", 0.0),  # a line encloses nothing
        ([], "nonzero", 0.0),
    ],
)
def test_winding_fill_paints_as_svg_does(rings, rule, area):
    shape = winding_fill(rings, rule)
    assert shape.area == pytest.approx(area)
    assert shape.is_valid
    assert isinstance(shape, (shapely.Polygon, shapely.MultiPolygon))  # an empty result too


def test_winding_fill_hole_is_a_hole():
    shape = winding_fill([SQUARE, HOLE_CW])
    assert not shape.contains(shapely.Point(5, 5)) and shape.contains(shapely.Point(1, 1))


def test_winding_fill_refuses_an_unknown_rule():
    with pytest.raises(ValueError, match="unknown fill rule 'inherit'"):
        winding_fill([SQUARE], "inherit")


def test_winding_numbers_by_hand():
    rings = [SQUARE, INNER, TRIANGLE_CW]
    w = winding_numbers(rings, np.array([1.0, 5.0, 15.0, 2.5]), np.array([9.0, 5.0, 5.0, 2.5]))
    assert list(w * np.sign(w[0])) == [1, 2, 0, 1]  # (2.5, 2.5): in SQUARE, INNER and the clockwise triangle: 1 + 1 - 1


def test_invalid_fill_rule_in_a_map_is_nonzero(tmp_path):
    d = "M0 0 H10 V10 H0 Z M2 2 H8 V8 H2 Z"  # same direction: a hole only under evenodd
    doc = ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
           f'<path id="a" d="{d}" fill-rule="bogus"/><path id="b" d="{d}" fill-rule="evenodd"/></svg>')
    shapes = SvgShapes(doc.encode(), "map.svg")
    assert shapes.area(shapes.element("a")).area == pytest.approx(100)
    assert shapes.area(shapes.element("b")).area == pytest.approx(64)


# ----------------------------------------------------------------------------- invariants


def _donut_case():
    """A 70 × 60 region with a 24 × 20 hole, and a label box as avoid zone."""
    outer = shapely.box(0, 0, 70, 60)
    hole = shapely.box(30, 20, 54, 40)
    avoid = shapely.box(6, 8, 20, 14)
    return outer.difference(hole), hole, avoid


#: Engines that fill little of the donut from the 5-motif TINY exemplar (measured 2026-12-02, seed
#: 5): growth grows 3 motifs (its rings need more neighbours than TINY has), optimize keeps 8 with
#: ``inside``, cellular sets motifs in cells away from the hole.  The invariants below hold for
#: them on richer exemplars (tests/test_engines_contract.py); here the non-vacuity checks fail.
SPARSE_ON_TINY = {"growth": "grows 3 motifs", "optimize": "keeps 8 motifs", "cellular": "motifs in cells, 1 near the hole"}


@pytest.mark.parametrize("engine", [pytest.param(e, marks=pytest.mark.xfail(strict=True, reason=f"{e} on TINY: {SPARSE_ON_TINY[e]}"))
                                    if e in SPARSE_ON_TINY else e for e in sorted(ENGINES)])  # fmt: skip
@pytest.mark.parametrize("mode", BOUNDARY_MODES)
def test_no_footprint_in_holes_or_avoid_zones(engine, mode):
    ex = parse_exemplar(TINY)
    stats = analyze(ex)
    shape, hole, avoid = _donut_case()
    region = Region.from_geometry(shape, avoid=avoid)
    arr = arrange(engine, ex, region, rng=np.random.default_rng(5), stats=stats, boundary=mode)
    assert len(arr) > 20
    fp = world_footprints(arr, ex.prototypes)
    # the hole was there to be filled: motifs come close to it (the checks below are not vacuous)
    assert (shapely.distance(hole, fp) < 3).sum() >= 3
    # avoid zones: no footprint meets them, in every mode
    assert not shapely.intersects(avoid, fp).any()
    in_hole = shapely.area(shapely.intersection(fp, hole))
    if mode == "inside":
        assert (in_hole == 0).all()
        assert shapely.contains(region.shape, fp).all()
    elif mode == "centroid":
        assert not shapely.contains_xy(hole, arr.xy[:, 0], arr.xy[:, 1]).any()
    else:  # clip and none keep motifs touching the region, none wholly in the hole
        assert shapely.intersects(region.shape, fp).all()
        assert not shapely.contains(hole, fp).any()


def test_clip_path_excludes_holes_and_avoid_zones():
    ex = parse_exemplar(TINY)
    shape, hole, avoid = _donut_case()
    region = Region.from_geometry(shape, avoid=avoid)
    arr = arrange("patch", ex, region, rng=np.random.default_rng(1), boundary="clip")
    text = svg_document(ex, arr, region, boundary="clip", params={})
    d = re.search(r'<clipPath id="svgtile-clip">\s*<path d="([^"]+)" clip-rule="evenodd"', text).group(1)
    rings = [np.array(re.findall(r"(-?[\d.]+) (-?[\d.]+)", ring), float) for ring in d.split("Z") if ring.strip()]
    painted = winding_fill(rings, "evenodd")
    assert painted.area == pytest.approx(shape.area - avoid.area, rel=1e-6)
    assert painted.intersection(hole).area == pytest.approx(0, abs=1e-9)


def test_keep_drops_motifs_meeting_avoid_zones_only():
    ex = parse_exemplar(TINY)
    region = Region.from_geometry(shapely.box(0, 0, 40, 40), avoid=shapely.box(10, 10, 20, 20))
    arr = arrange("tile", ex, Region.rectangle(40, 40), rng=np.random.default_rng(0), boundary="none")
    fp = world_footprints(arr, ex.prototypes)
    kept = region.keep(arr, ex.prototypes, "none")
    assert (kept == ~shapely.intersects(region.avoid, fp)).all()
    assert (~kept).sum() > 0


@pytest.mark.parametrize(
    ("geom", "avoid", "message"),
    [
        (shapely.LineString([(0, 0), (5, 5)]), None, "no area"),
        (shapely.Polygon(), None, "no area"),
        (shapely.box(0, 0, 5, 5), shapely.box(-1, -1, 6, 6), "inside its avoid zones"),
    ],
)
def test_unusable_regions_are_one_line_errors(geom, avoid, message):
    with pytest.raises(RegionError, match=message):
        Region.from_geometry(geom, avoid=avoid, source="map.svg#x")


def test_multipolygon_and_collection_regions():
    two = shapely.GeometryCollection([shapely.box(0, 0, 5, 5), shapely.box(10, 0, 15, 5), shapely.Point(3, 3)])
    region = Region.from_geometry(two)
    assert region.shape.geom_type == "MultiPolygon"
    assert region.area == pytest.approx(50)


# ----------------------------------------------------------------------------- reading from SVG

MAP = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">
  <g transform="translate(10 20)">
    <path id="donut" fill-rule="evenodd" d="M0 0 H40 V40 H0 Z M10 10 H30 V30 H10 Z"/>
    <path id="solid" d="M0 0 H40 V40 H0 Z M10 10 H30 V30 H10 Z"/>
    <path id="nonzero-hole" d="M0 0 H40 V40 H0 Z M10 10 V30 H30 V10 Z"/>
  </g>
  <g id="pair" transform="scale(2)"><rect x="0" y="0" width="5" height="5"/><circle cx="20" cy="2.5" r="2.5"/></g>
  <g id="labels" font-size="10" text-anchor="middle">
    <text x="50" y="90">Qal</text>
    <text x="50" y="60" transform="rotate(90 50 60)"><tspan x="50" y="60">Ksh</tspan></text>
  </g>
  <line id="fault" x1="0" y1="50" x2="100" y2="50" stroke="#000" stroke-width="2"/>
  <text id="word" x="0" y="0">x</text>
  <path id="open" d="M0 0 L10 0" fill="none" stroke="#000"/>
</svg>"""


@pytest.fixture
def mapfile(write_svg):
    return write_svg(MAP, "map.svg")


@pytest.mark.parametrize(("ident", "area"), [("donut", 1200), ("solid", 1600), ("nonzero-hole", 1200)])
def test_svg_region_fill_rule_and_transforms(mapfile, ident, area):
    shape = read_region_shape(f"{mapfile}#{ident}")
    assert shape.area == pytest.approx(area)
    assert shape.bounds == pytest.approx((10, 20, 50, 60))  # the group's translate applied


def test_svg_group_region_is_the_union_of_its_shapes(mapfile):
    shape = read_region_shape(f"{mapfile}#pair")
    assert shape.geom_type == "MultiPolygon"
    assert shape.area == pytest.approx(4 * (25 + np.pi * 2.5**2), rel=1e-3)  # scale(2) applied


def test_element_with_id_region_can_be_the_region(write_svg):
    # id="region" marks an exemplar's input region; in a map it is an ordinary shape
    path = write_svg('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 50 50">'
                     '<g id="units"><rect id="region" width="40" height="30" fill="none"/></g></svg>', "map.svg")  # fmt: skip
    assert read_region_shape(f"{path}#region").area == pytest.approx(1200)
    assert read_region_shape(f"{path}#units").area == pytest.approx(1200)


def test_avoid_zones_from_text_and_lines(mapfile):
    labels = read_avoid_shape(f"{mapfile}#labels", margin=1.0)
    # "Qal": three glyphs centred on x = 50, on the baseline y = 90
    assert labels.contains(shapely.Point(50, 87))
    assert not labels.contains(shapely.Point(50, 75))
    # the rotated "Ksh" runs vertically through (50, 60)
    assert labels.contains(shapely.Point(52, 50)) and labels.contains(shapely.Point(52, 67))
    fault = read_avoid_shape(f"{mapfile}#fault", margin=3.0)
    band = shapely.box(0, 49, 100, 51).buffer(3.0)  # stroke band 2 wide, grown by 3 all round
    assert fault.symmetric_difference(band).area < 0.01 * band.area


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("#missing", "no element with id 'missing'"),
        ("#word", "cannot be a region"),
        ("#open", None),  # an open two-point path encloses nothing
        ("", "name the region's element"),
    ],
)
def test_bad_region_specs(mapfile, spec, message):
    with pytest.raises(SvgtileError) as info:
        read_region_shape(f"{mapfile}{spec}")
    assert str(mapfile) in str(info.value)
    assert "\n" not in str(info.value)
    if message:
        assert message in str(info.value)


def test_synth_region_needs_exactly_one_of_size_and_region(mapfile):
    with pytest.raises(Exception, match="either --size"):
        synth_region(None, None)
    with pytest.raises(Exception, match="either --size"):
        synth_region((10, 10), f"{mapfile}#donut")
    region = synth_region(None, f"{mapfile}#donut", (f"{mapfile}#fault",), 1.0)
    assert region.avoid is not None and not region.shape.intersects(shapely.box(0, 48, 100, 52).buffer(-0.01))


def test_map_reading_keeps_comments_for_rewriting(mapfile):
    doc = SvgShapes.read(mapfile, comments=True)
    assert doc.area(doc.element("donut")).area == pytest.approx(1200)


# ----------------------------------------------------------------------------- edit stability


def _lines(arr) -> list[str]:
    cols = [fmt_array(arr.xy[:, 0]), fmt_array(arr.xy[:, 1]), fmt_array(arr.angle), fmt_array(arr.scale)]
    return [" ".join(row) for row in zip(map(str, arr.kind.tolist()), *cols, strict=True)]


def edited_polygons(w: float, radius_widths: float) -> tuple[shapely.Polygon, shapely.Polygon]:
    """The edit of :func:`edit_stability`: a wavy polygon of radius ``radius_widths`` exemplar
    widths ``w`` (user units), and the same with one vertex moved one width out."""
    a = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    r = radius_widths * w * (1 + 0.15 * np.sin(3 * a) + 0.08 * np.cos(7 * a))
    centre = np.array([13.7, 9.1]) * w
    pts = np.c_[r * np.cos(a), r * np.sin(a)] + centre
    moved = pts.copy()
    moved[5] += (pts[5] - centre) / np.linalg.norm(pts[5] - centre) * w  # one vertex, one width out
    return shapely.Polygon(pts), shapely.Polygon(moved)


def edit_comparison(ex, stats, *, radius_widths: float, seed: int, mode: str = "clip", engine: str = "patch",
                    **params):  # fmt: skip
    """The texture of ``ex`` (analysed as ``stats``) over the polygon of :func:`edited_polygons`
    and over its edited copy, the same seed: (n,) bool, whether each motif of the first is in the
    second byte for byte as written; (n,) float, its distance from the edit, user units; and the
    exemplar width, user units."""
    x0, y0, x1, y1 = ex.region.bounds
    w = max(x1 - x0, y1 - y0)
    before, after = edited_polygons(w, radius_widths)
    arr_a = arrange(engine, ex, Region(before), rng=np.random.default_rng(seed), stats=stats, boundary=mode, **params)
    arr_b = arrange(engine, ex, Region(after), rng=np.random.default_rng(seed), stats=stats, boundary=mode, **params)
    edit = shapely.symmetric_difference(before, after)
    return np.isin(_lines(arr_a), _lines(arr_b)), shapely.distance(edit, shapely.points(arr_a.xy)), w


def edit_stability(exemplar_path: Path, *, radius_widths: float = 6.0, seed: int = 3, mode: str = "clip",
                   engine: str = "patch"):
    """Fraction of motifs farther than two exemplar widths from a one-vertex edit of a large
    polygon that stay byte-identical (as written), and how many such motifs there are."""
    ex = read_exemplar(exemplar_path)
    same, distance, w = edit_comparison(ex, analyze(ex), radius_widths=radius_widths, seed=seed, mode=mode, engine=engine)
    far = distance > 2 * w
    return float(same[far].mean()), int(far.sum())


@pytest.mark.parametrize("name", ["gravel", "till"])
def test_edit_stability_at_least_95_percent(name):
    path = REPO / "exemplars" / f"{name}.svg"
    if not path.exists():
        pytest.skip(f"bundled exemplar {path} missing")
    stable, far = edit_stability(path)
    assert far > 2000  # the figure is measured on many motifs
    assert stable >= 0.95, f"{name}: only {stable:.4f} of far motifs unchanged"


def test_edit_stability_measure_can_fail(monkeypatch):
    """A sequential generator (draws depend on the region's extent) must score far below 0.95."""
    from svgtile.engines.patch import engine as patch

    path = REPO / "exemplars" / "gravel.svg"
    if not path.exists():
        pytest.skip("bundled exemplars missing")
    def unanchored(ctx, params):
        # shift the world anchor with the region's area: every copy moves when the outline does
        dx = (ctx.region.area * 1e-3) % 97.0
        moved = Region(shapely.transform(ctx.region.shape, lambda c: c - np.array([dx, 0.0])))
        arr = patch.PATCH.place(dataclasses.replace(ctx, region=moved), params)
        return type(arr)(arr.kind, arr.xy + np.array([dx, 0.0]), arr.angle, arr.scale)

    monkeypatch.setitem(ENGINES, "patch", fake_engine(unanchored))
    stable, _ = edit_stability(path, radius_widths=4.0)
    assert stable < 0.5


@pytest.mark.parametrize("mode", ["clip", "none"])
def test_a_motif_whose_outline_only_grazes_the_region_is_not_kept(mode):
    """Footprint outlines reach a little beyond the drawn motif (Prototype.excess): a disc 0.2 %
    of its radius clear of the region has an outline that meets it, yet is not kept; discs that
    really cross the edge are."""
    from svgtile.core.arrangement import Arrangement
    from svgtile.core.footprint import Prototype

    proto = Prototype.from_geometry(shapely.Point(0, 0).buffer(10.0, 256))
    assert proto.excess > 0.02
    region = Region(shapely.box(0, 0, 100, 100))
    xs = np.array([-10.02, -9.0, -5.0, 50.0])  # clear by 0.02, crossing by 1, by 5, inside
    arr = Arrangement(np.zeros(4, int), np.c_[xs, np.full(4, 50.0)], np.zeros(4), np.ones(4))
    outline = world_footprints(arr, [proto])
    assert shapely.intersects(region.shape, outline[0])  # the outline grazes the region …
    assert region.keep(arr, [proto], mode).tolist() == [False, True, True, True]  # … the disc does not
