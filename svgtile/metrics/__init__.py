"""Likeness figures: how well a texture reproduces its exemplar.

:func:`score` measures them all and returns a :class:`Score`, one typed field per figure (its
unit and which way is good in the class docstring; :meth:`Score.to_dict` is the JSON of
``svgtile score --json``).  The figures, by what they measure:

* :mod:`~svgtile.metrics.window` — where and at what scale: the interior, the mean spacing,
  the sample of a large texture;
* :mod:`~svgtile.metrics.rules` — overlaps, distance-rule violators, orientation arcs;
* :mod:`~svgtile.metrics.amounts` — density, globally and per window, and the kind mix;
* :mod:`~svgtile.metrics.pattern` — nearest gaps, pair correlation;
* :mod:`~svgtile.metrics.repeats` — repetition beyond what the exemplar shows inside itself,
  and :mod:`~svgtile.metrics.shown` what the exemplar shows at a displacement;
* :mod:`~svgtile.metrics.order` — the displacements the exemplar's own lattice explains, which
  repetition leaves out;
* :mod:`~svgtile.metrics.coverage` — the largest empty disc;
* :mod:`~svgtile.metrics.likeness` — the neighbourhood distance of Ma, Wei & Tong 2011
  (:mod:`svgtile.analysis.neighbourhood`) of the texture and of the ``tile`` and ``random``
  baselines, and :func:`likeness` between them;
* :mod:`~svgtile.metrics.scoring` — :class:`Score` and :func:`score`.
"""

from __future__ import annotations

from svgtile.analysis.neighbourhood import likeness, neighbourhood_distance, neighbourhoods
from svgtile.metrics.amounts import density, kind_mix_noise, kind_mix_tv, window_densities
from svgtile.metrics.coverage import exemplar_empty_disc, largest_empty_disc
from svgtile.metrics.likeness import Likeness, baseline_distances, texture_distance, turns_allowed
from svgtile.metrics.pattern import (
    KindPair,
    Repetition,
    Structure,
    pair_correlation,
    repetition,
    sampling_noise,
    structure,
    wasserstein,
)
from svgtile.metrics.rules import Conflicts, conflict_counts, orientation_outside
from svgtile.metrics.scoring import Score, score
from svgtile.metrics.window import Sample, interior, motif_sample, sample_windows, spacing

__all__ = [
    "Conflicts",
    "KindPair",
    "Likeness",
    "Repetition",
    "Sample",
    "Score",
    "Structure",
    "baseline_distances",
    "conflict_counts",
    "density",
    "exemplar_empty_disc",
    "interior",
    "kind_mix_noise",
    "kind_mix_tv",
    "largest_empty_disc",
    "likeness",
    "motif_sample",
    "neighbourhood_distance",
    "neighbourhoods",
    "orientation_outside",
    "pair_correlation",
    "repetition",
    "sample_windows",
    "sampling_noise",
    "score",
    "spacing",
    "structure",
    "texture_distance",
    "turns_allowed",
    "wasserstein",
    "window_densities",
]
