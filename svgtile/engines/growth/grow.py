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

The loop is sequential by nature (each placement changes the next seed's neighbourhood); it is
kept tight: an incremental bucket grid of placed elements and live seeds, a heap of seeds, and
one vectorised :func:`~svgtile.engines.growth.matching.best_match` per seed.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.engines.growth.connectivity import Rings, ring_of
from svgtile.engines.growth.matching import Weights, best_match

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


class _Buckets:
    """An incremental grid of points: ``add`` one, ``near`` returns the ids in the 3 × 3 buckets."""

    def __init__(self, size: float) -> None:
        self.size = size
        self.cells: dict[tuple[int, int], list[int]] = {}

    def add(self, i: int, x: float, y: float) -> None:
        self.cells.setdefault((int(x // self.size), int(y // self.size)), []).append(i)

    def near(self, x: float, y: float) -> list[int]:
        a, b = int(x // self.size), int(y // self.size)
        out: list[int] = []
        get = self.cells.get
        for da in (-1, 0, 1):
            for db in (-1, 0, 1):
                v = get((a + da, b + db))
                if v:
                    out.extend(v)
        return out


def grow(rings: Rings, piece: shapely.Geometry, start: np.ndarray, start_ring: int, *, fixed_xy: np.ndarray,
         more: np.ndarray | None = None, more_kind: np.ndarray | None = None,
         fixed_kind: np.ndarray, fixed_sub: np.ndarray, rotation: str, flow_angle: Callable[[np.ndarray], np.ndarray],
         priority: np.ndarray, weights: Weights, centre_gap: np.ndarray, noise: Callable[[int], np.ndarray],
         relax: Callable[[np.ndarray, np.ndarray, np.ndarray, int], np.ndarray] | None = None,
         relax_every: int = 0, limit: int = 1_000_000) -> Grown:  # fmt: skip
    """Grow motifs over ``piece`` from one seed at ``start`` (§5.1, §5.4).

    Parameters
    ----------
    rings : the reference ring shapes (:func:`~svgtile.engines.growth.connectivity.reference_rings`)
    piece : prepared shapely polygon — the only place seeds are made
    start : (2,) float array, user units — the initial seed
    start_ring : the reference ring the initial seed becomes when it has no placed neighbour
        (so that a repeating tile grows on its own lattice); −1 to let the match decide
    more, more_kind : (s, 2) float and (s,) int arrays, optional — further initial seeds and the
        kinds they must become (−1: any), grown in order of distance from ``start`` (refilling
        the holes a first growth left, see :mod:`.engine`)
    fixed_xy, fixed_kind, fixed_sub : (f, 2), (f,), (f,) — motifs placed before (neighbouring
        cells): they are neighbours in matching and are never moved
    rotation : ``none``, ``fit`` or ``flow``
    flow_angle : ``flow_angle(xy)`` → (q,) radians, the flow's direction at ``xy`` (``flow`` mode)
    priority : (k,) int array — each kind's priority, the higher grown first (§5.1)
    weights : eq. (2)'s weights
    centre_gap : (k, k) float array, user units — the closest two motifs of these kinds come
    noise : ``noise(step)`` → (r,) floats in [0, 1): the tie-breaking draw of step ``step``
    relax, relax_every : ``relax(xy, ring, theta, first)`` → relaxed xy of the grown motifs, run
        every ``relax_every`` placements (0: never here)
    limit : at most this many motifs

    Returns
    -------
    Grown
    """
    r_short = rings.short_length / 2
    reach = rings.radius * 1.1 + 1e-9
    wait = 5.0 * rings.mean_length
    f = len(fixed_xy)
    cap = f + 64
    exy = np.zeros((cap, 2))
    ekind = np.zeros(cap, np.int64)
    esub = np.zeros(cap, np.int64)
    exy[:f], ekind[:f], esub[:f] = fixed_xy, fixed_kind, fixed_sub
    n = f
    ering: list[int] = []
    etheta: list[float] = []
    elements = _Buckets(reach)
    for i in range(f):
        elements.add(i, exy[i, 0], exy[i, 1])
    seeds = _Buckets(reach)
    waiting = _Buckets(wait)  # for the priority rule's 5·l neighbourhood
    sxy: list[tuple[float, float]] = [(float(start[0]), float(start[1]))]
    skind: list[int] = [int(rings.kind[start_ring]) if start_ring >= 0 else -1]
    alive: list[bool] = [True]
    skey: list[float] = [0.0]  # each seed's current place in the queue
    seeds.add(0, *sxy[0])
    waiting.add(0, *sxy[0])
    heap: list[tuple[float, int]] = [(0.0, 0)]
    top = int(priority.max()) if len(priority) else 0
    levels = len(np.unique(priority)) > 1
    if more is not None:
        for (px, py), kk in zip(more, more_kind, strict=True):
            q = len(sxy)
            sxy.append((float(px), float(py)))
            skind.append(int(kk))
            alive.append(True)
            skey.append(float(np.hypot(px - start[0], py - start[1])))
            seeds.add(q, px, py)
            if levels:
                waiting.add(q, px, py)
            heap.append((skey[q], q))
        heapq.heapify(heap)
    step = 0
    while heap and n - f < limit:
        d0, s = heapq.heappop(heap)
        if not alive[s]:
            continue
        x, y = sxy[s]
        want = skind[s]
        if levels:
            mine = top if want < 0 else int(priority[want])
            ahead = [q for q in waiting.near(x, y) if alive[q] and q != s and skind[q] >= 0
                     and priority[skind[q]] > mine and (sxy[q][0] - x) ** 2 + (sxy[q][1] - y) ** 2 < wait * wait]  # fmt: skip
            if ahead:  # wait behind the farthest-queued higher-priority seed nearby
                skey[s] = max(d0, max(skey[q] for q in ahead)) + 1e-9
                heapq.heappush(heap, (skey[s], s))
                continue
        alive[s] = False
        ids = np.fromiter(elements.near(x, y), np.int64)
        rel = exy[ids] - (x, y)
        dist = np.hypot(rel[:, 0], rel[:, 1])
        close = dist < reach
        ids, rel, dist = ids[close], rel[close], dist[close]
        if len(ids) and dist.min() < r_short:
            continue  # merged (Fig. 6b)
        order = ring_of(rel, np.zeros(2))
        tar = rel[order]
        fa = float(flow_angle(np.array([[x, y]]))[0]) if rotation == "flow" else 0.0
        if start_ring >= 0 and s == 0 and not len(tar):
            options = [(start_ring, 0, fa, 0.0)]
        else:
            options = best_match(rings, tar, ekind[ids[order]], esub[ids[order]], want=want, rotation=rotation,
                                 flow_angle=fa, weights=weights, noise=noise(step), top=ALTERNATIVES)  # fmt: skip
        step += 1
        # the best match whose element does not collide (Fig. 6d); none: the seed is dropped
        fits = [o for o in options if not (len(ids) and (dist < centre_gap[rings.kind[o[0]], ekind[ids]]).any())]
        if not fits:
            continue
        r, k, theta, _ = fits[0]
        kind = int(rings.kind[r])
        if n == cap:
            cap *= 2
            exy = np.resize(exy, (cap, 2))
            ekind, esub = np.resize(ekind, cap), np.resize(esub, cap)
        exy[n], ekind[n], esub[n] = (x, y), kind, rings.element[r]
        elements.add(n, x, y)
        ering.append(r)
        etheta.append(theta)
        n += 1

        # new seeds: the ring slots not matched with a placed neighbour (§5.4, Fig. 2f–g)
        m = int(rings.size[r])
        free = np.ones(m, bool)
        free[(k + np.arange(len(tar))) % m] = False
        slots = np.flatnonzero(free)
        if len(slots):
            c, si = np.cos(theta), np.sin(theta)
            v = rings.rel[r, slots]
            p = np.c_[x + c * v[:, 0] - si * v[:, 1], y + si * v[:, 0] + c * v[:, 1]]
            inside = shapely.contains_xy(piece, p[:, 0], p[:, 1])
            for slot, (px, py), ok in zip(slots, p, inside, strict=True):
                if not ok:
                    continue
                near = elements.near(px, py)
                if near and (np.hypot(*(exy[near] - (px, py)).T) < r_short).any():
                    continue
                if any(alive[q] and (sxy[q][0] - px) ** 2 + (sxy[q][1] - py) ** 2 < r_short * r_short
                       for q in seeds.near(px, py)):  # fmt: skip
                    continue
                q = len(sxy)
                sxy.append((float(px), float(py)))
                skind.append(int(rings.nkind[r, slot]))
                alive.append(True)
                skey.append(float(np.hypot(px - start[0], py - start[1])))
                seeds.add(q, px, py)
                if levels:
                    waiting.add(q, px, py)
                heapq.heappush(heap, (skey[q], q))
        if relax is not None and relax_every and (n - f) % relax_every == 0:
            exy[f:n] = relax(exy[:n], np.array(ering), np.array(etheta), f)
    return Grown(exy[f:n].copy(), np.array(ering, np.int64), np.array(etheta))
