"""A jittered repeating tile with its jitter redrawn copy by copy (issues 12 and 13).

Many FGDC tiles draw their motifs on a lattice or in rows and then jitter each motif by hand
(610, 611, 617, 622, 664, 724 …), or keep each row exact but give the rows hand-drawn phases
(616, 618, 670 …).  Stamped on the period (the Tiling strategy, almeraj2013 §3) such a tile
repeats its jitter exactly — the repetition figure reads 1.000 — and growth on a tile snaps to the
tile's own sites, so it equals the stamp.  Here each motif of the tile is split into a **site**
and a **jitter**, ``xy = site + jitter``; every copy of the tile keeps the sites (so the lattice,
the rows and the kinds' order are the tile's) and draws the jitter anew, per world cell, from the
jitters the tile itself has:

* the site of motif ``i`` is the consensus of where its same-kind neighbours at the order's steps
  ``±v`` (:func:`svgtile.analysis.order.read_order`) put it, ``mean(xy_i, xy_j ∓ v)`` — Ma, Wei &
  Tong 2011 §3.2 compare exactly these neighbour vectors; the jitter is the rest;
* a motif of a **row** that is exact along x or y (the step's spread under
  :data:`~svgtile.analysis.order.EXACT_STEP` spacings) moves with its row, to a phase drawn from
  the tile's rows' phases per row and world band of copies across the rows (the row continues
  whole along itself, so it stays exact; rows that would break the distance rule draw again,
  :func:`row_shifts`);
* every other motif draws its jitter per world cell from those of its kind in the tile (where the
  tile has an exact step along an axis every motif is in a row, so only the rows' phases are
  drawn: FGDC 616, 617, 618, 669).

Draws are hashes of the run's key and world integers (:mod:`svgtile.core.cellrng`): the same
seed gives the same bytes; a band's row phases do not depend on the region's extent, and a
motif's redraws only on the copies near it (the redraw rounds have no fixed bound, so the tile
engine's ``reach`` is infinite with this option: tiled runs are run whole).  A drawn
motif that overlaps or breaks the distance rule draws again (up to :data:`ROUNDS` times); one
still in conflict then goes back to its tile position and, failing that, the conflicts are culled
as the tiling culls its seams (:func:`svgtile.core.conflicts.cull`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

from svgtile.analysis.order import EXACT_STEP, STEP_TOLERANCE, Order
from svgtile.analysis.stats import Stats, periodic_block
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius
from svgtile.core.region import Region

#: Redraws of a conflicting motif's jitter before it goes back to its tile position.
ROUNDS = 6
#: Redraws of a conflicting row's phase before it keeps its tile phase (a round costs one batched
#: conflict test of every pair of neighbouring rows).
ROW_ROUNDS = 16
_DRAW, _ROW, _ORDER = 11, 12, 13  # hash streams


def jitters(exemplar: Exemplar, order: Order) -> np.ndarray:
    """(m, 2) float array, user units: each motif's jitter off its site.

    The site of motif ``i`` is the consensus of where its same-kind neighbours at the order's steps
    ``±v`` put it, ``mean(xy_i, xy_j ∓ v)`` over the neighbours found within
    :data:`~svgtile.analysis.order.STEP_TOLERANCE` spacings (across the tile's edges); the jitter
    is ``xy_i`` less its site.  ``exemplar.period`` must be set.
    """
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    around = periodic_block(exemplar.motifs, exemplar.period)
    block, bkind = around.xy, around.kind
    tol = STEP_TOLERANCE * order.spacing
    total, count = xy.copy(), np.ones(len(xy))
    for k in np.unique(kind):
        own = np.flatnonzero(kind == k)
        peers = block[bkind == k]
        tree = cKDTree(peers)
        for step in order.steps:
            for v in (np.asarray(step.vector), -np.asarray(step.vector)):
                d, j = tree.query(xy[own] + v, distance_upper_bound=tol)
                hit = np.isfinite(d)
                total[own[hit]] += peers[j[hit]] - v
                count[own[hit]] += 1
    return xy - total / count[:, None]


def exact_rows(
    exemplar: Exemplar, order: Order
) -> tuple[np.ndarray, np.ndarray, int | None, float]:
    """The tile's rows exact along x (or y), and each row's phase along them.

    Returns
    -------
    row : (m,) int array, the motif's row (−1: the tile has no exact step along an axis)
    phase : (m,) float array, user units in [0, step): its row's phase (circular mean of the
        row's motifs' coordinates along the row, modulo the step)
    axis : 0 (rows along x), 1 (along y) or None
    step : the exact step's length, user units (0 if None)
    """
    xy = exemplar.motifs.xy
    m = len(xy)
    for s in order.steps:
        fold = min(s.angle, 180.0 - s.angle)
        axis = 0 if fold < 1.0 else 1 if abs(s.angle - 90.0) < 1.0 else None
        if axis is None or s.spread > EXACT_STEP * order.spacing:
            continue
        across, along = xy[:, 1 - axis], xy[:, axis]
        o = np.argsort(across, kind="stable")
        row = np.empty(m, dtype=np.int64)
        row[o] = np.cumsum(np.r_[0, np.diff(across[o]) > STEP_TOLERANCE * order.spacing])
        turn = np.exp(2j * np.pi * along / s.length)
        mean = np.bincount(row, turn.real) + 1j * np.bincount(row, turn.imag)
        phase = (np.angle(mean) / (2 * np.pi) % 1.0) * s.length
        return row, phase[row], axis, s.length
    return np.full(m, -1), np.zeros(m), None, 0.0


def redraw(exemplar: Exemplar, stats: Stats, order: Order, region: Region, keep: np.ndarray, *,
           key: int) -> Arrangement:  # fmt: skip
    """Copies of the tile's kept motifs over ``region``, each copy's jitter and row phases drawn anew.

    Copy ``(a, b)`` is the tile's motifs translated as :func:`svgtile.engines.tile.copies` does;
    then a motif of an exact row moves with its row along the row by ``φ' − φ_r`` (wrapped to
    ± half a step), ``φ'`` the phase of a row of the tile drawn per (row, band of copies across the
    rows; :func:`row_shifts`, where rows that would conflict draw again): the row continues whole
    across the copies along it.  Every other motif moves to its
    site plus a jitter of its kind drawn per (copy, motif) (:func:`jitters`), and draws again while
    it overlaps or breaks the distance rule, :data:`ROUNDS` times at most, then goes back to its
    tile position.  Conflicts left are culled.

    Parameters
    ----------
    exemplar, stats, order : the tile (``exemplar.period`` set), its analysis and order
    region : the output region (copies whose bounding disc meets its box)
    keep : (m,) bool array, the motifs every copy keeps (:func:`svgtile.engines.tile.periodic_keep`)
    key : the run's key

    Returns
    -------
    Arrangement with no overlaps and no distance-rule violations.
    """
    from svgtile.engines.tile import copies

    jitter = jitters(exemplar, order)
    row, _, axis, step = exact_rows(exemplar, order)
    idx = np.flatnonzero(keep)
    if len(idx) == 0:
        return Arrangement.empty()
    x0, y0, x1, y1 = exemplar.region.bounds
    w, h = x1 - x0, y1 - y0
    motifs = exemplar.motifs.take(keep)
    r = motif_radius(motifs, exemplar.prototypes)
    pad = 2 * float(np.abs(jitter).max()) + step
    X0, Y0, X1, Y1 = region.bounds
    a = np.arange(math.ceil((X0 + x0 - float((motifs.xy[:, 0] + r).max()) - pad) / w),
                  math.floor((X1 + x0 - float((motifs.xy[:, 0] - r).min()) + pad) / w) + 1)  # fmt: skip
    b = np.arange(math.ceil((Y0 + y0 - float((motifs.xy[:, 1] + r).max()) - pad) / h),
                  math.floor((Y1 + y0 - float((motifs.xy[:, 1] - r).min()) + pad) / h) + 1)  # fmt: skip
    A, B = (v.ravel() for v in np.meshgrid(a, b))
    base = copies(exemplar, motifs, A, B)
    n = len(base)
    i = np.tile(idx, len(A))
    ca, cb = np.repeat(A, len(idx)), np.repeat(B, len(idx))
    kind = base.kind
    tile_xy = base.xy.copy()

    # a row moves whole, by a phase drawn from the tile's rows' phases per (row, band of copies
    # across the rows), so it runs on unbroken across the copies along it; every other motif
    # moves to its site plus a jitter of its kind drawn per (copy, motif)
    in_row = row[i] >= 0
    site = tile_xy - jitter[i]
    pools = {k: jitter[(exemplar.motifs.kind == k) & (row < 0)] for k in np.unique(kind[~in_row])}
    xy = tile_xy.copy()
    if in_row.any():
        band = (cb if axis == 0 else ca)[in_row]
        bands, shifts = row_shifts(
            exemplar, stats, order, int(band.min()), int(band.max()), key=key
        )
        xy[in_row, axis] += shifts[band - bands[0], row[i[in_row]]]
        xy = np.round(xy, DECIMALS)

    def draw(attempt: np.ndarray, sel: np.ndarray) -> np.ndarray:
        out = xy[sel].copy()
        u = cellrng.uniform(key, _DRAW, ca[sel], cb[sel], i[sel], attempt[sel])
        for k, pool in pools.items():
            on = kind[sel] == k
            out[on] = (
                site[sel][on] + pool[np.minimum((u[on] * len(pool)).astype(int), len(pool) - 1)]
            )
        return np.round(out, DECIMALS)

    attempt = np.zeros(n, dtype=np.int64)
    free = ~in_row
    xy[free] = draw(attempt, free)
    # rows are settled (their phases were drawn against their neighbours); conflicts left are culled
    settled = in_row.copy()
    pri = cellrng.uniform(key, _ORDER, ca, cb, i)
    for _ in range(ROUNDS + 1):
        c = find_conflicts(
            Arrangement(kind, xy, base.angle, base.scale), exemplar.prototypes, stats.distance
        )
        loser = np.where(pri[c.i] < pri[c.j], c.i, c.j)
        loser = np.where(settled[loser], c.i + c.j - loser, loser)  # the other one moves
        move = np.zeros(n, dtype=bool)
        move[loser[~settled[loser]]] = True
        if not move.any():
            break
        attempt[move] += 1
        xy[move] = draw(attempt, move)
        back = move & (attempt >= ROUNDS)
        xy[back] = tile_xy[back]
        settled |= back
    arr = Arrangement(kind, xy, base.angle, base.scale)
    c = find_conflicts(arr, exemplar.prototypes, stats.distance)
    if len(c.i):
        arr = arr.take(cull(n, c, pri))
    rr = motif_radius(arr, exemplar.prototypes)
    p = arr.xy
    return arr.take(
        (p[:, 0] + rr > X0) & (p[:, 0] - rr < X1) & (p[:, 1] + rr > Y0) & (p[:, 1] - rr < Y1)
    )


def spread(jitter: np.ndarray) -> float:
    """Root-mean-square length of (n, 2) jitters, user units."""
    return float(np.sqrt((jitter**2).sum(axis=1).mean())) if len(jitter) else 0.0


def rows_repeat_within(exemplar: Exemplar, order: Order) -> float:
    """Share of the tile's exact rows whose kinds, in order along the row, repeat at a whole
    fraction of the period (a row of one kind, or kinds alternating, …); 0 when there are none.

    A row runs on whole along itself at any phase :func:`redraw` gives it, so a row whose kinds
    come in an order that repeats only at the tile's period (FGDC 654: six kinds) repeats at
    ``(w, 0)`` whatever its phase: redrawn it loses likeness and still repeats, and the tile is
    better stamped (reviewer, 2026-12-04).
    """
    row, _, axis, _ = exact_rows(exemplar, order)
    if axis is None:
        return 0.0
    kind, along = exemplar.motifs.kind, exemplar.motifs.xy[:, axis] % exemplar.period[axis]
    rows = np.unique(row)
    repeats = 0
    for q in rows:  # a few dozen rows of a tile
        m = np.flatnonzero(row == q)
        seq = kind[m[np.argsort(along[m], kind="stable")]]
        n = len(seq)
        repeats += any(n % p == 0 and np.array_equal(seq, np.roll(seq, p)) for p in range(1, n // 2 + 1))
    return repeats / len(rows)


def rows_fit(exemplar: Exemplar, order: Order, distance: np.ndarray) -> float:
    """Share of (row, phase) pairs of the tile whose row, moved alone to that phase, keeps the
    distance rule with the rest of the tile (across its edges); 0 when the tile has no exact rows.

    :func:`redraw` puts any row of the tile at any of the tiles' row phases: where most pairs
    conflict (FGDC 621: rows 8.9 units a step with phases over 5 units; 670: columns of dashes
    locked to their neighbours) the culled conflicts cost the density and the look, and the
    tile is better stamped.  The growth engine's row phases are checked alike
    (:func:`svgtile.engines.growth.rows_wander`).

    ``distance`` : (k, k) user units, the distance rule.
    """
    from svgtile.core.conflicts import cross_pairs

    row, phase, axis, step = exact_rows(exemplar, order)
    if axis is None:
        return 0.0
    motifs = exemplar.motifs
    block = periodic_block(motifs, exemplar.period)
    brow = np.tile(row, 9)
    rows = np.unique(row)
    phases = phase[np.unique(row, return_index=True)[1]]
    reach = 2 * float(motif_radius(motifs, exemplar.prototypes).max()) + float(distance.max())
    fit = 0
    for r in rows:
        own = np.flatnonzero(row == r)
        across = float(motifs.xy[own[0], 1 - axis])
        near = np.flatnonzero((brow != r) & (np.abs(block.xy[:, 1 - axis] - across) < reach))
        delta = (phases - phase[own[0]] + step / 2) % step - step / 2
        moved = np.repeat(motifs.xy[own][None], len(delta), 0)
        moved[:, :, axis] += delta[:, None]
        new = Arrangement(np.tile(motifs.kind[own], len(delta)), moved.reshape(-1, 2),
                          np.tile(motifs.angle[own], len(delta)), np.tile(motifs.scale[own], len(delta)))  # fmt: skip
        old = block.take(np.isin(np.arange(len(block)), near))
        group_new = np.repeat(np.arange(len(delta)), len(own))
        # every phase is checked against the same neighbours: one group per phase, the old repeated
        olds = Arrangement(np.tile(old.kind, len(delta)), np.tile(old.xy, (len(delta), 1)),
                           np.tile(old.angle, len(delta)), np.tile(old.scale, len(delta)))  # fmt: skip
        group_old = np.repeat(np.arange(len(delta)), len(old))
        a, _ = cross_pairs(
            new, olds, exemplar.prototypes, distance, complete=False, groups=(group_new, group_old)
        )
        fit += len(delta) - len(np.unique(group_new[a]))
    return fit / (len(rows) * len(phases))


def row_shifts(exemplar: Exemplar, stats: Stats, order: Order, first: int, last: int, *,
               key: int) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Each world row's shift along itself: ``(band, row)`` moves by ``φ' − φ_row`` (wrapped to
    ± half a step), ``φ'`` one of the tile's rows' phases drawn by a hash of ``(band, row,
    attempt)``.

    A row runs on whole along itself (its shift is one per band of copies), so whether two rows
    keep the distance rule is read on one period of them: of two rows that conflict the one of
    lower priority redraws, :data:`ROW_ROUNDS` times at most, then keeps its tile phase (shift 0).
    Bands around ``first … last`` are settled as far as a chain of redraws can reach, so that
    those asked for do not depend on the region's extent.

    Returns
    -------
    bands : (B,) int array, the bands ``first … last``
    shifts : (B, R) float array, user units, the shift of each band's rows (R rows in the tile)
    """
    from svgtile.core.conflicts import cross_pairs

    row, phase, axis, step = exact_rows(exemplar, order)
    motifs = exemplar.motifs
    period = np.asarray(exemplar.period, dtype=float)
    rows = np.unique(row)
    first_of = np.unique(row, return_index=True)[1]
    phases = phase[first_of]
    # neighbouring rows: (r, r', band offset e) whose motifs can come within the rule's reach
    reach = 2 * float(motif_radius(motifs, exemplar.prototypes).max()) + float(stats.distance.max())
    across = motifs.xy[first_of, 1 - axis]
    near = [(a, b, e) for a in rows for b in rows for e in (0, 1)
            if (e == 1 or a < b) and abs(across[b] + e * period[1 - axis] - across[a]) < reach + 1e-9]  # fmt: skip
    # a redraw moves a conflict on by one near pair a round at most (one row, or farther where the
    # reach spans several): settle enough bands around the ones asked for
    hop = max((abs(across[b] + e * period[1 - axis] - across[a]) for a, b, e in near), default=0.0)
    margin = max(math.ceil(2 * ROW_ROUNDS / len(rows)), math.ceil(2 * ROW_ROUNDS * hop / period[1 - axis])) + 1
    lo, hi = first - margin, last + margin
    band = np.repeat(np.arange(lo, hi + 1), len(rows))
    r = np.tile(rows, hi - lo + 1)
    n = len(band)
    attempt = np.zeros(n, dtype=np.int64)
    settled = np.zeros(n, dtype=bool)

    def shift_of(w: np.ndarray) -> np.ndarray:
        u = cellrng.uniform(key, _ROW, band[w], r[w], attempt[w])
        drawn = phases[np.minimum((u * len(phases)).astype(int), len(phases) - 1)]
        return np.where(
            settled[w], 0.0, (drawn - phase[first_of[r[w]]] + step / 2) % step - step / 2
        )

    keep = (band >= first) & (band <= last)
    if not near:  # no two rows come within the rule's reach: each keeps its first drawn phase
        return np.arange(first, last + 1), shift_of(np.flatnonzero(keep)).reshape(last - first + 1, len(rows))
    pa, pb, pe = (np.array(v) for v in zip(*near, strict=True))
    # world pairs: (band β, row a) against (band β + e, row b)
    wa = (np.arange(hi - lo + 1)[:, None] * len(rows) + pa[None]).ravel()
    wb = ((np.arange(hi - lo + 1)[:, None] + pe[None]) * len(rows) + pb[None]).ravel()
    inside = wb < n
    wa, wb = wa[inside], wb[inside]
    along = np.zeros(2)
    along[axis] = period[axis]
    members = [np.flatnonzero(row == q) for q in rows]

    def stretch(w: np.ndarray, shift: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Motifs of world rows ``w`` over three periods along, shifted; and the group of each."""
        idx = [members[q] for q in r[w]]
        size = np.array([len(x) for x in idx])
        m_ = np.concatenate(idx)
        g = np.repeat(np.arange(len(w)), size)
        off = np.zeros((len(m_), 2))
        off[:, axis] = np.repeat(shift, size)
        off[:, 1 - axis] = np.repeat((band[w] - lo) * period[1 - axis], size)
        xy = motifs.xy[m_] + off
        xy = np.concatenate([xy - along, xy, xy + along])
        return np.tile(m_, 3), xy, np.tile(g, 3)

    priority = cellrng.uniform(key, _ORDER, band, r)
    for _ in range(2 * ROW_ROUNDS):
        ma, xa, ga = stretch(wa, shift_of(wa))
        mb, xb, gb = stretch(wb, shift_of(wb))
        new = Arrangement(motifs.kind[ma], xa, motifs.angle[ma], motifs.scale[ma])
        old = Arrangement(motifs.kind[mb], xb, motifs.angle[mb], motifs.scale[mb])
        a, _ = cross_pairs(
            new, old, exemplar.prototypes, stats.distance, complete=False, groups=(ga, gb)
        )
        bad = np.unique(ga[a])
        if len(bad) == 0:
            break
        one, two = wa[bad], wb[bad]
        loser = np.where(priority[one] < priority[two], one, two)
        loser = np.where(settled[loser], one + two - loser, loser)
        loser = np.unique(loser[~settled[loser]])
        if len(loser) == 0:
            break
        attempt[loser] += 1
        settled[loser[attempt[loser] >= ROW_ROUNDS]] = True
    shifts = shift_of(np.arange(n))
    return np.arange(first, last + 1), shifts[keep].reshape(last - first + 1, len(rows))
