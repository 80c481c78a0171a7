"""The optimize engine's density step after a refilled solve (issues 12.4 and 14,
:func:`svgtile.engines.optimize.engine.fill_light`).

Ma, Wei & Tong 2011 keep the start's element count (§4); insertion (capped at ρ) refills most of
a patch start's seams, but a tile whose cover is in a few large marks keeps holes no prediction
fills.  Known answer: the tile copied on its own period is at ρ; with a third of its motifs taken
out of a band it is light, and the step brings it back to at least 0.9 ρ, with no overlap and no
distance-rule violation, the same on every run.
"""

from __future__ import annotations

import numpy as np
from test_optimize_period import H, W, tile

from svgtile import analyze
from svgtile.analysis.stats import footprint_areas
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import find_conflicts
from svgtile.core.region import Region
from svgtile.engines.base import Context
from svgtile.engines.optimize.engine import fill_light
from svgtile.svg.reader import parse_exemplar


def scatter_tile():
    """An irregular tile of 14 dots and dashes (no rows, no lattice) on a 24 × 18 period."""
    rng = np.random.default_rng(3)
    sites = np.array([[2.0, 2.5], [7.5, 1.5], [13.0, 3.0], [19.0, 2.0], [4.0, 7.5], [10.0, 7.0],
                      [16.0, 8.5], [21.5, 7.0], [1.5, 12.5], [7.0, 13.0], [12.5, 12.0], [18.0, 14.0],
                      [22.5, 12.5], [9.5, 16.5]]) + rng.uniform(-0.4, 0.4, (14, 2))  # fmt: skip
    ex = parse_exemplar(tile(sites, (np.arange(14) % 3 == 0).astype(int)))
    return ex, analyze(ex)


def density(arr, ex, region) -> float:
    return float(footprint_areas(arr, ex.prototypes).sum() / region.area)


def test_a_light_refilled_texture_is_raised_to_rho_without_conflicts():
    ex, stats = scatter_tile()
    n, reps = len(ex.motifs), (6, 6)
    shift = (np.stack(np.meshgrid(np.arange(reps[0]), np.arange(reps[1])), -1).reshape(-1, 2) * [W, H])
    xy = (ex.motifs.xy[None] + shift[:, None]).reshape(-1, 2)
    full = Arrangement(np.tile(ex.motifs.kind, len(shift)), xy, np.tile(ex.motifs.angle, len(shift)),
                       np.tile(ex.motifs.scale, len(shift))).quantized(DECIMALS)  # fmt: skip
    region = Region.rectangle(reps[0] * W, reps[1] * H)
    assert len(full) == n * 36 and abs(density(full, ex, region) / stats.density - 1) < 0.02
    # every other motif gone from the middle four tiles' width: light windows there
    gone = (xy[:, 0] > W) & (xy[:, 0] < 5 * W) & (np.arange(len(xy)) % 2 == 0)
    light = full.take(~gone)
    assert density(light, ex, region) < 0.8 * stats.density
    ctx = Context(ex, stats, region, "centroid", key=11, progress=lambda stage, fraction: None)
    out = fill_light(light, ctx)
    assert density(out, ex, region) >= 0.9 * stats.density
    assert len(find_conflicts(out, ex.prototypes, stats.distance)) == 0  # no overlap, no rule violation
    again = fill_light(light, ctx)
    assert all(np.array_equal(getattr(again, f), getattr(out, f)) for f in ("kind", "xy", "angle", "scale"))
