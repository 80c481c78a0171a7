"""What the exemplar shows at a displacement: ``P_ex(v)``, step 5 of
:func:`svgtile.metrics.repeats.repetition` (that module's exemplar side, kept apart for length).

The exemplar's share of motifs with a same-kind partner at ``v`` (:func:`_exemplar_shares`),
also at the divisors ``v / m`` that rows and lattices repeat at; read modulo the exemplar's
exact order where it has one (:func:`_reduced_shares`); and on a repeating tile, each kind at its
own step and to the figure's resolution (:func:`_kind_shares`).  The texture's side, the peaks
and the figure are in :mod:`svgtile.metrics.repeats`, which re-exports these.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.order import DIVIDE_MAX, DIVIDE_MIN, exact_partners
from svgtile.core.exemplar import Exemplar

#: The exemplar shows a displacement when at least this many of its motifs, shifted by it, stay
#: inside its input region (a share of fewer cannot be told from noise: it counts as not shown).
REPEAT_EX_MIN = 10
#: The exemplar shows a displacement v also when it repeats at v / m to within 1 / m of the
#: square (rows: m steps along a row), for whole m with |v| / m at least this many mean spacings …
REPEAT_DIVIDE = DIVIDE_MIN  # the same divisors auto's stamp_repeats tries
#: … and m at most this.
REPEAT_DIVIDE_MAX = DIVIDE_MAX
#: A kind's share of the exemplar's motifs at a shift counts where at least this many of them are
#: seen (:func:`_kind_shares`; a share of fewer is noise, and a kind never so seen counts as not shown).
REPEAT_KIND_MIN = 5
#: A repeating tile shows a displacement v also where a kind repeats at v / m to within the
#: square at each of the first this many multiples k · v / m (k < m) the tile can show, every one
#: of them (and at every further multiple it can show): a row or lattice jittered less than the
#: figure can resolve (:func:`_kind_shares`).
REPEAT_RESOLVED = 3


def _reduced_shares(
    exemplar: Exemplar, shifts: np.ndarray, steps: np.ndarray, half: float, shortest: float, tol: float
) -> np.ndarray:
    """(k,) float: ``P_ex`` of each shift, read modulo the exemplar's exact order (step 5).

    Where the exemplar has an exact order (``steps``, :func:`svgtile.metrics.order.order_steps`,
    at least 60 % of its motifs invariant under it), a texture that keeps it looks at ``v`` as the
    exemplar looks at ``v − t`` for any ``t`` of that lattice: a partner one lattice step further
    on is the same neighbour seen again, not a new repetition.  So ``P_ex(v)`` is the largest
    :func:`_exemplar_shares` over ``v`` and its reductions ``v − t``, ``t`` the lattice points
    around ``v`` (the four of the cell ``v`` lies in; rows: the two multiples of the step either
    side), leaving out a reduction whose ``± half`` square holds the origin (a motif would be
    its own partner).  A reduction counts only partners that are themselves on the lattice (a
    same-kind motif within ``tol`` one step on, either way, along every generator): the partner
    ``t`` further on is then the same neighbour seen again; a jittered partner is not repeated
    by the lattice, so content jittered off it and stamped at the period stays caught even where
    the rest of the tile keeps the steps.  Example: Equinor 40100, dots on an exact (16, 16) / (−16, 16) lattice with
    a second, offset site lattice half filled by each kind; a stamp's partner at (8, −56) is the
    tile's own (8, 8) neighbour one period down, which the exemplar shows.  A tile with no exact
    order (jittered, irregular) is read as before: its stamped period is never reduced.

    ``shifts`` (k, 2) float, user units; ``steps`` (m, 2) float, m ≤ 2; ``half``, ``shortest``
    as in :func:`_exemplar_shares`; ``tol`` user units, the exact steps' tolerance.
    """
    shifts = np.asarray(shifts, np.float64).reshape(-1, 2)
    if len(steps) == 0 or len(shifts) == 0:
        return _exemplar_shares(exemplar, shifts, half, shortest)
    g = np.asarray(steps[:2], np.float64)
    if len(g) == 1:
        gx, gy = g[0]
        m = np.floor((shifts @ g[0]) / (gx * gx + gy * gy))
        near = [m[:, None] * g[0] + i * g[0] for i in (0.0, 1.0)]
    else:
        (ax, ay), (bx, by) = g
        det = ax * by - ay * bx
        c1 = np.floor((by * shifts[:, 0] - bx * shifts[:, 1]) / det)
        c2 = np.floor((ax * shifts[:, 1] - ay * shifts[:, 0]) / det)
        near = [(c1 + i)[:, None] * g[0] + (c2 + j)[:, None] * g[1] for i in (0.0, 1.0) for j in (0.0, 1.0)]
    cand = [shifts] + [shifts - t for t in near]
    owner = np.tile(np.arange(len(shifts)), len(cand))
    cand = np.concatenate(cand)
    keep = np.abs(cand).max(axis=1) > half
    out = _exemplar_shares(exemplar, shifts, half, shortest)  # v itself, as before
    keep[: len(shifts)] = False
    if keep.any():
        xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
        period = getattr(exemplar, "period", None)
        on = np.ones(len(xy), dtype=bool)
        for step in g:
            on &= exact_partners(xy, kind, period, step, tol)
        share = _exemplar_shares(exemplar, cand[keep], half, shortest, partners=on)
        np.maximum.at(out, owner[keep], share)
    return out


def _exemplar_shares(
    exemplar: Exemplar, shifts: np.ndarray, half: float, shortest: float, partners: np.ndarray | None = None
) -> np.ndarray:
    """(k,) float: ``P_ex`` of each shift, step 5 of :func:`~svgtile.metrics.repeats.repetition`.

    ``P_ex(v) = max_m S(v / m, half / m)`` over the whole divisors ``m ≥ 1`` with
    ``|v| / m ≥ shortest`` (at most :data:`REPEAT_DIVIDE_MAX`), where ``S(u, e)`` is the share of
    the exemplar's motifs (unwrapped) with a same-kind motif within ``e`` (per axis) of
    ``x + u``, among those whose square ``x + u ± e`` lies inside the exemplar's input region's
    bounding box and whose point ``x + u`` lies ``e`` inside the region itself (the texture's
    references are asked the same, :class:`~svgtile.metrics.repeats._Room`; the box alone counted a disc-shaped
    exemplar's motifs whose square falls outside the disc, where no partner can stand) (0 where
    fewer than :data:`REPEAT_EX_MIN` do).  An exemplar that repeats at
    ``u`` to within ``e / m`` shows its order at ``m u`` to within ``e``: rows exact along x
    excuse the texture's partners 2, 3, … steps along a row, out to the tile's width and beyond,
    while a jittered or irregular tile stamped at its period is not excused (its content does
    not repeat at a fraction of the period to that precision).

    ``shifts`` (k, 2) float, user units, the squares' centres ``v``; ``half`` and ``shortest``
    user units; ``partners`` (n,) bool or None: only these motifs count as partners (all if None).
    """
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    out = np.zeros(len(shifts))
    if len(xy) == 0 or len(shifts) == 0:
        return out
    x0, y0, x1, y1 = exemplar.region.bounds
    peak, m = _divisors(shifts, shortest)
    u, e = shifts[peak] / m[:, None], half / m
    # every (divisor, motif) pair at once: the shifted square, and whether it lies inside
    tx, ty = xy[None, :, 0] + u[:, 0, None], xy[None, :, 1] + u[:, 1, None]
    ee = e[:, None]
    seen = (tx - ee >= x0) & (tx + ee <= x1) & (ty - ee >= y0) & (ty + ee <= y1)
    region = exemplar.region
    if region.area < (x1 - x0) * (y1 - y0) * (1.0 - 1e-9):  # not its box (a drawn disc, …): the region itself
        for each in np.unique(e):
            rows = np.flatnonzero(e == each)
            seen[rows] &= shapely.contains_xy(inset(region, each), tx[rows], ty[rows])
    row, col = np.nonzero(seen)
    # one tree over every kind: each kind's motifs moved apart along x by more than any reach
    apart = 4 * (x1 - x0 + y1 - y0 + np.abs(shifts).max() + half) + 1
    mate = slice(None) if partners is None else partners
    tree = cKDTree(np.c_[xy[mate, 0] + kind[mate] * apart, xy[mate, 1]])
    found = tree.query_ball_point(
        np.c_[tx[row, col] + kind[col] * apart, ty[row, col]], e[row], p=np.inf, return_length=True
    )
    eligible = np.bincount(row, minlength=len(m))
    hits = np.bincount(row, weights=found > 0, minlength=len(m))
    share = np.where(eligible >= REPEAT_EX_MIN, hits / np.maximum(eligible, 1), 0.0)
    np.maximum.at(out, peak, share)
    return out


def inset(region: shapely.Geometry, margin: float) -> shapely.Geometry:
    """The part of ``region`` (user units) more than ``margin`` inside it, prepared: a point
    there has room for its disc of radius ``margin`` (its square, in a rectangle).  The room test
    of both sides of the repetition figure: the exemplar's motifs here, the texture's references
    in :class:`svgtile.metrics.repeats._Room`."""
    inner = shapely.buffer(region, -margin)
    shapely.prepare(inner)
    return inner


def _divisors(shifts: np.ndarray, shortest: float) -> tuple[np.ndarray, np.ndarray]:
    """Every shift's whole divisors: ``(owner, m)``, (t,) int and (t,) float, ``m = 1 … M`` for
    each shift in turn, ``M = ⌊|v| / shortest⌋`` clipped to 1 … :data:`REPEAT_DIVIDE_MAX`.

    ``shifts`` (k, 2) float, ``shortest`` user units.  The divisors :func:`_exemplar_shares` and
    :func:`_kind_shares` read the exemplar at (``v / m``).
    """
    length = np.hypot(shifts[:, 0], shifts[:, 1])
    most = np.clip(np.floor(length / shortest), 1, REPEAT_DIVIDE_MAX).astype(np.int64)
    owner = np.repeat(np.arange(len(shifts)), most)
    m = (np.arange(most.sum()) - np.repeat(np.cumsum(most) - most, most) + 1).astype(np.float64)
    return owner, m


def _kind_shares(exemplar: Exemplar, shifts: np.ndarray, half: float, shortest: float) -> np.ndarray:
    """(k,) float: ``P_ex`` of each shift on a repeating tile, each kind read at its own step and
    to the figure's resolution (a floor under :func:`_reduced_shares`', which it extends).

    :func:`_exemplar_shares` asks one divisor ``m`` of ``v`` to explain every kind, to within
    ``half / m``.  A tile of several kinds in rows has a step per kind (FGDC 670: dots every
    1.798 units, 26 to the tile's width; dashes every ≈ 9.35, 5 to it, each dash moved by up to
    0.17 along its row), and a row whose motifs' offsets from their sites differ by less than the
    figure's square is, to the figure, a row: a texture that keeps it — stamped or grown anew —
    meets a partner at the tile's width in the square, as the tile meets one at each multiple of
    its step.  So for each kind ``c`` and divisor ``m`` (``|v| / m ≥ shortest``, ``m ≤``
    :data:`REPEAT_DIVIDE_MAX`), with ``u = v / m``:

    * *exact*: the share of c's motifs with a same-kind partner within ``half / m`` of ``x + u``
      (among those whose square lies in the tile's box), as in :func:`_exemplar_shares`;
    * *resolved* (``m > REPEAT_RESOLVED``): the share with a partner within ``half`` of ``x + k u``
      for **every** ``k = 1 … m − 1`` whose square lies in the box, counted only where the tile
      shows at least the first :data:`REPEAT_RESOLVED` multiples (each with at least
      :data:`REPEAT_EX_MIN` motifs of any kind in the box): the step holds to the square at
      every multiple the tile shows, so a texture that keeps it lands at ``v`` in the square.  A
      step that drifts off ``u`` (a lattice of step 1.92 in a tile of 20: a seam every period,
      which a texture keeping the step does not repeat at 20) misses a later multiple and is not
      shown.

    ``S_c(v)`` is the larger over both and every ``m``, 0 for a kind with fewer than
    :data:`REPEAT_KIND_MIN` motifs in the box at every ``m`` (a share of a handful is noise).  A shift with
    both components beyond the square is also shown as far as its parts along the tile's axes are
    surely shown together: ``max(0, S_c(v_x, 0) + S_c(0, v_y) − 1)`` (rows shown along x, stacked
    along y; the bound holds whichever motifs make up each share).  ``P_ex(v) = Σ_c f_c S_c(v)``,
    ``f_c`` the kind's share of the tile's motifs.  A stamp still counts wherever one kind's
    content is irregular or scattered beyond the square at the tile's period: then ``S_c < 1``
    there, while the stamp repeats every motif (Equinor 50090 with every motif moved by up to a
    bin: :func:`~svgtile.metrics.repeats.repetition` ≥ 0.8; by half a bin, two motifs' offsets differ by less than the
    square and it is not charged).

    ``shifts`` (k, 2) float, user units; ``half`` (the square's half side) and ``shortest`` user units.
    """
    shifts = np.asarray(shifts, np.float64).reshape(-1, 2)
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    if len(xy) == 0 or len(shifts) == 0:
        return np.zeros(len(shifts))
    freq = np.bincount(kind) / len(kind)
    both = (np.abs(shifts) > half).all(axis=1)
    nb = int(both.sum())
    axes = np.r_[shifts, shifts[both] * [1.0, 0.0], shifts[both] * [0.0, 1.0]]
    per = _kind_resolved(exemplar, axes, half, shortest)  # (k + 2 nb, c)
    main = per[: len(shifts)]
    parts = per[len(shifts) : len(shifts) + nb] + per[len(shifts) + nb :] - 1.0
    main[both] = np.maximum(main[both], parts)
    return main @ freq


def _kind_resolved(exemplar: Exemplar, shifts: np.ndarray, half: float, shortest: float) -> np.ndarray:
    """(k, c) float: ``S_c`` of each shift and kind, the larger of :func:`_kind_shares`' two readings.

    Asked in the order that leaves least to ask: every divisor's step ``u = v / m`` to the square
    first (``k = 1``); a motif with no partner there has none to the square ÷ m either, and fails
    the resolved reading; only divisors where some kind could beat the best exact share go on to
    ``k = 2, 3, …``, and only for the motifs that have held so far.  (A motif whose square at
    ``u`` is outside the tile's box but inside at ``k u`` — within ``half`` of the box's edge —
    is left out of the resolved reading.)
    """
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    kinds = int(kind.max()) + 1
    x0, y0, x1, y1 = exemplar.region.bounds
    # squares are asked only inside the box: each kind's partners moved apart by more than its size
    apart = 4 * (x1 - x0 + y1 - y0 + half) + 1
    tree = cKDTree(np.c_[xy[:, 0] + kind * apart, xy[:, 1]])
    onehot = np.eye(kinds, dtype=np.float64)[kind]  # (n, c)

    def probe(u: np.ndarray, e: np.ndarray, ask: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(t, n) bool each: the squares ``x + u ± e`` inside the box, and those with a same-kind
        partner (asked only where ``ask``, (t, n) bool, if given)."""
        tx, ty = xy[None, :, 0] + u[:, 0, None], xy[None, :, 1] + u[:, 1, None]
        ee = e[:, None]
        seen = (tx - ee >= x0) & (tx + ee <= x1) & (ty - ee >= y0) & (ty + ee <= y1)
        row, col = np.nonzero(seen if ask is None else seen & ask)
        found = np.zeros(seen.shape, dtype=bool)
        if len(row):  # the nearest same-kind motif (per axis), within the square (its edge included)
            d = tree.query(np.c_[tx[row, col] + kind[col] * apart, ty[row, col]], p=np.inf,
                           distance_upper_bound=float(e.max()) * (1 + 1e-9))[0]  # fmt: skip
            found[row, col] = d <= e[row]
        return seen, found

    shift, m = _divisors(shifts, shortest)
    u = shifts[shift] / m[:, None]
    seen1, found1 = probe(u, np.full(len(m), half))
    out = np.zeros((len(shifts), kinds))
    # the exact reading, u to the square ÷ m: a partner there is one in the square, and a square
    # ÷ m near the box's edge may lie inside where the square does not
    seen, found = probe(u, half / m, found1 | ~seen1)
    ok = seen.sum(axis=1) >= REPEAT_EX_MIN
    if ok.any():
        np.maximum.at(out, shift[ok], _kind_share(found[ok], seen[ok], onehot))
    # the resolved reading, k u to the square for every k < m (x + u's square is inside the box
    # wherever x + k u's is, for a motif whose own square is: the box is convex)
    tries = (m > REPEAT_RESOLVED) & (seen1.sum(axis=1) >= REPEAT_EX_MIN)
    if tries.any():
        bound = _kind_share(found1[tries], seen1[tries], onehot)  # S_c ≤ its share at k = 1
        better = (bound > out[shift[tries]]).any(axis=1)
        tries[np.flatnonzero(tries)[~better]] = False
    held = found1[tries]
    for step in range(2, int(m[tries].max(initial=0))):
        live = m[tries] > step  # the divisors with a multiple k = step < m left to ask
        if not live.any():
            break
        at = np.flatnonzero(tries)[live]
        seen_k, found_k = probe(u[at] * step, np.full(len(at), half), held[live])
        held[live] &= found_k | ~seen_k
        if step <= REPEAT_RESOLVED:  # the first multiples must be shown, each by enough motifs
            gone = seen_k.sum(axis=1) < REPEAT_EX_MIN
            if gone.any():
                drop = np.flatnonzero(live)[gone]
                tries[np.flatnonzero(tries)[drop]] = False
                held = np.delete(held, drop, axis=0)
    if tries.any():
        np.maximum.at(out, shift[tries], _kind_share(held, seen1[tries], onehot))
    return out


def _kind_share(hit: np.ndarray, seen: np.ndarray, onehot: np.ndarray) -> np.ndarray:
    """(t, c) float: per test and kind, the share of the kind's seen motifs that hit (0 where
    fewer than :data:`REPEAT_KIND_MIN` of the kind are seen)."""
    hits, sees = (hit & seen).astype(np.float64) @ onehot, seen.astype(np.float64) @ onehot
    return np.where(sees >= REPEAT_KIND_MIN, hits / np.maximum(sees, 1.0), 0.0)
