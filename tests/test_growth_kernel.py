"""The growth engine's compiled loop (svgtile/engines/growth/kernel.py, issue 13): its pieces
against numpy and shapely on hand-made inputs, its resumable state, and golden textures.

The golden textures under tests/golden/growth-*.svg were written by the numpy implementation the
kernel replaced (commit 1b5ba1c); the kernel must reproduce them byte for byte.  Regenerate with
``pytest tests/test_growth_kernel.py --update-golden`` only for an intended change.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile import read_exemplar
from svgtile.cli.main import main
from svgtile.engines.growth import kernel
from svgtile.engines.growth.connectivity import reference_rings
from svgtile.engines.growth.engine import centre_gaps, kind_priority
from svgtile.engines.growth.grow import grow
from svgtile.engines.growth.matching import Weights, best_match

REPO = Path(__file__).resolve().parents[1]
GOLDEN = Path(__file__).parent / "golden"


@pytest.mark.parametrize("n", [1, 2, 3, 7, 8, 9, 15, 16, 17, 30])
def test_sums_are_numpys_to_the_bit(n):
    a = np.random.default_rng(n).normal(size=(50, n)) * 1e3
    got = np.array([kernel._sum(row, n) for row in a])
    assert np.array_equal(got, a.sum(-1))


def test_inside_is_shapelys_contains_with_the_boundary_outside():
    poly = shapely.Polygon([(0, 0), (10, 0), (10, 10), (3, 10), (0, 4)], holes=[[(4, 4), (6, 4), (6, 6), (4, 6)]])
    coords = np.concatenate([shapely.get_coordinates(g) for g in shapely.get_rings(poly)])
    starts = np.cumsum([0] + [len(shapely.get_coordinates(g)) for g in shapely.get_rings(poly)]).astype(np.int64)
    pts = np.random.default_rng(0).uniform(-1, 11, (2000, 2))
    edges = np.array([[0, 5], [10, 5], [5, 0], [5, 10], [4, 5], [5, 6], [0, 0], [10, 10], [6, 6], [1.5, 7], [0, 2]])
    pts = np.r_[pts, edges, np.round(pts[:200])]  # on edges, vertices and whole-number grid points
    got = np.array([kernel.inside(x, y, coords, starts) for x, y in pts])
    assert np.array_equal(got, shapely.contains_xy(poly, pts[:, 0], pts[:, 1]))
    assert got.any() and not got.all()


def test_the_heap_pops_in_key_then_id_order():
    rng = np.random.default_rng(1)
    keys = rng.integers(0, 20, 200).astype(float)  # many equal keys: ties go to the lower id
    hkey, hid, hn = np.zeros(200), np.zeros(200, np.int64), 0
    for q, k in enumerate(keys):
        hn = kernel._heap_push(hkey, hid, hn, k, q)
    popped = []
    while hn:
        k, q, hn = kernel._heap_pop(hkey, hid, hn)
        popped.append((k, q))
    assert popped == sorted(zip(keys.tolist(), range(200), strict=True))


def test_growth_resumes_after_each_relaxation_and_when_its_arrays_fill():
    ex = read_exemplar(REPO / "exemplars" / "gravel.svg")
    rings = reference_rings(ex)
    piece = shapely.box(0, 0, 60, 60)
    calls = []

    def relax(xy, ring, theta, first):
        calls.append(len(xy) - first)
        return xy[first:] + 0.0

    kw = dict(fixed_xy=np.zeros((0, 2)), fixed_kind=np.zeros(0, np.int64), fixed_sub=np.zeros(0, np.int64),
              rotation="none", flow=None, priority=kind_priority(ex, {}), weights=Weights(),
              centre_gap=centre_gaps(ex, len(ex.kinds)))  # fmt: skip
    g = grow(rings, piece, np.array([30.0, 30.0]), 0, draws=np.random.default_rng(3), relax=relax, relax_every=10,
             room=8, **kw)  # fmt: skip
    plain = grow(rings, piece, np.array([30.0, 30.0]), 0, draws=np.random.default_rng(3), **kw)
    assert len(g.xy) > 8 * 8  # more than the first arrays hold: grown through FULL three times
    assert calls == list(range(10, len(g.xy) + 1, 10))
    assert np.array_equal(g.xy, plain.xy) and np.array_equal(g.ring, plain.ring)  # relax here moved nothing
    assert shapely.contains_xy(piece, g.xy[:, 0], g.xy[:, 1]).all()


def test_growth_stops_at_the_limit():
    ex = read_exemplar(REPO / "exemplars" / "gravel.svg")
    rings = reference_rings(ex)
    g = grow(rings, shapely.box(0, 0, 60, 60), np.array([30.0, 30.0]), 0, fixed_xy=np.zeros((0, 2)),
             fixed_kind=np.zeros(0, np.int64), fixed_sub=np.zeros(0, np.int64), rotation="none", flow=None,
             priority=kind_priority(ex, {}), weights=Weights(), centre_gap=centre_gaps(ex, len(ex.kinds)),
             draws=np.random.default_rng(3), limit=17)  # fmt: skip
    assert len(g.xy) == 17


GOLDEN_RUNS = {
    "growth-gravel-none-seed1.svg": ("gravel", ["--rotation", "none", "--seed", "1"]),
    "growth-marsh-fit-seed2.svg": ("marsh", ["--rotation", "fit", "--seed", "2"]),
    "growth-shale-none-seed3.svg": ("shale", ["--rotation", "none", "--seed", "3"]),
}


@pytest.mark.parametrize("name", sorted(GOLDEN_RUNS))
def test_growth_golden(tmp_path, update_golden, name):
    """Same bytes as the numpy implementation wrote (see the module docstring)."""
    exemplar, opts = GOLDEN_RUNS[name]
    out = tmp_path / name
    assert main(["synth", str(REPO / "exemplars" / f"{exemplar}.svg"), "-o", str(out), "--size", "50x40",
                 "--engine", "growth", "--relax-every", "7", *opts]) == 0  # fmt: skip
    golden = GOLDEN / name
    if update_golden:
        golden.write_bytes(out.read_bytes())
    assert out.read_bytes() == golden.read_bytes(), f"{name} differs from {golden}"


@pytest.mark.parametrize(("seed", "held"), [(0, 0.1), (1, 0.1), (2, 0.5), (3, 1.0)])  # 1.0: every row's ends fixed
def test_the_normal_equations_are_the_sparse_products_bit_for_bit(seed, held):
    import scipy.sparse as sp

    from svgtile.engines.growth.relax import PULL, _normal_equations

    rng = np.random.default_rng(seed)
    f, e = 40, 150
    ci, cj = rng.integers(0, f, e), rng.integers(0, f, e)
    cj[cj == ci] = -1  # a row joins two different motifs (or a motif and a fixed one)
    ci[rng.random(e) < held] = -1
    cj[rng.random(e) < held] = -1
    b = rng.normal(size=(e, 2)) * 10
    N, rhs = _normal_equations(ci, cj, b, f)
    rows = np.arange(e)
    fi, fj = ci >= 0, cj >= 0
    A = sp.csr_matrix((np.r_[np.ones(fj.sum()), -np.ones(fi.sum())], (np.r_[rows[fj], rows[fi]],
                       np.r_[cj[fj], ci[fi]])), shape=(e, f))  # fmt: skip
    want = (A.T @ A + PULL * sp.identity(f)).tocsc()
    want.sum_duplicates()  # what spsolve does first: sorts each column's rows (the product leaves them unsorted)
    assert np.array_equal(N.indptr, want.indptr) and np.array_equal(N.indices, want.indices)
    assert np.array_equal(N.data, want.data)
    assert rhs.dtype == np.float64 and np.array_equal(rhs, A.T @ b)


def test_closer_decides_as_hypot_does_even_at_the_threshold():
    """kernel.closer answers ``hypot(dx, dy) < t`` from squares when that is safe: it must agree
    with hypot everywhere, most of all where the two differ by a rounding (t = hypot itself and
    its neighbouring floats, where the sum of squares alone would err)."""
    rng = np.random.default_rng(5)
    d = rng.normal(size=(4000, 2)) * 10.0 ** rng.integers(-3, 4, (4000, 1))
    h = np.hypot(d[:, 0], d[:, 1])
    near = np.r_[h, np.nextafter(h, np.inf), np.nextafter(h, 0), np.nextafter(np.nextafter(h, np.inf), np.inf)]
    t = np.r_[near, h * rng.uniform(0.5, 1.5, len(h)), 0.0, np.inf]
    dx, dy = np.r_[np.tile(d[:, 0], 5), 0.0, 1.0], np.r_[np.tile(d[:, 1], 5), 0.0, 1.0]
    got = np.array([kernel.closer(a, b, c) for a, b, c in zip(dx, dy, t, strict=True)])
    assert np.array_equal(got, np.hypot(dx, dy) < t)
    squares = np.sqrt(dx * dx + dy * dy) < t  # what the squares alone would say: wrong at the edge
    assert (squares != got).any() and got.any() and not got.all()


def _every_match(rings, tar, tkind, tsub, want, mode, fa, w, noise):
    """eq. (1)-(3) for every (reference, shift) pair, in numpy, no pair abandoned: (r, k, θ, err)
    sorted by error, ties in (r, k) order."""
    t, out = len(tar), []
    for r in range(len(rings.size)):
        m = rings.size[r]
        if m < t or (want >= 0 and rings.kind[r] != want):
            continue
        for k in range(m):
            s = (k + np.arange(t)) % m
            ref = rings.rel[r, s]
            theta = fa if mode == kernel.FLOW else 0.0
            if mode == kernel.FIT:
                theta = math.atan2((ref[:, 0] * tar[:, 1] - ref[:, 1] * tar[:, 0]).sum(),
                                   (ref[:, 0] * tar[:, 0] + ref[:, 1] * tar[:, 1]).sum())  # fmt: skip
            co, si = math.cos(theta), math.sin(theta)  # libm's, as compiled code calls
            d = np.hypot(co * ref[:, 0] - si * ref[:, 1] - tar[:, 0], si * ref[:, 0] + co * ref[:, 1] - tar[:, 1])
            err = w.distance * d.sum() / rings.mean_length
            bad, same = (rings.nkind[r, s] != tkind).sum(), (rings.nsub[r, s] == tsub).sum()
            err = err + w.kind * bad if w.kind else err
            err = err + w.subid * same if w.subid else err
            out.append((r, k, theta, err + 1e-9 * noise[r]))
    return sorted(out, key=lambda x: x[3])


@pytest.mark.parametrize("exemplar", ["gravel", "shale"])
@pytest.mark.parametrize("mode", [kernel.NONE, kernel.FIT, kernel.FLOW])
def test_match_returns_the_best_of_every_pair_though_it_abandons_pairs_early(exemplar, mode):
    """kernel.match abandons a pair as soon as bounds of its error (square roots first, then
    partial sums) exceed the worst kept; what it returns must be the best of every pair, exactly."""
    rings = reference_rings(read_exemplar(REPO / "exemplars" / f"{exemplar}.svg"))
    rng = np.random.default_rng(11)
    w = Weights(subid=0.5)
    for trial in range(60):
        r0 = int(rng.integers(len(rings.size)))
        t = int(rng.integers(1, rings.size[r0] + 1))
        tar = rings.rel[r0, :t] + rng.normal(0, 0.05 * rings.mean_length, (t, 2))  # near a real ring: close errors
        tkind, tsub = rings.nkind[r0, :t].copy(), rings.nsub[r0, :t].copy()
        tkind[rng.random(t) < 0.2] = 0
        noise, fa, top = rng.random(len(rings.size)), float(rng.uniform(-3, 3)), [1, 4][trial % 2]
        want = -1 if trial % 3 else int(rings.kind[r0])
        got = best_match(rings, tar, tkind, tsub, want=want, rotation=["none", "fit", "flow"][mode], flow_angle=fa,
                         weights=w, noise=noise, top=top)  # fmt: skip
        expect = _every_match(rings, tar, tkind, tsub, want, mode, fa, w, noise)[:top]
        assert got == [(int(r), int(k), float(th), float(e)) for r, k, th, e in expect]


def test_ring_slots_are_numpys_rotated_rings_bit_for_bit():
    """Relaxation's wanted neighbour offsets (kernel.ring_slots) against the numpy expression it
    replaced: the same rows, in the same order, to the bit."""
    rings = reference_rings(read_exemplar(REPO / "exemplars" / "shale.svg"))
    rng = np.random.default_rng(2)
    ring, theta, first = rng.integers(0, len(rings.size), 300), rng.uniform(-4, 4, 300), 17
    i, want = kernel.ring_slots(rings.rel, rings.size, ring, np.cos(theta), np.sin(theta), first)
    valid = np.arange(rings.rel.shape[1])[None, :] < rings.size[ring][:, None]
    c, s = np.cos(theta)[:, None], np.sin(theta)[:, None]
    v = rings.rel[ring]
    expect = np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)[valid]
    assert np.array_equal(i, np.broadcast_to((first + np.arange(300))[:, None], valid.shape)[valid])
    assert np.array_equal(want, expect) and len(set(rings.size[ring].tolist())) > 1
