"""Hole filling after the patch engine's density repair: the kinds a window lacks *by area*,
largest first, dropped into its empty places (issue 12).  Shared with the density windows
(:mod:`svgtile.engines.windows`) outside the patch engine so that another engine can use the same
implementation: the optimize engine (Ma, Wei & Tong 2011) loses the same large kinds at its
start's seams, but filling after its solver lowered its likeness too much to be its default
(measured, not merged: benchmarks/README.md, "optdens14"); it fills only a refilled texture that
is light as a whole (:func:`svgtile.engines.optimize.engine.fill_light`, "optfill").

Density repair (almeraj2013 §3.4, :func:`svgtile.engines.patch.density.adjust_density`) pastes
discs of the exemplar: an exemplar motif lands where the disc puts it or not at all.  On FGDC
scatter tiles — breccias and conglomerates whose large fragments are each drawn once, fields of
packed dashes — a pasted disc rarely fits whole around what the copies left, so windows stay at
half to four fifths of ρ, and what they lack is the large kinds: the start loses them where copies
meet, and the dots that fit anywhere are what comes back.  Density is the covered *area*, so a
window short of ρ is short of the area of some kinds; counted by motifs, the 2 % of fragments
that carry a third of 612's ink look like nothing.

:func:`fill_holes` runs only where density repair left a window wholly inside the region (at
the first offset) below ρ(1 − tolerance); it then fills every window below ρ, up to ρ (windows
partly outside the region measure its edge as much as the texture, and a small region's textures
are left as density repair made them).  Each round:

1. every window's *area deficit per kind* is the exemplar's covered area of that kind, scaled to
   the window, minus what the window holds;
2. sample points on a world-anchored grid (half the exemplar's mean spacing, each point jittered
   inside its cell by a hash of the cell) in the sparse windows are the candidate places; points
   inside a motif's inscribed disc are dropped at once;
3. each point proposes :data:`PROPOSALS` kinds drawn in proportion to the window's deficit, each
   in the orientation and scale of a random exemplar instance of that kind (so a kind's look is
   the exemplar's);
4. a proposal is kept if it lies inside the region and keeps the distance rule ``d_ij`` from the
   texture, or if the motifs it breaks the rule with are at most :data:`DISPLACE_MAX`, all of
   kinds its window holds more than its share of (by area), and together under
   :data:`DISPLACE_SHARE` of its area: then it displaces them (the dots that culling packed into
   the hole a fragment needs; almeraj2013 §3.4 lets an inserted element remove a few); of the
   proposals left, a conflict-free set is taken, the largest gain of area first;
5. per window and kind, proposals are added in that order while they do not exceed the kind's
   deficit (one motif over at most), and per window while their gain does not exceed the
   window's shortfall.

Every random choice is a hash of the run's key and integer world coordinates
(:mod:`svgtile.core.cellrng`), as in the rest of the engine.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import Stats, footprint_areas
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import cross_pairs, cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius
from svgtile.core.region import Region
from svgtile.engines.windows import (
    WINDOW_OFFSETS,
    region_windows,
    window_cover,
    window_of,
    window_size,
)

# hash streams (after density.py's six)
_JITTER, _KIND, _INSTANCE, _ORDER = range(6, 10)

#: Rounds of hole filling; each measures the windows again at the next of four half-window offsets.
ROUNDS = 4

#: Kinds proposed at each sample point (drawn by area deficit, with replacement).
PROPOSALS = 2

#: A proposal may displace at most this many motifs, of kinds its window holds too much of by
#: area, whose area together is below this share of its own (dots packed around the holes a
#: fragment needs: almeraj2013 §3.4's insertion "may remove a few elements").
DISPLACE_MAX, DISPLACE_SHARE = 5, 0.5

#: Windows below this fraction of ρ are filled (up to ρ) once the texture has one below ρ(1 − tol).
FILL_BELOW = 0.9

#: Sample points are this fraction of the exemplar's mean spacing apart.
STEP = 0.5


def sparse_windows(arr: Arrangement, exemplar: Exemplar, stats: Stats, region: Region,
                   offset: np.ndarray, areas: np.ndarray | None = None) -> tuple | None:  # fmt: skip
    """The exemplar-sized windows at ``offset`` (user units) and what their motifs cover
    (``areas``: the (n,) footprint areas of ``arr``, if known).

    Returns None if no window lies mostly in the region, else ``(origin, ids, area, covered,
    win)``: the windows' origin, their (w, 2) integer ids and (w,) area inside the region, the
    (w,) footprint area their motifs cover and the (n,) window of each motif (-1: none of them).
    """
    size = window_size(exemplar)
    windows = region_windows(region, size, offset)
    if windows is None:
        return None
    origin, ids, area = windows
    win, covered = window_cover(arr, exemplar.prototypes, origin, size, ids, areas)
    return origin, ids, area, covered, win


def fill_holes(
    arr: Arrangement, exemplar: Exemplar, stats: Stats, region: Region, boundary: str, *, key: int,
    tolerance: float, rounds: int = ROUNDS,
) -> Arrangement:  # fmt: skip
    """Fill the windows below ρ with the kinds they lack by area, if a window wholly inside the
    region is below ρ(1 − ``tolerance``).

    Parameters
    ----------
    arr : the texture after density repair, n motifs, no conflicts
    exemplar, stats : the exemplar and its analysis (ρ, ``d_ij``, kind frequencies)
    region, boundary : the output region and boundary mode (candidates are filtered by it)
    key : the run's root key (:mod:`svgtile.core.cellrng`)
    tolerance : a texture whose whole windows are within ρ(1 − tolerance) is left alone (the
        engine's density tolerance)
    rounds : at most this many rounds

    Returns
    -------
    Arrangement: the motifs of ``arr`` not displaced, in their order, then the motifs added
    (``arr`` itself when the texture is not sparse); no overlaps and no distance-rule violations.
    """
    size = window_size(exemplar)
    offsets = WINDOW_OFFSETS * size
    for rnd in range(rounds):
        areas = footprint_areas(arr, exemplar.prototypes)
        found = sparse_windows(arr, exemplar, stats, region, offsets[rnd % 4], areas)
        if found is None:
            if rnd == 0:  # no window at the first offset, none wholly inside: not sparse
                return arr
            continue
        _, _, area, covered, _ = found
        whole = area >= (1 - 1e-9) * size.prod()
        if rnd == 0 and not (whole & (covered < stats.density * (1 - tolerance) * area)).any():
            return arr  # density repair did its work: the texture as it left it
        new, removed = _round(arr, areas, exemplar, stats, region, boundary, found, key=key, rnd=rnd)
        if len(new):
            arr = Arrangement.concat([arr.take(~removed), new])
    return arr


def kind_targets(exemplar: Exemplar) -> np.ndarray:
    """(k,) covered area of each kind per unit area of the exemplar's region (sums to ρ)."""
    ex = exemplar.motifs
    per_kind = np.bincount(ex.kind, weights=footprint_areas(ex, exemplar.prototypes), minlength=len(exemplar.prototypes))
    return per_kind / exemplar.region.area


def _round(arr, areas, exemplar, stats, region, boundary, found, *, key: int, rnd: int) -> tuple[Arrangement, np.ndarray]:
    """One round of :func:`fill_holes` (steps 1–5 of the module's docstring): the motifs to add
    and the (n,) bool mask of the motifs of ``arr`` they displace; ``areas`` the (n,) footprint
    areas of ``arr``."""
    origin, ids, area, covered, win = found
    protos = exemplar.prototypes
    ex = exemplar.motifs
    k, size = len(protos), window_size(exemplar)
    sparse = covered < stats.density * FILL_BELOW * area
    # 1. area deficits, (w, k) and (w,)
    mine = win >= 0
    have = np.bincount(win[mine] * k + arr.kind[mine], weights=areas[mine], minlength=len(ids) * k).reshape(len(ids), k)
    target = kind_targets(exemplar)[None, :] * area[:, None]
    lack = np.maximum(target - have, 0.0)
    surplus = have - target  # > 0: too much
    short = np.where(sparse, stats.density * area - covered, 0.0)
    if not sparse.any():
        return arr.take(np.zeros(0, dtype=np.int64)), np.zeros(len(arr), dtype=bool)

    # 2. jittered world grid points in the sparse windows
    step = STEP * math.sqrt(exemplar.region.area / max(len(ex), 1))
    span = np.ceil(size / step).astype(np.int64) + 1  # grid cells across a window, with its edges
    first = np.floor((origin + ids[sparse] * size) / step).astype(np.int64)  # (s, 2)
    di, dj = (v.ravel() for v in np.meshgrid(np.arange(span[0]), np.arange(span[1])))
    cells = np.unique((first[:, None, :] + np.stack([di, dj], -1)[None, :, :]).reshape(-1, 2), axis=0)
    gi, gj = cells[:, 0], cells[:, 1]
    u = cellrng.uniform(key, _JITTER, gi[:, None], gj[:, None], rnd, np.arange(2)[None, :])
    pts = (cells + u) * step
    w_of = window_of(pts, origin, size, ids)
    ok = w_of >= 0
    ok[ok] = sparse[w_of[ok]] & (lack[w_of[ok]].sum(axis=1) > 0)
    ok &= shapely.contains_xy(region.shape, pts[:, 0], pts[:, 1])
    if len(arr):
        tree = cKDTree(arr.xy, balanced_tree=False, compact_nodes=False)
        inner = motif_radius(arr, protos, inner=True)
        d, m = tree.query(pts, k=1, workers=-1)
        ok &= d >= inner[m]  # not inside a motif
    else:
        tree = None
    pts, w_of, gi, gj = pts[ok], w_of[ok], gi[ok], gj[ok]
    if not len(pts):
        return arr.take(np.zeros(0, dtype=np.int64)), np.zeros(len(arr), dtype=bool)

    # 3. proposals: kinds by area deficit, each an exemplar instance's look
    p = np.repeat(np.arange(len(pts)), PROPOSALS)
    c = np.tile(np.arange(PROPOSALS), len(pts))
    cdf = np.cumsum(lack[w_of], axis=1)
    cdf /= cdf[:, -1:]
    draw = cellrng.uniform(key, _KIND, gi[p], gj[p], rnd, c)
    kind = np.minimum((draw[:, None] >= cdf[p]).sum(axis=1), k - 1)
    by_kind = np.argsort(ex.kind, kind="stable")
    first, count = np.searchsorted(ex.kind[by_kind], kind), np.bincount(ex.kind, minlength=k)[kind]
    pick = by_kind[first + (cellrng.uniform(key, _INSTANCE, gi[p], gj[p], rnd, c) * count).astype(np.int64) % count]
    new = Arrangement(kind, pts[p], ex.angle[pick], ex.scale[pick]).quantized(DECIMALS)
    w_new = w_of[p]

    # 4. the proposals that keep the rule against the texture and lie in the region, or that
    # displace a few motifs of kinds their window holds too much of (by area) and together
    # smaller than half of it; then a conflict-free set of them, the largest gain first
    none = np.zeros(len(arr), dtype=bool)
    good = region.keep(new, protos, boundary)
    new, w_new, gi_n, gj_n, c_n = new.take(good), w_new[good], gi[p][good], gj[p][good], c[good]
    a = footprint_areas(new, protos)
    cost = np.zeros(len(new))
    hit_a = hit_b = np.zeros(0, dtype=np.int64)
    if tree is not None and len(new):
        # a shortcut that changes nothing: proposals whose inscribed disc already overlaps that
        # of more than DISPLACE_MAX motifs, of one the window cannot spare, or of motifs of half
        # its area cannot be kept, and are dropped before the exact (costly) pairs are found
        surely = _surely_blocked(new, a, arr, areas, inner, tree, protos, win, surplus)
        new, w_new, gi_n, gj_n, c_n, a = (new.take(~surely), w_new[~surely], gi_n[~surely], gj_n[~surely],
                                          c_n[~surely], a[~surely])  # fmt: skip
        # the motifs each proposal breaks the rule with; a proposal that some of them already
        # reject (more than DISPLACE_MAX, one unspared, or too large) needs no more exact tests
        dead = np.zeros(len(new), dtype=bool)

        def hopeless(ha, hb):
            dead[:] |= _displacing(ha, hb, len(new), a, arr, areas, win, surplus, 1.0 + 1e-9)[0]
            return dead

        hit_a, hit_b = cross_pairs(new, arr, protos, stats.distance, tree, hopeless=hopeless)
        rejected, cost = _displacing(hit_a, hit_b, len(new), a, arr, areas, win, surplus)
        ok = ~rejected & ~dead
        keep_at = np.flatnonzero(ok)
        remap = np.full(len(new), -1)
        remap[keep_at] = np.arange(len(keep_at))
        sel = ok[hit_a]
        hit_a, hit_b = remap[hit_a[sel]], hit_b[sel]
        new, w_new, gi_n, gj_n, c_n, a, cost = (new.take(keep_at), w_new[keep_at], gi_n[keep_at], gj_n[keep_at],
                                                c_n[keep_at], a[keep_at], cost[keep_at])  # fmt: skip
    if not len(new):
        return new, none
    jitter = cellrng.uniform(key, _ORDER, gi_n, gj_n, rnd, c_n)
    priority = -(a - cost) * (1.0 + 0.01 * jitter)  # lower is kept first: the largest gain
    keep = cull(len(new), find_conflicts(new, protos, stats.distance), priority)

    # 5. per window and kind, largest first, up to the kind's deficit; per window up to its own
    idx = np.flatnonzero(keep)
    idx = idx[np.lexsort((priority[idx], new.kind[idx], w_new[idx]))]
    slot = w_new[idx] * k + new.kind[idx]
    take = _cumsum_within(a[idx], slot) - a[idx] < lack.ravel()[slot]
    idx = idx[take]
    idx = idx[np.lexsort((priority[idx], w_new[idx]))]  # the largest gain first within each window
    gain = a[idx] - cost[idx]
    idx = idx[_cumsum_within(gain, w_new[idx]) - gain < short[w_new[idx]]]
    taken = np.zeros(len(new), dtype=bool)
    taken[idx] = True
    removed = none.copy()
    removed[hit_b[taken[hit_a]]] = True
    return new.take(np.flatnonzero(taken)), removed


def _surely_blocked(new, a, arr, areas, inner_old, tree, protos, win, surplus) -> np.ndarray:
    """(m,) bool: proposals that step 4 of :func:`fill_holes` would surely reject, by inscribed
    discs alone (two overlapping inscribed discs are two overlapping footprints); ``areas`` and
    ``inner_old`` the (n,) footprint areas and inscribed radii of ``arr``."""
    k = min(DISPLACE_MAX + 1, len(arr))
    d, idx = tree.query(new.xy, k=k, workers=-1)
    d, idx = d.reshape(len(new), k), idx.reshape(len(new), k)
    inner_new = motif_radius(new, protos, inner=True)
    hit = (d < inner_new[:, None] + inner_old[idx]) & (inner_new[:, None] > 0) & (inner_old[idx] > 0)
    spare = (win[idx] >= 0) & (surplus[np.maximum(win[idx], 0), arr.kind[idx]] > 0)
    many = hit.sum(axis=1) > DISPLACE_MAX
    unspared = (hit & ~spare).any(axis=1)
    costly = (hit * areas[idx]).sum(axis=1) >= DISPLACE_SHARE * a
    return many | unspared | costly


def _displacing(hit_a, hit_b, m, a, arr, areas, win, surplus, over: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Step 4's test of the m proposals against the motifs they break the rule with, pairs
    ``(hit_a, hit_b)`` (proposal, motif of ``arr``): (m,) bool rejected — more than
    :data:`DISPLACE_MAX` of them, one of a kind its window cannot spare, or together at least
    :data:`DISPLACE_SHARE` × ``over`` of the proposal's area ``a`` (m,) — and (m,) their area.
    On a subset of a proposal's pairs, a rejection (``over`` a little above 1, against the
    rounding of the sums) holds for all of them."""
    spare = (win[hit_b] >= 0) & (surplus[np.maximum(win[hit_b], 0), arr.kind[hit_b]] > 0)
    count = np.bincount(hit_a, minlength=m)
    cost = np.bincount(hit_a, weights=areas[hit_b], minlength=m)
    unspared = np.bincount(hit_a, weights=~spare, minlength=m)
    ok = (count == 0) | ((count <= DISPLACE_MAX) & (unspared == 0) & (cost < DISPLACE_SHARE * over * a))
    return ~ok, cost


def _cumsum_within(values: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """(n,) running sum of ``values`` within runs of equal, sorted ``labels`` (inclusive)."""
    if not len(values):
        return values
    csum = np.cumsum(values)
    starts = np.r_[0, np.flatnonzero(np.diff(labels)) + 1]
    base = np.repeat(csum[starts] - values[starts], np.diff(np.r_[starts, len(labels)]))
    return csum - base
