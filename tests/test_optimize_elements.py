"""Several samples per elongated motif (Ma, Wei & Tong 2011 §3.1; issue 14): the layout, the
motif placed and turned from its samples, and dashes in rows kept along their rows."""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from svgtile import analyze
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.optimize.elements import ELONGATED, layout
from svgtile.svg.reader import parse_exemplar

#: Straight rows of dashes, each row in its own direction (degrees), dashes along it.
ROWS = (-12, 8, 15, -4, 10)


def dash_rows(dot: bool = False) -> str:
    uses = []
    for r, (y0, th) in enumerate(zip(np.arange(6, 60, 12), ROWS, strict=True)):
        for t in np.arange(-30, 30, 5.5) + (r % 2) * 2:
            x, y = 30 + t * np.cos(np.radians(th)), y0 + t * np.sin(np.radians(th))
            if 0.5 < x < 59.5 and 0.5 < y < 59.5:
                uses.append(f'<use href="#dash" transform="translate({x:.3f} {y:.3f}) rotate({th})"/>')
    if dot:  # a compact kind beside the dashes
        uses.append('<use href="#dot" x="30" y="0.9"/>')
    return ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 60 60"><defs>'
            '<symbol id="dash" overflow="visible"><line x1="-2" y1="0" x2="2" y2="0" stroke="black" stroke-width="0.6"/></symbol>'
            '<symbol id="dot" overflow="visible"><circle r="0.5"/></symbol></defs>'
            '<rect id="region" x="0" y="0" width="60" height="60" fill="none"/>' + "".join(uses) + "</svg>")  # fmt: skip


def test_a_dash_is_two_samples_and_its_pose_comes_back_from_them():
    ex = parse_exemplar(dash_rows(dot=True), source="rows")
    lay = layout(ex.prototypes, ELONGATED)
    dash = int(np.argmax([p.radius for p in ex.prototypes]))
    assert lay is not None and lay.elongated[dash] and not lay.elongated[1 - dash]
    # the samples sit on the stroke's axis (x), inside its 4.6 length, half a footprint width in
    assert abs(lay.ends[dash][1]) < 1e-6 and 1.5 < abs(lay.ends[dash][0]) < 2.3
    rng = np.random.default_rng(0)
    n = 50
    kind = rng.integers(0, 2, n)
    arr = Arrangement(kind, rng.uniform(0, 100, (n, 2)), rng.uniform(-180, 180, n), np.ones(n))
    xy, attr, owner = lay.samples(arr)
    assert len(xy) == n + int((kind == dash).sum())
    assert set(attr[kind[owner] == dash] % 3) == {1, 2} and set(attr[kind[owner] != dash] % 3) == {0}
    centre, angle, two = lay.poses(arr, xy, owner)
    np.testing.assert_allclose(centre, arr.xy, atol=1e-9)
    turned = np.abs((angle - arr.angle + 180) % 360 - 180)
    assert (turned[two] < 1e-6).all() and (two == (kind == dash)).all()
    assert layout(ex.prototypes, 0.0) is None  # off: one sample per motif


def _misalignment(arr: Arrangement, dash: int) -> float:
    """Median angle (degrees, 0–90) between each dash and the direction to its nearest dash."""
    d = arr.take(arr.kind == dash)
    _, nb = cKDTree(d.xy).query(d.xy, k=2)
    v = d.xy[nb[:, 1]] - d.xy
    return float(np.median(np.abs((d.angle - np.degrees(np.arctan2(v[:, 1], v[:, 0])) + 90) % 180 - 90)))


def test_two_samples_keep_dashes_along_their_rows_better_than_one():
    ex = parse_exemplar(dash_rows(), source="rows")
    stats = analyze(ex)
    dash = 0
    assert _misalignment(ex.motifs, dash) < 0.5  # the exemplar: every dash along its row
    got = {}
    for elongated in (0.0, ELONGATED):
        got[elongated] = np.mean([
            _misalignment(synthesize(ex, Region.rectangle(150, 150), "optimize", seed=seed, stats=stats,
                                     params={"elongated": elongated, "renew": 0.0}).arrangement, dash)
            for seed in (1, 2, 3)
        ])  # fmt: skip
    # measured 6.9° with one sample per dash, 5.9° with two; the layouts compared without renewal,
    # which re-seats one-sample motifs only (with it, one sample a dash: 4.4°, renew14)
    assert got[ELONGATED] < got[0.0] - 0.5, got
