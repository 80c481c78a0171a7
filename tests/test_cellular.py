"""The cellular engine (issue 15, legakis2001): corners, edges and the face of a map unit, each
textured by the generator its tree routes it to, cells that never overlap nor leave the unit."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile import analyze, read_exemplar
from svgtile.core.cells import CORNER, EDGE, FACE, LINE
from svgtile.core.flow import FlowField
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.base import Controls
from svgtile.engines.cellular.frame import FlowFrame, RotatedFrame
from svgtile.engines.cellular.mesh import base_mesh
from svgtile.engines.cellular.tree import parse_description, read_description
from svgtile.errors import ParameterError
from svgtile.gis.geojson import cellwork_features
from svgtile.svg.writer import result_document

REPO = Path(__file__).resolve().parents[1]
GRAVEL = REPO / "exemplars" / "gravel.svg"
#: Limestone: bricks 6 high and 14 long in running bond, corner bricks, alternating edge bricks.
LIMESTONE = {"course": 6.0, "length": 14.0, "offset": 0.5}


@cache
def gravel():
    ex = read_exemplar(GRAVEL)
    return ex, analyze(ex)


def l_unit() -> shapely.Polygon:
    """An L-shaped unit with a square hole turned by 30°: 6 convex corners on the outside (5 convex,
    1 reflex) and 4 reflex ones on the hole (the face turns right there)."""
    outer = shapely.Polygon([(0, 0), (200, 0), (200, 80), (90, 80), (90, 170), (0, 170)])
    hole = shapely.affinity.rotate(shapely.box(30, 30, 60, 60), 30)
    return outer.difference(hole)


def run(description=LIMESTONE, shape=None, tmp_path=None, seed=1, boundary="inside", controls=None, **params):
    ex, stats = gravel()
    if tmp_path is not None and description is not None:
        path = tmp_path / "tree.json"
        path.write_text(json.dumps(description))
        params = {"tree": str(path), **params}
    return synthesize(ex, Region(shape if shape is not None else l_unit()), "cellular", seed=seed, stats=stats,
                      boundary=boundary, params=params, controls=controls)  # fmt: skip


@pytest.fixture(scope="module")
def limestone(tmp_path_factory):
    """Limestone bricks with gravel set in a third of them (chert nodules, say)."""
    return run({**LIMESTONE, "motifs": {"share": 0.35}}, tmp_path=tmp_path_factory.mktemp("lime"))


def test_base_mesh_finds_convex_and_reflex_corners_and_every_ring():
    mesh = base_mesh(l_unit())
    assert len(mesh.rings) == 2
    assert (mesh.corner_turn > 0).sum() == 5 + 0 and (mesh.corner_turn < 0).sum() == 1 + 4
    assert len(mesh.edges) == 6 + 4
    # every edge runs from corner to corner along the boundary
    assert shapely.length(mesh.edges).sum() == pytest.approx(l_unit().boundary.length)


def test_corner_cells_sit_on_every_convex_and_reflex_corner(limestone):
    cells = limestone.cells
    corners = cells.shapes[cells.feature == CORNER]
    mesh = base_mesh(l_unit())
    pts = shapely.points(mesh.corner_xy)
    near = [shapely.dwithin(corners, p, 1e-4).sum() for p in pts]  # cells are written at 4 decimals
    assert near == [1] * len(pts), "exactly one corner cell at each corner"


def test_edge_cells_run_parallel_to_the_boundary(limestone):
    assert worst_edge_turn(limestone.cells, l_unit()) <= 5.0


def worst_edge_turn(cells, unit) -> float:
    """Degrees: the most any edge cell's sides turn from the boundary next to it."""
    edge = cells.shapes[cells.feature == EDGE]
    assert len(edge) > 40
    boundary = unit.boundary
    worst = 0.0
    for cell in edge:
        # the cell's sides (its minimum rotated rectangle's) run along and across the boundary:
        # whole bricks, half bricks and the short cells next to corners alike
        rect = np.asarray(shapely.minimum_rotated_rectangle(cell).exterior.coords)
        side = rect[1] - rect[0]
        p = shapely.line_locate_point(boundary, shapely.point_on_surface(cell))
        a, b = (np.asarray(shapely.line_interpolate_point(boundary, p + d).coords[0]) for d in (-0.5, 0.5))
        t = b - a
        diff = (np.degrees(np.arctan2(side[1], side[0]) - np.arctan2(t[1], t[0]))) % 90.0
        worst = max(worst, float(min(diff, 90.0 - diff)))
    return worst


def test_no_cell_leaves_the_unit_and_no_two_overlap(limestone):
    cells = limestone.cells.cells
    unit = l_unit()
    assert shapely.covered_by(cells, shapely.buffer(unit, 1e-4)).all()  # cells are written at 4 decimals
    tree = shapely.STRtree(cells)
    i, j = tree.query(cells, predicate="intersects")
    keep = i < j
    overlap = shapely.area(shapely.intersection(cells[i[keep]], cells[j[keep]]))
    assert overlap.max(initial=0.0) < 1e-3  # rounding to 4 decimals, nothing more
    # the cells claim the whole unit (mortar 0): occupancy leaves no gaps bigger than slivers
    assert shapely.area(cells).sum() == pytest.approx(unit.area, rel=0.01)


def test_face_cells_are_bricks_in_running_bond(limestone):
    cells = limestone.cells
    face = cells.shapes[cells.feature == FACE]
    whole = face[np.isclose(shapely.area(face), 6 * 14, rtol=1e-6)]
    assert len(whole) > 0.6 * len(face)
    lo = shapely.bounds(whole)
    rows = np.round(lo[:, 1] / 6).astype(int)
    # joints of course j sit at (i + j/2) · 14 (offset 0.5), world-anchored
    phase = (lo[:, 0] / 14 - 0.5 * rows) % 1.0
    assert np.allclose(np.minimum(phase, 1 - phase), 0.0, atol=1e-6)


def test_mortar_shrinks_cells_apart(tmp_path):
    result = run({**LIMESTONE, "mortar": 1.0}, tmp_path=tmp_path)
    cells = result.cells.cells
    tree = shapely.STRtree(cells)
    i, j = tree.query(cells, predicate="dwithin", distance=0.99)
    assert (i == j).all()


def test_a_labelled_edge_goes_to_its_own_generator(tmp_path):
    unit = shapely.box(0, 0, 120, 90)
    (tmp_path / "map.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 200">'
                                      '<path id="fault" d="M -5 90 L 125 90" stroke="#000" fill="none"/></svg>')  # fmt: skip
    tree = {**LIMESTONE, "tree": [
        {"feature": "edge", "label": "fault", "generator": "edge_blocks", "style": "fill:none;stroke:#ff0000"},
        {"feature": "corner", "generator": "corner"},
        {"feature": "edge", "generator": "edge_bricks"},
        {"feature": "face", "generator": "bricks"}]}  # fmt: skip
    result = run(tree, shape=unit, tmp_path=tmp_path, label=f"fault={tmp_path / 'map.svg'}#fault")
    cells = result.cells
    red = cells.styles.index("fill:none;stroke:#ff0000")
    # the fault's cells are outlined in red (their joints, each drawn once) …
    joints = shapely.get_parts(cells.shapes[(cells.style == red) & (cells.feature == LINE)])
    assert len(joints) >= 6
    assert np.all(shapely.bounds(joints)[:, [1, 3]] >= 84.0 - 1e-3)  # all in the course along y = 90 …
    along = shapely.intersection(shapely.union_all(joints), shapely.box(-1, 84 - 1e-3, 121, 84 + 1e-3))
    assert along.length > 0.8 * 120  # … and they line it (between the corner cells)
    # equal blocks, not alternating bricks, along the fault
    faulted = cells.shapes[(cells.feature == EDGE) & (np.abs(shapely.bounds(cells.shapes)[:, 3] - 90.0) < 1e-3)
                           & (np.abs(shapely.bounds(cells.shapes)[:, 1] - 84.0) < 1e-3)]  # fmt: skip
    assert len(faulted) >= 6
    widths = np.sort(np.ptp(shapely.bounds(faulted)[:, [0, 2]], axis=1))
    assert np.ptp(widths[1:-1]) < 1e-6  # (the end ones meet the corner cells)
    plain = run(tree, shape=unit, tmp_path=tmp_path)  # no label given: no red cells
    assert "fill:none;stroke:#ff0000" not in plain.cells.styles


def arcs_flow() -> FlowField:
    """A flow turning around a centre below the unit: courses bend along arcs."""
    theta = np.linspace(-1.2, 1.2, 40)
    strokes = [np.stack([100 + r * np.sin(theta), 260 - r * np.cos(theta)], 1) for r in (160, 200, 240, 280)]
    return FlowField.from_strokes(strokes)


def misfit(result, flow) -> np.ndarray:
    """Degrees between each whole face brick's long axis and the flow at its centre."""
    face = result.cells.shapes[result.cells.feature == FACE]
    whole = face[shapely.area(face) > 0.9 * 6 * 14]
    assert len(whole) > 50
    rect = [np.asarray(shapely.minimum_rotated_rectangle(c).exterior.coords) for c in whole]
    long = np.array([max(np.diff(r[:3], axis=0), key=lambda v: np.hypot(*v)) for r in rect])
    want = flow.direction(shapely.get_coordinates(shapely.centroid(whole)))
    cos = np.abs(np.sum(long * want, axis=1)) / np.hypot(long[:, 0], long[:, 1])
    return np.degrees(np.arccos(np.minimum(cos, 1.0)))


def test_courses_follow_a_flow(tmp_path):
    flow = arcs_flow()
    unit = shapely.box(20, 20, 180, 120)
    result = run({**LIMESTONE, "tree": [{"feature": "face", "generator": "bricks"}]}, shape=unit,
                 tmp_path=tmp_path, controls=Controls(flow=flow))  # fmt: skip
    assert np.quantile(misfit(result, flow), 0.9) < 8.0
    # straight courses (strike 0) miss the same flow by up to ~25° at the unit's sides
    straight = run({**LIMESTONE, "tree": [{"feature": "face", "generator": "bricks"}]}, shape=unit, tmp_path=tmp_path)
    assert np.quantile(misfit(straight, flow), 0.9) > 12.0


def test_the_l_unit_with_a_hole_under_a_flow_keeps_every_rule(tmp_path):
    """Issue 15's done-when in one run: limestone in the L-shaped unit with a hole, courses along a
    --flow: a corner cell at each convex and reflex corner, edge cells within 5° of the boundary,
    no cell cut (inside) nor overlapping, face bricks along the flow."""
    flow, unit = arcs_flow(), l_unit()
    result = run(LIMESTONE, tmp_path=tmp_path, controls=Controls(flow=flow))
    cells = result.cells
    corners = cells.shapes[cells.feature == CORNER]
    pts = shapely.points(base_mesh(unit).corner_xy)
    assert [int(shapely.dwithin(corners, p, 1e-4).sum()) for p in pts] == [1] * len(pts)
    assert worst_edge_turn(cells, unit) <= 5.0
    polys = cells.cells
    assert shapely.covered_by(polys, shapely.buffer(unit, 1e-4)).all()
    i, j = shapely.STRtree(polys).query(polys, predicate="intersects")
    assert shapely.area(shapely.intersection(polys[i[i < j]], polys[j[i < j]])).max(initial=0.0) < 1e-3
    assert np.quantile(misfit(result, flow), 0.9) < 8.0


def test_flow_frame_maps_and_projects_back():
    flow = FlowField.uniform(30.0)
    frame = FlowFrame(flow, shapely.box(0, 0, 100, 60), 3.0)
    xy = np.array([[10.0, 10.0], [50.0, 30.0], [90.0, 50.0]])
    assert np.allclose(frame.map(frame.project(xy)), xy, atol=1e-6)
    rot = RotatedFrame(30.0)
    st, st2 = frame.project(xy), rot.project(xy)
    assert np.allclose(np.diff(st, axis=0), np.diff(st2, axis=0), atol=1e-3)  # a uniform flow = a strike


def test_every_generator_fills_without_overlap(tmp_path):
    unit = shapely.Polygon([(0, 0), (150, 10), (140, 100), (10, 90)])
    for face in ("blocks", "bricks", "ashlar", "rhombs"):
        tree = {**LIMESTONE, "tree": [{"feature": "corner", "generator": "corner"},
                                      {"feature": "edge", "generator": "edge_blocks"},
                                      {"feature": "face", "generator": face}]}  # fmt: skip
        cells = run(tree, shape=unit, tmp_path=tmp_path).cells.cells
        i, j = shapely.STRtree(cells).query(cells, predicate="intersects")
        keep = i < j
        # (cells are written at 4 decimals: rounding may leave overlaps of ~1e-4 unit²)
        assert shapely.area(shapely.intersection(cells[i[keep]], cells[j[keep]])).max(initial=0) < 1e-3, face
        assert shapely.area(cells).sum() == pytest.approx(unit.area, rel=0.01), face
    ashlar = run({**LIMESTONE, "tree": [{"feature": "face", "generator": "ashlar"}]}, shape=unit, tmp_path=tmp_path)
    sizes = np.unique(np.round(shapely.area(ashlar.cells.cells), 3))
    assert len(sizes) >= 3  # stones of several sizes …
    assert shapely.area(ashlar.cells.cells).max() <= 4 * 2 * (6 / 3) ** 2 + 1e-6  # … none past the limit


def test_bedding_lines_solid_and_dashed(tmp_path):
    unit = shapely.box(0, 0, 100, 60)
    desc = {**LIMESTONE, "cell_style": "", "tree": [{"feature": "face", "generator": "none"}],
            "lines": [{"every": 2, "start": 0}, {"every": 2, "start": 1, "dash": [4.0, 2.0], "offset": 0.5}]}  # fmt: skip
    cells = run(desc, shape=unit, tmp_path=tmp_path).cells
    assert (cells.feature == LINE).all() and len(cells.cells) == 0
    lines = cells.shapes
    y = shapely.bounds(lines)[:, 1]
    solid = lines[np.isclose(y % 12, 0)]
    dashed = lines[np.isclose(y % 12, 6)]
    assert len(solid) and (shapely.length(solid) == pytest.approx(100.0))
    inner = dashed[(shapely.bounds(dashed)[:, 0] > 0) & (shapely.bounds(dashed)[:, 2] < 100)]
    assert np.allclose(shapely.length(inner), 4.0)


def test_motifs_in_cells_lie_in_their_cells(limestone):
    ex, _ = gravel()
    from svgtile.core.footprint import world_footprints

    arr = limestone.arrangement
    assert len(arr) > 50
    cells = limestone.cells.cells
    fp = world_footprints(arr, ex.prototypes)
    inside = np.array([shapely.covered_by(f, cells).any() for f in fp])
    assert inside.all()


def test_same_seed_same_bytes_and_cells_written(tmp_path):
    a, b = run(tmp_path=tmp_path, seed=4), run(tmp_path=tmp_path, seed=4)
    text = result_document(a)
    assert text == result_document(b)
    assert text.count('class="svgtile-corner"') == (a.cells.feature == CORNER).sum()
    assert text.count("<path class=") == len(a.cells)
    assert 'cells="' in text
    features = cellwork_features(a.cells)
    assert {f["geometry"]["type"] for f in features} == {"Polygon", "MultiLineString"}  # cells, their joints
    assert sum(f["geometry"]["type"] == "Polygon" for f in features) == len(a.cells.cells)
    assert len(features) == len(a.cells)


def test_an_edit_changes_cells_only_near_it(tmp_path):
    """With the bond anchored to the world (with the fewest half bricks, an edit may shift a face's
    bond by half a brick: tests/test_cellular_fidelity.py)."""
    unit = shapely.Polygon([(0, 0), (300, 0), (300, 200), (150, 200), (0, 200)])
    moved = shapely.Polygon([(0, 0), (300, 0), (300, 200), (150, 230), (0, 200)])  # one vertex pulled out
    a = run(shape=unit, tmp_path=tmp_path, halves="anchored").cells.cells
    b = run(shape=moved, tmp_path=tmp_path, halves="anchored").cells.cells
    far = shapely.distance(shapely.LineString([(0, 200), (150, 230), (300, 200)]), a) > 40
    same = set(shapely.to_wkb(shapely.normalize(b)).tolist())
    kept = np.array([w in same for w in shapely.to_wkb(shapely.normalize(a[far])).tolist()])
    assert far.sum() > 200 and kept.mean() > 0.97


@pytest.mark.parametrize(
    ("data", "message"),
    [
        ({"tree": [{"feature": "face", "generator": "lava"}]}, "unknown generator 'lava' for a face"),
        ({"course": -1}, "course must not be negative"),
        ({"tree": [{"feature": "roof", "generator": "bricks"}]}, "feature must be one of"),
        ({"colour": 1}, "unknown key 'colour'"),
        ({"lines": [{"dash": [1]}]}, "lines.dash must be two positive numbers"),
    ],
)
def test_bad_descriptions_are_one_clear_error(data, message):
    with pytest.raises(ParameterError, match=message):
        parse_description(data, "tree.toml")


def test_toml_description_and_a_bad_file(tmp_path):
    good = tmp_path / "t.toml"
    good.write_text('course = 5\nlength = 11\n[[tree]]\nfeature = "face"\ngenerator = "ashlar"\n')
    d = read_description(good)
    assert (d.course, d.length) == (5.0, 11.0)
    assert d.tree.route({"feature": "face"}).generator == "ashlar"
    assert d.tree.route({"feature": "edge"}) is None
    bad = tmp_path / "b.toml"
    bad.write_text("course = = 5")
    with pytest.raises(ParameterError, match=r"b\.toml: not valid TOML"):
        read_description(bad)


@pytest.mark.parametrize(
    ("desc", "message"),
    [
        ({**LIMESTONE, "course": 1e-4, "length": 1e-4}, "cells of 0.0001 x 0.0001 would number"),
        ({**LIMESTONE, "lines": [{"every": 1, "dash": [1e-5, 1e-5]}]}, "bedding lines would take"),
        ({**LIMESTONE, "course": 1e-6, "length": 1e8}, "courses of 1e-06 are too fine"),
        ({**LIMESTONE, "lines": [{"every": 1, "wave": [0.0, 1.0], "wave_period": 1e-6}]}, "bedding lines would take"),
    ],
)
def test_a_description_of_countless_cells_or_line_points_is_refused_before_the_work(tmp_path, desc, message):
    """A tiny course, cell length or wave period would allocate without bound: one clear error."""
    with pytest.raises(ParameterError, match=message):
        run(desc, shape=shapely.box(0, 0, 100, 60), tmp_path=tmp_path)


def test_fine_straight_courses_are_not_taken_for_countless_points(tmp_path):
    """Solid lines in a straight frame are drawn end to end: 6,000 courses of 0.01 are 6,000 lines
    of a few points each, which is no reason to refuse."""
    desc = {**LIMESTONE, "cell_style": "", "tree": [{"feature": "face", "generator": "none"}],
            "lines": [{"every": 1}], "course": 0.01, "length": 1e4}  # fmt: skip
    cells = run(desc, shape=shapely.box(0, 0, 100, 60), tmp_path=tmp_path).cells
    assert (cells.feature == LINE).sum() > 5000
