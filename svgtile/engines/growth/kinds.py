"""The final kind pass: each motif's kind re-chosen against its joined ring (Ijiri et al. 2008, §5.2).

Growth gives a seed its kind from the one ring slot that made it (§5.4, Fig. 2f–g) and matches
its reference among the rings of that kind (eq. 1–3).  Each choice is good for the neighbours
placed *then*; the ring a motif ends with — its neighbours on every side, those of the
neighbouring cells among them — is matched by no one.  On a hand-drawn exemplar of rows the
error adds up with distance from the cell's start seed (marsh, one cell 300 units wide: E 0.43
within 20 units of the start, 0.96 at 70–100; benchmarks/README.md, "Growth's kinds"), and
most of it is kinds: with kinds ignored E is 0.12 against the tile's 0.07, with them 0.72
against 0.32.

This pass re-decides the kinds with the paper's own error.  A motif's neighbourhood error is
eq. (3) of its complete ring — its Gabriel neighbours now, counter-clockwise
(:func:`~svgtile.engines.growth.connectivity.ring_of`) — against the reference rings of its
kind, the best shift and reference (eq. 1, :func:`~svgtile.engines.growth.kernel.match`); the
pass lowers the sum of those errors over the texture by changing kinds alone, in sweeps: every
motif that may change finds the kind that lowers the errors of the rings it is in (its own and
its neighbours') the most, and it changes when that lowers the sum and no ring neighbour would
gain more by changing (so two neighbours never change on each other's old kinds in one sweep).
Positions stay; a motif that changes kind copies the best-matching reference element of its new
kind (its sub-id, angle and scale, §5.4).  The exact footprint check is the engine's: a changed
motif that would overlap, break the distance rule or cross a barrier keeps its old kind.

Changing kinds alone to lower a neighbourhood error moves the kind mix wherever one kind fits more
neighbourhoods than its share: on marsh (kind 0: 0.41 of the exemplar's tufts, 0.40 of the
texture's without the passes) the first version took it to 0.31 (kind-mix TV 0.12–0.15) and L
from 0.77 to 0.85, nearly all of its gain.  Both passes now hold each kind's count to the
exemplar's share (:func:`mix_bounds`, ± :data:`MIX`), and the engine sends back the changes its
exact check would leave uneven; with the mix held the passes add little (marsh, seeds 1–7: L 0.770
without them, 0.778 with; benchmarks/README.md, "growth's kind mix").

Deterministic and world-anchored: it reads only positions, kinds and sub-ids, with no draws.
The sweeps are one compiled loop (:func:`sweep`) over the motifs — sequential by nature, each
sweep reads the kinds the last one left — calling the matching kernel once per ring evaluated.

The engine follows the sweeps with a second pass (``then``: :mod:`.neighbourkinds`, ma2011's
k-nearest neighbourhoods) before the changed motifs' references are found.
"""

from __future__ import annotations

from collections.abc import Callable

import numba
import numpy as np
from scipy.spatial import cKDTree

from svgtile.engines.growth import Weights
from svgtile.engines.growth.connectivity import Rings, ring_of
from svgtile.engines.growth.kernel import NONE, match

#: Sweeps of the pass (marsh at 300 × 300, seeds 1–3, L, when the pass held no kind mix: none 0.763
#: / 0.769 / 0.755, two 0.807 / 0.790 / 0.770, four 0.821 / 0.798 / 0.772, eight the same as four).
SWEEPS = 4
#: Each kind's count over a piece's motifs and the fixed ones around it stays within this share
#: of their number of the exemplar's (by count), or where it already is if further
#: (:func:`mix_bounds`): the passes change kinds alone, and left free they drift the mix towards
#: the kind that fits the most neighbourhoods (marsh, 300 × 300: kind 0 0.40 → 0.31 of the motifs
#: against the exemplar's 0.41, kind-mix TV 0.009 → 0.116; benchmarks/README.md "growth's kind
#: mix").  The optimize engine's kind step holds the same share
#: (:data:`svgtile.engines.optimize.assign.MIX`), per world window.
MIX = 0.01
#: The error of a ring no reference can match (larger than any ring's: M kind terms and M
#: neighbours several edge lengths off).
UNMATCHED = 1e6


def mix_bounds(kind: np.ndarray, movable: np.ndarray, frequency: np.ndarray | None,
               nkind: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """The counts the kind passes hold the kinds to.

    Counted over every motif given, the fixed ones around a piece (the cell's earlier motifs and
    its earlier-phase neighbours', whose kinds count but stay) with its own: a piece of 60–90
    motifs alone would round each bound outwards by up to a motif, and pieces side by side would
    add those up.

    Parameters
    ----------
    kind : (n,) int array
    movable : (n,) bool array — the motifs whose kinds may change (no bound — ``lo`` 0, ``hi`` the
        int64 maximum ÷ 2 — when none may)
    frequency : (k,) float array, each kind's share of the exemplar's motifs (by count), or None
        for no bound
    nkind : int ≥ k, the kinds the passes may choose

    Returns
    -------
    count, lo, hi : (nkind,) int arrays — each kind's count among the n motifs now, and the least
    and most it may reach: ``(frequency ± MIX) × n`` rounded outwards, widened to hold the count it
    has (a kind already past the band may only come back)
    """
    count = np.bincount(np.asarray(kind), minlength=nkind).astype(np.int64)
    if frequency is None or not np.any(movable):
        return count, np.zeros(nkind, np.int64), np.full(nkind, np.iinfo(np.int64).max // 2, np.int64)
    f = np.zeros(nkind)
    f[: len(frequency)] = frequency
    n = int(count.sum())
    lo = np.minimum(np.floor((f - MIX) * n), count).astype(np.int64)
    hi = np.maximum(np.ceil((f + MIX) * n), count).astype(np.int64)
    return count, lo, hi


def neighbour_rings(xy: np.ndarray, centres: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray]:
    """Each centre's complete ring among ``xy``: the Gabriel neighbours within ``reach``,
    counter-clockwise (:func:`~svgtile.engines.growth.connectivity.ring_of`).

    Parameters
    ----------
    xy : (n, 2) float array, user units
    centres : (c,) int array — indices into ``xy``
    reach : float, user units

    Returns
    -------
    ptr : (c + 1,) int array; ``idx[ptr[q]:ptr[q + 1]]`` is centre q's ring
    idx : (p,) int array — indices into ``xy``
    """
    near = cKDTree(xy).query_ball_point(xy[centres], reach)
    parts = []
    for c, nb in zip(centres, near, strict=True):  # a loop over rings: each is a small compiled call
        nb = np.array([q for q in nb if q != c], np.int64)
        parts.append(nb[ring_of(xy[nb], xy[c])] if len(nb) else nb)
    ptr = np.concatenate([[0], np.cumsum([len(p) for p in parts])]).astype(np.int64)
    return ptr, (np.concatenate(parts) if parts else np.zeros(0, np.int64)).astype(np.int64)


@numba.njit(cache=True)
def _error(c, kind, sub, xy, ptr, idx, rel, size, rkind, nkind, nsub, mean_length, w, noise, out):  # pragma: no cover
    """Eq. (3) of centre ``c``'s ring (row ``c`` of ``ptr``/``idx``) with kinds ``kind``; the best
    reference ring in ``out[0][0]``."""
    t = ptr[c + 1] - ptr[c]
    tar = np.empty((t, 2))
    tkind = np.empty(t, np.int64)
    tsub = np.empty(t, np.int64)
    for j in range(t):
        q = idx[ptr[c] + j]
        tar[j, 0], tar[j, 1] = xy[q, 0] - xy[c, 0], xy[q, 1] - xy[c, 1]
        tkind[j], tsub[j] = kind[q], sub[q]
    got = match(rel, size, rkind, nkind, nsub, mean_length, tar, tkind, tsub, kind[c], NONE, 0.0, w[0], w[1], w[2],
                noise, 1, out[0], out[1], out[2], out[3])  # fmt: skip
    return out[3][0] if got else UNMATCHED


@numba.njit(cache=True)
def sweep(kind, sub, xy, ptr, idx, mptr, midx, movable, k, rel, size, rkind, nkind, nsub, mean_length, w,
          sweeps, ring_of_motif, count, lo, hi):  # fmt: skip  # pragma: no cover
    """The pass's sweeps over ``kind`` ((n,) int, changed in place); returns (n,) the reference
    ring each changed motif now copies (−1: unchanged).

    Centre ``c`` (a row of ``ptr``) is motif ``c``; ``mptr``/``midx`` list, for each motif, the
    centres whose rings hold it; ``movable`` ((n,) bool) the motifs that may change; ``w`` eq.
    (2)'s weights; ``ring_of_motif`` is filled with the reference each changed motif matches.
    A change from kind ``a`` to ``q`` is made only while ``count[a] > lo[a]`` and ``count[q] <
    hi[q]`` (:func:`mix_bounds`; ``count`` is updated in place)."""
    n = kind.shape[0]
    noise = np.zeros(rel.shape[0])
    out = (np.empty(1, np.int64), np.empty(1, np.int64), np.empty(1), np.empty(1))
    needed = movable.copy()  # the rings a change can touch: those of the movable motifs, those holding one
    for i in range(n):
        if movable[i]:
            for m in range(mptr[i], mptr[i + 1]):
                needed[midx[m]] = True
    cur = np.empty(n)
    fresh = np.zeros(n, np.bool_)  # cur[c] holds ring c's error with the kinds as they are
    gain = np.zeros(n)
    best = kind.copy()
    dirty = movable.copy()  # gain[i] and best[i] must be found again
    for _ in range(sweeps):
        for c in range(n):
            if needed[c] and not fresh[c]:
                cur[c] = _error(c, kind, sub, xy, ptr, idx, rel, size, rkind, nkind, nsub, mean_length, w, noise, out)
                fresh[c] = True
        for i in range(n):
            if not dirty[i]:
                continue  # no ring it is in, nor any of their members, changed kind: its gain stands
            dirty[i] = False
            gain[i], best[i] = 0.0, kind[i]
            old = kind[i]
            if count[old] <= lo[old]:
                continue  # its kind may not lose a motif
            for a in range(k):
                if a == old or count[a] >= hi[a]:
                    continue
                kind[i] = a
                d = _error(i, kind, sub, xy, ptr, idx, rel, size, rkind, nkind, nsub, mean_length, w, noise, out) - cur[i]
                for m in range(mptr[i], mptr[i + 1]):
                    c = midx[m]
                    d += _error(c, kind, sub, xy, ptr, idx, rel, size, rkind, nkind, nsub, mean_length, w, noise,
                                out) - cur[c]  # fmt: skip
                if d < gain[i] - 1e-9:
                    gain[i], best[i] = d, a
            kind[i] = old
        flip = np.zeros(n, np.bool_)
        for i in range(n):
            if gain[i] >= 0.0:
                continue
            flip[i] = True
            for j in range(ptr[i], ptr[i + 1]):  # a ring neighbour that gains more changes instead
                q = idx[j]
                if gain[q] < gain[i] or (gain[q] == gain[i] and q < i):
                    flip[i] = False
                    break
        if not flip.any():
            break
        for f in range(n):
            if not flip[f]:
                continue
            if count[kind[f]] <= lo[kind[f]] or count[best[f]] >= hi[best[f]]:
                dirty[f] = True  # an earlier change this sweep used the room: its choice is found again
                continue
            count[kind[f]] -= 1
            count[best[f]] += 1
            kind[f] = best[f]
            # the rings whose error reads f's kind: its own and those holding it; and every motif
            # whose gain reads one of them (the ring's centre and its members)
            for m in range(-1, mptr[f + 1] - mptr[f]):
                c = f if m < 0 else midx[mptr[f] + m]
                fresh[c] = False
                dirty[c] = movable[c]
                for j in range(ptr[c], ptr[c + 1]):
                    dirty[idx[j]] = movable[idx[j]]
    for i in range(n):
        if ring_of_motif[i] == -2:  # asked for: the reference its (new) ring matches best
            e = _error(i, kind, sub, xy, ptr, idx, rel, size, rkind, nkind, nsub, mean_length, w, noise, out)
            ring_of_motif[i] = out[0][0] if e < UNMATCHED else -1
    return ring_of_motif


def repick(rings: Rings, xy: np.ndarray, kind: np.ndarray, sub: np.ndarray, movable: np.ndarray, *,
           weights: Weights, sweeps: int = SWEEPS, frequency: np.ndarray | None = None,
           then: Callable[[np.ndarray], np.ndarray] | None = None) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """The kinds of ``movable`` motifs re-chosen against their complete rings (§5.2, eq. 1–3).

    Parameters
    ----------
    rings : the reference ring shapes
    xy : (n, 2) float array, user units — the motifs: those that may change and the fixed ones
        around them (a neighbouring cell's), whose rings count but whose kinds stay
    kind, sub : (n,) int arrays — their kinds and sub-ids
    movable : (n,) bool array
    weights : eq. (2)'s weights
    sweeps : at most this many sweeps (fewer when one changes nothing)
    frequency : (k,) float array, the exemplar's kind shares (by count): each kind's count over the
        n motifs (the fixed ones count, the movable ones change) is held to them
        (:func:`mix_bounds`); None leaves it free
    then : a further pass over the kinds the sweeps leave ((n,) int → (n,) int, changing only
        ``movable`` motifs: :func:`~svgtile.engines.growth.neighbourkinds.neighbourhood_kinds`), made
        before each changed motif's reference ring is found

    Returns
    -------
    kind : (n,) int array — the new kinds (unchanged where not ``movable``)
    ring : (n,) int array — for each motif whose kind changed, the reference ring it now copies
        (its sub-id, angle and scale); −1 elsewhere
    """
    n = len(xy)
    kind = np.array(kind, np.int64)
    if n == 0 or not movable.any() or sweeps <= 0 or len(rings) == 0:
        return kind, np.full(n, -1, np.int64)
    xy = np.ascontiguousarray(xy, float)
    ptr, idx = neighbour_rings(xy, np.arange(n), rings.radius * 1.1 + 1e-9)
    owner = np.repeat(np.arange(n), np.diff(ptr))
    order = np.argsort(idx, kind="stable")  # for each motif, the centres whose rings hold it
    midx = owner[order].astype(np.int64)
    mptr = np.searchsorted(idx[order], np.arange(n + 1)).astype(np.int64)
    before = kind.copy()
    out = np.full(n, -1, np.int64)
    new = kind.copy()
    movable = np.asarray(movable, np.bool_)
    k = int(max(rings.kind.max(), rings.nkind.max(), kind.max()) + 1)
    if frequency is not None:
        k = max(k, len(frequency))
    count, lo, hi = mix_bounds(new, movable, frequency, k)
    sweep(new, np.asarray(sub, np.int64), xy, ptr, idx, mptr, midx, movable, k, rings.rel, rings.size, rings.kind,
          rings.nkind, rings.nsub, rings.mean_length, np.array([weights.distance, weights.kind, weights.subid]),
          sweeps, out, count, lo, hi)  # fmt: skip
    if then is not None:
        new = np.asarray(then(new), np.int64)
    changed = new != before
    if changed.any():
        out[changed] = -2
        none = np.zeros(1, np.int64)
        sweep(new, np.asarray(sub, np.int64), xy, ptr, idx, mptr, midx, np.zeros(n, np.bool_), 1, rings.rel,
              rings.size, rings.kind, rings.nkind, rings.nsub, rings.mean_length,
              np.array([weights.distance, weights.kind, weights.subid]), 0, out, none, none, none)  # fmt: skip
    return new, np.where(changed, out, -1)
