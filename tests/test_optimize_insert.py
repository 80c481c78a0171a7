"""Insertion capped at the exemplar's density (issue 14; Ma, Wei & Tong 2011 §4.1, :mod:`svgtile.engines.optimize.insert`).

The neighbourhoods predict where elements are missing; the cap says how many may be added: in
world-anchored windows, only while the window's covered fraction is below ρ.  Known answers on a
square lattice of dots (ρ = one dot per 36 square units): a full lattice takes nothing however
many places are proposed, a lattice with holes takes as many as it lacks, the best-ranked first.
"""

from __future__ import annotations

import numpy as np
import pytest
from test_optimize_period import H, W, tile

from svgtile import analyze
from svgtile.analysis.stats import footprint_areas
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.region import Region
from svgtile.engines.optimize.insert import capped
from svgtile.svg.reader import parse_exemplar

STEP, N = 6.0, 12  # the lattice's step, user units, and sites per side of the output
WINDOW = 3 * STEP  # the cap's windows: 3 × 3 sites, 16 of them over the output
ALONG, ACROSS = np.array([STEP / 2, 0.0]), np.array([0.0, STEP / 2])  # half a step, user units


def lattice():
    """The exemplar (a 4 × 3 lattice of dots of step 6 on a 24 × 18 tile), its analysis, and
    the output's sites: the lattice over a 72 × 72 square, (144, 2)."""
    sites = (np.stack(np.meshgrid(np.arange(4), np.arange(3)), -1).reshape(-1, 2) + 0.5) * STEP
    ex = parse_exemplar(tile(sites * [W / 24, H / 18], np.zeros(12, int)).replace("#dash", "#dot"))
    g = (np.arange(N) + 0.5) * STEP
    return ex, analyze(ex), np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)


def dots(xy: np.ndarray) -> Arrangement:
    n = len(xy)
    return Arrangement(np.zeros(n, int), xy, np.zeros(n), np.ones(n)).quantized(DECIMALS)


def window_of(xy: np.ndarray) -> np.ndarray:
    return np.floor(xy / WINDOW).astype(int) @ [1, 1000]


def test_a_full_lattice_takes_nothing_however_much_is_proposed():
    """Every window of the full lattice is at ρ: the middles of its rows and columns (what an
    uncapped insertion of rows tighter than the exemplar's would add) are all refused."""
    ex, stats, full = lattice()
    assert stats.density == pytest.approx(footprint_areas(dots(full), ex.prototypes).sum() / (N * STEP) ** 2)
    mids = np.r_[full + ALONG, full + ACROSS]
    mids = mids[(mids < N * STEP).all(axis=1)]
    taken = capped(dots(full), dots(mids), np.arange(len(mids), dtype=float), ex, stats,
                   Region.rectangle(N * STEP, N * STEP), window=WINDOW)  # fmt: skip
    assert len(mids) > 200 and not taken.any()


def test_holes_are_filled_up_to_rho_the_best_ranked_first():
    """A lattice with 7 sites emptied (two in one window) and 300 proposals — the holes, ranked
    first, and the middles of the rows, ranked below — takes exactly the holes: each window
    gets what it lacks and not one motif more."""
    ex, stats, full = lattice()
    holes = np.array([3 * N + 3, 3 * N + 4, 3 * N + 8, 6 * N + 5, 8 * N + 2, 8 * N + 9, 10 * N + 6])
    arr = dots(np.delete(full, holes, axis=0))
    mids = full + ALONG
    mids = mids[mids[:, 0] < N * STEP]
    new = dots(np.r_[full[holes], mids])
    rank = np.r_[np.full(len(holes), 1000.0) + np.arange(len(holes)), np.arange(len(mids), dtype=float)]
    region = Region.rectangle(N * STEP, N * STEP)
    taken = capped(arr, new, rank, ex, stats, region, window=WINDOW)
    assert taken[: len(holes)].all() and not taken[len(holes):].any()
    # ranked the other way round, each window still takes as many as it lacks, now of the middles
    taken = capped(arr, new, -rank, ex, stats, region, window=WINDOW)
    lack = np.bincount(np.unique(window_of(full[holes]), return_inverse=True)[1].ravel())
    got = [taken[window_of(new.xy) == w].sum() for w in np.unique(window_of(full[holes]))]
    assert got == list(lack) and taken.sum() == len(holes)


def test_the_cap_at_a_place_does_not_depend_on_how_far_the_region_extends():
    """World-anchored windows: growing the region leaves the decisions inside the old one as
    they were (the engine contract's edit stability)."""
    ex, stats, full = lattice()
    rng = np.random.default_rng(3)
    keep = rng.random(len(full)) > 0.2
    arr = dots(full[keep])
    holes = np.repeat(full[~keep], 2, axis=0)  # each hole proposed twice: the cap takes about half
    new = dots(holes + rng.uniform(-1, 1, holes.shape))
    rank = rng.random(len(new))
    small = capped(arr, new, rank, ex, stats, Region.rectangle(N * STEP, N * STEP), window=WINDOW)
    shifted = arr.xy + 4 * WINDOW * np.array([1.0, 0.0])  # the lattice again, to the right: a region twice as wide
    both = Arrangement.concat([arr, dots(shifted)])
    wide = capped(both, Arrangement.concat([new, dots(new.xy + 4 * WINDOW * np.array([1.0, 0.0]))]), np.r_[rank, rank], ex, stats,
                  Region.rectangle(2 * N * STEP, N * STEP), window=WINDOW)  # fmt: skip
    assert 0 < small.sum() < len(new)
    assert np.array_equal(wide[: len(new)], small)
