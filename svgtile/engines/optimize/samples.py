"""Exemplar elements and their neighbourhoods (Ma, Wei & Tong 2011 §3.1, §3.2, §4.2).

Every exemplar motif is one element sample at its centroid, carrying its kind, angle and scale
as attributes ``q`` (§3.1).  Each sample's neighbourhood is its ``2k`` nearest neighbours
(:data:`svgtile.analysis.neighbourhood.EXEMPLAR_FACTOR`, the paper's unbounded ``n(s_i)``), found
across the tile's edges when the exemplar is a repeating tile.  The k-coherence similarity sets
of §4.2 — for each sample, the few other samples whose neighbourhoods are closest to its own —
are built here once per exemplar.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from svgtile.analysis.neighbourhood import EXEMPLAR_FACTOR
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.engines.optimize.match import candidate_costs


@dataclass(frozen=True, eq=False)
class Samples:
    """The exemplar's element samples and neighbourhoods, everything the solver looks up.

    Attributes
    ----------
    xy : (m, 2) float array, user units
    kind : (m,) int array
    angle : (m,) float array, degrees
    scale : (m,) float array
    spacing : float, user units — the exemplar's mean spacing ``sqrt(area / m)``; relative
        positions are measured in it
    rel : (m, ke, 2) float array, spacings — neighbour positions relative to each sample, nearest
        first, NaN where absent (``ke = 2k``)
    nkind : (m, ke) int array, −1 where absent
    nindex : (m, ke) int array, the neighbour's sample index (a tile's copies map back), −1 absent
    similar : (m, K) int array — the k-coherence similarity set of each sample (§4.2)
    period : (W, H) user units or None
    """

    xy: np.ndarray
    kind: np.ndarray
    angle: np.ndarray
    scale: np.ndarray
    spacing: float
    rel: np.ndarray
    nkind: np.ndarray
    nindex: np.ndarray
    similar: np.ndarray
    period: tuple[float, float] | None
    tree: cKDTree
    tree_index: np.ndarray

    def __len__(self) -> int:
        return len(self.kind)

    def nearest(self, q: np.ndarray) -> np.ndarray:
        """(…) int: the sample nearest to each exemplar-space position ``q`` (…, 2), user units;
        on a tile, positions wrap."""
        shape = q.shape[:-1]
        _, i = self.tree.query(q.reshape(-1, 2))
        return self.tree_index[np.asarray(i, dtype=np.intp)].reshape(shape)


def _block(xy: np.ndarray, period: tuple[float, float] | None, k: int) -> tuple[np.ndarray, np.ndarray, int]:
    """Points and sample indices of the exemplar and, on a tile, enough translated copies around
    it for ``k`` neighbours; the index of the unshifted copy's first point."""
    m = len(xy)
    if period is None:
        return xy, np.arange(m), 0
    r = 1
    while (2 * r + 1) ** 2 * m < k + 1 or r < 1:
        r += 1
    shifts = np.array([(i, j) for i in range(-r, r + 1) for j in range(-r, r + 1)], float)
    pts = (xy[None, :, :] + shifts[:, None, :] * np.asarray(period, float)).reshape(-1, 2)
    return pts, np.tile(np.arange(m), len(shifts)), (len(shifts) // 2) * m


def exemplar_samples(exemplar: Exemplar, k: int, *, alpha: float = 1.0, similar: int = 2,
                     motifs: Arrangement | None = None) -> Samples:
    """The samples of ``exemplar`` with neighbourhoods of ``2k`` and similarity sets of ``similar``.

    Ma, Wei & Tong 2011 §3.1 (one sample per rigid motif, at its centroid), §3.2 (neighbourhoods)
    and §4.2 (the k-coherence similarity set: for each sample, the ``similar`` other samples of
    smallest eq. (1) distance to it, the sample itself first).

    Parameters
    ----------
    exemplar : the exemplar (a tile when ``exemplar.period`` is set)
    k : output neighbourhood size
    alpha : cost of a kind mismatch, squared spacings
    similar : K, the size of each similarity set
    motifs : the samples when they are not the motifs (several per elongated motif,
        :mod:`.elements`: kind is then the sample's attribute); positions are still measured in
        the motifs' spacing
    """
    spacing = float(np.sqrt(exemplar.region.area / max(len(exemplar.motifs), 1)))
    motifs = exemplar.motifs if motifs is None else motifs
    m = len(motifs)
    period = getattr(exemplar, "period", None)
    ke = EXEMPLAR_FACTOR * k
    pts, index, own = _block(motifs.xy, period, ke)
    tree = cKDTree(pts)
    q = min(ke + 1, len(pts))
    _, nb = tree.query(pts[own : own + m], k=q)
    nb = np.asarray(nb, dtype=np.intp).reshape(m, q)[:, 1:]  # the first hit is the sample itself
    got = nb.shape[1]
    rel = np.full((m, ke, 2), np.nan)
    nkind = np.full((m, ke), -1, dtype=np.int64)
    nindex = np.full((m, ke), -1, dtype=np.int64)
    rel[:, :got] = (pts[nb] - motifs.xy[:, None, :]) / spacing
    nindex[:, :got] = index[nb]
    nkind[:, :got] = motifs.kind[index[nb]]
    # similarity sets (§4.2): every sample against every other, its own k nearest as the texture side
    cand = np.broadcast_to(np.arange(m), (m, m)).copy()
    cost = candidate_costs(rel[:, :k].copy(), nkind[:, :k].copy(), motifs.kind.copy(), cand, rel, nkind, motifs.kind.copy(), alpha)
    cost[np.arange(m), np.arange(m)] = -1.0  # the sample itself first
    sim = np.argsort(cost, axis=1, kind="stable")[:, : similar + 1]
    if sim.shape[1] < similar + 1:
        sim = np.pad(sim, ((0, 0), (0, similar + 1 - sim.shape[1])), mode="edge")
    lookup = cKDTree(pts) if period is not None else tree
    return Samples(motifs.xy, motifs.kind, motifs.angle, motifs.scale, spacing, rel, nkind, nindex, sim,
                   period, lookup, index)  # fmt: skip


def wrap(q: np.ndarray, exemplar: Exemplar) -> np.ndarray:
    """Exemplar-space positions ``q`` (…, 2) brought into the tile (identity off a tile)."""
    period = getattr(exemplar, "period", None)
    if period is None:
        return q
    x0, y0 = exemplar.region.bounds[:2]
    origin = np.array([x0, y0])
    return origin + np.mod(q - origin, np.asarray(period, float))
