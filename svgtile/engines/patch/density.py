"""Density repair of the patch engine (almeraj2013 §3.4): windows the size of the input region
brought to the exemplar's density ρ by random removal, or by pasting discs of the exemplar.

See :mod:`svgtile.engines.patch.engine` for the engine and the deviations from the paper.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import (
    Stats,
    footprint_areas,
)
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import (
    cross_conflicts,
    cross_pairs,
    cull,
    discs_close,
    find_conflicts,
    slack,
)
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius, rotation
from svgtile.core.region import Region
from svgtile.engines.base import Progress
from svgtile.engines.patch.orientation import turn, vary_orientations
from svgtile.engines.windows import (
    WINDOW_OFFSETS,
    region_windows,
    window_cover,
    window_of,
    window_size,
)

# hash streams: one per independent random choice of the engine
_ROTATE, _PRIORITY, _ORIENT, _DISC, _DISC_ROTATE, _REMOVE = range(6)

#: How strongly density thinning favours removing kinds the texture has too many of.
KIND_BALANCE = 4.0

#: How strongly density filling favours kinds the window lacks (against chance, which weighs 1).
LACK_WEIGHT = 3.0

#: At most this many motifs may be displaced by one motif of a lacking kind (§3.4 insertion).
DISPLACE_MAX = 5

#: A density-repair round adds no more motifs of a kind to a window than keep it within this
#: fraction above its exemplar frequency there (§3.4).
KIND_CAP = 0.05

#: The roomiest spot for a lacking kind is refined around this many samples per window, on a grid
#: this many times finer (:func:`_roomiest`).
REFINE_KEEP, REFINE = 3, 4

#: … after the room is measured only at the samples (this many per window) where the nearest motif
#: leaves the most (:func:`_roomiest`).
SCREEN = 24

#: The roomiest-spot search measures this many of the screened samples per window first
#: (:func:`_roomiest`, ``lazy``).
LAZY_FIRST = 6

#: Empty discs and room are searched on a grid of this many × this many samples per window.
SAMPLES = 12

#: The empty-disc search bounds every sample by its nearest motif and measures this many of the
#: most promising per window first (:func:`_largest_empty_discs`).
LED_FIRST = 8


# ----------------------------------------------------------------------------- §3.4


def adjust_density(
    arr: Arrangement, exemplar: Exemplar, stats: Stats, region: Region, p, boundary: str, *,
    key: int, progress: Progress, rules: Sequence[np.ndarray] = (),
) -> Arrangement:  # fmt: skip
    """Bring every exemplar-sized window to density ρ (almeraj2013 §3.4).

    Windows the size of the input region's bounding box tile the plane from the world origin,
    shifted by half a window every other round.  A window denser than ρ(1 + tol) loses random
    motifs (rule violators and motifs of over-represented kinds first) until it is just above ρ;
    a window sparser than ρ(1 − tol) receives the motifs of a disc of the exemplar, congruent to
    the window's largest empty disc and placed at random over the exemplar, if they break neither
    the overlap nor the distance rule.  Rounds stop when all windows are within tolerance for a
    full cycle of offsets, or after ``p.density_rounds`` rounds.

    ``rules`` are (k, k) distances (user units) pasted motifs keep from the texture, used in equal
    shares of the rounds in turn (default: ``d_ij`` throughout).  The patch engine passes the
    junction rule relaxed step by step to ``d_ij`` (:func:`svgtile.analysis.stats.junction_distance`):
    holes too small for one step are filled at the next.
    """
    rules = list(rules) or [stats.distance]
    size = window_size(exemplar)
    offsets = WINDOW_OFFSETS * size
    protos = exemplar.prototypes
    quiet = 0
    for rnd in range(p.density_rounds):
        progress("density", 0.3 + 0.7 * rnd / p.density_rounds)
        windows = region_windows(region, size, offsets[rnd % 4])
        if windows is None:
            break
        origin, ids, area = windows
        win, covered = window_cover(arr, protos, origin, size, ids)
        density = covered / area
        dense = density > stats.density * (1 + p.density_tolerance)
        sparse = density < stats.density * (1 - p.density_tolerance)
        if not dense.any() and not sparse.any():
            quiet += 1
            if quiet >= 4:
                break
            continue
        quiet = 0
        if dense.any():
            arr = arr.take(_thin(arr, win, dense, area * stats.density, stats, protos, key=key, rnd=rnd))
        if sparse.any():
            win, covered = window_cover(arr, protos, origin, size, ids)
            deficit = (stats.density * area - covered)[sparse]
            rule = rules[min(len(rules) - 1, len(rules) * rnd // p.density_rounds)]
            new, removed = _fill(
                arr, exemplar, stats, region, p, boundary, origin, size, ids[sparse], deficit, key=key, rnd=rnd,
                rule=rule,
            )
            arr = Arrangement.concat([arr.take(~removed), new])
    return arr


def _thin(arr, win, dense, target, stats, protos, *, key: int, rnd: int) -> np.ndarray:
    """Remove random motifs from dense windows until each is just above its target area.

    Returns the (n,) mask of motifs kept.
    """
    area = footprint_areas(arr, protos)
    cand = np.flatnonzero((win >= 0) & dense[np.maximum(win, 0)])
    # weighted random order (Efraimidis & Spirakis 2006): kinds over-represented against the
    # exemplar's frequencies are removed first, which repairs the kind mix culling skewed
    freq = np.bincount(arr.kind, minlength=len(protos)) / max(len(arr), 1)
    weight = (np.maximum(freq, 1e-9) / np.maximum(stats.frequency, 1e-9)) ** KIND_BALANCE
    u = cellrng.uniform(key, _REMOVE, rnd, _cell_key(arr.xy[cand]))
    rank = np.log(np.maximum(u, 1e-300)) / weight[arr.kind[cand]]
    order = np.lexsort((-rank, win[cand]))  # per window, highest rank first
    cand = cand[order]
    w = win[cand]
    covered = np.bincount(w, weights=area[cand], minlength=len(dense))
    starts = np.r_[0, np.flatnonzero(np.diff(w)) + 1]
    csum = np.cumsum(area[cand])
    removed = csum - np.repeat(csum[starts] - area[cand][starts], np.diff(np.r_[starts, len(w)]))
    remove = covered[w] - removed >= target[w]  # a prefix of each window: stops just above ρ
    keep = np.ones(len(arr), dtype=bool)
    keep[cand[remove]] = False
    return keep


def _cell_key(xy: np.ndarray) -> np.ndarray:
    """A world-anchored integer per position (to derive per-motif randomness from)."""
    q = np.round(xy * 1e3).astype(np.int64)
    return q[:, 0] * np.int64(0x1F3D5B79) ^ q[:, 1]


def _fill(arr, exemplar, stats, region, p, boundary, origin, size, ids, deficit, *, key: int, rnd: int, rule: np.ndarray):
    """The motifs to insert into each sparse window (almeraj2013 §3.4, "too sparse").

    For each window, the largest empty disc is found and a congruent disc is placed at random
    over the exemplar, as in the paper; the exemplar is then superimposed so that the two discs
    coincide (turned by θ ~ U[−M, M], motifs turned as for the grid copies, :func:`turn`).  Its
    motifs inside the window are the candidates: those in the empty disc first (the paper's
    insertion), then the rest, which fill the window's smaller holes in the same pass.  A
    candidate is rejected if it would overlap the texture or come closer to it than ``rule``
    (motif by motif, so one bad motif at the rim does not waste the whole disc); of the rest, a
    conflict-free set is taken, favouring kinds the window lacks, until the window's ``deficit``
    of footprint area is met, and no kind beyond its share of the window (:data:`KIND_CAP`).
    ``p.disc_tries`` placements are tried per window; every other one is centred on a motif of
    the kind the window lacks most and pasted where that kind has the most room
    (:func:`_roomiest`); it may displace a few motifs (see :func:`_displacement`).  Candidates
    of different placements are held to ``rule`` too, those of one placement to ``d_ij``.
    Kinds are counted per window, so a far edit does not change what a window receives (thinning
    and §3.3's kind balancing still count over the whole texture).

    Returns
    -------
    new : Arrangement of the motifs to insert
    removed : (len(arr),) bool, the motifs they displace
    """
    protos = exemplar.prototypes
    tree = cKDTree(arr.xy, balanced_tree=False, compact_nodes=False) if len(arr) else None
    centre, radius, nearest = _largest_empty_discs(arr, tree, protos, region, origin, size, ids)

    ex = exemplar.motifs
    x0, y0, x1, y1 = exemplar.region.bounds
    wins, tries = len(ids), p.disc_tries
    wid = np.repeat(np.arange(wins), tries)
    tid = np.tile(np.arange(tries), wins)
    u = cellrng.uniform(key, _DISC, rnd, ids[wid, 0, None], ids[wid, 1, None], tid[:, None], np.arange(2)[None, :])
    r = np.minimum(radius[wid, None], np.array([(x1 - x0) / 2, (y1 - y0) / 2]))
    source = np.array([x0, y0]) + r + u * (np.array([x1 - x0, y1 - y0]) - 2 * r)  # disc centres over the exemplar
    # every other try centres the exemplar on a motif of the kind the window lacks most, placed
    # where that kind has the most room (usually the largest kind, the hardest to place); each
    # window counts its own kinds, so a far edit does not change its choice
    k = len(protos)
    mine = window_of(arr.xy, origin, size, ids)
    have = np.bincount(mine[mine >= 0] * k + arr.kind[mine >= 0], minlength=wins * k).reshape(wins, k)
    freq = (have + stats.frequency) / (have.sum(axis=1, keepdims=True) + 1.0)  # one motif of prior
    lack = np.log(np.maximum(freq, 1e-6) / np.maximum(stats.frequency, 1e-6))  # (windows, k)
    want = np.argmin(np.where(stats.frequency > 0, lack, np.inf), axis=1)  # (windows,)
    by_kind = np.argsort(ex.kind, kind="stable")
    first, count = np.searchsorted(ex.kind[by_kind], want), np.bincount(ex.kind, minlength=k)[want]
    pick = by_kind[first[wid] + (u[:, 0] * count[wid]).astype(np.int64) % count[wid]]
    odd = tid % 2 == 1
    source = np.where(odd[:, None], ex.xy[pick], source)
    spot, room = _roomiest(arr, tree, protos, region, origin, size, ids, want, rule, ex, nearest=nearest)
    centre = np.where(odd[:, None], spot[wid], centre[wid])  # (tries, 2): where each try is pasted
    radius = np.where(odd, room[wid], radius[wid])
    theta = p.max_rotation * (2 * cellrng.uniform(key, _DISC_ROTATE, rnd, ids[wid, 0], ids[wid, 1], tid) - 1)

    # every exemplar motif of every placement, (tries, m, 2), the rotation broadcast over the
    # motifs (not gathered per motif); then those whose centroid falls in the window, in
    # (try, motif) order
    offset = np.matmul(rotation(theta)[:, None], (ex.xy[None, :, :] - source[:, None, :])[..., None])[..., 0]
    xy = centre[:, None, :] + offset
    lo = (origin + ids[wid] * size)[:, None, :]
    t_of, e_of = np.nonzero(((xy >= lo) & (xy < lo + size)).all(axis=2))
    xy = xy[t_of, e_of]
    angle = turn(ex.kind[e_of], ex.angle[e_of], theta[t_of], stats)
    new = Arrangement(ex.kind[e_of], xy, angle, ex.scale[e_of]).quantized(DECIMALS)
    if p.vary_orientation:
        new = vary_orientations(new, stats, cellrng.uniform(key, _ORIENT, rnd, _cell_key(new.xy)))
    if len(new) == 0:
        return new, np.zeros(len(arr), dtype=bool)
    in_disc = np.hypot(*(new.xy - centre[t_of]).T) <= radius[t_of]
    if tree is not None:  # most candidates land on a motif: the nearest centroid tells, cheaply
        inner = np.array([pr.inner for pr in protos])
        # no clash is possible beyond the widest rule plus two of the largest inscribed radii: the
        # search stops there (a motif not found there gets idx = len(arr) and is no clash)
        reach = max(float(rule.max()), 0.0) + float(inner.max()) * (float(new.scale.max()) + float(arr.scale.max()))
        near, idx = tree.query(new.xy, k=1, distance_upper_bound=reach, workers=-1)
        found = idx < len(arr)
        idx = np.where(found, idx, 0)
        a_in, b_in = inner[new.kind] * new.scale, inner[arr.kind[idx]] * arr.scale[idx]
        bound = near - a_in - b_in  # footprint distance is at most this when both radii > 0
        clash = found & (a_in > 0) & (b_in > 0) & (bound < np.maximum(rule[new.kind, arr.kind[idx]], 0))
        clash &= ~in_disc  # those may still displace (see _displacement)
        # thin or concave kinds (tufts, dashes) have tiny inscribed radii: a few discs along their
        # strokes (svgtile.core.discs) show most of the rest too close to that nearest motif,
        # which is cross_conflicts' own first test on the pair (same rule, slack and margin)
        rest = np.flatnonzero(found & ~clash & ~in_disc)
        if len(rest):
            pair_rule = np.maximum(rule[new.kind[rest], arr.kind[idx[rest]]] - slack(protos), 0.0)
            clash[rest[discs_close(new, arr, protos, rest, idx[rest], pair_rule)]] = True
        new, t_of, in_disc = new.take(~clash), t_of[~clash], in_disc[~clash]
    free = ~cross_conflicts(new, arr, protos, rule, tree)
    inside = region.keep(new, protos, boundary)
    candidate = in_disc & ~free & inside & odd[t_of]
    displace, victim_of = _displacement(new, arr, rule, protos, tree, lack, candidate, wid[t_of])
    ok = (free & inside) | displace

    # a conflict-free subset: displacing motifs, then motifs of the empty disc, then kinds the
    # window lacks
    orig = np.flatnonzero(ok)
    new, t_of, in_disc, displace = new.take(ok), t_of[ok], in_disc[ok], displace[ok]
    score = (
        cellrng.uniform(key, _PRIORITY, rnd, _cell_key(new.xy))
        + LACK_WEIGHT * (np.clip(lack[wid[t_of], new.kind], -1, 1) - 2.0 * in_disc)
        - 8.0 * LACK_WEIGHT * displace
    )
    keep = cull(len(new), find_conflicts(new, protos, stats.distance, group=t_of, junction=rule), score)
    new, score, w, orig, displace = new.take(keep), score[keep], wid[t_of[keep]], orig[keep], displace[keep]

    # per window, in score order, until its deficit of covered area is met
    order = np.lexsort((score, w))
    new, w, orig, displace, score = new.take(order), w[order], orig[order], displace[order], score[order]
    area = footprint_areas(new, protos)
    csum = np.cumsum(area)
    starts = np.r_[0, np.flatnonzero(np.diff(w)) + 1] if len(w) else np.zeros(0, np.int64)
    before = csum - area - np.repeat(csum[starts] - area[starts], np.diff(np.r_[starts, len(w)]))
    take = (before < deficit[w]) | displace
    # no kind beyond its share in its window: small kinds fit every hole, and would stand in for the
    # large (counted per window, like the lacking kind above)
    added = np.flatnonzero(take & ~displace)
    total = have.sum(axis=1) + np.bincount(w[added], minlength=len(ids))
    room_for = np.ceil(stats.frequency[None, :] * total[:, None] * (1 + KIND_CAP)) - have  # (windows, k)
    added = added[np.argsort(score[added], kind="stable")]  # the best of each kind first
    slot = w[added] * k + new.kind[added]
    take[added[_rank_within(slot) >= room_for.ravel()[slot]]] = False
    removed = np.isin(victim_of, orig[take & displace]) & (victim_of >= 0)
    return new.take(take), removed


def _displacement(new, arr, rule, protos, tree, lack, candidate, window):
    """Which candidates may take their place by removing the few motifs in their way.

    A kind hard to place (large, with wide distances) finds no empty disc big enough once
    culling has packed the small kinds around it, so the texture lacks it for good.  A candidate
    of the kind its window lacks most, centred where that kind has the most room, may displace up
    to DISPLACE_MAX conflicting motifs of kinds the window has enough of and whose area together is
    smaller than its own — one per window and round.

    Returns
    -------
    displace : (len(new),) bool, the candidates that displace
    victim_of : (len(arr),) int, the candidate displacing each motif, or -1
    """
    displace = np.zeros(len(new), dtype=bool)
    victim_of = np.full(len(arr), -1, dtype=np.int64)
    idx = np.flatnonzero(candidate)
    if len(idx) == 0:
        return displace, victim_of
    area_new = footprint_areas(new, protos)[idx]
    area_old = footprint_areas(arr, protos)

    def unfit(a, b, over=1.0):
        """(len(idx),) bool: too many motifs in the way, too large, or of a scarce kind — on a
        subset of a candidate's pairs too (``over`` a little above 1, against rounding)."""
        count = np.bincount(a, minlength=len(idx))
        cost = np.bincount(a, weights=area_old[b], minlength=len(idx))
        scarce = np.bincount(a, weights=(lack[window[idx[a]], arr.kind[b]] < 0).astype(float), minlength=len(idx))
        return (count > DISPLACE_MAX) | (cost >= area_new * over) | (scarce != 0), count

    # a candidate the pairs known so far already rule out needs no more exact tests
    dead = np.zeros(len(idx), dtype=bool)

    def hopeless(a, b):
        dead[:] |= unfit(a, b, 1.0 + 1e-9)[0]
        return dead

    a, b = cross_pairs(new.take(idx), arr, protos, rule, tree, hopeless=hopeless)
    bad, count = unfit(a, b)
    good = ~bad & (count > 0) & ~dead
    # one per window: the first good candidate; and no motif displaced twice
    first = np.full(window.max() + 1, -1)
    for c in idx[good][::-1]:  # a loop over windows' few candidates, not over motifs
        first[window[c]] = c
    chosen = first[first >= 0]
    local = {int(c): k for k, c in enumerate(idx)}
    sel = np.isin(a, [local[int(c)] for c in chosen])
    owners = np.unique(a[sel])
    for k in owners:
        victims = b[a == k]
        if (victim_of[victims] >= 0).any():
            continue
        victim_of[victims] = idx[k]
        displace[idx[k]] = True
    return displace, victim_of


def _largest_empty_discs(arr, tree, protos, region: Region, origin, size, ids, samples: int = SAMPLES):
    """Centre and radius of (approximately) the largest empty disc in each window.

    Each window is sampled on a ``samples × samples`` grid; a sample's clearance is a lower bound
    of its distance to every footprint (distance to the nearest centroids minus their bounding
    radius, and the window's edges), so the returned disc is empty.

    Returns
    -------
    centre : (w, 2) float array, user units
    radius : (w,) float array, ≥ 0
    nearest : the samples' nearest motif and whether each lies in the region, ``(d, m, inside)``
        each (w·samples²,) in the order :func:`_roomiest` samples them (``d``, ``m`` None for an
        empty texture) — one neighbour query serves both searches
    """
    g = (np.arange(samples) + 0.5) / samples
    gx, gy = (v.ravel() for v in np.meshgrid(g, g))
    lo = origin + ids * size  # (w, 2)
    pts = lo[:, None, :] + np.stack([gx, gy], -1)[None, :, :] * size  # (w, s, 2)
    pts = pts.reshape(-1, 2)
    owner = np.repeat(np.arange(len(ids)), len(gx))
    edge = np.minimum(
        np.minimum(pts[:, 0] - lo[owner, 0], lo[owner, 0] + size[0] - pts[:, 0]),
        np.minimum(pts[:, 1] - lo[owner, 1], lo[owner, 1] + size[1] - pts[:, 1]),
    )
    inside = shapely.contains_xy(region.shape, pts[:, 0], pts[:, 1])
    if not len(arr):
        clear = np.where(inside, edge, -np.inf)
        best = _best_per_owner(clear, owner)
        return pts[best], np.maximum(clear[best], 0.0), (None, None, inside)
    radius = motif_radius(arr, protos)
    k = min(6, len(arr))

    def exact(at):
        dist, idx = tree.query(pts[at], k=k, workers=-1)
        dist, idx = dist.reshape(len(at), k), idx.reshape(len(at), k)
        return np.minimum(edge[at], np.minimum((dist - radius[idx]).min(axis=1), dist[:, -1] - radius.max()))

    # the nearest motif alone bounds a sample's clearance from above; the bound over k neighbours
    # is computed only where that upper bound can still reach the window's best (ties included),
    # which gives the same discs as computing it at every sample
    d1, m1 = tree.query(pts, k=1, workers=-1)
    upper = np.where(inside, np.minimum(edge, d1 - radius[m1]), -np.inf)
    clear = np.full(len(pts), -np.inf)
    per = len(gx)
    first = np.argsort(-upper.reshape(len(ids), per), axis=1, kind="stable")[:, :LED_FIRST]
    first = (first + (np.arange(len(ids)) * per)[:, None]).ravel()
    first = first[inside[first]]
    clear[first] = exact(first)
    top = np.full(len(ids), -np.inf)
    np.maximum.at(top, owner[first], clear[first])
    done = np.zeros(len(pts), dtype=bool)
    done[first] = True
    rest = np.flatnonzero(~done & inside & (upper >= top[owner]))
    if len(rest):
        clear[rest] = exact(rest)
    best = _best_per_owner(clear, owner)
    return pts[best], np.maximum(clear[best], 0.0), (d1, m1, inside)


def _best_per_owner(value: np.ndarray, owner: np.ndarray) -> np.ndarray:
    """Index of the largest ``value`` of each owner present (the last of ties), by owner.

    ``value`` must hold no NaN.  Two scatter-maxima instead of a sort of every sample.
    """
    present, inv = np.unique(owner, return_inverse=True)
    top = np.full(len(present), -np.inf)
    np.maximum.at(top, inv, value)
    tied = np.flatnonzero(value == top[inv])
    best = np.full(len(present), -1, dtype=np.int64)
    np.maximum.at(best, inv[tied], tied)
    return best


def _rank_within(labels: np.ndarray) -> np.ndarray:
    """(n,) int: how many earlier entries share each entry's label (0 for the first of each)."""
    order = np.argsort(labels, kind="stable")
    rank = np.empty(len(labels), dtype=np.int64)
    rank[order] = np.arange(len(labels)) - np.searchsorted(labels[order], labels[order])
    return rank


def _roomiest(arr, tree, protos, region: Region, origin, size, ids, kind, rule, ex, samples: int = SAMPLES, *,
              nearest=None, lazy: bool = True):  # fmt: skip
    """Per window, the point where a motif of ``kind[window]`` has the most room under ``rule``.

    The largest empty disc (§3.4) is where a small motif fits best, not a large one with wide
    distances: a motif of kind L at p keeps ``rule`` from every motif m if
    ``|p − x_m| − r_m − r_L ≥ rule[L, kind m]`` (bounding radii: a lower bound of the footprint
    distance), so its room at p is the smallest left-hand minus right-hand side.  The nearest
    motif of each kind is found in that kind's own k-d tree (the nearest motif overall may not
    be the binding one) and taken at the kind's largest radius.  Each window is sampled on a
    ``samples × samples`` grid, then around its :data:`REFINE_KEEP` roomiest samples on a grid
    :data:`REFINE` times finer.

    Parameters
    ----------
    kind : (w,) int array, the kind to make room for in each window
    rule : (k, k) float array, user units
    ex : the exemplar's motifs (their largest scale per kind sizes the motif)
    nearest : ``(d, m, inside)`` of the same samples from :func:`_largest_empty_discs`, if at hand
    lazy : measure the room (one k-d tree query per kind) only at the samples where the nearest
        motif's own term — an upper bound of the room — can still reach the best kept (the
        :data:`LAZY_FIRST` most promising per window first); the same spots as measuring all

    Returns
    -------
    spot : (w, 2) the roomiest sample of each window inside the region (if it has one)
    clear : (w,) its clearance to every footprint (the empty-disc radius there), ≥ 0; 0 for a
        spot outside the region
    """
    radius = motif_radius(arr, protos)
    largest = np.zeros(len(protos))
    np.maximum.at(largest, ex.kind, ex.scale)
    size_of = np.array([p.radius for p in protos]) * largest  # (k,) bounding radius at the largest scale
    # a kind's motifs are exemplar copies: none is larger than the kind at its largest exemplar scale
    trees = [(j, cKDTree(arr.xy[arr.kind == j], balanced_tree=False, compact_nodes=False), float(size_of[j]))
             for j in np.unique(arr.kind)]  # fmt: skip
    far = float(rule.max() + size_of.max()) + float(size.max())  # beyond: room to spare (+ r_j)
    lo = origin + ids * size  # (w, 2)

    def measure(pts, owner, at=None):
        """room, clear at ``pts`` (all, or the indices ``at``; -inf elsewhere)."""
        inside = shapely.contains_xy(region.shape, pts[:, 0], pts[:, 1])
        room = np.where(inside, np.inf, -np.inf)
        clear = np.min(np.concatenate([pts - lo[owner], lo[owner] + size - pts], axis=1), axis=1)  # window edges
        clear[~inside] = -np.inf
        if at is not None:
            skip = np.ones(len(pts), dtype=bool)
            skip[at] = False
            room[skip] = clear[skip] = -np.inf
        q = np.flatnonzero(inside) if at is None else at[inside[at]]
        want = kind[owner[q]]
        for j, t, r_j in trees:
            need = size_of[want] + rule[want, j]
            d, _ = t.query(pts[q], k=1, distance_upper_bound=far + r_j, workers=-1)
            clear[q] = np.minimum(clear[q], d - r_j)  # inf beyond the bound
            room[q] = np.minimum(room[q], d - r_j - need)
        return room, clear

    def cap(pts, owner, d=None, m=None):
        """An upper bound of ``measure``'s room at ``pts`` from the nearest motif alone: its
        kind's term, which the room cannot exceed (inf where that term is beyond the bound)."""
        if d is None:
            d, m = tree.query(pts, k=1, workers=-1)
        j, want = arr.kind[m], kind[owner]
        # the same expression as ``measure``'s, (d - r_j) - (s_want + rule): a bound written
        # otherwise can fall an ulp under the room it bounds and drop a tied sample (reviewer)
        return np.where(d >= far + size_of[j], np.inf, d - size_of[j] - (size_of[want] + rule[want, j]))

    g = (np.arange(samples) + 0.5) / samples
    cell = np.stack([v.ravel() for v in np.meshgrid(g, g)], -1)  # (s², 2) in window units
    pts = (lo[:, None, :] + cell[None, :, :] * size).reshape(-1, 2)
    owner = np.repeat(np.arange(len(ids)), len(cell))
    if tree is not None and len(cell) > SCREEN:
        # the nearest motif's term bounds the room from above: only the best bounds are measured
        d, m, inside = nearest if nearest is not None and nearest[0] is not None else (
            *tree.query(pts, k=1, workers=-1), shapely.contains_xy(region.shape, pts[:, 0], pts[:, 1]))  # fmt: skip
        want = kind[owner]
        upper = d - radius[m] - size_of[want] - rule[want, arr.kind[m]]
        upper[~inside] = -np.inf
        upper = upper.reshape(len(ids), len(cell))
        pick = np.argsort(-upper, axis=1, kind="stable")[:, :SCREEN]
        cell_of = pick.ravel()
        pts = (lo[:, None, :] + cell[pick] * size).reshape(-1, 2)
        owner = np.repeat(np.arange(len(ids)), SCREEN)
        rows = np.arange(len(ids))[:, None]
        bound = cap(pts, owner, d.reshape(upper.shape)[rows, pick].ravel(), m.reshape(upper.shape)[rows, pick].ravel())
    else:
        cell_of = np.tile(np.arange(len(cell)), len(ids))
        bound = None
    per = len(pts) // len(ids)
    keep = min(REFINE_KEEP, per)
    if lazy and bound is not None:
        # the room is measured first at the samples of the best bounds, then wherever the bound
        # reaches the window's keep-th best room (ties included): the same best samples
        first = np.argsort(-bound.reshape(len(ids), per), axis=1, kind="stable")[:, : min(LAZY_FIRST, per)]
        first = (first + (np.arange(len(ids)) * per)[:, None]).ravel()
        room, clear = measure(pts, owner, first)
        floor = -np.sort(-room.reshape(len(ids), per), axis=1)[:, keep - 1]
        done = np.zeros(len(pts), dtype=bool)
        done[first] = True
        rest = np.flatnonzero(~done & (bound >= floor[owner]))
        if len(rest):
            r_rest, c_rest = measure(pts, owner, rest)
            room[rest], clear[rest] = r_rest[rest], c_rest[rest]
    else:
        room, clear = measure(pts, owner)
    # the best few samples of each window, each refined on a finer grid over its own cell
    best = np.argsort(-room.reshape(len(ids), per), axis=1, kind="stable")[:, :keep]
    f = ((np.arange(REFINE) + 0.5) / REFINE - 0.5) / samples
    sub = np.stack([v.ravel() for v in np.meshgrid(f, f)], -1)  # (REFINE², 2)
    centre = cell[cell_of.reshape(len(ids), per)[np.arange(len(ids))[:, None], best]]  # (w, keep, 2)
    fine = (lo[:, None, None, :] + (centre[:, :, None, :] + sub[None, None, :, :]) * size).reshape(-1, 2)
    fine_owner = np.repeat(np.arange(len(ids)), keep * len(sub))
    if lazy and tree is not None:
        # only where the bound reaches the window's best room so far (ties included)
        best_yet = room.reshape(len(ids), per).max(axis=1)
        f_room, f_clear = measure(fine, fine_owner, np.flatnonzero(cap(fine, fine_owner) >= best_yet[fine_owner]))
    else:
        f_room, f_clear = measure(fine, fine_owner)
    pts, owner = np.concatenate([pts, fine]), np.concatenate([owner, fine_owner])
    room, clear = np.concatenate([room, f_room]), np.concatenate([clear, f_clear])
    top = _best_per_owner(room, owner)
    return pts[top], np.maximum(clear[top], 0.0)



def uniform_at(key: int, stream: int, cell: np.ndarray) -> np.ndarray:
    return cellrng.uniform(key, stream, cell[:, 0], cell[:, 1], cell[:, 2])
