"""Likeness that sees order: the neighbourhood distance of a texture between two baselines.

The neighbourhood distance ``E`` of Ma, Wei & Tong 2011 (§3.2, eq. 1;
:func:`svgtile.analysis.neighbourhood.neighbourhood_distance`) compares each texture motif's
neighbours — where they are and of which kind — with the most similar neighbourhood of the
exemplar.  Its value alone is hard to read (squared spacings; a jittered exemplar is not a
lattice), so it is placed between two textures made from the same exemplar::

    L = (E_random − E) / (E_random − E_tile)

``E_tile`` is the distance of copies stamped side by side (the ``tile`` engine), ``E_random``
that of darts thrown with the exemplar's density, kind mix and distance rule (the ``random``
engine).  L = 1 is as faithful to the exemplar's order as stamping copies, 0 no better than
dart throwing.  Both baselines are synthesized once per exemplar and process, on a square of
:func:`baseline_region` (a fixed number of exemplar widths), with :data:`BASELINE_SEED`.

How the figure is measured, and why:

* centres — the texture's motifs in the interior (:func:`svgtile.metrics.window.interior`),
  :data:`SAMPLE` of them drawn with a generator seeded by :data:`SAMPLE_SEED`; their neighbours
  are drawn from the whole texture, so a centre near the interior's edge still has all its
  neighbours;
* scale — positions in the exemplar's mean spacing (:func:`svgtile.metrics.window.spacing`);
  an imported tile's neighbourhoods wrap across its edges (``exemplar.period``);
* turns — the neighbourhood may turn (:func:`turns_allowed`) when the exemplar's motifs show
  every orientation: gravel or breccia is alike whichever way it is turned, rows are not;
* α — :data:`ALPHA` = 1, a wrong kind as costly as a neighbour one spacing off: how far apart
  the baselines lie hardly depends on α (measured on the bundled exemplars and imported tiles
  of each data set, ``benchmarks/choose_alpha.py``; benchmarks/README.md, "Choosing α").

References
----------
Ma, Wei & Tong 2011, Discrete element textures, §3.2 Neighborhood Metric (../shared/papers/).
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import numpy as np

from svgtile.analysis.neighbourhood import likeness, neighbourhood_distance
from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.errors import SvgtileError
from svgtile.metrics.window import exemplar_size, finite_or_none, in_window, interior, spacing

#: Neighbours per neighbourhood (Ma, Wei & Tong use the neighbours within a radius; six is the
#: first ring of a hexagonal packing).
K = 6
#: Cost of a kind mismatch, squared spacings: a neighbour of the wrong kind costs as much as
#: one displaced by √α spacings (module docstring: how it was chosen).
ALPHA = 1.0
#: Texture motifs measured.  The sample's error is small against what L tells apart: on the
#: 177k-motif gravel texture of benchmarks/README.md, L's standard deviation over 20 sample
#: seeds is 0.027 (0.020 with 1000 motifs, at twice the cost).
SAMPLE = 500
#: Seed of the sample's generator: the same texture gives the same figure.
SAMPLE_SEED = 0x5C0E
#: Seed of the baseline textures.
BASELINE_SEED = 1
#: The baselines fill a square this many exemplar widths on a side …
BASELINE_WIDTHS = 3
#: … or larger, so that its interior holds about this many motifs.
BASELINE_MOTIFS = 600
#: A kind "shows every orientation" when its exemplar arc is at least this wide, degrees: the
#: arc of a few dozen uniform angles falls short of 360° by their largest gap.
FULL_ARC = 180.0


@dataclass(frozen=True)
class Likeness:
    """The neighbourhood distance of a texture, of the two baselines, and where it lies between.

    Attributes
    ----------
    distance : float or None
        ``E`` of the texture, squared exemplar spacings; 0 is the exemplar's own order.
    tile : float or None
        ``E_tile``: the same for the ``tile`` engine on :func:`baseline_region`.
    random : float or None
        ``E_random``: the same for the ``random`` engine there.
    likeness : float or None
        ``L = (E_random − E) / (E_random − E_tile)``: 1 as faithful as stamping copies, 0 no
        better than dart throwing; None when a distance is undefined or ``E_random ≤ E_tile``.
    """

    distance: float | None
    tile: float | None
    random: float | None
    likeness: float | None


def turns_allowed(stats: Stats) -> bool:
    """Whether neighbourhoods may turn: every kind shows every orientation (arc ≥ :data:`FULL_ARC`)."""
    return bool(len(stats.arc_width)) and bool((stats.arc_width >= FULL_ARC).all())


def texture_distance(
    exemplar: Exemplar, stats: Stats, arrangement: Arrangement, inside: np.ndarray
) -> float:
    """``E`` of a texture: Ma, Wei & Tong 2011 §3.2 eq. (1), measured as the module says.

    Parameters
    ----------
    exemplar, stats : the exemplar and its analysis
    arrangement : the texture, n motifs, user units
    inside : (n,) bool, the motifs that may be centres (those in the interior)

    Returns
    -------
    float, squared spacings; NaN without centres, or when the exemplar has no neighbourhood of
    :data:`K` neighbours to compare with (K motifs or fewer, and not a repeating tile).
    """
    s = spacing(stats)
    centres = np.flatnonzero(inside)
    too_few = len(exemplar.motifs) <= K and exemplar.period is None
    if not math.isfinite(s) or len(centres) == 0 or len(exemplar.motifs) == 0 or too_few:
        return math.nan
    ex = exemplar.motifs
    return neighbourhood_distance(
        arrangement.xy, arrangement.kind, ex.xy, ex.kind, spacing=s, k=K, alpha=ALPHA,
        period=exemplar.period, rotate=turns_allowed(stats), centres=centres, sample=SAMPLE,
        rng=np.random.default_rng(SAMPLE_SEED),
    )  # fmt: skip


def baseline_region(exemplar: Exemplar, stats: Stats) -> Region:
    """The square the baselines fill: :data:`BASELINE_WIDTHS` exemplar widths, or enough that
    its interior (one width in from each edge) holds :data:`BASELINE_MOTIFS` motifs."""
    width = max(exemplar_size(exemplar))
    side = BASELINE_WIDTHS * width
    if stats.count_density > 0:
        side = max(side, math.sqrt(BASELINE_MOTIFS / stats.count_density) + 2 * width)
    return Region.rectangle(side, side)


_BASELINES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def baseline_distances(exemplar: Exemplar, stats: Stats) -> tuple[float, float]:
    """``(E_tile, E_random)`` of the exemplar, computed once per exemplar object and process."""
    known = _BASELINES.get(exemplar)
    if known is None or known[0] is not stats:
        region = baseline_region(exemplar, stats)
        window = interior(exemplar, region)
        found = []
        for engine in ("tile", "random"):
            try:
                arr = synthesize(exemplar, region, engine, seed=BASELINE_SEED, stats=stats).arrangement
            except SvgtileError:  # no baseline, no L; the texture's own figures still stand
                found.append(math.nan)
                continue
            found.append(texture_distance(exemplar, stats, arr, in_window(arr, window)))
        known = (stats, (found[0], found[1]))
        _BASELINES[exemplar] = known
    return known[1]


def measure(
    exemplar: Exemplar, stats: Stats, arrangement: Arrangement, inside: np.ndarray, *,
    baselines: tuple[float, float] | None = None,
) -> Likeness:  # fmt: skip
    """:class:`Likeness` of a texture whose motifs in its interior are ``inside`` ((n,) bool);
    ``baselines``: :func:`baseline_distances` of the exemplar, if already known."""
    e = texture_distance(exemplar, stats, arrangement, inside)
    e_tile, e_random = baselines if baselines is not None else baseline_distances(exemplar, stats)
    # baselines that do not tell order from disorder leave L undefined, not wild
    apart = e_random > e_tile
    return Likeness(
        distance=finite_or_none(e),
        tile=finite_or_none(e_tile),
        random=finite_or_none(e_random),
        likeness=finite_or_none(likeness(e, e_tile, e_random)) if apart else None,
    )
