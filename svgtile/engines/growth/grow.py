"""Local growth from a seed (Ijiri et al. 2008, §5.1 and §5.4): the sequential heart of the engine.

Seeds are grown nearest-first from the initial seed (§5.1).  Growing a seed finds its placed
neighbours, the reference ring that fits them best (:mod:`.matching`), replaces the seed by that
reference element, overlays the reference ring on the seed and turns every ring slot that was not
matched with a placed neighbour into a new seed with the slot's kind (§5.4, Fig. 2).  The
heuristics of Fig. 6 keep the growth from crowding or tearing:

* a new seed within r_short (half the shortest reference edge) of a placed element or of a live
  seed is merged into it (Fig. 6b) — the edge then ends at what was found;
* a seed whose motif would come closer to a placed one than any pair of the same kinds does in
  the exemplar is a collision and is dropped (Fig. 6d, on centres; footprints are checked
  exactly afterwards, see :mod:`.engine`);
* a seed that would leave the growth area — the piece of a cell between barriers, inside the
  ``--grow-within`` shapes — is not made, so growth never crosses a barrier.

Not done from Fig. 6: the angle test (c) and the extra untyped seed on an edge longer than
l_long (e); a hole they would fill is regrown by the engine's refill rounds instead.  Edges are
not stored: a seed's neighbours are found afresh among the placed motifs by the Gabriel rule of
:func:`~svgtile.engines.growth.connectivity.ring_of`, the rule the reference rings are made by.

Priorities (§5.1): a seed is grown only when no seed of a higher-priority kind is alive within
5·l of it (l: the exemplar's mean edge length); until then it waits behind that seed.

The loop is sequential by nature (each placement changes the next seed's neighbourhood), so it
runs compiled (:func:`svgtile.engines.growth.kernel.run`): a heap of seeds, bucket grids of placed
elements and live seeds as linked lists in arrays, and the matching of eq. (1)–(4) as one loop
over (reference, shift) pairs.  This module sets up its arrays and serves its requests (more
room, a relaxation).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.engines.growth import kernel
from svgtile.engines.growth.connectivity import Rings
from svgtile.engines.growth.matching import ROTATION_MODES, Weights

#: A seed whose best match collides tries the next best, up to this many matches in all.
ALTERNATIVES = 4


@dataclass(frozen=True, eq=False)
class Grown:
    """Motifs grown in one piece (struct of arrays, n motifs).

    Attributes
    ----------
    xy : (n, 2) float array, user units
    ring : (n,) int array — the reference ring each motif copies (its kind, angle, scale, sub-id)
    theta : (n,) float array, radians — the rotation applied to that ring (§5.3)
    """

    xy: np.ndarray
    ring: np.ndarray
    theta: np.ndarray


def _grid(bounds: tuple[float, float, float, float], size: float) -> np.ndarray:
    """A bucket grid ``(size, a0, b0, na, nb)`` over ``bounds`` grown by two buckets: bucket
    ``(x // size, y // size)`` as in a grid anchored at the world origin."""
    x0, y0, x1, y1 = bounds
    a0, b0 = int(x0 // size) - 2, int(y0 // size) - 2
    return np.array([size, a0, b0, int(x1 // size) + 3 - a0, int(y1 // size) + 3 - b0], float)


def rings_of(piece: shapely.Geometry) -> tuple[np.ndarray, np.ndarray]:
    """``piece``'s ring coordinates ((p, 2) float, each ring closed) and where each ring starts."""
    parts = shapely.get_rings(piece)
    coords = [shapely.get_coordinates(g) for g in parts]
    return np.concatenate(coords), np.cumsum([0] + [len(c) for c in coords]).astype(np.int64)


def grow(rings: Rings, piece: shapely.Geometry, start: np.ndarray, start_ring: int, *, fixed_xy: np.ndarray,
         more: np.ndarray | None = None, more_kind: np.ndarray | None = None,
         fixed_kind: np.ndarray, fixed_sub: np.ndarray, rotation: str,
         flow: tuple[np.ndarray, float, float, float] | None,
         priority: np.ndarray, weights: Weights, centre_gap: np.ndarray, draws: np.random.Generator,
         relax: Callable[[np.ndarray, np.ndarray, np.ndarray, int], np.ndarray] | None = None,
         relax_every: int = 0, limit: int = 1_000_000,
         outline: tuple[np.ndarray, np.ndarray] | None = None, room: int | None = None) -> Grown:  # fmt: skip
    """Grow motifs over ``piece`` from one seed at ``start`` (§5.1, §5.4).

    Parameters
    ----------
    rings : the reference ring shapes (:func:`~svgtile.engines.growth.connectivity.reference_rings`)
    piece : shapely polygon — the only place seeds are made
    start : (2,) float array, user units — the initial seed
    start_ring : the reference ring the initial seed becomes when it has no placed neighbour
        (so that a repeating tile grows on its own lattice); −1 to let the match decide
    more, more_kind : (s, 2) float and (s,) int arrays, optional — further initial seeds and the
        kinds they must become (−1: any), grown in order of distance from ``start`` (refilling
        the holes a first growth left, see :mod:`.engine`)
    fixed_xy, fixed_kind, fixed_sub : (f, 2), (f,), (f,) — motifs placed before (neighbouring
        cells): they are neighbours in matching and are never moved
    rotation : ``none``, ``fit`` or ``flow``
    flow : ``(table, x0, y0, step)``: the flow's direction (radians) sampled on a grid, row i and
        column j at ``(x0 + j·step, y0 + i·step)``, nearest sample (``flow`` mode; else None)
    priority : (k,) int array — each kind's priority, the higher grown first (§5.1)
    weights : eq. (2)'s weights
    centre_gap : (k, k) float array, user units — the closest two motifs of these kinds come
    draws : the tie-breaking draws (one ``draws.random(r)`` per match, in growth order)
    relax, relax_every : ``relax(xy, ring, theta, first)`` → relaxed xy of the grown motifs, run
        every ``relax_every`` placements (0: never here)
    limit : at most this many motifs
    outline : ``piece``'s rings as :func:`rings_of` gives them, if at hand (a piece grown in
        several rounds: made once)
    room : how many motifs and seeds the loop's first arrays hold (default: what the piece's
        area holds, so the loop seldom stops to have them doubled); the outcome is the same

    Returns
    -------
    Grown
    """
    r_short = rings.short_length / 2
    reach = rings.radius * 1.1 + 1e-9
    wait = 5.0 * rings.mean_length
    M = rings.rel.shape[1]
    f = len(fixed_xy)
    more = np.zeros((0, 2)) if more is None else np.asarray(more, float)
    more_kind = np.zeros(0, np.int64) if more_kind is None else np.asarray(more_kind, np.int64)
    levels = len(np.unique(priority)) > 1
    egrid = _grid(piece.bounds, reach)
    wgrid = _grid(piece.bounds, wait)
    # fixed motifs beyond the grid are out of every seed's reach (seeds are made inside the piece)
    x0, y0 = (egrid[1:3] - 1) * reach
    x1, y1 = (egrid[1:3] + egrid[3:5] + 1) * reach
    kept = np.flatnonzero((fixed_xy[:, 0] >= x0) & (fixed_xy[:, 0] <= x1) & (fixed_xy[:, 1] >= y0)
                          & (fixed_xy[:, 1] <= y1))  # fmt: skip
    if room is None:  # what a piece this large holds (a lattice of edge l has one motif per 0.87·l²)
        room = 64 + int(piece.area / (0.5 * rings.mean_length**2))
    ecap = f + room
    scap = 1 + len(more) + room + M
    exy = np.zeros((ecap, 2))
    ekind = np.zeros(ecap, np.int64)
    esub = np.zeros(ecap, np.int64)
    exy[:f], ekind[:f], esub[:f] = fixed_xy, fixed_kind, fixed_sub
    enext = np.full(ecap, -1, np.int64)
    ehead = np.full(int(egrid[3] * egrid[4]), -1, np.int64)
    kernel.link(egrid, ehead, enext, exy, kept)
    state = [exy, ekind, esub, np.zeros(ecap, np.int64), np.zeros(ecap), enext, ehead, egrid,
             np.zeros((scap, 2)), np.zeros(scap, np.int64), np.zeros(scap, np.bool_), np.zeros(scap),
             np.full(scap, -1, np.int64), np.full(len(ehead), -1, np.int64),
             np.full(int(wgrid[3] * wgrid[4]), -1, np.int64), np.full(scap, -1, np.int64), wgrid,
             np.zeros(scap), np.zeros(scap, np.int64)]  # fmt: skip
    seeds = np.concatenate([np.reshape(start, (1, 2)), more])
    kinds = np.concatenate([[int(rings.kind[start_ring]) if start_ring >= 0 else -1], more_kind]).astype(np.int64)
    keys = np.concatenate([[0.0], np.hypot(more[:, 0] - start[0], more[:, 1] - start[1])])
    ns = len(seeds)
    hn = kernel.plant(tuple(state), seeds, kinds, keys, levels)
    mode = ROTATION_MODES[rotation]
    ivars = np.array([f, ns, hn, start_ring, f, limit, relax_every if relax is not None else 0, mode, ALTERNATIVES,
                      levels, int(priority.max()) if len(priority) else 0, M], np.int64)  # fmt: skip
    fvars = np.array([r_short, reach, wait, rings.mean_length, weights.distance, weights.kind, weights.subid,
                      float(start[0]), float(start[1])])  # fmt: skip
    coords, starts = outline if outline is not None else rings_of(piece)
    flow_arg = flow if flow is not None and mode == kernel.FLOW else (np.zeros((1, 1)), 0.0, 0.0, 1.0)
    while True:
        code = kernel.run(tuple(state), ivars, fvars, rings.rel, rings.size, rings.kind, rings.element, rings.nkind,
                          rings.nsub, priority.astype(np.int64), centre_gap, coords, starts, flow_arg, draws)  # fmt: skip
        n = int(ivars[0])
        if code == kernel.RELAX:
            state[0][f:n] = relax(state[0][:n], state[3][: n - f], state[4][: n - f], f)
        elif code == kernel.FULL:
            state = _enlarge(state)
        else:
            break
    return Grown(state[0][f:n].copy(), state[3][: n - f].copy(), state[4][: n - f].copy())


#: Which arrays of the kernel's state are per motif and per seed; :func:`_enlarge` doubles them.
_PER_MOTIF, _PER_SEED = (0, 1, 2, 3, 4, 5), (8, 9, 10, 11, 12, 15, 17, 18)


def _enlarge(state: list) -> list:
    """The kernel's state with twice the room for motifs and seeds (new links −1)."""
    out = list(state)
    for group in (_PER_MOTIF, _PER_SEED):
        for i in group:
            a = state[i]
            fill = -1 if i in (5, 12, 15) else 0
            b = np.full((2 * len(a), *a.shape[1:]), fill, a.dtype)
            b[: len(a)] = a
            out[i] = b
    return out
