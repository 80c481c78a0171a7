"""The neighbourhood distance of Ma, Wei & Tong 2011: a likeness figure that sees order.

Each texture motif's neighbourhood — the relative positions and kinds of its ``k`` nearest
neighbours — is compared with every neighbourhood of the exemplar (eq. 1 of the paper, with the
greedy pairing of §3.2), the closest exemplar neighbourhood is kept, and the costs are averaged
over the texture's motifs.  Positions are measured in the exemplar's mean spacing, so the figure
is dimensionless: 0 when every texture neighbourhood occurs in the exemplar exactly.

In the analysis stage so that engines (the optimize engine, ma2011) and the metrics share one
implementation.  Standalone for now: :func:`svgtile.metrics.score` does not call it yet.

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
#: The greedy pairings are computed on blocks of at most this many float64 distances.
BLOCK = 1 << 22


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
) -> np.ndarray:
    """Eq. (1) for G pairs of neighbourhoods, pairing greedily (§3.2).

    Parameters
    ----------
    p_t : (G, k, 2) texture neighbourhoods, spacings; NaN rows are absent neighbours.
    k_t : (G, k) int kinds
    p_e : (G, ke, 2) exemplar neighbourhoods, spacings; NaN rows are absent.
    k_e : (G, ke) int kinds
    alpha : cost of a kind mismatch, squared spacings

    Returns
    -------
    (G,) float: Σ |Δp|² + α·[kinds differ] over the texture's neighbours.  The pair with the
    smallest |Δp| is taken first, both its members are then excluded, and so on.  A texture
    neighbour left without partner (the exemplar has too few motifs) costs ``|p̂|² + α``, as if
    paired with nothing at the centre.
    """
    g, k, _ = p_t.shape
    ke = p_e.shape[1]
    d = ((p_t[:, :, None, :] - p_e[:, None, :, :]) ** 2).sum(axis=-1)
    d = np.where(np.isnan(d), np.inf, d).reshape(g, k * ke)
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
    c_t = texture_kind[centres]
    c_e = exemplar_kind

    n_e, ke = k_e.shape
    if rotate:
        # (c,) angle of the texture's nearest neighbour, (n_e, R) of the exemplar's k nearest.
        phi_t = np.arctan2(p_t[:, 0, 1], p_t[:, 0, 0])
        phi_e = np.arctan2(p_e[:, :k, 1], p_e[:, :k, 0])
        phi_t = np.nan_to_num(phi_t)
        phi_e = np.where(np.isnan(phi_e), phi_e[:, :1], phi_e)
        phi_e = np.nan_to_num(phi_e)
    else:
        phi_e = np.zeros((n_e, 1))
    r = phi_e.shape[1]
    per_centre = n_e * r * k * ke
    batch = max(1, BLOCK // max(per_centre, 1))
    best = np.empty(len(centres))
    for start in range(0, len(centres), batch):
        sl = slice(start, start + batch)
        pt, kt, ct = p_t[sl], k_t[sl], c_t[sl]
        b = len(pt)
        # (b, n_e, r, k, 2): every texture neighbourhood against every exemplar one and turn.
        if rotate:
            turn = phi_e[None, :, :] - phi_t[sl, None, None]
            cos, sin = np.cos(turn)[..., None], np.sin(turn)[..., None]
            x, y = pt[:, None, None, :, 0], pt[:, None, None, :, 1]
            pr = np.stack([cos * x - sin * y, sin * x + cos * y], axis=-1)
        else:
            pr = np.broadcast_to(pt[:, None, None], (b, n_e, r, k, 2))
        g = b * n_e * r
        cost = _greedy_costs(
            pr.reshape(g, k, 2),
            np.broadcast_to(kt[:, None, None], (b, n_e, r, k)).reshape(g, k),
            np.broadcast_to(p_e[None, :, None], (b, n_e, r, ke, 2)).reshape(g, ke, 2),
            np.broadcast_to(k_e[None, :, None], (b, n_e, r, ke)).reshape(g, ke),
            alpha,
        ).reshape(b, n_e, r)
        cost += alpha * (ct[:, None, None] != c_e[None, :, None])
        best[sl] = cost.min(axis=(1, 2))
    return float(best.mean())


def likeness(e: float, e_tile: float, e_random: float) -> float:
    """Where a distance ``e`` lies between two baselines: 1 at ``e_tile``, 0 at ``e_random``.

    ``(e_random − e) / (e_random − e_tile)``; above 1 is better than the tile, below 0 worse
    than random.  NaN when the baselines coincide.
    """
    den = e_random - e_tile
    return (e_random - e) / den if den != 0 else math.nan
