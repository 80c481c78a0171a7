"""Where and at what scale the figures are measured: the interior, the mean spacing, the sample.

Figures are measured on the texture's *interior* — the output region shrunk by one exemplar
width — so that border effects (motifs cut or dropped at the edge) do not dominate.  A motif is
*in* a window when its centroid is.  Lengths a figure is measured with (ranges, bins, grid steps)
are multiples of the exemplar's *mean spacing* ``s = 1 / sqrt(λ)``, λ its motifs per unit area,
so the figures do not depend on the drawing's scale.  Large textures are measured on a sample of
their motifs where a figure is a distribution (:func:`motif_sample`), and a texture of more than
:data:`SAMPLE_ABOVE` motifs has its structure figures (nearest gaps, pair correlation:
:data:`svgtile.metrics.scoring.SAMPLED`) measured on a few windows spread over its interior
(:func:`sample_windows`).

:func:`interior`, :func:`in_window` and :func:`exemplar_size` are those of
:mod:`svgtile.analysis.window`, named here too: an engine that reads density as the figures do
(:func:`svgtile.engines.optimize.engine.fill_light`) may not import this later stage.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.analysis.stats import Stats
from svgtile.analysis.window import exemplar_size as exemplar_size
from svgtile.analysis.window import in_window as in_window
from svgtile.analysis.window import interior as interior
from svgtile.core.arrangement import Arrangement
from svgtile.core.cellrng import hash64


def spacing(stats: Stats) -> float:
    """The exemplar's mean spacing ``s = 1 / sqrt(λ)``, λ its motifs per unit area (user units):
    :attr:`~svgtile.analysis.stats.Stats.spacing`."""
    return stats.spacing


def motif_sample(arr: Arrangement, index: np.ndarray, most: int) -> np.ndarray:
    """At most ``most`` of the motifs ``index``: those with the smallest hash of kind and position.

    Deterministic and independent of the motifs' order; a hash does not alias with a periodic
    layout the way a stride through reading order would.

    Parameters
    ----------
    arr : Arrangement of n motifs
    index : (m,) int array, indices into ``arr``
    most : largest size of the sample

    Returns
    -------
    (min(m, most),) int array, sorted (``index`` itself if it is small enough)
    """
    if len(index) <= most:
        return index
    q = np.round(arr.xy[index] * 1e4).astype(np.int64)
    h = hash64(0x5C0E, 0, arr.kind[index], q[:, 0], q[:, 1])
    if most <= 0:
        return index[:0]
    # the first ``most`` of a stable sort of h, as a set, without sorting all m: every hash below
    # the most-th smallest, then those equal to it in index order (a stable sort's tie order)
    cut = h[np.argpartition(h, most - 1)[most - 1]]
    below = np.flatnonzero(h < cut)
    tied = np.flatnonzero(h == cut)[: most - len(below)]
    return np.sort(index[np.concatenate([below, tied])])


def finite_or_none(value: float | None) -> float | None:
    """A JSON-able float: None for a missing or non-finite value."""
    return None if value is None or not math.isfinite(value) else float(value)


#: A texture with more motifs than this in its window has its structure figures measured on
#: sample windows (:func:`sample_windows`; repetition and the neighbourhood distance already
#: measure a fixed sample of the whole window and are not).  Below it the structure figures
#: measure at most a few thousand motifs per kind (:data:`~svgtile.metrics.pattern.GAP_SAMPLES`),
#: so windows save little (none measurable at 60,000 motifs) and only add their deviation;
#: benchmarks/README.md, "`svgtile score` on sample windows".
SAMPLE_ABOVE = 100_000
#: The sample windows together cover this many motifs' worth of the window (about) …
SAMPLE_MOTIFS = 20_000
#: … on a grid of about this many cells per side of the window's bounding box …
SAMPLE_GRID = 3
#: … refined this many times (2× finer each time) when too few windows fit an irregular window.
SAMPLE_REFINE = 2


@dataclass(frozen=True)
class Sample:
    """Where the structure figures of a large texture were measured (:func:`sample_windows`).

    Attributes
    ----------
    windows : int
        Number of sample windows.
    window_size : (float, float)
        Width and height of each, user units.
    motifs : int
        Motifs centred in the sample windows.
    of : int
        Motifs centred in the whole window ``I`` (the figures' window).
    """

    windows: int
    window_size: tuple[float, float]
    motifs: int
    of: int

    def describe(self) -> str:
        """One line for the text report: ``9 windows of 335.9 × 335.9, 20,141 of 163,356 motifs``."""
        w, h = self.window_size
        return f"{self.windows} windows of {w:.4g} × {h:.4g}, {self.motifs:,} of {self.of:,} motifs"


def sample_windows(
    window: shapely.Geometry, xy: np.ndarray, inside: np.ndarray, *, above: int = SAMPLE_ABOVE,
    motifs: int = SAMPLE_MOTIFS,
) -> tuple[shapely.Geometry, Sample] | None:  # fmt: skip
    """Sample windows spread over ``window``, by a fixed rule from its bounds (no randomness).

    With ``n`` motifs in ``window`` (more than ``above``) and ``B`` its bounding box, ``B`` is
    cut into a grid of ``gx × gy`` equal cells, ``gx·gy ≈ SAMPLE_GRID²`` and the cells about
    square; each cell shrunk about its centre by ``t = √(motifs / n)`` (at most ¾) is a sample
    window if ``window`` contains it.  Rectangular ``window``: every cell gives one, and they
    hold about ``motifs`` motifs.  When the windows that fit hold fewer than half of
    ``motifs`` (an irregular map region), the grid is made 2× finer, at most
    :data:`SAMPLE_REFINE` times; then the texture is measured whole.  Windows are separated by
    at least a quarter of a cell, so a figure whose reach is shorter than that (pair
    correlation: three spacings; a cell holds at least ``above / SAMPLE_GRID²`` motifs) never
    pairs motifs of two windows.

    Parameters
    ----------
    window : shapely geometry, the figures' window ``I``
    xy : (n, 2) float array, the texture's centroids, user units
    inside : (n,) bool, the motifs in ``window``
    above : sample only when more than this many motifs are in ``window``
    motifs : about how many motifs the sample windows hold

    Returns
    -------
    (windows, sample) — a MultiPolygon of the sample windows (axis-aligned rectangles) and its
    :class:`Sample` — or None when the texture is not sampled.
    """
    n = int(inside.sum())
    if n <= above or window.is_empty:
        return None
    x0, y0, x1, y1 = window.bounds
    width, height = x1 - x0, y1 - y0
    if not (width > 0 and height > 0):
        return None
    t = min(math.sqrt(motifs / n), 0.75)
    for level in range(SAMPLE_REFINE + 1):
        g = SAMPLE_GRID * 2**level
        gx = max(1, round(g * math.sqrt(width / height)))
        gy = max(1, round(g * math.sqrt(height / width)))
        cw, ch = width / gx, height / gy
        cx, cy = np.meshgrid(x0 + (np.arange(gx) + 0.5) * cw, y0 + (np.arange(gy) + 0.5) * ch)
        cx, cy = cx.ravel(), cy.ravel()
        a, b = t * cw / 2, t * ch / 2
        boxes = shapely.box(cx - a, cy - b, cx + a, cy + b)
        boxes = boxes[shapely.contains(window, boxes)]
        if len(boxes) == 0:
            continue
        union = shapely.multipolygons(boxes)
        held = int((inside & shapely.contains_xy(union, xy[:, 0], xy[:, 1])).sum())
        if held >= motifs / 2:
            return union, Sample(len(boxes), (2 * a, 2 * b), held, n)
    return None


#: Around the sample windows, neighbours of their motifs are taken this many mean spacings of the
#: exemplar's rarest kind out: the nearest motif of a kind lies farther with probability
#: ``exp(−π·4²)`` at random (Poisson), far less in a packed texture.
SAMPLE_HALO = 4.0
