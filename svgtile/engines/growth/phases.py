"""Row phases: growth on a tile of hand-jittered rows that does not repeat at the tile's period.

On a repeating tile the growth engine moves each grown motif to the nearest site of its kind in
the tile's pattern (:meth:`.engine.Growth.on_sites`), so that fronts grown from two seeds meet in
step.  On a tile whose rows are drawn by hand — FGDC 619 and 620: eighteen rows of dashes (619:
dashes and dots by turns), each row repeating its content exactly every 8.93 units along x, each
row put at its own hand-drawn phase — the tile's pattern repeats the eighteen phases at the tile's height, and so does every
texture snapped to it, as stamping the tile does.

Such a tile holds more than its period tells: a row is exact along x, so it may be moved along
itself by any phase and still be the tile's row; and the tile shows how a row's phase follows
the one below (its *row-to-row phase steps*).  This module makes world rows out of the tile's
rows, in the tile's order and at the tile's heights, and gives world row ``k`` the phase of row
``k − 1`` plus one of the tile's own phase steps, drawn by a world-anchored hash of ``(key, k)``
(:mod:`svgtile.core.cellrng`) among those that keep the two rows clear of the distance rule
(:func:`fitting_steps`) — a Markov chain of phases over the world rows, the texture
``tests/row_probes.py``'s ``markov_rows`` samples.  Neighbouring rows relate as some pair of the
tile's rows does; the phase wanders, so the tile's period is gone.  Growth still decides which
sites are filled and the kinds, as on any tile; only the sites move.

It applies to a tile (read by :func:`row_phases`) whose motifs fall into at least
:data:`~svgtile.engines.growth.rows.MIN_ROWS` rows across y, whose whole pattern repeats
exactly by a step along x shorter than the tile's width (an exact symmetry step of
:func:`svgtile.analysis.order.symmetry_steps`, the row's step), and which has no exact step
across its rows: a tile whose rows already repeat at a shorter step across them (a brick or a
lattice drawn exactly: FGDC 711, vineyard) has its order in that step and keeps its sites.  Of
the twenty regular FGDC and osm-carto tiles only 619 and 620 are such tiles (FGDC 670's rows of
dashes are jittered along x: they have no along-row step; and its rows repeat every four rows
within the exact-step tolerance).

References
----------
Ijiri, Měch, Igarashi & Miller 2008, §5.4 (growth places the ring's slots; here the slots snap to
the world rows' sites instead of the tile's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from svgtile.analysis.order import EXACT_STEP, symmetry_steps
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.engines.growth.rows import MIN_ROWS

#: The hash stream of the phase steps (the engine's own streams are 0–3).
STREAM = 4
#: Phases are summed as whole multiples of this many user units, so that a world row's phase is
#: exact however far it lies from the origin (an integer walk, no rounding drift).
QUANTUM = 1e-6
#: :meth:`RowPhases.walk` works out the phases of this many rows more each way than it is asked for.
WALK_BLOCK = 256
#: :meth:`RowPhases.sites` looks at the sites of this many world rows nearest a position's height.
NEAR = 3
#: A site's distance counts its across-row part this many times: a prediction lies on its row's
#: height exactly but up to half a row step off its phase, and must snap onto its own row.
ACROSS_WEIGHT = 4.0


@dataclass(frozen=True, eq=False)
class RowPhases:
    """A tile's rows as world rows with wandering phases.

    Attributes
    ----------
    period : (2,) float array, user units — the tile's width and height
    step : float, user units — the exact step along a row (x)
    row : (m,) int array — the tile row of each exemplar motif (0 the lowest y)
    phase : (n,) int array, :data:`QUANTUM` units — each tile row's phase: x of its first motif of
        its lowest kind, modulo ``step``
    steps : (n,) int array, :data:`QUANTUM` units — the tile's phase step from each row to the next
        (the last to the first row's copy above), modulo ``step``
    choices : (n, n) int array — row ``r``'s first ``count[r]`` entries are the steps (indices
        into ``steps``) by which row ``r + 1`` may follow row ``r``: those that put no motif of
        the two rows in conflict (:func:`fitting_steps`); its own, ``r``, always among them
    count : (n,) int array
    key : int — the run's root key (:func:`svgtile.core.cellrng.root_key`)
    """

    period: np.ndarray
    step: float
    row: np.ndarray
    phase: np.ndarray
    steps: np.ndarray
    choices: np.ndarray
    count: np.ndarray
    key: int
    _walks: dict = field(default_factory=dict, repr=False)  # the phases worked out so far (:meth:`walk`)

    @property
    def rows(self) -> int:
        return len(self.phase)

    def reach(self, ring_radius: float) -> float:
        """User units: how far around a motif the gap fill (:mod:`.gapfill`) predicts on these rows
        — the ring radius, and at least one along-row step.  The tile's predictions across rows
        land up to half a step off a row at its own phase and are snapped to its sites, two of
        them at times onto one; a motif's neighbours along its own row are exact, so a gap in a
        row closes from both ends (FGDC 620: its ring radius 6.8 is under its step, 8.93, and
        holes two dashes wide and five rows high stayed open)."""
        return 1.05 * max(ring_radius, 1.01 * self.step)

    def walk(self, k: np.ndarray) -> np.ndarray:
        """(…) int: the phase of world rows ``k`` (int array; row ``b·n + r`` is tile row ``r`` of
        tile copy ``b``), in :data:`QUANTUM` units modulo the step.  Row 0 has tile row 0's phase;
        row ``k + 1`` adds a phase step that fits after row ``k``'s tile row (``choices``), chosen
        by a hash of ``(key, k)`` — summed from row 0, so a row's phase is the same whatever rows
        are asked for with it."""
        k = np.asarray(k, np.int64)
        lo, hi = min(int(k.min(initial=0)), 0), max(int(k.max(initial=0)), 0)
        table = self._walks.get("table")
        if table is None or lo < self._walks["lo"] or hi >= self._walks["lo"] + len(table):
            # the phases of rows lo … hi, a block of WALK_BLOCK rows more each way: a run asks again and again
            lo, hi = min(lo, self._walks.get("lo", 0)) - WALK_BLOCK, max(hi, self._walks.get("hi", 0)) + WALK_BLOCK
            i = np.arange(lo, hi)
            r = i % self.rows
            pick = (cellrng.hash64(self.key, STREAM, i) % self.count[r].astype(np.uint64)).astype(np.int64)
            d = self.steps[self.choices[r, pick]]
            up = np.cumsum(d[i >= 0])  # up[k − 1] = the steps of rows 0 … k − 1
            down = np.cumsum(d[i < 0][::-1])  # down[j − 1] = the steps of rows −j … −1
            table = (self.phase[0] + np.r_[-down[::-1], 0, up[:-1]]) % round(self.step / QUANTUM)
            self._walks.update(table=table, lo=lo, hi=hi)
        return table[k - self._walks["lo"]]

    def shift(self, b: np.ndarray, r: np.ndarray) -> np.ndarray:
        """(…) float, user units in [0, step): how far tile row ``r`` of tile copy ``b`` (int
        arrays, broadcast) is moved along x from where the tile puts it."""
        q = round(self.step / QUANTUM)
        return ((self.walk(np.asarray(b) * self.rows + r) - self.phase[r]) % q) * QUANTUM

    def place(self, exemplar: Exemplar, s: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """(…, 2) float: where exemplar motif ``s`` of tile copy ``(a, b)`` lies (int arrays,
        broadcast; copy ``(0, 0)`` is the tile where it is drawn)."""
        w, h = self.period
        s, a, b = np.broadcast_arrays(s, a, b)
        xy = exemplar.motifs.xy[s]
        return np.stack([xy[..., 0] + a * w + self.shift(b, self.row[s]), xy[..., 1] + b * h], axis=-1)

    def sites(self, exemplar: Exemplar, xy: np.ndarray, kind: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each position moved to the nearest site of its kind in the world rows (across-row
        distance counted :data:`ACROSS_WEIGHT` times): (n, 2) positions and (n,) the exemplar
        motifs (sub-ids) they now copy.

        The sites looked at are those of the :data:`NEAR` world rows nearest each position's
        height — a site farther across costs more than the worst miss along a nearer row — so a
        position weighs a few rows' motifs, not every motif of the tile.

        Parameters
        ----------
        exemplar : the tile
        xy : (n, 2) float array, user units
        kind : (n,) int array
        """
        motifs = exemplar.motifs
        w, h = self.period
        n = self.rows
        height = np.bincount(self.row, weights=motifs.xy[:, 1], minlength=n) / np.bincount(self.row, minlength=n)
        out, sub = np.array(xy, float).reshape(-1, 2), np.zeros(len(xy), np.int64)
        for c in np.unique(kind):
            i = np.flatnonzero(kind == c)
            # (n, L) the kind's motifs of each tile row, −1 where a row has fewer
            mine = np.flatnonzero(motifs.kind == c)
            mine = mine[np.argsort(self.row[mine], kind="stable")]
            count = np.bincount(self.row[mine], minlength=n)
            table = np.full((n, max(int(count.max()), 1)), -1, np.int64)
            table[self.row[mine], np.arange(len(mine)) - np.repeat(np.cumsum(count) - count, count)] = mine
            # (n_i, NEAR) the nearest world rows: tile row and copy
            copy = np.round((out[i, 1, None] - height[None]) / h).astype(np.int64)
            off = np.abs(out[i, 1, None] - height[None] - copy * h) + np.where(count > 0, 0.0, np.inf)[None]
            near = np.argsort(off, axis=1, kind="stable")[:, : min(NEAR, n)]
            b = np.take_along_axis(copy, near, axis=1)
            cand = table[near]  # (n_i, NEAR, L)
            valid = cand >= 0
            cand = np.maximum(cand, 0)
            x0 = motifs.xy[cand, 0] + self.shift(b, near)[..., None]
            a = np.round((out[i, 0, None, None] - x0) / w)
            site = np.stack([x0 + a * w, motifs.xy[cand, 1] + (b * h)[..., None]], axis=-1).reshape(len(i), -1, 2)
            miss = (site - out[i, None]) * (1.0, ACROSS_WEIGHT)
            cost = np.where(valid.reshape(len(i), -1), np.hypot(miss[..., 0], miss[..., 1]), np.inf)
            best = np.argmin(cost, axis=1)
            out[i], sub[i] = site[np.arange(len(i)), best], cand.reshape(len(i), -1)[np.arange(len(i)), best]
        return out, sub


def fitting_steps(exemplar: Exemplar, row: np.ndarray, steps: np.ndarray, step: float, distance: np.ndarray,
                  ) -> np.ndarray:  # fmt: skip
    """(n, n) bool: whether row ``r + 1`` may follow row ``r`` by phase step ``steps[j]`` — no
    footprint of the two rows overlapping or closer than the distance rule ``distance`` ((k, k),
    user units) — the tile's own step ``j = r`` always.

    A phase step is another pair of rows' relation; the rows' heights and the hand's jitter differ
    from pair to pair, so not every step suits every pair (FGDC 619: dashes one row apart keep
    3.29 units, its rows lie 2.8–3.2 apart; unchecked, 48–132 motifs of ``markov_rows`` break the
    rule over 4 × 4 tiles, and the exact check left holes in growth's rows).  All n² pairs of
    rows are laid out at once, far apart, and checked in one :func:`find_conflicts`.

    Parameters
    ----------
    row : (m,) int array — each exemplar motif's tile row
    steps : (n,) int array, :data:`QUANTUM` units — the tile's row-to-row phase steps
    step : float, user units — the along-row step
    """
    m = exemplar.motifs
    w, h = exemplar.period
    n = len(steps)
    r, j = (v.ravel() for v in np.meshgrid(np.arange(n), np.arange(n), indexing="ij"))
    # row r + 1 moves by (steps[j] − steps[r]) from where the tile has it; the last row's next is
    # row 0 of the copy above
    moved = ((steps[j] - steps[r]) % round(step / QUANTUM)) * QUANTUM
    parts, owner, lower = [], [], []
    for side, nxt in ((0, r), (1, (r + 1) % n)):
        s = [np.flatnonzero(row == x) for x in nxt]
        cnt = np.array([len(x) for x in s])
        idx = np.concatenate(s)
        c = np.repeat(np.arange(n * n), cnt)
        for a in (-1, 0, 1):
            xy = m.xy[idx] + np.c_[a * w + side * moved[c], side * (r[c] == n - 1) * h + c * 4 * h]
            parts.append(Arrangement(m.kind[idx], xy, m.angle[idx], m.scale[idx]))
            owner.append(c)
            lower.append(np.full(len(idx), side == 0 and a == 0))
    both = Arrangement.concat(parts)
    owner, lower = np.concatenate(owner), np.concatenate(lower)
    side = np.concatenate([np.full(len(p), k >= 3) for k, p in enumerate(parts)])
    found = find_conflicts(both, exemplar.prototypes, distance)
    i, k = found.i, found.j
    # a pair of one configuration, one motif of row r's middle copy, the other of row r + 1
    hit = (owner[i] == owner[k]) & (side[i] != side[k]) & (lower[i] | lower[k])
    bad = np.zeros(n * n, bool)
    bad[owner[i[hit]]] = True
    ok = ~bad.reshape(n, n)
    ok[np.arange(n), np.arange(n)] = True
    return ok


def row_phases(exemplar: Exemplar, key: int, distance: np.ndarray) -> RowPhases | None:
    """The world rows of a tile of rows exact along x whose phases repeat only at the tile's
    height (see the module docstring), or None for any other exemplar.

    ``distance`` is the distance rule ((k, k), user units; :func:`fitting_steps`).  The rows are
    cut where the motifs' sorted y jump by more than half the mean spacing
    ``√(w·h / m)``; the step along them is the tile's exact symmetry step along x (tolerance
    :data:`svgtile.analysis.order.EXACT_STEP` spacings), which must map every motif and divide
    the width; an exact step across the rows that maps every motif refuses the tile (one that maps
    some rows only is a few rows the hand happened to draw at one relation, and does not).
    """
    if exemplar.period is None or len(exemplar.motifs) < MIN_ROWS:
        return None
    m = exemplar.motifs
    w, h = (float(v) for v in exemplar.period)
    spacing = math.sqrt(w * h / len(m))
    tol = EXACT_STEP * spacing
    found = symmetry_steps(m.xy, m.kind, (w, h), tol)
    along = [s for s in found if abs(s.vector[1]) <= tol and s.support >= 1.0]
    across = [s for s in found if abs(s.vector[1]) > tol and s.support >= 1.0]
    if not along or across:  # no row step, or the rows' phases repeat at a step across them
        return None
    step = abs(float(along[0].vector[0]))
    whole = round(w / step)
    if not (tol < step < w - tol and abs(whole * step - w) <= tol):
        return None
    step = w / whole  # the width holds a whole number of steps: the exact value, not the measured one
    y = m.xy[:, 1]
    by = np.argsort(y, kind="stable")
    row = np.empty(len(y), np.int64)
    row[by] = np.r_[0, np.cumsum(np.diff(y[by]) > 0.5 * spacing)]
    n = int(row.max()) + 1
    if n < MIN_ROWS:
        return None
    q = round(step / QUANTUM)
    phase = np.array([round(float(np.min(m.xy[(row == r) & (m.kind == m.kind[row == r].min()), 0] % step)) / QUANTUM)
                      for r in range(n)], np.int64) % q  # fmt: skip
    steps = np.diff(np.r_[phase, phase[0]]) % q
    ok = fitting_steps(exemplar, row, steps, step, distance)
    count = ok.sum(1)
    choices = np.argsort(~ok, axis=1, kind="stable")  # each row's fitting steps first, in order
    return RowPhases(np.array([w, h]), step, row, phase, steps, choices, count, int(key))


def on_rows(phases: RowPhases, exemplar: Exemplar, cand: Arrangement, support: np.ndarray,
            ) -> tuple[Arrangement, np.ndarray, np.ndarray]:  # fmt: skip
    """The gap fill's candidates (:func:`.gapfill.candidates`: the tile's own predictions around
    each placed motif) moved onto the world rows' sites, merged where they meet, supports added.

    Parameters
    ----------
    phases : the world rows
    exemplar : the tile
    cand : the c predicted motifs
    support : (c,) int array — how many placed motifs predict each

    Returns
    -------
    arrangement : the distinct sites, quantized; sub : their exemplar motifs; support : summed
    """
    xy, sub = phases.sites(exemplar, cand.xy, cand.kind)
    ex = exemplar.motifs
    arr = Arrangement(ex.kind[sub], xy, ex.angle[sub], ex.scale[sub]).quantized(DECIMALS)
    key = np.c_[sub, np.round(arr.xy * 10**DECIMALS).astype(np.int64)]
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    total = np.bincount(inverse.ravel(), weights=support, minlength=len(first)).astype(np.int64)
    return arr.take(first), sub[first], total


__all__ = ["ACROSS_WEIGHT", "NEAR", "QUANTUM", "STREAM", "RowPhases", "fitting_steps", "on_rows", "row_phases"]
