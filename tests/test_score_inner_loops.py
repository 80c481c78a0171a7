"""The inner loops that ``svgtile score`` spends its time in give what their plain forms give, bit for bit.

Each plain form here is the computation as it stood before it was made faster (issue 11's last
criterion; timings in benchmarks/README.md), written out so that a change of the fast one
that changes an answer fails here.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import shapely
from scipy.ndimage import distance_transform_edt

from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.metrics import coverage, pattern
from svgtile.svg.reader import read_exemplar
from svgtile.svg.texture import _own_use_block, read_texture
from svgtile.svg.writer import svg_document

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"


def _texture(name: str, n: int, side: float, seed: int) -> tuple[Arrangement, list]:
    """n motifs of the bundled exemplar ``name``'s kinds, anywhere in a square of ``side``, any turn."""
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    rng = np.random.default_rng(seed)
    kinds = len(ex.prototypes)
    arr = Arrangement(
        rng.integers(0, kinds, n), rng.uniform(-0.1 * side, 1.1 * side, (n, 2)),
        rng.uniform(-180, 180, n), rng.choice([1.0, 0.75, 1.5], n),
    )  # fmt: skip
    return arr, ex.prototypes


def _plain_outline_raster(arr, protos, ox, oy, nx, ny, step, feature):
    """The outline pixels of :func:`svgtile.metrics.coverage._raster_clearance`, as first written:
    every outline point of a kind at once, then its pixel by ``np.floor`` of a fresh array."""
    for k, proto in enumerate(protos):
        idx = np.flatnonzero(arr.kind == k)
        scale = float(arr.scale.max())
        rings = [shapely.segmentize(shapely.linearrings(r), step / max(scale, 1e-12)) for r in proto.rings]
        local = np.concatenate([shapely.get_coordinates(r) for r in rings])
        turn = np.radians(arr.angle[idx])
        cos, sin = np.cos(turn) * arr.scale[idx], np.sin(turn) * arr.scale[idx]
        wx = cos[:, None] * local[:, 0] - sin[:, None] * local[:, 1] + arr.xy[idx, 0, None]
        wy = sin[:, None] * local[:, 0] + cos[:, None] * local[:, 1] + arr.xy[idx, 1, None]
        ix = np.floor((wx.ravel() - ox) / step).astype(np.int64)
        iy = np.floor((wy.ravel() - oy) / step).astype(np.int64)
        ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
        feature[iy[ok], ix[ok]] = True
    return feature


def test_raster_clearance_marks_the_outline_pixels_of_the_plain_loop(monkeypatch):
    arr, protos = _texture("gravel", 3000, 400.0, 11)
    window = shapely.box(20.0, 30.0, 380.0, 370.0)
    region = shapely.box(0.0, 0.0, 400.0, 400.0)
    step = 1.37
    # chunks of a few motifs each, and a chunk that holds them all: the same raster
    for chunk in (1 << 9, 1 << 30):
        monkeypatch.setattr(coverage, "_OUTLINE_CHUNK", chunk)
        xy, estimate = coverage._raster_clearance(arr, protos, window, region, step)
        pad = 2 * step
        x0, y0, x1, y1 = window.bounds
        ox, oy = x0 - pad, y0 - pad
        nx, ny = math.ceil((x1 - x0 + 2 * pad) / step), math.ceil((y1 - y0 + 2 * pad) / step)
        xs, ys = ox + (np.arange(nx) + 0.5) * step, oy + (np.arange(ny) + 0.5) * step
        gx, gy = np.meshgrid(xs, ys)
        plain = _plain_outline_raster(arr, protos, ox, oy, nx, ny, step, ~shapely.contains_xy(region, gx, gy))
        keep = shapely.contains_xy(window, gx, gy)
        iy, ix = np.nonzero(keep)
        want = distance_transform_edt(~plain)[iy, ix] * step
        assert plain.sum() > 10_000 and (~plain).sum() > 1000  # outlines drawn, and space between
        assert np.array_equal(xy, np.stack([xs[ix], ys[iy]], axis=1))
        assert np.array_equal(estimate, want)


def test_pixel_rounds_as_the_plain_expression():
    # points on and next to pixel edges, where the order of the operations decides the pixel
    rng = np.random.default_rng(3)
    step, origin = 0.1, -2.3
    centre = rng.uniform(-50, 50, (400, 1)).round(1)
    edge = np.arange(-200, 200)[None, :] * step + origin - centre
    turned = edge + rng.choice([0.0, 1e-15, -1e-15, 1e-13, -1e-13], edge.shape)
    want = np.floor((turned + centre - origin) / step).astype(np.int64).ravel()
    got = coverage._pixel(turned.copy(), centre, origin, step)
    assert np.array_equal(got, want)
    # the test sees the order: the other association of the same sum lands elsewhere
    assert not np.array_equal(np.floor((turned + (centre - origin)) / step).astype(np.int64).ravel(), want)


def test_a_kind_first_met_on_the_last_line_is_kept(tmp_path):
    # the text scan splits the lines only up to the last group's first line: here the very last
    ex = read_exemplar(EXEMPLARS / "gravel.svg")
    rng = np.random.default_rng(8)
    n = 400
    kind = np.zeros(n, np.int64)
    kind[-1] = 1
    arr = Arrangement(kind, rng.uniform(5, 195, (n, 2)), rng.uniform(-180, 180, n), np.ones(n))
    path = tmp_path / "t.svg"
    path.write_text(svg_document(ex, arr, Region.rectangle(200, 200), boundary="none", params={}))
    skeleton, lines = _own_use_block(path.read_bytes())
    assert lines.first.tolist() == [0, n - 1]
    assert skeleton.count(b"<use ") == 2 and skeleton.rstrip().endswith(b"</svg>")
    back, _ = read_texture(path, ex)
    want = read_exemplar(path).motifs
    for field in ("kind", "xy", "angle", "scale"):
        assert np.array_equal(getattr(back, field), getattr(want, field)), field
    assert back.kind[-1] == 1 and len(back) == n


def test_set_covariance_of_apart_rectangles_is_the_plain_sum(monkeypatch):
    # nine sample windows far apart; displacements shorter than that
    boxes = shapely.MultiPolygon([shapely.box(x, y, x + 37.5 + x / 7, y + 41.25 - y / 11)
                                  for x in (0.0, 120.0, 240.0) for y in (0.0, 130.0, 260.0)])  # fmt: skip
    rng = np.random.default_rng(12)
    d = rng.uniform(-45.0, 45.0, (20_001, 2))
    d[::7] = d[::7].round(1)  # some on the windows' widths exactly
    parts = shapely.bounds(shapely.get_parts(boxes))
    w, h = parts[:, 2] - parts[:, 0], parts[:, 3] - parts[:, 1]
    plain = (np.maximum(w[None, :] - np.abs(d[:, 0:1]), 0.0) * np.maximum(h[None, :] - np.abs(d[:, 1:2]), 0.0)).sum(axis=1)
    want = np.maximum(plain, 1e-12 * (boxes.bounds[2] - boxes.bounds[0]) * (boxes.bounds[3] - boxes.bounds[1]))
    for chunk in (1, 1000, 1 << 13, 1 << 30):
        monkeypatch.setattr(pattern, "_PAIR_CHUNK", chunk)
        got = pattern._set_covariance(boxes, d, reach=50.0)
        assert np.array_equal(got, want), chunk
    assert (want > 1e-6).sum() > 10_000  # most displacements overlap some window


def test_the_ground_and_cell_searches_find_what_the_regular_expressions_find():
    """``_first_match`` (``bytes.find`` of the pattern's head, then a match there) is
    ``pattern.search``, and ``_without_ground`` is ``_OWN_GROUND.sub(rb"\\1", count=1)``, on
    documents with decoys (the head without the rest), one ground, two, and none."""
    from svgtile.svg import texture

    ground = b'<path class="svgtile-ground" style="fill:#eee;stroke:none" fill-rule="evenodd" d="M0 0h9v9z" />'
    group = b'<g id="svgtile" clip-path="url(#c)">'
    cell = b'<path class="svgtile-edge" d="M0 0"/>'
    docs = [
        b"<svg>" + group + b"\n  " + ground + b"\n<use/></g></svg>",
        b'<svg><g id="svgtile-x">\n<path class="svgtile-face"/>' + group + b"\n\t" + ground + group + b"\n" + ground + b"</g></svg>",
        b'<svg><g id="svgtile"><path class="svgtile-" /><path class="svgtile-lines" />' + cell + b"</g></svg>",
        b'<svg><g id="svgtile">\n<use/><path class="svgtile-corne" /></g></svg>',
        b"",
    ]
    for doc in docs:
        for regex, head in ((texture._CELL_PATH, texture._CELL_HEAD), (texture._OWN_GROUND, texture._GROUND_HEAD)):
            fast, plain = texture._first_match(regex, head, doc), regex.search(doc)
            assert (fast and fast.span()) == (plain and plain.span()), (regex.pattern, doc)
        assert texture._without_ground(doc) == texture._OWN_GROUND.sub(rb"\1", doc, count=1), doc
    assert texture._without_ground(docs[0]) != docs[0] and texture._first_match(texture._CELL_PATH, texture._CELL_HEAD, docs[2])


def _plain_motif_sample(arr, index, most):
    """:func:`svgtile.metrics.window.motif_sample` as first written: a stable sort of every hash."""
    from svgtile.core.cellrng import hash64

    if len(index) <= most:
        return index
    q = np.round(arr.xy[index] * 1e4).astype(np.int64)
    h = hash64(0x5C0E, 0, arr.kind[index], q[:, 0], q[:, 1])
    return np.sort(index[np.argsort(h, kind="stable")[:most]])


def test_motif_sample_picks_the_stable_sorts_first_hashes_ties_included():
    """score11e: a partition instead of a sort of all the hashes; motifs of the same kind at the
    same place hash alike, and the tie at the cut goes to the lower index as in a stable sort."""
    from svgtile.metrics.window import motif_sample

    rng = np.random.default_rng(0)
    for n, most, same in [(20_000, 4000, 0), (5000, 4000, 0), (1000, 10, 500), (1000, 999, 900), (50, 1, 30),
                          (2000, 1500, 1990), (300, 0, 0)]:  # fmt: skip
        xy, kind = rng.uniform(0, 100, (n, 2)), rng.integers(0, 3, n)
        xy[:same], kind[:same] = xy[0], kind[0]
        arr = Arrangement(kind, xy, np.zeros(n), np.ones(n))
        index = np.sort(rng.choice(2 * n, size=n, replace=False)) % n if same else np.arange(n)
        fast, plain = motif_sample(arr, index, most), _plain_motif_sample(arr, index, most)
        assert fast.dtype == plain.dtype and fast.tobytes() == plain.tobytes(), (n, most, same)
