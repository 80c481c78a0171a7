"""The neighbourhood distance of Ma, Wei & Tong 2011: a likeness figure that sees order.

Each texture motif's neighbourhood — the relative positions and kinds of its ``k`` nearest
neighbours — is compared with every neighbourhood of the exemplar (eq. 1 of the paper, with the
greedy pairing of §3.2), the closest exemplar neighbourhood is kept, and the costs are averaged
over the texture's motifs.  Positions are measured in the exemplar's mean spacing, so the figure
is dimensionless: 0 when every texture neighbourhood occurs in the exemplar exactly.

In the analysis stage so that engines (the optimize engine, ma2011) and the metrics share one
implementation; :mod:`svgtile.metrics.likeness` makes it a figure of :func:`svgtile.metrics.score`.

References
----------
Ma, Wei & Tong 2011, Discrete element textures, §3.2 Neighborhood Metric, eq. (1).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial import cKDTree

#: Exemplar neighbourhoods hold this many times ``k`` neighbours: the paper gives n(s_i) an
#: infinite extent so that it never runs out before the texture's; twice ``k`` also covers
#: ties at the k-th distance (a square lattice has 4 neighbours at a, 4 at a·√2).
EXEMPLAR_FACTOR = 2
#: Arrays of about this many float64 at most: texture neighbourhoods are taken in batches, and the
#: grid's field built in chunks, that keep each of their arrays within it.
BLOCK = 1 << 21
#: (Exemplar neighbourhood, turn) pairs bounded by position and paired per texture neighbourhood and
#: round of the branch and bound (16 ran fastest of 4–24 over the whole sets; benchmarks/README.md,
#: "score11k").
ROUND = 16
#: Cells per side of the grid on which neighbourhoods are bounded (:func:`_turned_field`): the
#: field costs GRID² per exemplar neighbour and turn, a coarser grid a looser bound; 12–16 ran
#: fastest over the bundled and whole-set exemplars whose motifs turn (8: 4 % slower, 24: 25 %,
#: 32: 75 %; benchmarks/README.md, "score11j"), and 16 serves those whose motifs do not ("score11k").
GRID = 16
#: … fewer where the field (:func:`_turned_field`) would hold more than this many float64 (64 MiB):
#: an exemplar of many motifs and kinds; a coarser grid is a looser bound, never a wrong one.
FIELD_MAX = 1 << 23


def neighbourhoods(
    xy: np.ndarray,
    kind: np.ndarray,
    k: int,
    *,
    period: tuple[float, float] | None = None,
    centres: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The ``k`` nearest neighbours of each motif: their positions relative to it and kinds.

    Ma, Wei & Tong 2011, §3.2: ``p̂(s') = p(s') − p(s)``.

    Parameters
    ----------
    xy : (n, 2) float array, user units
    kind : (n,) int array
    k : number of neighbours
    period : (W, H) user units, or None.  When given, ``xy`` is one tile of a periodic
        texture: neighbours are found among the tile and its 8 translated copies (a 3×3 block,
        more when the tile has too few motifs), so a motif at the tile's edge sees the next tile.
    centres : (m,) int array of indices into ``xy``, or None for all.  The motifs whose
        neighbourhoods are wanted; their neighbours are drawn from all of ``xy``.

    Returns
    -------
    rel : (m, k, 2) float array, user units, nearest first; NaN where there are fewer than ``k``
        other motifs.
    kinds : (m, k) int array, −1 where ``rel`` is NaN.
    """
    xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
    kind = np.asarray(kind).reshape(-1)
    n = len(xy)
    centres = np.arange(n) if centres is None else np.asarray(centres, dtype=np.intp)
    pts, pkind, self_index = xy, kind, centres
    if period is not None and n:
        w, h = float(period[0]), float(period[1])
        r = 1
        while (2 * r + 1) ** 2 * n < k + 1:
            r += 1
        shifts = np.array([(i, j) for i in range(-r, r + 1) for j in range(-r, r + 1)], float)
        pts = (xy[None, :, :] + shifts[:, None, :] * (w, h)).reshape(-1, 2)
        pkind = np.tile(kind, len(shifts))
        # The unshifted copy is block (r, r) of the (2r+1)² blocks.
        self_index = centres + (len(shifts) // 2) * n
    m = len(centres)
    rel = np.full((m, k, 2), np.nan)
    kinds = np.full((m, k), -1, dtype=np.int64)
    if m == 0 or k == 0 or len(pts) < 2:
        return rel, kinds
    q = min(k + 1, len(pts))
    tree = cKDTree(pts)
    _, idx = tree.query(pts[self_index], k=q)
    idx = idx.reshape(m, q)
    # Drop the motif itself (not merely the first hit: a coincident motif may come first).
    is_self = idx == self_index[:, None]
    drop = np.where(is_self.any(axis=1), is_self.argmax(axis=1), q - 1)
    keep = np.ones_like(idx, dtype=bool)
    keep[np.arange(m), drop] = False
    nb = idx[keep].reshape(m, q - 1)
    got = min(k, q - 1)
    rel[:, :got] = pts[nb[:, :got]] - pts[self_index][:, None, :]
    kinds[:, :got] = pkind[nb[:, :got]]
    return rel, kinds


def _greedy_costs(
    p_t: np.ndarray,
    k_t: np.ndarray,
    p_e: np.ndarray,
    k_e: np.ndarray,
    alpha: float,
    *,
    d: np.ndarray | None = None,
) -> np.ndarray:
    """Eq. (1) for G pairs of neighbourhoods, pairing greedily (§3.2).

    Parameters
    ----------
    p_t : (G, k, 2) texture neighbourhoods, spacings; NaN rows are absent neighbours.
    k_t : (G, k) int kinds
    p_e : (G, ke, 2) exemplar neighbourhoods, spacings; NaN rows are absent.
    k_e : (G, ke) int kinds
    alpha : cost of a kind mismatch, squared spacings
    d : (G, k, ke) :func:`_square_distances` of ``p_t`` and ``p_e``, if already computed

    Returns
    -------
    (G,) float: Σ |Δp|² + α·[kinds differ] over the texture's neighbours.  The pair with the
    smallest |Δp| is taken first, both its members are then excluded, and so on.  A texture
    neighbour left without partner (the exemplar has too few motifs) costs ``|p̂|² + α``, as if
    paired with nothing at the centre.
    """
    g, k, _ = p_t.shape
    ke = p_e.shape[1]
    d = (_square_distances(p_t, p_e) if d is None else d.copy()).reshape(g, k * ke)
    rows = np.arange(g)
    cost = np.zeros(g)
    matched = np.zeros((g, k), dtype=bool)
    d3 = d.reshape(g, k, ke)
    for _ in range(k):
        flat = d.argmin(axis=1)
        best = d[rows, flat]
        ok = np.isfinite(best)
        i, j = np.divmod(flat, ke)
        cost += np.where(ok, best + alpha * (k_t[rows, i] != k_e[rows, j]), 0.0)
        matched[rows[ok], i[ok]] = True
        d3[rows, i, :] = np.inf
        d3[rows, :, j] = np.inf
    present = ~np.isnan(p_t[:, :, 0])
    lone = present & ~matched
    cost += np.where(lone, (p_t**2).sum(axis=-1) + alpha, 0.0).sum(axis=1)
    return cost


def _turns(p_t: np.ndarray, p_e: np.ndarray, k: int, rotate: bool) -> tuple[np.ndarray, np.ndarray]:
    """The turns tried per pair of neighbourhoods, as two angle arrays, radians.

    Returns ``phi_t`` (m,) and ``phi_e`` (n_e, r): a texture neighbourhood is turned by
    ``phi_e[j, t] − phi_t`` before it is compared with exemplar neighbourhood ``j``.  Without
    ``rotate`` there is one turn, by nothing.  With it, the turns bring the texture's nearest
    neighbour onto the direction of each of the exemplar neighbourhood's ``k`` nearest.
    """
    if not rotate:
        return np.zeros(len(p_t)), np.zeros((len(p_e), 1))
    phi_t = np.nan_to_num(np.arctan2(p_t[:, 0, 1], p_t[:, 0, 0]))
    phi_e = np.arctan2(p_e[:, :k, 1], p_e[:, :k, 0])
    phi_e = np.nan_to_num(np.where(np.isnan(phi_e), phi_e[:, :1], phi_e))
    return phi_t, phi_e


def _square_distances(p_t: np.ndarray, p_e: np.ndarray, *, finite: bool = False) -> np.ndarray:
    """(G, k, ke) squared distances between the neighbours of G pairs of neighbourhoods
    ((G, k, 2) and (G, ke, 2)), infinite where either is absent (NaN).  ``finite``: the caller
    knows ``p_t`` has no NaN and ``p_e`` has ±inf for NaN, so nothing needs replacing."""
    d = p_t[:, :, None, 0] - p_e[:, None, :, 0]
    d *= d  # in place: the same products as dx * dx, one (G, k, ke) array fewer to allocate
    dx = p_t[:, :, None, 1] - p_e[:, None, :, 1]
    dx *= dx
    d += dx
    if not finite:
        d[np.isnan(d)] = np.inf
    return d


def _bound(d: np.ndarray, p_t: np.ndarray, k_t: np.ndarray, k_e: np.ndarray, alpha: float) -> np.ndarray:
    """A lower bound of :func:`_greedy_costs` from its :func:`_square_distances` ``d``, (G,):
    each texture neighbour pays at least its cheapest partner or being left alone."""
    low = (d + alpha * (k_t[:, :, None] != k_e[:, None, :])).min(axis=-1)
    lone = (p_t**2).sum(axis=-1) + alpha
    return np.where(np.isnan(lone), 0.0, np.minimum(low, lone)).sum(axis=-1)


def _turned(x: np.ndarray, y: np.ndarray, cos: np.ndarray, sin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points ``(x, y)`` turned by the angle of ``cos``, ``sin`` (arrays that broadcast together)."""
    return cos * x - sin * y, sin * x + cos * y


def _turned_field(
    p_t: np.ndarray, k_t: np.ndarray, phi_t: np.ndarray, p_e: np.ndarray, k_e: np.ndarray, phi_e: np.ndarray,
    alpha: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:  # fmt: skip
    """Lower bounds of eq. (1) for every texture neighbourhood under every turn, read off a grid.

    A turn (:func:`_turns`) brings the texture neighbourhood's nearest neighbour onto the
    direction of one of the exemplar neighbourhood's; in the frame where both of those lie on the
    +x axis (the texture neighbourhood turned by ``−phi_t``, the exemplar one by ``−phi_e[j, t]``)
    the distances are those of the turn.  There the texture neighbours lie in a square of
    :data:`GRID` × :data:`GRID` cells; for each turned exemplar neighbourhood ``(j, t)``, each
    kind ``c`` and each cell the *field* holds ``min_q (|cell − q|² + α·[kind(q) ≠ c])`` — the
    squared distance from the cell (a closed box, a hair wider than the cell so that rounding in
    either frame cannot make it more; the outer cells reach to infinity) to the nearest exemplar
    neighbour ``q``, or to the nearest of kind ``c`` without the α.  A texture neighbour of kind
    ``c`` in that cell then costs at least the field's value there, or ``|p̂|² + α`` left alone;
    summed over the neighbours, a bound of the greedy pairing (a matching) under that turn:
    ``field[:, cells].min(lone).sum()``, the centres' own kinds left to the caller.  Without
    turns (``phi`` all 0, r = 1) the frame is the neighbourhoods' own, unturned.

    Parameters
    ----------
    p_t : (m, k, 2) texture neighbourhoods, spacings (NaN: absent); k_t : (m, k) their kinds
    phi_t : (m,), phi_e : (n_e, r), radians: :func:`_turns`
    p_e : (n_e, ke, 2) exemplar neighbourhoods, spacings, ±inf where absent; k_e : (n_e, ke)
    alpha : cost of a kind mismatch

    Returns
    -------
    field : (n_e·r, kinds · G² + 1) float, squared spacings: row ``j·r + t``; per kind (those
        of the present neighbours, numbered in order) a block of G² cells, G ≤ :data:`GRID`; a
        last column of 0 (an absent texture neighbour's)
    cells : (m, k) int, each texture neighbour's column in ``field`` (cell and kind)
    lone : (m, k) float, ``|p̂|² + α``, 0 for an absent neighbour
    """
    n_e, r = phi_e.shape
    ke = k_e.shape[1]
    x, y = p_t[..., 0], p_t[..., 1]
    # (m, k), the texture neighbourhoods' own frame
    tx, ty = _turned(x, y, np.cos(-phi_t)[:, None], np.sin(-phi_t)[:, None])
    absent = np.isnan(tx)
    # the exemplar neighbourhoods turned, (n_e·r, ke); an absent neighbour stays infinitely far
    with np.errstate(invalid="ignore"):
        ex, ey = _turned(p_e[:, None, :, 0], p_e[:, None, :, 1], np.cos(-phi_e)[:, :, None], np.sin(-phi_e)[:, :, None])
    ex, ey = ex.reshape(n_e * r, ke), ey.reshape(n_e * r, ke)
    far = ~(np.isfinite(ex) & np.isfinite(ey))
    ex, ey = np.where(far, 0.0, ex), np.where(far, 0.0, ey)
    # the kinds of present neighbours numbered 0, 1, … (a kind may be any integer, −1 too)
    kq = np.repeat(k_e, r, axis=0)
    labels, dense = np.unique(np.concatenate([k_t[~absent], kq[~far]]), return_inverse=True)
    kinds = max(len(labels), 1)
    present = int((~absent).sum())
    kt = np.zeros(k_t.shape, np.intp)
    kt[~absent] = dense[:present]
    kq = np.full(kq.shape, kinds, np.intp)  # absent: a kind of their own, never asked for
    kq[~far] = dense[present:]
    # the grid: GRID cells a side, fewer if the field would outgrow FIELD_MAX; it spans 99 % of
    # the texture neighbours, its outer cells reach to infinity (a stray far neighbour is still
    # in a cell, and does not coarsen every other's)
    grid = max(1, min(GRID, math.isqrt(max((FIELD_MAX // max(n_e * r, 1) - 1) // kinds, 1))))
    spread = np.maximum(np.abs(tx[~absent]), np.abs(ty[~absent]))
    half = (float(np.quantile(spread, 0.99)) if len(spread) else 0.0) + 1e-12
    side = 2 * half / grid
    ix = np.clip(np.floor((np.nan_to_num(tx) + half) / side), 0, grid - 1).astype(np.intp)
    iy = np.clip(np.floor((np.nan_to_num(ty) + half) / side), 0, grid - 1).astype(np.intp)
    cells = np.where(absent, kinds * grid * grid, ix * grid + iy + kt * grid * grid)
    lone = np.where(absent, 0.0, x * x + y * y + alpha)
    pad = 1e-9 * (1 + half)
    lo = -half + side * np.arange(grid) - pad  # (grid,) each cell's low and high edges
    hi = lo + side + 2 * pad
    lo[0], hi[-1] = -np.inf, np.inf
    field = np.zeros((n_e * r, kinds * grid * grid + 1))  # the last column an absent neighbour's
    rows = max(1, BLOCK // ((ke + kinds + 1) * grid * grid))  # d and own within BLOCK floats
    for a in range(0, n_e * r, rows):
        sl = slice(a, a + rows)
        gap = []
        for q in (ex[sl], ey[sl]):  # per axis, the distance from each cell's span to q (0 inside)
            g = np.maximum(np.maximum(lo - q[:, :, None], q[:, :, None] - hi), 0.0)
            g[far[sl]] = np.inf
            gap.append(g * g)
        d = (gap[0][:, :, :, None] + gap[1][:, :, None, :]).reshape(len(gap[0]), ke, -1)  # (rows, ke, grid²)
        # per kind, the nearest neighbour of that kind: one pass per neighbour, whatever the kinds
        own = np.full((len(d), kinds + 1, grid * grid), np.inf)
        at = np.arange(len(d))
        for i in range(ke):
            c = kq[sl, i]
            own[at, c] = np.minimum(own[at, c], d[:, i])
        field[sl, :-1] = np.minimum(own[:, :kinds], d.min(axis=1)[:, None, :] + alpha).reshape(len(d), -1)
    return field, cells, lone


def _nearest_costs(
    p_t: np.ndarray,
    k_t: np.ndarray,
    c_t: np.ndarray,
    p_e: np.ndarray,
    k_e: np.ndarray,
    c_e: np.ndarray,
    alpha: float,
    *,
    rotate: bool,
) -> np.ndarray:
    """For each texture neighbourhood, its smallest eq. (1) distance to an exemplar one.

    Exact, by branch and bound: the greedy pairing (:func:`_greedy_costs`, k passes over all
    k·ke neighbour pairs) is what costs, and most exemplar neighbourhoods are far from a given
    texture one.  A lower bound of eq. (1) is cheap — each texture neighbour costs at least its
    cheapest partner, ``min_q |p̂ − q̂|² + α·[kinds differ]``, or being left alone, whichever is
    less — so the pairing is computed in order of increasing bound, a few candidates per round,
    and stops for a centre once its next bound exceeds the best distance found.  Candidates are
    ordered by that bound read off a grid (:func:`_turned_field`, per turn where neighbourhoods
    may turn), and each is bounded again at its exact positions (:func:`_bound`) before it is
    paired.  The result is the minimum over every exemplar neighbourhood and turn, bit for bit
    (``tests/test_neighbourhood.py`` compares it with every pairing): a bound only decides what is
    paired, never a cost.

    Parameters
    ----------
    p_t : (m, k, 2) texture neighbourhoods, spacings (NaN: absent)
    k_t : (m, k) int kinds of the neighbours; c_t : (m,) kinds of the centres
    p_e : (n_e, ke, 2) exemplar neighbourhoods, spacings; k_e : (n_e, ke); c_e : (n_e,)
    alpha : cost of a kind mismatch, squared spacings
    rotate : try the turns of :func:`_turns`

    Returns
    -------
    (m,) float, squared spacings
    """
    m, k, _ = p_t.shape
    n_e = len(k_e)
    phi_t, phi_e = _turns(p_t, p_e, k, rotate)
    r = phi_e.shape[1]
    # The bound may sum its terms in another order than the pairing: a hair of slack keeps it
    # a bound in floating point.
    slack = 1 + 1e-9
    best = np.full(m, np.inf)
    # texture neighbourhoods a batch: their grid bounds (n_e·r, b, k) and a round's distances
    # (b·ROUND, k, ke), with its copies in the pairing, within BLOCK floats each
    batch = max(1, BLOCK // max(n_e * r * k, min(ROUND, n_e * r) * k * p_e.shape[1], 1))
    # Exemplar neighbours, an absent one infinitely far; texture neighbourhoods all present
    # (the texture has more than k motifs) need no test for absent ones.
    p_far = np.nan_to_num(p_e, nan=np.inf)
    whole = not np.isnan(p_t).any()
    field, cells, lone_t = _turned_field(p_t, k_t, phi_t, p_far, k_e, phi_e, alpha)
    for start in range(0, m, batch):
        sl = slice(start, start + batch)
        pt, kt, ct = p_t[sl], k_t[sl], c_t[sl]
        b = len(pt)
        # (b, n_e·r): the grid bound of every (exemplar neighbourhood, turn); r = 1 without turns
        low = np.minimum(field[:, cells[sl]], lone_t[sl]).sum(axis=-1).T
        low += np.repeat(alpha * (ct[:, None] != c_e[None, :]), r, axis=1)
        order = np.argsort(low, axis=1, kind="stable")
        low = np.take_along_axis(low, order, axis=1)
        top = np.full(b, np.inf)
        for pos in range(0, n_e * r, ROUND):
            live = low[:, pos : pos + ROUND] <= top[:, None] * slack
            if not live.any():
                break
            rows, cols = np.nonzero(live)
            je, jr = np.divmod(order[rows, pos + cols], r)
            pair = pt[rows]
            if rotate:  # each texture neighbourhood turned for the exemplar one
                turn = (phi_e[je, jr] - phi_t[start + rows])[:, None]
                pair = np.stack(_turned(pair[..., 0], pair[..., 1], np.cos(turn), np.sin(turn)), axis=-1)
            cost = alpha * (ct[rows] != c_e[je])
            q, kq = p_far[je], k_e[je]
            d = _square_distances(pair, q, finite=whole)
            # bounded by position before pairing: the grid's cells blur what this sees
            near = _bound(d, pair, kt[rows], kq, alpha) + cost <= top[rows] * slack
            rows, pair, q, kq, d, cost = rows[near], pair[near], q[near], kq[near], d[near], cost[near]
            cost += _greedy_costs(pair, kt[rows], q, kq, alpha, d=d)
            np.minimum.at(top, rows, cost)
        best[sl] = top
    return best


def neighbourhood_distance(
    texture_xy: np.ndarray,
    texture_kind: np.ndarray,
    exemplar_xy: np.ndarray,
    exemplar_kind: np.ndarray,
    *,
    spacing: float,
    k: int = 6,
    alpha: float = 1.0,
    period: tuple[float, float] | None = None,
    rotate: bool = False,
    centres: np.ndarray | None = None,
    sample: int | None = 2000,
    rng: np.random.Generator | None = None,
) -> float:
    """Mean distance of the texture's neighbourhoods to their nearest exemplar neighbourhood.

    Ma, Wei & Tong 2011, §3.2 eq. (1).  For each measured texture motif ``s_o`` and every
    exemplar motif ``s_i``::

        |n(s_o) − n(s_i)|² = α·[q(s_o) ≠ q(s_i)]
                             + Σ_{s'_o ∈ n(s_o)} |p̂(s'_o) − p̂(s'_i)|² + α·[q(s'_o) ≠ q(s'_i)]

    with ``p̂`` relative positions in exemplar spacings, ``q`` the kind, ``n(s_o)`` the ``k``
    nearest neighbours and ``n(s_i)`` the ``2k`` nearest (the paper's unbounded exemplar
    neighbourhood, :data:`EXEMPLAR_FACTOR`); neighbours are paired greedily, closest pair first,
    each used once.  The centre's own kind term is an addition to eq. (1), which compares only
    neighbours: it makes a texture that swaps the kinds of a two-kind lattice unlike it.  The
    smallest distance over ``s_i`` is kept and averaged over ``s_o``.

    Parameters
    ----------
    texture_xy : (n, 2) float array, user units
    texture_kind : (n,) int array
    exemplar_xy : (m, 2) float array, user units (tens to a few hundred motifs)
    exemplar_kind : (m,) int array
    spacing : the exemplar's mean spacing, user units (:func:`svgtile.metrics.window.spacing`)
    k : neighbours per neighbourhood
    alpha : cost of a kind mismatch, in squared spacings (1: like a neighbour one spacing off)
    period : (W, H) user units when the exemplar is a periodic tile (:func:`neighbourhoods`)
    rotate : let each texture neighbourhood turn before it is compared, for exemplars whose
        motifs show every orientation.  The turns tried per exemplar neighbourhood bring the
        texture motif's nearest neighbour onto the direction of each of the exemplar's ``k``
        nearest, so an exactly rotated copy is found even when nearest neighbours tie.
    centres : (c,) int indices of the texture motifs to measure (e.g. those in the interior),
        None for all; neighbours are drawn from the whole texture.
    sample : at most this many of ``centres`` are measured, chosen with ``rng``; None for all.
    rng : required when ``centres`` has more than ``sample`` motifs.

    Returns
    -------
    float, dimensionless (squared spacings); NaN when there is nothing to measure.
    """
    texture_xy = np.asarray(texture_xy, dtype=np.float64).reshape(-1, 2)
    exemplar_xy = np.asarray(exemplar_xy, dtype=np.float64).reshape(-1, 2)
    texture_kind = np.asarray(texture_kind).reshape(-1)
    exemplar_kind = np.asarray(exemplar_kind).reshape(-1)
    if not (spacing > 0 and math.isfinite(spacing)):
        raise ValueError(f"spacing must be positive and finite, not {spacing!r}")
    if k < 1:
        raise ValueError(f"k must be at least 1, not {k!r}")
    if not (alpha >= 0 and math.isfinite(alpha)):
        raise ValueError(f"alpha must be zero or positive and finite, not {alpha!r}")
    centres = np.arange(len(texture_xy)) if centres is None else np.asarray(centres, np.intp)
    if sample is not None and len(centres) > sample:
        if rng is None:
            raise ValueError(
                f"{len(centres)} motifs to measure, more than sample={sample}: pass rng"
            )
        centres = np.sort(rng.choice(centres, size=sample, replace=False))
    if len(centres) == 0 or len(exemplar_xy) == 0:
        return math.nan

    p_t, k_t = neighbourhoods(texture_xy, texture_kind, k, centres=centres)
    p_e, k_e = neighbourhoods(exemplar_xy, exemplar_kind, EXEMPLAR_FACTOR * k, period=period)
    p_t = p_t / spacing
    p_e = p_e / spacing
    best = _nearest_costs(p_t, k_t, texture_kind[centres], p_e, k_e, exemplar_kind, alpha, rotate=rotate)
    return float(best.mean())


def likeness(e: float, e_tile: float, e_random: float) -> float:
    """Where a distance ``e`` lies between two baselines: 1 at ``e_tile``, 0 at ``e_random``.

    ``(e_random − e) / (e_random − e_tile)``; above 1 is better than the tile, below 0 worse
    than random.  NaN when the baselines coincide.
    """
    den = e_random - e_tile
    return (e_random - e) / den if den != 0 else math.nan
