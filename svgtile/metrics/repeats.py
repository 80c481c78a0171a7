"""Repetition: how strongly a texture repeats itself beyond what its exemplar shows.

:func:`repetition` finds the texture's most populated same-kind displacements and compares the
share of motifs repeated at each with the exemplar's own share at the same displacement (issue
13): repetition the exemplar contains inside itself — rows at a free phase, a kind's clustering,
the exemplar against itself — is not counted; repetition at a displacement the exemplar cannot
show (its tile's period stamped over irregular content, a patch copied) is.  Displacements on
the exemplar's exact lattice (:mod:`svgtile.metrics.order`) are left out first, so that a
texture of an exact lattice tile — stamping it is faithful — is not charged for its period.

What a viewer sees, and what the figure therefore leaves out (rep13e): where a tile is its exact
lattice, kinds and all, a motif's partner one period away is its neighbour inside the tile seen
again — the exemplar's share is read modulo that lattice; and where an exemplar is drawn in rows,
partners at a whole row offset are as common as motifs thrown at random along a line — that is
the chance there, not the plane's.  And what the figure cannot resolve it does not charge
(rep13f): on a repeating tile each kind is read at its own step, and a row or lattice whose
motifs' offsets from their sites differ by less than the figure's square, at every multiple of its
step the tile shows, shows the multiples beyond it (:func:`~svgtile.metrics.shown._kind_shares`).
Repetition is what is left: the same cluster of irregular content recurring (a tile jittered
beyond the square stamped, a patch or a run copied).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.order import SHORT_PERIOD
from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.metrics.order import BOX, EXACT, explained, order_steps
from svgtile.metrics.shown import (  # noqa: F401  (the exemplar's side, step 5; _exemplar_shares re-exported for its tests)
    REPEAT_DIVIDE,
    REPEAT_EX_MIN,
    _exemplar_shares,
    _kind_shares,
    _reduced_shares,
    inset,
)
from svgtile.metrics.window import exemplar_size, in_window, motif_sample, spacing

#: Repetition: displacements are binned on a grid of this many mean spacings …
REPEAT_BIN = 0.1
#: … counted from this many mean spacings (or half the exemplar's size, if smaller) …
REPEAT_MIN = SHORT_PERIOD  # auto's stamp_repeats reads a period shorter than this as the pattern's lattice
#: … up to this many exemplar sizes (the larger side of the input region's bounding box) …
REPEAT_REACH = 1.5
#: … from at most this many reference motifs.
REPEAT_SAMPLES = 4000
#: The texture's this many most populated displacement peaks are compared with the exemplar's
#: share (few: the figure is a maximum over them, and a maximum over many peaks of noise rises
#: above the chance level of one).
REPEAT_PEAKS = 4
#: The texture's share at a displacement is never taken over fewer references than this (or all
#: of them, if fewer): short of it, references without room count as without a partner, as every
#: one did before the room rule (step 4 of :func:`repetition`).  The peaks are the texture's own
#: most populated bins, so a share over a handful of references with room is the largest of
#: several draws of noise: random placement over a square one exemplar width wide, 30 seeds of
#: boulders, gravel, sand and marsh, read 0.09–0.12 on average and over 0.2 on 2–4 seeds with
#: shares over as few as 10 (benchmarks/README.md "room07").
REPEAT_ROOM_MIN = 50


@dataclass(frozen=True)
class Repetition:
    """What :func:`repetition` finds.

    Attributes
    ----------
    repetition : float or None
        Excess of motifs repeated at one of the texture's most common displacements over what
        the exemplar itself shows there (or chance, if more), in [0, 1]: ≈ 1 for a tiling of
        irregular content, ≈ 0 for random placement, for a faithful texture of a lattice and
        for the exemplar scored against itself; lower is less repetitive.  The figure reported
        and gated.
    repetition_raw : float or None
        The texture's share ``P_tex(v)`` at that displacement, in [0, 1].
    repetition_vector : (float, float) or None
        Its displacement ``v = (dx, dy)``, user units.
    repetition_exemplar : float or None
        The exemplar's own share ``P_ex(v)`` there (modulo its exact order, if it has one), in
        [0, 1] (0: the exemplar cannot show v).
    repetition_order : float or None
        The figure before issue 13: excess over chance at the single most common displacement
        the exemplar's exact order does not explain, blind to repetition the exemplar shows
        inside itself (rows at a free phase, the exemplar against itself: 0.28 for sand).
        (This and ``repetition_total`` take ``P_tex`` as the figure does, with ``room``.)
    repetition_order_vector : (float, float) or None
        Its displacement, user units.
    repetition_total : float or None
        The figure over every displacement, the exemplar's own lattice steps included (what
        ``repetition`` was before issue 12): ≈ 1 for any texture of a lattice.
    repetition_total_vector : (float, float) or None
        Its displacement, user units.
    order_steps : tuple of (float, float)
        The exemplar's steps whose lattice was left out (:func:`svgtile.metrics.order.order_steps`),
        user units; empty when the exemplar has no exact order.
    """

    repetition: float | None
    repetition_raw: float | None
    repetition_vector: tuple[float, float] | None
    repetition_total: float | None = None
    repetition_total_vector: tuple[float, float] | None = None
    order_steps: tuple[tuple[float, float], ...] = ()
    repetition_exemplar: float | None = None
    repetition_order: float | None = None
    repetition_order_vector: tuple[float, float] | None = None


def repetition(
    arr: Arrangement, exemplar: Exemplar, stats: Stats, window: shapely.Geometry, *, inside: np.ndarray | None = None,
    trees: list[cKDTree] | None = None, room: shapely.Geometry | None = None,
) -> Repetition:  # fmt: skip
    """How strongly the arrangement repeats itself beyond what the exemplar shows inside itself.

    ≈ 1 for a tiling of irregular content, ≈ 0 for random placement, for a faithful texture of
    a lattice or of rows, and for the exemplar against itself.  With ``s`` the mean spacing and
    ``L`` the exemplar's size (larger side of the input region's bounding box):

    1. Reference motifs: those in ``window`` (at most :data:`REPEAT_SAMPLES`, see
       :func:`~svgtile.metrics.window.motif_sample`).  For each reference a, every *same-kind*
       motif b of the texture with ``r0 ≤ |x_b − x_a| < R`` gives the displacement ``x_b − x_a``, where
       ``r0 = min(REPEAT_MIN · s, L / 2)`` (beyond local packing) and
       ``R = max(REPEAT_REACH · L, 2 r0)`` (reaching past the exemplar's own period).
    2. **The exemplar's exact order is left out**: displacements within ±1.5 bins (per axis) of
       the lattice generated by the exemplar's exact steps are dropped
       (:mod:`svgtile.metrics.order` states the rule and why: a true lattice tile's period is
       such a step combination — stamping an exact lattice is faithful — an irregular tile's
       period and a jittered lattice's are not).
    3. The remaining displacements are binned on a square grid of step ``q = REPEAT_BIN · s``
       (``⌊d / q⌋`` per axis), in the half-plane ``dx > 0`` (or ``dx = 0, dy ≥ 0``: the histogram
       is symmetric).  The peaks ``v_1 … v_K`` are the :data:`REPEAT_PEAKS` most populated bins,
       each at least 3 bins (per axis) from the ones before (greedy, row-major on a tie), so that
       one peak split over neighbouring bins is one peak.
    4. ``P_tex(v)``: the fraction of references with at least one same-kind partner whose
       (remaining) displacement falls in ``v`` or one of its 8 neighbouring bins (a ``3q × 3q``
       square, so rounding at bin edges does not matter), among the references that have room
       for one: whose point ``x + v`` lies ``1.5 q`` inside ``room`` (the texture's region; for
       a rectangle, the square inside it), as ``P_ex`` counts only the exemplar's motifs whose
       square stays inside it (the same rule: the exemplar scored against itself, every motif a
       reference, reads ``P_tex`` = the exemplar's share at ``v`` itself ≤ ``P_ex``, so 0).
       The share is never taken over fewer than :data:`REPEAT_ROOM_MIN` references (all of
       them, if fewer): short of that, references without room count as without a partner.
       With fewer than :data:`REPEAT_EX_MIN` with room the texture cannot show ``v`` and
       ``P_tex = 0``, as ``P_ex`` is then.
       (Counting every reference read a region of two tile widths, where half the references
       have no room one period on, as half as repetitive as it is: FGDC 654's stamped tile, a
       dot lattice with irregular dashes, scored 0.00 at 2 × 2 tiles and 1.00 at 3 × 3.)
    5. ``P_ex(v)``: the same share in the exemplar's own motifs, unwrapped (a repeating tile is
       not continued across its edges), over the motifs whose ``3q × 3q`` square at ``v`` lies
       inside the bounding box of the exemplar's input region, its centre inside the region
       itself by as much — the part of the exemplar that overlaps itself when shifted by
       ``v`` (:mod:`svgtile.metrics.shown` reads it).  With fewer than :data:`REPEAT_EX_MIN`
       such motifs the exemplar cannot show ``v`` and ``P_ex = 0``: a displacement as long as
       the tile (its period stamped) is never excused — unless the exemplar has an exact order (step 2): then ``P_ex(v)`` is read
       modulo it, the most the exemplar shows at ``v − t`` for the lattice points ``t`` around
       ``v`` (:func:`~svgtile.metrics.shown._reduced_shares`): in a tile that is its exact lattice, kinds and all, a
       partner one period further on is the same neighbour seen again.  On a repeating tile
       ``P_ex`` is at least :func:`~svgtile.metrics.shown._kind_shares`' reading: each kind at
       its own divisor of ``v``,
       and rows or lattices whose step holds to the square at every multiple the tile shows.
       It is asked only at the peaks with an excess left and at the first (the peak reported
       when none is left), so ``repetition_exemplar`` is the reported peak's, either way.
    6. At random, a reference of kind c has a partner in a square with probability
       ``p_c = 1 − exp(−λ_c · 9 q²)`` (Poisson, λ_c the kind's motifs per unit area in
       ``window``); ``P0`` is the mean of ``p_c`` over the references.  On a drawn exemplar
       of rows, at a shift that is a whole number of row pitches across the rows, chance is
       that of motifs thrown at random along a line instead, ``F(v)`` (:func:`_rows_floor`;
       0 elsewhere): rows put every partner on a line.  With
       ``b(v) = max(P0, F(v), P_ex(v))``,
       ``repetition = max_k max(0, (P_tex(v_k) − b(v_k)) / (1 − b(v_k)))`` — the excess over
       what the exemplar shows (or chance), as in Cohen's κ; ``repetition_vector`` is the mean
       displacement in the square of the peak that gives it, ``repetition_raw`` its ``P_tex``,
       ``repetition_exemplar`` its ``P_ex``.

    In a tiling of irregular content of period t every interior motif has a partner at exactly
    t, which the exemplar cannot show: ``repetition`` = 1.  Rows the exemplar draws at a free
    phase, a kind's clusters, any repetition inside the exemplar are excused where the texture
    repeats no more often than the exemplar does.  For random placement ``P_tex ≈ P0`` and
    ``repetition`` ≈ 0 (a maximum over K peaks of noise: K is kept small).
    ``repetition_order`` is step 6 at the single mode ``v_1`` against ``P0`` alone (the figure
    of issue 12, before issue 13); ``repetition_total`` the same without step 2 (the figure
    before issue 12, ≈ 1 for any texture of a lattice).  Both are kept so that nothing is lost.

    ``inside`` : (n,) bool, the motifs in ``window``, if known; ``trees`` : :func:`kind_trees`
    of ``arr``, if built; ``room`` : where the texture's motifs may stand (its region; :func:`svgtile.metrics.score`
    passes it), or None: every reference counts in step 4, room or not (the figure before
    the room was asked, which reads a texture little larger than the period as less repetitive).

    Returns
    -------
    Repetition: the figures are None if no motif is in ``window``, the vectors if no
    displacement was found.
    """
    if inside is None:
        inside = in_window(arr, window)
    if not inside.any() or not stats.count_density > 0:
        return Repetition(None, None, None)
    s = spacing(stats)
    size = max(exemplar_size(exemplar))
    q = REPEAT_BIN * s
    r0 = min(REPEAT_MIN * s, size / 2)
    reach = max(REPEAT_REACH * size, 2 * r0)
    steps = order_steps(exemplar, s, REPEAT_MIN * s)
    own = tuple((float(x), float(y)) for x, y in steps)
    ref = motif_sample(arr, np.flatnonzero(inside), REPEAT_SAMPLES)
    roomy = None if room is None else _Room(room, 1.5 * q, arr.xy[ref])
    lam = np.bincount(arr.kind[inside], minlength=len(stats.frequency)) / window.area
    chance = float(np.mean(-np.expm1(-lam[arr.kind[ref]] * 9 * q * q)))

    who, disp = [], []
    for c in np.unique(arr.kind[ref]):
        mine = ref[arr.kind[ref] == c]
        peers = np.flatnonzero(arr.kind == c)
        tree = trees[c] if trees else cKDTree(arr.xy[peers])
        found = cKDTree(arr.xy[mine]).sparse_distance_matrix(tree, reach, output_type="ndarray")
        keep = (found["v"] >= r0) & (found["v"] < reach)
        a, b = mine[found["i"][keep]], peers[found["j"][keep]]
        who.append(a)
        disp.append(arr.xy[b] - arr.xy[a])
    who = np.concatenate(who) if who else np.zeros(0, np.int64)
    if len(who) == 0:
        return Repetition(0.0, 0.0, None, 0.0, None, own, 0.0, 0.0, None)
    disp = np.concatenate(disp)
    # with no order to leave out, the total's mode is the first peak below (the same bin: the
    # most populated, the first in row-major order on a tie), so its figures are taken there
    total = _mode_share(who, disp, ref, len(arr), q, reach, chance, roomy) if len(steps) else None
    mine = ~explained(disp, steps, BOX * q) if len(steps) else slice(None)  # no order: nothing to leave out
    who, disp = who[mine], disp[mine]
    cell = np.floor(disp / q).astype(np.int64)
    peaks = _peaks(cell, math.ceil(reach / q) + 1, REPEAT_PEAKS)
    if len(peaks) == 0:  # no displacement left, or none in the half-plane the peaks are taken in
        if total is None:
            total = _mode_share(who, disp, ref, len(arr), q, reach, chance, roomy)
        return Repetition(0.0, 0.0, None, *total[::2], own, 0.0, 0.0, None)
    centres = (peaks + 0.5) * q
    fit = roomy.at(centres) if roomy is not None else [None] * len(peaks)  # (k, r) bool: room at each peak
    raws, vectors = [], []
    for (mx, my), fit_k in zip(peaks, fit, strict=True):
        near = (np.abs(cell[:, 0] - mx) <= 1) & (np.abs(cell[:, 1] - my) <= 1)
        has = np.zeros(len(arr), dtype=bool)
        has[who[near]] = True
        raws.append(_share(has, ref, fit_k))
        vector = disp[near].mean(axis=0)
        vectors.append((float(vector[0]), float(vector[1])))
    # the single mode against chance alone: the figure of issue 12
    order = (max(0.0, (raws[0] - chance) / (1.0 - chance)) if chance < 1 else 0.0, vectors[0])
    if total is None:  # _mode_share's figures of the same bin
        total = (order[0], raws[0], vectors[0])
    raws = np.array(raws)
    shown = _reduced_shares(exemplar, centres, steps, BOX * q, REPEAT_DIVIDE * s, EXACT * s)
    base = np.maximum(np.maximum(chance, _rows_floor(exemplar, centres, lam[arr.kind[ref]], q)), shown)
    if exemplar.period is not None:
        # a tile's kinds at their own steps (the reading can only raise P_ex, so it is asked only
        # where there is an excess to lower, and at the first peak, which is reported if none is left)
        ask = raws > base
        ask[0] = True
        shown[ask] = np.maximum(shown[ask], _kind_shares(exemplar, centres[ask], BOX * q, REPEAT_DIVIDE * s))
        base = np.maximum(base, shown)
    excess = np.where(base < 1, np.maximum(0.0, (raws - base) / np.where(base < 1, 1.0 - base, 1.0)), 0.0)
    k = int(np.argmax(excess))  # the first of the largest
    return Repetition(
        float(excess[k]), float(raws[k]), vectors[k], total[0], total[2], own, float(shown[k]), order[0], order[1]
    )


def _peaks(cell: np.ndarray, half: int, most: int) -> np.ndarray:
    """(k, 2) int: the ``most`` most populated bins of ``cell`` in the half-plane, each > 2 bins apart.

    ``cell`` (p, 2) int, the bin of each displacement, ``|cell| < half`` per axis.  Greedy: the
    most populated bin, then the most populated at least 3 bins (per axis) from those taken, …;
    row-major order on a tie.  Step 3 of :func:`repetition`.
    """
    side = 2 * half + 1
    upper = (cell[:, 0] > 0) | ((cell[:, 0] == 0) & (cell[:, 1] >= 0))
    key = (cell[upper, 0] + half) * side + (cell[upper, 1] + half)
    if side * side <= 1 << 24:
        count = np.bincount(key, minlength=side * side)
        values = np.flatnonzero(count)
        count = count[values]
    else:
        values, count = np.unique(key, return_counts=True)
    # a peak suppresses at most 24 bins around it: the `most` peaks are among the top 25·most
    top = np.argsort(-count, kind="stable")[: 25 * most]
    taken: list[tuple[int, int]] = []
    for key in values[top]:
        x, y = int(key) // side - half, int(key) % side - half
        if all(abs(x - tx) > 2 or abs(y - ty) > 2 for tx, ty in taken):
            taken.append((x, y))
            if len(taken) == most:
                break
    return np.array(taken, dtype=np.int64).reshape(-1, 2)


def _rows_floor(exemplar: Exemplar, shifts: np.ndarray, lam_ref: np.ndarray, q: float) -> np.ndarray:
    """(k,) float: chance of a same-kind partner in the ``3q × 3q`` square at each shift in a
    texture that keeps the exemplar's rows, 0 where the shift is no whole row offset.

    A drawn exemplar of rows (:func:`svgtile.engines.growth.rows.row_lines`: marsh's tufts) puts
    every motif on one of evenly spaced lines, ``pitch`` apart.  A texture faithful to it does
    too, so every partner's displacement across the rows is a whole number of pitches, and two
    motifs on rows ``n`` pitches apart fall into one square about as often as two motifs thrown
    at random along a line fall into one ``3q`` stretch of it — far more often than two thrown
    over the plane (the figure's ``P0``): the rows concentrate partners on the lines.  That is
    what a viewer sees as rows, not as a repeat.  So at a shift within ``1.5 q`` across of a whole
    row offset the figure's chance is, per reference of kind c,
    ``1 − exp(−λ_c · pitch · 3q · a)``: ``λ_c · pitch`` the kind's motifs per unit length of row,
    ``a`` the share of the exemplar's motif pairs whose offsets from their lines (the hand's
    jitter) differ by at most ``1.5 q`` (they meet in the square's height); the mean over the
    references.  Along the rows nothing is excused: more partners than that — a run copied, a
    period stamped — is repetition.  A repeating tile has no row lines here (its period is read
    by the exact order and ``P_ex``).

    ``shifts`` (k, 2) float, user units; ``lam_ref`` (r,) float, λ of each reference's kind
    (motifs per square user unit, in the window); ``q`` the bin, user units.
    """
    out = np.zeros(len(shifts))
    if len(shifts) == 0 or len(lam_ref) == 0:
        return out
    from svgtile.engines.growth.rows import row_lines  # the row lines of a drawn exemplar

    lines = row_lines(exemplar)
    if lines is None:
        return out
    across = np.asarray(shifts, np.float64) @ lines.across
    whole = np.abs(across - np.round(across / lines.pitch) * lines.pitch) <= BOX * q
    res = np.sort(lines.residual)
    m = len(res)
    # pairs i < j (sorted) with res[j] − res[i] ≤ 1.5 q, counted without forming the m² pairs
    close = np.searchsorted(res, res + BOX * q, side="right") - np.arange(1, m + 1)
    meet = float(close.sum() / (m * (m - 1) / 2)) if m > 1 else 1.0
    p = float(np.mean(-np.expm1(-lam_ref * lines.pitch * 3 * q * meet)))
    out[whole] = p
    return out


class _Room:
    """Which references have room for a partner at a shift (step 4 of :func:`repetition`).

    ``room`` the texture's region (shapely, user units; holes and several parts allowed);
    ``margin`` the square's half side, user units; ``xy`` (r, 2) the references' positions.
    A reference has room at ``v`` where ``x + v`` lies ``margin`` inside ``room``: its square
    ``x + v ± margin`` lies inside a rectangle, and a disc of that radius inside any region.
    """

    def __init__(self, room: shapely.Geometry, margin: float, xy: np.ndarray) -> None:
        self.inner = inset(room, margin)
        self.xy = xy

    def at(self, shifts: np.ndarray) -> np.ndarray:
        """(k, r) bool: room at each of ``shifts`` (k, 2), user units."""
        shifts = np.asarray(shifts, np.float64).reshape(-1, 2)
        p = self.xy[None, :, :] + shifts[:, None, :]
        return shapely.contains_xy(self.inner, p[..., 0], p[..., 1])


def _share(has: np.ndarray, ref: np.ndarray, fit: np.ndarray | None) -> float:
    """``P_tex``: the share of the references ``ref`` (r,) with a partner (``has``, (n,) bool per
    motif), among those with room (``fit``, (r,) bool; None: every one, the reading without
    ``room``), over at least :data:`REPEAT_ROOM_MIN` of them (or r, if fewer); 0 where fewer than
    :data:`REPEAT_EX_MIN` have room."""
    if fit is None:
        return float(has[ref].mean())
    roomy = ref[fit]
    if len(roomy) < REPEAT_EX_MIN:  # the texture cannot show v, as the exemplar cannot (step 5)
        return 0.0
    return float(has[roomy].sum() / max(len(roomy), min(len(ref), REPEAT_ROOM_MIN)))


def _mode_share(
    who: np.ndarray, disp: np.ndarray, ref: np.ndarray, n: int, q: float, reach: float, chance: float,
    roomy: _Room | None = None,
) -> tuple[float, float, tuple[float, float] | None]:  # fmt: skip
    """Steps 3–5 of :func:`repetition`: (corrected, raw, vector) of the displacements given.

    ``who`` (p,) the reference of each displacement ``disp`` (p, 2); ``ref`` the references;
    ``n`` the motif count; ``q`` the bin, ``reach`` R, ``chance`` P0; ``roomy`` which references have
    room at a shift (None: every one).
    """
    if len(who) == 0:
        return 0.0, 0.0, None
    cell = np.floor(disp / q).astype(np.int64)
    half = math.ceil(reach / q) + 1
    side = 2 * half + 1
    key = (cell[:, 0] + half) * side + (cell[:, 1] + half)
    # v and −v are equally common: the mode is taken in the half-plane dx > 0 (or dx = 0, dy ≥ 0)
    upper = (cell[:, 0] > 0) | ((cell[:, 0] == 0) & (cell[:, 1] >= 0))
    if side * side <= 1 << 24:
        count = np.bincount(key[upper], minlength=side * side)
        mode = int(np.argmax(count))
    else:
        values, count = np.unique(key[upper], return_counts=True)
        mode = int(values[np.argmax(count)])
    mx, my = mode // side - half, mode % side - half
    near = (np.abs(cell[:, 0] - mx) <= 1) & (np.abs(cell[:, 1] - my) <= 1)
    has = np.zeros(n, dtype=bool)
    has[who[near]] = True
    raw = _share(has, ref, None if roomy is None else roomy.at((np.array([mx, my]) + 0.5) * q)[0])
    corrected = max(0.0, (raw - chance) / (1.0 - chance)) if chance < 1 else 0.0
    if not near.any():
        return corrected, raw, None
    vector = disp[near].mean(axis=0)
    return corrected, raw, (float(vector[0]), float(vector[1]))
