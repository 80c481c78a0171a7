"""How much the texture holds: the covered fraction, globally and per window, and the kind mix.

almeraj2013 §3.4 keeps the density ρ (the covered fraction) and the kind frequencies ``f_i`` of
the exemplar; these figures say how close a texture comes.  :func:`density`, the covered fraction
counted by centroid, is :func:`svgtile.analysis.window.density`, named here too.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.special import gammaln

from svgtile.analysis.stats import Stats, footprint_areas
from svgtile.analysis.window import density as density
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.metrics.window import exemplar_size, in_window


def kind_mix_tv(
    arr: Arrangement,
    stats: Stats,
    window: shapely.Geometry | None = None,
    *,
    inside: np.ndarray | None = None,
    classes: bool = True,
) -> float:
    """Total variation distance between the kind frequencies of ``arr`` and the exemplar's.

    ``½ Σ_c |f'_c − f_c|`` over the motifs in ``window`` (all of them if None; ``inside``, (n,)
    bool, if already known): 0 is the exemplar's mix, 1 if no motif is counted.

    With ``classes`` (the default) the frequencies are those of the kinds' shape classes
    (:attr:`Stats.classes <svgtile.analysis.stats.Stats.classes>`, issue 12.3): kinds drawn fewer than
    :data:`~svgtile.analysis.classes.RARE_BELOW` times are counted with the rare kinds of like
    shape.  Per kind, a one-off fragment is 1/n of the exemplar, and which of them a window holds
    is chance: FGDC 606 draws 60 of its 246 motifs once each, and a fair draw of one tile's worth
    of motifs from its exact mix already stands at TV 0.10 per kind (:func:`kind_mix_noise`).  Where no
    kind is pooled the two readings are the same number.  ``classes=False`` counts each kind.
    """
    kind = arr.kind
    if inside is not None:
        kind = kind[inside]
    elif window is not None:
        kind = kind[in_window(arr, window)]
    if len(kind) == 0:
        return 1.0
    cls = stats.kind_classes if classes else np.arange(len(stats.frequency))
    c = int(cls.max(initial=-1)) + 1
    freq = np.bincount(cls[kind], minlength=c) / len(kind)
    want = np.bincount(cls, weights=stats.frequency, minlength=c)  # the frequencies themselves per kind
    return float(0.5 * np.abs(freq - want).sum())


def kind_mix_noise(motifs: int, frequency: np.ndarray) -> float:
    """Expected TV distance of a fair draw from the exemplar's kind mix: what chance alone gives.

    ``motifs`` kinds drawn independently with probabilities ``frequency`` ((k,) float, summing to
    1) have counts ``N_i ~ Binomial(n, f_i)``, and ``E[½ Σ_i |N_i / n − f_i|]`` is computed per
    kind in closed form (de Moivre's mean absolute deviation of the binomial,
    ``E|N − n f| = 2 n f (1 − f) · C(n−1, m−1) f^(m−1) (1 − f)^(n−m)`` with ``m = ⌊n f⌋ + 1``,
    through log-gamma).  A texture's per-kind TV near this is the mix of the exemplar read
    through a window of ``motifs`` motifs, not a skew.  0 for no motifs.
    """
    n = int(motifs)
    f = np.asarray(frequency, dtype=np.float64)
    f = f[(f > 0) & (f < 1)]
    if n <= 0 or len(f) == 0:
        return 0.0
    m = np.floor(n * f) + 1  # ≤ n, since 0 < f < 1
    log_term = gammaln(n) - gammaln(m) - gammaln(n - m + 1) + (m - 1) * np.log(f) + (n - m) * np.log1p(-f)
    mad = 2 * n * f * (1 - f) * np.exp(log_term)
    return float(0.5 * mad.sum() / n)


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
    w, h = exemplar_size(exemplar)
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
