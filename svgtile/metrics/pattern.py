"""The texture's structure against the exemplar's: nearest gaps, pair correlation, repetition.

Second-order figures of the motifs as a marked point pattern (kinds are the marks), each defined
in the docstring of the function that computes it: :func:`structure` (nearest footprint gaps
and pair correlation per ordered kind pair); :func:`repetition` (how strongly the arrangement
repeats itself beyond what the exemplar shows) lives in :mod:`svgtile.metrics.repeats` and is
re-exported here.  Distributions of large textures are measured on a sample of their
motifs (:func:`svgtile.metrics.window.motif_sample`).

References
----------
Illian, Penttinen, Stoyan & Stoyan 2008, Statistical Analysis and Modelling of Spatial Point
Patterns, §4.3 (pair correlation function, translation edge correction).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import GAP_MIN_SAMPLES, Stats, nearest_gaps
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import world_footprints
from svgtile.metrics.repeats import (  # noqa: F401  (re-exported: the figure lived here before issue 13)
    REPEAT_BIN,
    REPEAT_MIN,
    REPEAT_REACH,
    REPEAT_SAMPLES,
    Repetition,
    _mode_share,
    repetition,
)
from svgtile.metrics.window import exemplar_size, finite_or_none, in_window, motif_sample, spacing

#: At most this many texture motifs per kind are measured for nearest gaps.
GAP_SAMPLES = 4000
#: Draws of the nearest-gap sampling noise (:func:`sampling_noise`), and their fixed seed.
NOISE_DRAWS = 64
NOISE_SEED = 0x6A9
#: Pair correlation is computed for distances up to this many mean spacings …
PAIR_RANGE = 3.0
#: … in this many equal bins …
PAIR_BINS = 12
#: … for the ordered kind pairs with at least this many exemplar pairs closer than the range.
PAIR_MIN_PAIRS = 20
#: At most this many texture motifs per kind are reference points of the pair correlation.
PAIR_SAMPLES = 10_000


@dataclass(frozen=True)
class KindPair:
    """The structure figures of one ordered kind pair (i, j) (see :func:`structure`).

    Attributes
    ----------
    kinds : (int, int)
        ``(i, j)``, indices into the exemplar's kinds.
    names : (str, str)
        Their names.
    gap_samples : (int, int)
        Nearest gaps measured: exemplar motifs of kind i, texture motifs of kind i.
    exemplar_mean_gap : float or None
        ``mean(G^E_ij)``, user units (None without exemplar gaps).
    gap_distance : float or None
        ``D_ij``, dimensionless; 0 is the exemplar's structure (None if the pair does not count).
    gap_noise : float or None
        ``N_ij``, dimensionless: ``D_ij`` near it cannot be told from the exemplar's structure.
    exemplar_pairs_in_range : int
        Exemplar (i, j) pairs closer than the pair-correlation range.
    pair_correlation_distance : float or None
        ``P_ij``, dimensionless; 0 is the exemplar's structure (None if the pair does not count).
    """

    kinds: tuple[int, int]
    names: tuple[str, str]
    gap_samples: tuple[int, int]
    exemplar_mean_gap: float | None
    gap_distance: float | None
    gap_noise: float | None
    exemplar_pairs_in_range: int
    pair_correlation_distance: float | None


@dataclass(frozen=True)
class Structure:
    """What :func:`structure` finds: frequency-weighted means over the kind pairs that count.

    Attributes
    ----------
    gap_distance : float or None
        Mean nearest-gap distance ``D``, dimensionless; 0 is the exemplar's structure.
    gap_noise : float or None
        Mean sampling noise ``N`` of ``gap_distance``, dimensionless.
    pair_correlation_distance : float or None
        Mean pair-correlation distance ``P``, dimensionless; 0 is the exemplar's structure.
    kind_pairs : tuple of KindPair
        Every ordered kind pair (i, j), in row-major order.
    """

    gap_distance: float | None
    gap_noise: float | None
    pair_correlation_distance: float | None
    kind_pairs: tuple[KindPair, ...]


def kind_trees(arr: Arrangement, k: int) -> list[cKDTree]:
    """One k-d tree per kind of the centroids of that kind's motifs, in index order.

    :func:`structure` and :func:`repetition` both search a kind's motifs; building the trees
    once serves both (a tree of the same points answers the same).
    """
    return [cKDTree(arr.xy[arr.kind == c]) for c in range(k)]


def structure(
    exemplar: Exemplar, stats: Stats, arr: Arrangement, window: shapely.Geometry, *,
    geoms: np.ndarray | None = None, inside: np.ndarray | None = None, trees: list[cKDTree] | None = None,
) -> Structure:  # fmt: skip
    """Distances between the exemplar's and the texture's structure, per ordered kind pair.

    **Nearest gaps.**  For an ordered kind pair (i, j), the gap of a motif a of kind i is the
    footprint distance to the nearest *other* motif of kind j:
    ``G(a) = min_{b ≠ a, kind b = j} dist(F_a, F_b)``.  The exemplar's sample ``G^E_ij`` holds it
    for every exemplar motif of kind i (neighbours from the exemplar); the texture's ``G^T_ij``
    for the motifs of kind i in ``window`` (at most :data:`GAP_SAMPLES`, neighbours from the whole
    texture, so the window's edge does not lengthen gaps).  The exemplar's gaps are taken as it
    shows them — a motif near the input region's edge may have its true nearest neighbour outside,
    unseen — the convention of ``d_ij`` in :mod:`svgtile.analysis.stats`.  A pair counts if ``G^E_ij`` has at
    least :data:`GAP_MIN_SAMPLES` values and a positive mean; then

    ``D_ij = W1(G^E_ij, G^T_ij) / mean(G^E_ij)``

    with ``W1`` the 1-Wasserstein distance of the empirical distributions
    (``∫ |F^E(t) − F^T(t)| dt``), and ``gap_distance = Σ f_i f_j D_ij / Σ f_i f_j`` over the
    pairs that count (``f`` the exemplar's kind frequencies).

    **Sampling noise.**  An exemplar holds few motifs (often under 20 of a kind), so ``D_ij`` is
    far from 0 even for a texture of exactly the process that drew the exemplar.
    ``N_ij = E W1(S, G^T_ij) / mean(G^E_ij)``, ``S`` a sample of ``|G^E_ij|`` values drawn with
    replacement from ``G^T_ij`` (:func:`sampling_noise`), is what ``D_ij`` would be on average
    if the exemplar's gaps were drawn from the texture's distribution; ``gap_noise`` is its
    weighted mean as above.  ``gap_distance`` near ``gap_noise`` says the exemplar cannot tell the
    texture's gap structure from its own; well above it, that they differ.  A tiling scores
    below the noise, as it repeats the exemplar's very sample.  (The exemplar's gaps are taken
    as it shows them, so its motifs at the edge lack their neighbours beyond it: a tiling, which
    gives them those neighbours, is not at 0 either.)

    **Pair correlation.**  ``g_ij(r)`` of the centroids (:func:`pair_correlation`) for
    ``0 ≤ r < R``, ``R = min(PAIR_RANGE · s, ½ · shorter side of the input region's bounding
    box)``, in :data:`PAIR_BINS` equal bins; the exemplar's on its input region, the texture's on
    ``window``, both with the translation edge correction.  A pair counts if the exemplar has at
    least :data:`PAIR_MIN_PAIRS` (a, b) pairs closer than R; then

    ``P_ij = (1/R) ∫_0^R |g^E_ij(r) − g^T_ij(r)| dr``

    (the mean absolute difference over the bins; 1 is as large as g itself at random), and
    ``pair_correlation_distance`` is its frequency-weighted mean as above.

    A pair whose texture side cannot be measured (no motif of kind i in ``window``, or none of
    kind j) gets None and is left out of the means; either mean is None if no pair is left.

    Parameters
    ----------
    exemplar, stats : the exemplar and its analysis
    arr : the texture
    window : where the texture is measured (shapely geometry)
    geoms : (n,) world footprints of ``arr``, if built
    inside : (n,) bool, the motifs of ``arr`` in ``window``, if known
    trees : :func:`kind_trees` of ``arr``, if built

    Returns
    -------
    Structure
    """
    protos = exemplar.prototypes
    k = len(protos)
    ex = exemplar.motifs
    if geoms is None:
        geoms = world_footprints(arr, protos)
    ex_geoms = world_footprints(ex, protos)
    if inside is None:
        inside = in_window(arr, window)
    freq = stats.frequency

    s = spacing(stats)
    w, h = exemplar_size(exemplar)
    reach = min(PAIR_RANGE * s, 0.5 * min(w, h))
    g_ex, n_ex = pair_correlation(ex.xy, ex.kind, k, exemplar.region, reach)
    g_tex, _ = pair_correlation(arr.xy, arr.kind, k, window, reach, sample=PAIR_SAMPLES)
    have = np.bincount(arr.kind[inside], minlength=k) > 0

    pairs = []
    gap_num = gap_den = pc_num = pc_den = noise_num = 0.0
    for i in range(k):
        src_ex = np.flatnonzero(ex.kind == i)
        src_tex = motif_sample(arr, np.flatnonzero(inside & (arr.kind == i)), GAP_SAMPLES)
        for j in range(k):
            ge = nearest_gaps(ex, protos, src_ex, j, geoms=ex_geoms)
            ge = ge[np.isfinite(ge)]
            gt = nearest_gaps(arr, protos, src_tex, j, geoms=geoms, tree=trees[j] if trees else None)
            gt = gt[np.isfinite(gt)]
            d_gap = noise = None
            if len(ge) >= GAP_MIN_SAMPLES and ge.mean() > 0 and len(gt):
                d_gap = wasserstein(ge, gt) / float(ge.mean())
                noise = sampling_noise(gt, len(ge)) / float(ge.mean())
                gap_num += freq[i] * freq[j] * d_gap
                noise_num += freq[i] * freq[j] * noise
                gap_den += freq[i] * freq[j]
            d_pc = None
            if n_ex[i, j] >= PAIR_MIN_PAIRS and have[i] and have[j]:
                d_pc = float(np.abs(g_ex[i, j] - g_tex[i, j]).mean())
                pc_num += freq[i] * freq[j] * d_pc
                pc_den += freq[i] * freq[j]
            pairs.append(
                KindPair(
                    kinds=(i, j),
                    names=(exemplar.kinds[i].name, exemplar.kinds[j].name),
                    gap_samples=(len(ge), len(gt)),
                    exemplar_mean_gap=finite_or_none(float(ge.mean())) if len(ge) else None,
                    gap_distance=d_gap,
                    gap_noise=noise,
                    exemplar_pairs_in_range=int(n_ex[i, j]),
                    pair_correlation_distance=d_pc,
                )
            )
    return Structure(
        gap_distance=float(gap_num / gap_den) if gap_den > 0 else None,
        gap_noise=float(noise_num / gap_den) if gap_den > 0 else None,
        pair_correlation_distance=float(pc_num / pc_den) if pc_den > 0 else None,
        kind_pairs=tuple(pairs),
    )


def sampling_noise(values: np.ndarray, n: int, draws: int = NOISE_DRAWS) -> float:
    """Mean 1-Wasserstein distance between ``n`` values drawn from ``values`` and ``values`` itself.

    The draws are with replacement, from a generator seeded with :data:`NOISE_SEED` (a figure is
    a function of its inputs).  0 for constant values; it shrinks like ``1/√n``.

    Parameters
    ----------
    values : (m,) float array, a large sample of a distribution
    n : the size of the small sample
    draws : how many small samples are averaged
    """
    values = np.sort(np.asarray(values, dtype=np.float64))
    if len(values) == 0 or n <= 0:
        return 0.0
    rng = np.random.default_rng(NOISE_SEED)
    picks = np.sort(rng.integers(0, len(values), size=(draws, n)), axis=1)
    return float(np.mean([wasserstein(values[row], values) for row in picks]))


def wasserstein(u: np.ndarray, v: np.ndarray) -> float:
    """1-Wasserstein distance ``∫ |F_u(t) − F_v(t)| dt`` of two 1-D samples' empirical distributions.

    (As :func:`scipy.stats.wasserstein_distance`, without importing scipy.stats.)
    """
    u, v = np.sort(u), np.sort(v)
    t = np.sort(np.concatenate([u, v]))
    fu = np.searchsorted(u, t[:-1], side="right") / len(u)
    fv = np.searchsorted(v, t[:-1], side="right") / len(v)
    return float(np.sum(np.abs(fu - fv) * np.diff(t)))


def pair_correlation(
    xy: np.ndarray, kind: np.ndarray, k: int, window: shapely.Geometry, reach: float,
    bins: int = PAIR_BINS, *, sample: int | None = None,
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Pair correlation ``g_ij(r)`` of the points in ``window``, translation edge-corrected.

    With ``n_i`` points of kind i in the window ``W``, ``λ_i = n_i / |W|``, bins
    ``[r_k, r_{k+1})`` of area ``A_k = π (r_{k+1}² − r_k²)`` and the set covariance
    ``γ(d) = |W ∩ (W + d)|``::

        g_ij[k] = Σ_{a ∈ S_i} Σ_{b of kind j, b ≠ a, |x_b − x_a| ∈ bin k} 1 / γ(x_b − x_a)
                  · (n_i / |S_i|) / (λ_i λ_j A_k)

    where ``S_i`` is every point of kind i in ``W`` (or a sample of ``sample`` of them), partners
    ``b`` are the points in ``W``.  For a Poisson pattern ``E g = 1`` at every r; a hard core
    gives 0 below it, clusters > 1 (Illian et al. 2008, §4.3.3).

    Parameters
    ----------
    xy : (n, 2) float array, points (centroids)
    kind : (n,) int array
    k : number of kinds
    window : shapely geometry, ``W``
    reach : float, user units; the bins cover ``[0, reach)``
    bins : number of bins
    sample : largest number of reference points per kind (None: all)

    Returns
    -------
    g : (k, k, bins) float array (0 where a kind is missing)
    pairs : (k, k) int array, ordered (a, b) pairs closer than ``reach`` among all points in ``W``
        (counted on the sample and scaled up if sampled)
    """
    inside = shapely.contains_xy(window, xy[:, 0], xy[:, 1])
    xy, kind = xy[inside], kind[inside]
    g = np.zeros((k, k, bins))
    pairs = np.zeros((k, k), dtype=np.int64)
    n = np.bincount(kind, minlength=k)
    if len(xy) < 2 or not reach > 0:
        return g, pairs
    area = float(window.area)
    edges = np.linspace(0.0, reach, bins + 1)
    ring = np.pi * (edges[1:] ** 2 - edges[:-1] ** 2)
    tree = cKDTree(xy)
    pts = Arrangement(kind, xy, np.zeros(len(kind)), np.ones(len(kind)))
    for i in range(k):
        ref = np.flatnonzero(kind == i)
        if sample is not None:
            ref = motif_sample(pts, ref, sample)
        if len(ref) == 0:
            continue
        found = cKDTree(xy[ref]).sparse_distance_matrix(tree, reach, output_type="ndarray")
        a, b, dist = ref[found["i"]], found["j"].astype(np.int64), found["v"]
        keep = (a != b) & (dist < reach)
        a, b, dist = a[keep], b[keep], dist[keep]
        weight = (n[i] / len(ref)) / _set_covariance(window, xy[b] - xy[a], reach)
        slot = np.minimum((dist / reach * bins).astype(np.int64), bins - 1)
        np.add.at(g[i], (kind[b], slot), weight)
        pairs[i] = np.round(np.bincount(kind[b], minlength=k) * n[i] / len(ref)).astype(np.int64)
    lam = n / area
    norm = np.outer(lam, lam)[:, :, None] * ring[None, None, :]
    return np.divide(g, norm, out=np.zeros_like(g), where=norm > 0), pairs


#: Displacements :func:`_set_covariance` measures against the sample windows at once.
_PAIR_CHUNK = 1 << 13


def _set_covariance(window: shapely.Geometry, d: np.ndarray, reach: float = math.inf) -> np.ndarray:
    """(p,) ``γ(d) = |W ∩ (W + d)|`` for displacements ``d`` (p, 2), square user units.

    Exact for an axis-aligned rectangle, ``(w − |dx|)(h − |dy|)``, and for axis-aligned
    rectangles ``W_k`` (the sample windows of :func:`svgtile.metrics.window.sample_windows`) at
    least ``reach`` apart along x or y, ``|d|`` below ``reach``: no shift that short moves one
    onto another, so ``γ(d) = Σ_k (w_k − |dx|)(h_k − |dy|)``.  Otherwise measured with shapely
    on the displacements rounded to ``sqrt(|W|) / 1000`` (relative error about perimeter × step
    / area, a few tenths of a percent).
    """
    x0, y0, x1, y1 = window.bounds
    box = (x1 - x0) * (y1 - y0)
    parts = _apart_rectangles(window, reach) if window.geom_type == "MultiPolygon" else None
    if window.geom_type == "Polygon" and abs(window.area - box) <= 1e-9 * box:
        gamma = np.maximum(x1 - x0 - np.abs(d[:, 0]), 0.0) * np.maximum(y1 - y0 - np.abs(d[:, 1]), 0.0)
    elif parts is not None:
        w, h = parts[:, 2] - parts[:, 0], parts[:, 3] - parts[:, 1]
        # np.maximum, not np.clip(…, 0, None): the same values, and clip's slow path took ten times
        # as long on the million pairs × 9 windows of a sampled 177k-motif texture; in chunks of
        # _PAIR_CHUNK pairs, in place, so the (pairs, windows) products stay in the cache
        gamma = np.empty(len(d))
        for a in range(0, len(d), _PAIR_CHUNK):
            sl = slice(a, a + _PAIR_CHUNK)
            across = w[None, :] - np.abs(d[sl, 0:1])
            np.maximum(across, 0.0, out=across)
            down = h[None, :] - np.abs(d[sl, 1:2])
            np.maximum(down, 0.0, out=down)
            across *= down
            gamma[sl] = across.sum(axis=1)
    else:
        step = math.sqrt(window.area) / 1000
        key, back = np.unique(np.round(d / step).astype(np.int64), axis=0, return_inverse=True)
        shift = key * step
        count = shapely.get_num_coordinates(window)
        moved = shapely.transform(
            np.full(len(key), window, dtype=object), lambda c: c + np.repeat(shift, count, axis=0)
        )
        gamma = shapely.area(shapely.intersection(window, moved))[back.ravel()]
    return np.maximum(gamma, 1e-12 * box)


def _apart_rectangles(window: shapely.Geometry, reach: float) -> np.ndarray | None:
    """(m, 4) bounds of the parts of ``window`` if each is an axis-aligned rectangle and every
    two are at least ``reach`` apart along x or y; None otherwise."""
    parts = shapely.get_parts(window)
    bounds = shapely.bounds(parts)
    boxes = (bounds[:, 2] - bounds[:, 0]) * (bounds[:, 3] - bounds[:, 1])
    if not np.allclose(shapely.area(parts), boxes, rtol=1e-9, atol=0) or not math.isfinite(reach):
        return None
    gap_x = np.maximum(bounds[:, None, 0] - bounds[None, :, 2], bounds[None, :, 0] - bounds[:, None, 2])
    gap_y = np.maximum(bounds[:, None, 1] - bounds[None, :, 3], bounds[None, :, 1] - bounds[:, None, 3])
    apart = np.maximum(gap_x, gap_y) >= reach
    np.fill_diagonal(apart, True)
    return bounds if apart.all() else None
