"""Figures that say how well a texture reproduces its exemplar.

almeraj2013 §4 notes that the field lacks "clear notions of similarity … for geometric
arrangements"; :func:`score` gathers the figures svgtile uses instead, each defined in the
docstring of the function that computes it:

* conflicts — overlapping pairs and distance-rule violators (:func:`svgtile.core.conflicts.find_conflicts`);
* density — the covered fraction against ρ, globally and over windows (:func:`density`,
  :func:`window_densities`);
* kind mix — total variation distance of the kind frequencies (:func:`kind_mix_tv`);
* orientation — motifs outside their kind's arc (:func:`orientation_outside`);
* structure — nearest footprint gaps and pair correlation, per kind pair (:func:`structure`);
* repetition — how strongly the arrangement repeats itself (:func:`repetition`);
* coverage — the largest hole against the exemplar's (:func:`largest_empty_disc`).

Measured on the texture's *interior* — the output region shrunk by one exemplar width — so that
border effects (motifs cut or dropped at the edge) do not dominate.  A motif is *in* a window when
its centroid is.  The lengths a figure is measured with (ranges, bins, grid steps) are multiples of
the exemplar's *mean spacing* ``s = 1 / sqrt(λ)``, λ the exemplar's motifs per unit area
(:func:`spacing`), so the figures do not depend on the drawing's scale.

Large textures are measured on a sample of their motifs where a figure is a distribution (gaps,
pair correlation, repetition): the sample is the motifs with the smallest hash of their kind and
rounded position (:func:`_sample`), so it is spread over the texture, never aliases with a
periodic layout, and does not depend on the order of the motifs.

References
----------
AlMeraj, Kaplan & Asente 2013, Patch-based geometric texture synthesis (../shared/papers/).
Illian, Penttinen, Stoyan & Stoyan 2008, Statistical Analysis and Modelling of Spatial Point
Patterns, §4.3 (pair correlation function, translation edge correction).
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.ndimage import distance_transform_edt
from scipy.spatial import cKDTree

from svgtile.analysis.stats import (
    GAP_MIN_SAMPLES,
    Stats,
    footprint_areas,
    in_arcs,
    nearest_distances,
    nearest_gaps,
)
from svgtile.core.arrangement import Arrangement
from svgtile.core.cellrng import hash64
from svgtile.core.conflicts import find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import Prototype, motif_radius, world_footprints
from svgtile.core.region import Region

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
#: Repetition: displacements are binned on a grid of this many mean spacings …
REPEAT_BIN = 0.1
#: … counted from this many mean spacings (or half the exemplar's size, if smaller) …
REPEAT_MIN = 2.0
#: … up to this many exemplar sizes (the larger side of the input region's bounding box) …
REPEAT_REACH = 1.5
#: … from at most this many reference motifs.
REPEAT_SAMPLES = 4000
#: Largest empty disc: the first grid of candidate centres has this many mean spacings …
COVER_STEP = 0.25
#: … and is refined this many times, 4× finer each time …
COVER_LEVELS = 2
#: … around at most this many of the best centres.
COVER_KEEP = 2048
#: At most this many centres of the first grid are measured exactly (see largest_empty_disc).
COVER_EXACT = 16_384


# ----------------------------------------------------------------------------- basics


def interior(exemplar: Exemplar, region: Region) -> shapely.Geometry:
    """The output region shrunk by the larger side of the input region's bounding box."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return region.interior(max(x1 - x0, y1 - y0))


def density(arr: Arrangement, exemplar: Exemplar, window: shapely.Geometry) -> float:
    """Footprint area of the motifs whose centroid lies in ``window``, over its area.

    Counting by centroid is an unbiased estimate of the covered fraction (motifs cut by the
    window's edge are counted in full as often as they are missed).
    """
    inside = shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1])
    return float(footprint_areas(arr, exemplar.prototypes)[inside].sum() / window.area)


def kind_mix_tv(arr: Arrangement, stats: Stats, window: shapely.Geometry | None = None) -> float:
    """Total variation distance between the kind frequencies of ``arr`` and the exemplar's."""
    kind = arr.kind
    if window is not None:
        kind = kind[shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1])]
    if len(kind) == 0:
        return 1.0
    freq = np.bincount(kind, minlength=len(stats.frequency)) / len(kind)
    return float(0.5 * np.abs(freq - stats.frequency).sum())


def spacing(stats: Stats) -> float:
    """The exemplar's mean spacing ``s = 1 / sqrt(λ)``, λ its motifs per unit area (user units)."""
    return 1.0 / math.sqrt(stats.count_density) if stats.count_density > 0 else math.inf


def _size(exemplar: Exemplar) -> tuple[float, float]:
    """Width and height of the input region's bounding box, user units."""
    x0, y0, x1, y1 = exemplar.region.bounds
    return x1 - x0, y1 - y0


def _inside(arr: Arrangement, window: shapely.Geometry) -> np.ndarray:
    return shapely.contains_xy(window, arr.xy[:, 0], arr.xy[:, 1])


def _sample(arr: Arrangement, index: np.ndarray, most: int) -> np.ndarray:
    """At most ``most`` of the motifs ``index``: those with the smallest hash of kind and position.

    Deterministic and independent of the motifs' order; a hash does not alias with a periodic
    layout the way a stride through reading order would.
    """
    if len(index) <= most:
        return index
    q = np.round(arr.xy[index] * 1e4).astype(np.int64)
    h = hash64(0x5C0E, 0, arr.kind[index], q[:, 0], q[:, 1])
    return np.sort(index[np.argsort(h, kind="stable")[:most]])


def _number(value: float | None) -> float | None:
    """A JSON-able float: None for a missing or non-finite value."""
    return None if value is None or not math.isfinite(value) else float(value)


# ----------------------------------------------------------------------------- the score


def score(exemplar: Exemplar, stats: Stats, arrangement: Arrangement, region: Region) -> dict:
    """All figures of a texture against its exemplar, as plain JSON-able data.

    Figures are measured on the interior ``I`` (:func:`interior`; the whole region if the
    interior is empty) unless said otherwise; ``s`` is the exemplar's mean spacing (:func:`spacing`),
    ρ its density, ``f_i`` its kind frequencies.  Undefined figures are ``None``.

    Parameters
    ----------
    exemplar : the parsed exemplar
    stats : its analysis
    arrangement : the texture, n motifs
    region : the output region the texture fills

    Returns
    -------
    dict with the keys

    ``window`` : str
        ``"interior"``, or ``"region"`` when the region is too small to have an interior.
    ``window_area`` : float
        Area of ``I``, square user units.
    ``motifs`` : int
        Motifs whose centroid lies in ``I``.
    ``spacing`` : float
        ``s``, user units.
    ``overlaps`` : int
        Pairs of motifs whose footprints share area (touching does not count), at least one of
        them in ``I``.
    ``violators`` : int
        Motifs in ``I`` with a neighbour (anywhere) whose footprint is closer than ``d_ij``
        (almeraj2013 §3.1; an overlapping neighbour is closer unless ``d_ij = 0``), less the
        rounding slack of :func:`svgtile.core.conflicts.slack`.
    ``violator_fraction`` : float or None
        ``violators / motifs``.
    ``overlaps_total``, ``violators_total`` : int
        The same over the whole texture.
    ``density_ratio`` : float or None
        Covered fraction of ``I`` over ρ (:func:`density`); 1 is right.
    ``density_windows`` : int
        Windows of :func:`window_densities`.
    ``density_cv`` : float or None
        Coefficient of variation ``std(D_w) / mean(D_w)`` of the window densities (population
        standard deviation; None with fewer than 2 windows); 0 is even.
    ``density_min_ratio``, ``density_max_ratio`` : float or None
        ``min_w D_w / ρ`` and ``max_w D_w / ρ``.
    ``kind_mix_tv`` : float
        Total variation distance ``½ Σ_i |f'_i − f_i|`` of the kind frequencies in ``I``
        (:func:`kind_mix_tv`); 0 is right, 1 if ``I`` holds no motif.
    ``orientation_outside`` : float or None
        Fraction of the motifs in ``I`` whose orientation lies outside their kind's exemplar arc
        (:func:`orientation_outside`).
    ``gap_distance`` : float or None
        Nearest-gap distance of :func:`structure`; 0 is the exemplar's structure.
    ``gap_noise`` : float or None
        What ``gap_distance`` would be, on average, if the exemplar's gaps were a sample of the
        texture's own (:func:`structure`): a ``gap_distance`` near it cannot be told from the
        exemplar's structure with so few exemplar motifs.
    ``pair_correlation_distance`` : float or None
        Pair-correlation distance of :func:`structure`; 0 is the exemplar's structure.
    ``kind_pairs`` : list of dict
        Per ordered kind pair, the details of :func:`structure`.
    ``repetition`` : float or None
        Excess over chance of motifs repeated at the most common displacement
        (:func:`repetition`): ≈ 1 for a tiling, ≈ 0 for random placement.
    ``repetition_raw`` : float or None
        The same without the chance correction.
    ``repetition_vector`` : [dx, dy] or None
        The most common displacement, user units.
    ``empty_disc_radius`` : float
        Radius of the largest disc centred in ``I``, inside the region, that meets no footprint
        (:func:`largest_empty_disc`), user units.
    ``exemplar_empty_disc_radius`` : float
        The same for the exemplar: centred in and inside its input region.
    ``coverage`` : float or None
        ``empty_disc_radius / exemplar_empty_disc_radius``: ≈ 1 or below is as well covered
        as the exemplar, ≫ 1 is a hole.
    """
    arr = arrangement
    protos = exemplar.prototypes
    window = interior(exemplar, region)
    kind_of_window = "interior"
    if window.is_empty or window.area <= 0:
        window, kind_of_window = region.shape, "region"
    inside = _inside(arr, window)
    n_in = int(inside.sum())
    geoms = world_footprints(arr, protos)

    out: dict = {
        "window": kind_of_window,
        "window_area": float(window.area),
        "motifs": n_in,
        "spacing": _number(spacing(stats)),
    }
    out.update(conflict_counts(arr, protos, stats, inside, geoms))

    out["density_ratio"] = _number(density(arr, exemplar, window) / stats.density) if stats.density > 0 else None
    windows = window_densities(arr, exemplar, window)
    out["density_windows"] = len(windows)
    mean = float(windows.mean()) if len(windows) else 0.0
    out["density_cv"] = _number(float(windows.std()) / mean) if len(windows) >= 2 and mean > 0 else None
    ratio = windows / stats.density if stats.density > 0 and len(windows) else None
    out["density_min_ratio"] = _number(float(ratio.min())) if ratio is not None else None
    out["density_max_ratio"] = _number(float(ratio.max())) if ratio is not None else None

    out["kind_mix_tv"] = kind_mix_tv(arr, stats, window)
    out["orientation_outside"] = _number(orientation_outside(arr, stats, window))

    found = structure(exemplar, stats, arr, window, geoms=geoms)
    out["gap_distance"] = found["gap_distance"]
    out["gap_noise"] = found["gap_noise"]
    out["pair_correlation_distance"] = found["pair_correlation_distance"]
    out["kind_pairs"] = found["kind_pairs"]

    out.update(repetition(arr, exemplar, stats, window))

    step = COVER_STEP * spacing(stats) if stats.count_density > 0 else None
    r_tex, _ = largest_empty_disc(arr, protos, window, region.shape, step=step, geoms=geoms)
    r_ex, _ = largest_empty_disc(exemplar.motifs, protos, exemplar.region, exemplar.region, step=step)
    out["empty_disc_radius"] = r_tex
    out["exemplar_empty_disc_radius"] = r_ex
    out["coverage"] = _number(r_tex / r_ex) if r_ex > 0 else None
    return out


# ----------------------------------------------------------------------------- conflicts


def conflict_counts(
    arr: Arrangement, protos: list[Prototype], stats: Stats, inside: np.ndarray, geoms: np.ndarray | None = None
) -> dict:
    """Overlaps and distance-rule violators, in a window and in total.

    Parameters
    ----------
    arr : Arrangement of n motifs
    protos : kind prototypes
    stats : the exemplar's analysis (its ``d_ij``)
    inside : (n,) bool, the motifs in the window
    geoms : (n,) world footprints, if built

    Returns
    -------
    dict with ``overlaps`` (pairs sharing area with at least one end inside), ``violators``
    (motifs inside with a neighbour closer than ``d_ij``), ``violator_fraction`` (of the motifs
    inside; None if none), ``overlaps_total`` and ``violators_total`` (whole arrangement).
    """
    found = find_conflicts(arr, protos, stats.distance, geoms)
    touch = inside[found.i] | inside[found.j]
    violator = np.zeros(len(arr), dtype=bool)
    violator[found.i[found.violation]] = violator[found.j[found.violation]] = True
    n_in = int(inside.sum())
    return {
        "overlaps": int((found.overlap & touch).sum()),
        "violators": int((violator & inside).sum()),
        "violator_fraction": float((violator & inside).sum() / n_in) if n_in else None,
        "overlaps_total": int(found.overlap.sum()),
        "violators_total": int(violator.sum()),
    }


# ----------------------------------------------------------------------------- density, orientation


def window_densities(arr: Arrangement, exemplar: Exemplar, window: shapely.Geometry) -> np.ndarray:
    """Covered fraction ``D_w`` of each window the size of the input region tiling ``window``.

    The windows are the cells of a grid of the input region's bounding-box size ``w × h``,
    centred on ``window``'s bounding box, that lie wholly inside ``window`` (``⌊W/w⌋ × ⌊H/h⌋``
    of them for a ``W × H`` rectangle).  ``D_w`` is the footprint area of the motifs whose
    centroid lies in cell ``w`` (cells are half-open), over ``w·h`` — as in :func:`density`.

    Returns
    -------
    (m,) float array, in row-major order of the grid; empty if no cell fits.
    """
    w, h = _size(exemplar)
    x0, y0, x1, y1 = window.bounds
    nx, ny = math.floor((x1 - x0) / w + 1e-9), math.floor((y1 - y0) / h + 1e-9)
    if nx < 1 or ny < 1:
        return np.zeros(0)
    ox, oy = x0 + ((x1 - x0) - nx * w) / 2, y0 + ((y1 - y0) - ny * h) / 2
    cx, cy = np.meshgrid(np.arange(nx), np.arange(ny))
    cx, cy = cx.ravel(), cy.ravel()
    cells = shapely.box(ox + cx * w, oy + cy * h, ox + (cx + 1) * w, oy + (cy + 1) * h)
    fits = shapely.contains(shapely.buffer(window, 1e-9 * max(w, h)), cells)
    ix = np.floor((arr.xy[:, 0] - ox) / w).astype(np.int64)
    iy = np.floor((arr.xy[:, 1] - oy) / h).astype(np.int64)
    ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
    area = np.bincount(iy[ok] * nx + ix[ok], footprint_areas(arr, exemplar.prototypes)[ok], minlength=nx * ny)
    return area[fits] / (w * h)


def orientation_outside(arr: Arrangement, stats: Stats, window: shapely.Geometry) -> float | None:
    """Fraction of the motifs in ``window`` outside their kind's orientation arc (almeraj2013 §3.5).

    Uses :func:`svgtile.analysis.stats.in_arcs` (with its rounding tolerance); None if no motif is in
    ``window``.
    """
    inside = _inside(arr, window)
    if not inside.any():
        return None
    return float((~in_arcs(arr.angle[inside], arr.kind[inside], stats)).mean())


# ----------------------------------------------------------------------------- structure


def structure(
    exemplar: Exemplar, stats: Stats, arr: Arrangement, window: shapely.Geometry, *, geoms: np.ndarray | None = None
) -> dict:
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
    geoms : world footprints of ``arr``, if built

    Returns
    -------
    dict: ``gap_distance``, ``gap_noise``, ``pair_correlation_distance`` (float or None) and
    ``kind_pairs``, a list over the ordered kind pairs (i, j) of dicts with ``kinds`` [i, j],
    ``names``, ``gap_samples`` [exemplar, texture], ``exemplar_mean_gap``, ``gap_distance``, ``gap_noise``,
    ``exemplar_pairs_in_range`` and ``pair_correlation_distance``.
    """
    protos = exemplar.prototypes
    k = len(protos)
    ex = exemplar.motifs
    if geoms is None:
        geoms = world_footprints(arr, protos)
    ex_geoms = world_footprints(ex, protos)
    inside = _inside(arr, window)
    freq = stats.frequency

    s = spacing(stats)
    w, h = _size(exemplar)
    reach = min(PAIR_RANGE * s, 0.5 * min(w, h))
    g_ex, n_ex = pair_correlation(ex.xy, ex.kind, k, exemplar.region, reach)
    g_tex, _ = pair_correlation(arr.xy, arr.kind, k, window, reach, sample=PAIR_SAMPLES)
    have = np.bincount(arr.kind[inside], minlength=k) > 0

    pairs = []
    gap_num = gap_den = pc_num = pc_den = noise_num = 0.0
    for i in range(k):
        src_ex = np.flatnonzero(ex.kind == i)
        src_tex = _sample(arr, np.flatnonzero(inside & (arr.kind == i)), GAP_SAMPLES)
        for j in range(k):
            ge = nearest_gaps(ex, protos, src_ex, j, geoms=ex_geoms)
            ge = ge[np.isfinite(ge)]
            gt = nearest_gaps(arr, protos, src_tex, j, geoms=geoms)
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
                {
                    "kinds": [i, j],
                    "names": [exemplar.kinds[i].name, exemplar.kinds[j].name],
                    "gap_samples": [len(ge), len(gt)],
                    "exemplar_mean_gap": _number(float(ge.mean())) if len(ge) else None,
                    "gap_distance": d_gap,
                    "gap_noise": noise,
                    "exemplar_pairs_in_range": int(n_ex[i, j]),
                    "pair_correlation_distance": d_pc,
                }
            )
    return {
        "gap_distance": float(gap_num / gap_den) if gap_den > 0 else None,
        "gap_noise": float(noise_num / gap_den) if gap_den > 0 else None,
        "pair_correlation_distance": float(pc_num / pc_den) if pc_den > 0 else None,
        "kind_pairs": pairs,
    }


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
            ref = _sample(pts, ref, sample)
        if len(ref) == 0:
            continue
        found = cKDTree(xy[ref]).sparse_distance_matrix(tree, reach, output_type="ndarray")
        a, b, dist = ref[found["i"]], found["j"].astype(np.int64), found["v"]
        keep = (a != b) & (dist < reach)
        a, b, dist = a[keep], b[keep], dist[keep]
        weight = (n[i] / len(ref)) / _set_covariance(window, xy[b] - xy[a])
        slot = np.minimum((dist / reach * bins).astype(np.int64), bins - 1)
        np.add.at(g[i], (kind[b], slot), weight)
        pairs[i] = np.round(np.bincount(kind[b], minlength=k) * n[i] / len(ref)).astype(np.int64)
    lam = n / area
    norm = np.outer(lam, lam)[:, :, None] * ring[None, None, :]
    return np.divide(g, norm, out=np.zeros_like(g), where=norm > 0), pairs


def _set_covariance(window: shapely.Geometry, d: np.ndarray) -> np.ndarray:
    """(p,) ``γ(d) = |W ∩ (W + d)|`` for displacements ``d`` (p, 2), square user units.

    Exact for an axis-aligned rectangle, ``(w − |dx|)(h − |dy|)``; otherwise measured with
    shapely on the displacements rounded to ``sqrt(|W|) / 1000`` (relative error about
    perimeter × step / area, a few tenths of a percent).
    """
    x0, y0, x1, y1 = window.bounds
    box = (x1 - x0) * (y1 - y0)
    if window.geom_type == "Polygon" and abs(window.area - box) <= 1e-9 * box:
        gamma = np.clip(x1 - x0 - np.abs(d[:, 0]), 0, None) * np.clip(y1 - y0 - np.abs(d[:, 1]), 0, None)
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


# ----------------------------------------------------------------------------- repetition


def repetition(arr: Arrangement, exemplar: Exemplar, stats: Stats, window: shapely.Geometry) -> dict:
    """How strongly the arrangement repeats itself: ≈ 1 for a tiling, ≈ 0 for random placement.

    With ``s`` the mean spacing and ``L`` the exemplar's size (larger side of the input region's
    bounding box):

    1. Reference motifs: those in ``window`` (at most :data:`REPEAT_SAMPLES`, see
       :func:`_sample`).  For each reference a, every *same-kind* motif b of the texture with
       ``r0 ≤ |x_b − x_a| < R`` gives the displacement ``x_b − x_a``, where
       ``r0 = min(REPEAT_MIN · s, L / 2)`` (beyond local packing) and
       ``R = max(REPEAT_REACH · L, 2 r0)`` (reaching past the exemplar's own period).
    2. Displacements are binned on a square grid of step ``q = REPEAT_BIN · s``
       (``⌊d / q⌋`` per axis); ``v`` is the bin holding the most displacements among the bins
       of the half-plane ``dx > 0`` (or ``dx = 0, dy ≥ 0``) — the histogram is symmetric, ``v``
       and ``−v`` tie — and the first in row-major order on a tie.
    3. ``repetition_raw`` ``P`` is the fraction of references with at least one same-kind
       partner whose displacement falls in ``v`` or one of its 8 neighbouring bins (a
       ``3q × 3q`` square, so rounding at bin edges does not matter); ``repetition_vector`` is
       the mean of those displacements.
    4. At random, a reference of kind c has such a partner with probability
       ``p_c = 1 − exp(−λ_c · 9 q²)`` (Poisson, λ_c the kind's motifs per unit area in
       ``window``); with ``P0`` the mean of ``p_c`` over the references,
       ``repetition = max(0, (P − P0) / (1 − P0))`` — the excess over chance, as in Cohen's κ.

    In a tiling of period t every motif in the interior has a partner at exactly t, so P = 1
    and ``repetition`` = 1.  For random placement P ≈ P0 (≈ 0.09 Σ f_c² with these constants)
    and ``repetition`` ≈ 0.  An exemplar that is itself a lattice scores high whatever the
    engine: the figure measures repetition, not its cause.

    Returns
    -------
    dict with ``repetition``, ``repetition_raw`` (floats; None if no motif is in ``window``)
    and ``repetition_vector`` ([dx, dy] in user units, or None if no displacement was found).
    """
    none = {"repetition": None, "repetition_raw": None, "repetition_vector": None}
    inside = _inside(arr, window)
    if not inside.any() or not stats.count_density > 0:
        return none
    s = spacing(stats)
    size = max(_size(exemplar))
    q = REPEAT_BIN * s
    r0 = min(REPEAT_MIN * s, size / 2)
    reach = max(REPEAT_REACH * size, 2 * r0)
    ref = _sample(arr, np.flatnonzero(inside), REPEAT_SAMPLES)
    lam = np.bincount(arr.kind[inside], minlength=len(stats.frequency)) / window.area
    chance = float(np.mean(-np.expm1(-lam[arr.kind[ref]] * 9 * q * q)))

    who, disp = [], []
    for c in np.unique(arr.kind[ref]):
        mine = ref[arr.kind[ref] == c]
        peers = np.flatnonzero(arr.kind == c)
        found = cKDTree(arr.xy[mine]).sparse_distance_matrix(cKDTree(arr.xy[peers]), reach, output_type="ndarray")
        keep = (found["v"] >= r0) & (found["v"] < reach)
        a, b = mine[found["i"][keep]], peers[found["j"][keep]]
        who.append(a)
        disp.append(arr.xy[b] - arr.xy[a])
    who = np.concatenate(who) if who else np.zeros(0, np.int64)
    if len(who) == 0:
        return {"repetition": 0.0, "repetition_raw": 0.0, "repetition_vector": None}
    disp = np.concatenate(disp)
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
    has = np.zeros(len(arr), dtype=bool)
    has[who[near]] = True
    raw = float(has[ref].mean())
    corrected = max(0.0, (raw - chance) / (1.0 - chance)) if chance < 1 else 0.0
    vector = disp[near].mean(axis=0)
    return {
        "repetition": corrected,
        "repetition_raw": raw,
        "repetition_vector": [float(vector[0]), float(vector[1])],
    }


# ----------------------------------------------------------------------------- coverage


def largest_empty_disc(
    arr: Arrangement, protos: list[Prototype], centres: shapely.Geometry, within: shapely.Geometry,
    *, step: float | None = None, geoms: np.ndarray | None = None,
) -> tuple[float, np.ndarray]:  # fmt: skip
    """The largest disc centred in ``centres``, inside ``within``, that meets no footprint.

    The clearance of a point p is ``c(p) = min(dist(p, footprints), dist(p, ∂within))``; the
    radius returned is ``max c`` over a grid of candidate centres in ``centres`` of ``step``,
    refined :data:`COVER_LEVELS` times by a grid 4× finer (``±step/2`` about a point) around the
    :data:`COVER_KEEP` best points within ``step/√2`` of the best.  ``c`` is 1-Lipschitz, so the
    radius is a lower bound within ``step / 4**COVER_LEVELS / √2`` of the true one, unless more
    than :data:`COVER_KEEP` points compete for the best.

    Exact GEOS distances (:func:`~svgtile.analysis.stats.nearest_distances`) are taken on few points of
    the first grid: a distance transform of a raster of pixel ``step`` (pixels holding a point of
    a footprint's outline, or outside ``within``, are features;
    :func:`scipy.ndimage.distance_transform_edt`) gives each grid point an estimate
    ``e ≥ c − step/√2``; points are measured exactly in decreasing order of
    ``e`` until no point left can be within ``step/√2`` of the best clearance found, or
    :data:`COVER_EXACT` points were measured (a texture as regular as a tiling has as many
    holes as large as the largest: one of them is enough).

    Parameters
    ----------
    arr : the motifs
    protos : kind prototypes
    centres : shapely geometry where a centre may lie
    within : shapely geometry the disc must lie in (contains ``centres``)
    step : first grid step, user units (default: a 40th of the larger side of ``centres``)
    geoms : world footprints of ``arr``, if built

    Returns
    -------
    radius : float, user units (0 if ``centres`` is empty)
    centre : (2,) float array
    """
    if centres.is_empty:
        return 0.0, np.full(2, np.nan)
    x0, y0, x1, y1 = centres.bounds
    size = max(x1 - x0, y1 - y0)
    if step is None or not (step > 0 and math.isfinite(step)):
        step = size / 40
    step = max(step, size / 2000)  # at most ~4M pixels
    edge = within.boundary
    if len(arr):
        if geoms is None:
            geoms = world_footprints(arr, protos)
        tree = cKDTree(arr.xy)
        radius = motif_radius(arr, protos)

    def clearance(p: np.ndarray) -> np.ndarray:
        pts = shapely.points(p)
        c = shapely.distance(edge, pts)
        if len(arr):
            c = np.minimum(c, nearest_distances(p, np.zeros(len(p)), pts, tree, radius, geoms))
        return c

    p, e = _raster_clearance(arr, protos, centres, within, step)
    if len(p) == 0:
        p = np.array(shapely.get_coordinates(shapely.point_on_surface(centres)))
        e = np.full(1, np.inf)
    order = np.argsort(-e, kind="stable")
    p, e = p[order], e[order]
    c = np.full(len(p), -np.inf)
    done, batch = 0, 256
    while done < min(len(p), COVER_EXACT) and (done == 0 or e[done] >= c[:done].max() - math.sqrt(2) * step):
        end = min(done + batch, len(p), COVER_EXACT)
        c[done:end] = clearance(p[done:end])
        done, batch = end, 2 * batch
    p, c = p[:done], c[:done]
    fine = np.arange(-2, 3) / 4
    for _ in range(COVER_LEVELS):
        good = np.flatnonzero(c >= c.max() - step / math.sqrt(2))
        good = good[np.argsort(-c[good], kind="stable")[:COVER_KEEP]]
        ox, oy = np.meshgrid(fine * step, fine * step)
        q = (p[good, None, :] + np.stack([ox.ravel(), oy.ravel()], axis=1)[None]).reshape(-1, 2)
        q = q[shapely.contains_xy(centres, q[:, 0], q[:, 1])]
        p, c = np.concatenate([p[good], q]), np.concatenate([c[good], clearance(q)])
        step /= 4
    best = int(np.argmax(c))
    return float(max(c[best], 0.0)), p[best].copy()


#: Most outline points :func:`_raster_clearance` holds in memory at once.
_OUTLINE_CHUNK = 1 << 22


def _raster_clearance(
    arr: Arrangement, protos: list[Prototype], centres: shapely.Geometry, within: shapely.Geometry, step: float
) -> tuple[np.ndarray, np.ndarray]:
    """Pixel centres in ``centres`` of a raster of pixel ``step``, and a clearance estimate of each.

    Features are the pixels holding a point of a footprint outline (outlines sampled at most
    ``step`` apart) and the pixels whose centre is outside ``within``; the estimate is the
    distance to the nearest feature pixel's centre.  Every footprint and the outside of
    ``within`` have a feature pixel centre within ``step/√2`` of them, so the estimate is at
    least the clearance minus ``step/√2`` (inside a footprint it may be much more: only the
    exact clearance says 0).

    Returns
    -------
    xy : (m, 2) float array, pixel centres in ``centres``
    estimate : (m,) float array, user units
    """
    x0, y0, x1, y1 = centres.bounds
    pad = 2 * step
    ox, oy = x0 - pad, y0 - pad
    nx, ny = math.ceil((x1 - x0 + 2 * pad) / step), math.ceil((y1 - y0 + 2 * pad) / step)
    gx, gy = np.meshgrid(ox + (np.arange(nx) + 0.5) * step, oy + (np.arange(ny) + 0.5) * step)
    feature = ~shapely.contains_xy(within, gx, gy)
    if len(arr):
        reach = float(motif_radius(arr, protos).max())
        near = (
            (arr.xy[:, 0] > ox - reach) & (arr.xy[:, 0] < ox + nx * step + reach)
            & (arr.xy[:, 1] > oy - reach) & (arr.xy[:, 1] < oy + ny * step + reach)
        )  # fmt: skip
        scale = float(arr.scale.max())
        for k, proto in enumerate(protos):
            idx = np.flatnonzero(near & (arr.kind == k))
            if len(idx) == 0:
                continue
            rings = [shapely.segmentize(shapely.linearrings(r), step / max(scale, 1e-12)) for r in proto.rings]
            local = np.concatenate([shapely.get_coordinates(r) for r in rings])
            turn = np.radians(arr.angle[idx])
            cos, sin = np.cos(turn) * arr.scale[idx], np.sin(turn) * arr.scale[idx]
            rows = max(1, _OUTLINE_CHUNK // len(local))
            for a in range(0, len(idx), rows):
                sl = slice(a, a + rows)
                wx = cos[sl, None] * local[:, 0] - sin[sl, None] * local[:, 1] + arr.xy[idx[sl], 0, None]
                wy = sin[sl, None] * local[:, 0] + cos[sl, None] * local[:, 1] + arr.xy[idx[sl], 1, None]
                ix = np.floor((wx.ravel() - ox) / step).astype(np.int64)
                iy = np.floor((wy.ravel() - oy) / step).astype(np.int64)
                ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
                feature[iy[ok], ix[ok]] = True
    if feature.all():
        estimate = np.zeros(feature.shape)
    elif feature.any():
        estimate = distance_transform_edt(~feature) * step
    else:
        estimate = np.full(feature.shape, np.inf)
    keep = shapely.contains_xy(centres, gx, gy)
    return np.stack([gx[keep], gy[keep]], axis=1), estimate[keep]
