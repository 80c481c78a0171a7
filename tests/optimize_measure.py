"""Likeness, repetition, conflicts and density of a texture: what the optimize tests assert.

L is :func:`svgtile.analysis.neighbourhood.likeness` of the texture's neighbourhood distance
(Ma, Wei & Tong 2011 eq. (1)) between the ``tile`` (L = 1) and ``random`` (L = 0) engines' on
the same region and seed, measured on the motifs of the score's interior window.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from svgtile.analysis.neighbourhood import likeness, neighbourhood_distance
from svgtile.engines import synthesize
from svgtile.metrics import score
from svgtile.metrics.window import in_window, interior, spacing

SAMPLE = 300


@dataclass(frozen=True)
class Measure:
    likeness: float
    repetition: float
    overlaps: int
    violators: int
    density_ratio: float
    energy: float
    kind_mix: float = float("nan")  # svgtile score's kind-mix TV


def distance(ex, stats, region, arr, *, centres: np.ndarray | None = None, sample: int | None = SAMPLE) -> float:
    """Eq. (1)'s mean neighbourhood distance of ``arr``: at ``centres`` if given, else at its motifs
    in the score's interior window; a fixed draw of ``sample`` of them (None: every one)."""
    if centres is None:
        window = interior(ex, region)
        centres = np.flatnonzero(in_window(arr, window)) if not window.is_empty else None
    return neighbourhood_distance(arr.xy, arr.kind, ex.motifs.xy, ex.motifs.kind, spacing=spacing(stats), k=6,
                                  period=getattr(ex, "period", None), centres=centres, sample=sample,
                                  rng=np.random.default_rng(0))  # fmt: skip


def measure(ex, stats, region, engine="optimize", *, seed=1, refine=0, baselines=None, **params) -> Measure:
    res = synthesize(ex, region, engine, seed=seed, stats=stats, params=params, refine=refine)
    if baselines is None:
        baselines = tuple(distance(ex, stats, region, synthesize(ex, region, b, seed=seed, stats=stats).arrangement)
                          for b in ("tile", "random"))  # fmt: skip
    e = distance(ex, stats, region, res.arrangement)
    s = score(ex, stats, res.arrangement, region)
    return Measure(likeness(e, *baselines), s.repetition, s.overlaps_total, s.violators_total, s.density_ratio, e,
                   s.kind_mix_tv)  # fmt: skip
