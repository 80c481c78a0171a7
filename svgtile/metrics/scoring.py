"""The score: every figure of a texture against its exemplar, as one typed record.

almeraj2013 §4 notes that the field lacks "clear notions of similarity … for geometric
arrangements"; :func:`score` gathers the figures svgtile uses instead, each defined in the
docstring of the function that computes it, in the module named after what it measures:

* conflicts — overlapping pairs and distance-rule violators (:mod:`svgtile.metrics.rules`);
* density and kind mix — the covered fraction against ρ, globally and over windows, and the
  total variation distance of the kind frequencies (:mod:`svgtile.metrics.amounts`);
* orientation — motifs outside their kind's arc (:mod:`svgtile.metrics.rules`);
* structure and repetition — nearest footprint gaps and pair correlation per kind pair, and how
  strongly the arrangement repeats itself (:mod:`svgtile.metrics.pattern`);
* coverage — the largest hole against the exemplar's (:mod:`svgtile.metrics.coverage`);
* likeness — the neighbourhood distance of Ma, Wei & Tong 2011 (§3.2, eq. 1) of the texture
  and of two baselines, and where the texture lies between them (:mod:`svgtile.metrics.likeness`).

Where and at what scale they are measured (the interior, the mean spacing, the sample of a
large texture) is :mod:`svgtile.metrics.window`.

References
----------
AlMeraj, Kaplan & Asente 2013, Patch-based geometric texture synthesis (../shared/papers/).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import world_footprints
from svgtile.core.region import Region
from svgtile.metrics.amounts import density, kind_mix_tv, window_densities
from svgtile.metrics.coverage import COVER_STEP, largest_empty_disc
from svgtile.metrics.likeness import measure as measure_likeness
from svgtile.metrics.pattern import KindPair, kind_trees, repetition, structure
from svgtile.metrics.rules import conflict_counts, orientation_outside
from svgtile.metrics.window import finite_or_none, in_window, interior, spacing


@dataclass(frozen=True)
class Score:
    """Every figure of a texture against its exemplar (:func:`score`).

    Figures are measured on the window ``I`` — the texture's interior, or the whole region when
    it has none — unless said otherwise.  ``s`` is the exemplar's mean spacing, ρ its density.
    Undefined figures are None.  The field order is the order of ``svgtile score --json``.

    Attributes
    ----------
    window : str
        ``"interior"``, or ``"region"`` when the region is too small to have an interior.
    window_area : float
        Area of ``I``, square user units.
    motifs : int
        Motifs whose centroid lies in ``I``.
    spacing : float or None
        ``s``, user units.
    overlaps : int
        Pairs of motifs whose footprints share area (touching does not count), at least one of
        them in ``I``; 0 is right.
    violators : int
        Motifs in ``I`` with a neighbour (anywhere) whose footprint is closer than ``d_ij``
        (almeraj2013 §3.1); 0 is right.
    violator_fraction : float or None
        ``violators / motifs``; 0 is right.
    overlaps_total : int
        ``overlaps`` over the whole texture.
    violators_total : int
        ``violators`` over the whole texture.
    density_ratio : float or None
        Covered fraction of ``I`` over ρ, dimensionless; 1 is right.
    density_windows : int
        Exemplar-sized windows the density is compared over.
    density_cv : float or None
        Coefficient of variation ``std(D_w) / mean(D_w)`` of the window densities (None with
        fewer than 2 windows); 0 is even.
    density_min_ratio : float or None
        ``min_w D_w / ρ``; 1 is right, near 0 is a sparse window.
    density_max_ratio : float or None
        ``max_w D_w / ρ``; 1 is right, well above it is a crowded window.
    kind_mix_tv : float
        Total variation distance ``½ Σ_i |f'_i − f_i|`` of the kind frequencies in ``I``, in
        [0, 1]; 0 is right, 1 if ``I`` holds no motif.
    orientation_outside : float or None
        Fraction of the motifs in ``I`` whose orientation lies outside their kind's exemplar
        arc; 0 is right.
    gap_distance : float or None
        Nearest-gap distance, dimensionless; 0 is the exemplar's structure, lower is better.
    gap_noise : float or None
        What ``gap_distance`` would be on average if the exemplar's gaps were a sample of the
        texture's own: a ``gap_distance`` near it cannot be told from the exemplar's structure.
    pair_correlation_distance : float or None
        Pair-correlation distance, dimensionless; 0 is the exemplar's structure, lower is better.
    kind_pairs : tuple of KindPair
        Per ordered kind pair, the details of the structure figures.
    repetition : float or None
        Excess over chance of motifs repeated at the most common displacement the exemplar's
        order does not explain, in [0, 1]: ≈ 1 for a tiling of irregular content, ≈ 0 for
        random placement or a faithful texture of a lattice; lower is better.
    repetition_raw : float or None
        ``repetition`` without the chance correction.
    repetition_vector : (float, float) or None
        That displacement, user units.
    repetition_total : float or None
        The same over every displacement, the exemplar's own lattice included (``repetition``
        before issue 12): ≈ 1 for any texture of a lattice.
    repetition_total_vector : (float, float) or None
        Its displacement, user units.
    repetition_order_steps : tuple of (float, float)
        The exemplar's steps whose lattice ``repetition`` leaves out, user units (empty: none).
    empty_disc_radius : float
        Radius of the largest disc centred in ``I``, inside the region, that meets no
        footprint, user units.
    exemplar_empty_disc_radius : float
        The same for the exemplar: centred in and inside its input region, user units.
    coverage : float or None
        ``empty_disc_radius / exemplar_empty_disc_radius``: ≈ 1 or below is as well covered as
        the exemplar, ≫ 1 is a hole; lower is better.
    neighbourhood_distance : float or None
        ``E``: mean distance of the neighbourhoods of (a sample of) the motifs in ``I`` to their
        most similar exemplar neighbourhood (ma2011 §3.2 eq. 1), squared spacings; 0 is the
        exemplar's own order, lower is better.
    neighbourhood_tile : float or None
        ``E_tile``: the same for the ``tile`` engine's texture of the exemplar (the baseline of
        :mod:`svgtile.metrics.likeness`, on a fixed region, not this texture's).
    neighbourhood_random : float or None
        ``E_random``: the same for the ``random`` engine's.
    likeness : float or None
        ``L = (E_random − E) / (E_random − E_tile)``: 1 keeps the exemplar's order as well as
        stamping copies, 0 no better than dart throwing; higher is better.
    """

    window: str
    window_area: float
    motifs: int
    spacing: float | None
    overlaps: int
    violators: int
    violator_fraction: float | None
    overlaps_total: int
    violators_total: int
    density_ratio: float | None
    density_windows: int
    density_cv: float | None
    density_min_ratio: float | None
    density_max_ratio: float | None
    kind_mix_tv: float
    orientation_outside: float | None
    gap_distance: float | None
    gap_noise: float | None
    pair_correlation_distance: float | None
    kind_pairs: tuple[KindPair, ...]
    repetition: float | None
    repetition_raw: float | None
    repetition_vector: tuple[float, float] | None
    repetition_total: float | None
    repetition_total_vector: tuple[float, float] | None
    repetition_order_steps: tuple[tuple[float, float], ...]
    empty_disc_radius: float
    exemplar_empty_disc_radius: float
    coverage: float | None
    neighbourhood_distance: float | None
    neighbourhood_tile: float | None
    neighbourhood_random: float | None
    likeness: float | None

    def to_dict(self) -> dict:
        """The figures as plain JSON-able data: a dict in field order, tuples as lists."""
        return _plain(self)


def _plain(value):
    if dataclasses.is_dataclass(value):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    return value


def score(exemplar: Exemplar, stats: Stats, arrangement: Arrangement, region: Region) -> Score:
    """All figures of a texture against its exemplar.

    Parameters
    ----------
    exemplar : the parsed exemplar
    stats : its analysis
    arrangement : the texture, n motifs, user units
    region : the output region the texture fills

    Returns
    -------
    Score
    """
    arr = arrangement
    protos = exemplar.prototypes
    window = interior(exemplar, region)
    kind_of_window = "interior"
    if window.is_empty or window.area <= 0:
        window, kind_of_window = region.shape, "region"
    inside = in_window(arr, window)
    geoms = world_footprints(arr, protos)
    conflicts = conflict_counts(arr, protos, stats, inside, geoms)

    density_ratio = (
        finite_or_none(density(arr, exemplar, window, inside=inside) / stats.density) if stats.density > 0 else None
    )
    windows = window_densities(arr, exemplar, window)
    mean = float(windows.mean()) if len(windows) else 0.0
    ratio = windows / stats.density if stats.density > 0 and len(windows) else None
    trees = kind_trees(arr, len(protos))
    found = structure(exemplar, stats, arr, window, geoms=geoms, inside=inside, trees=trees)
    rep = repetition(arr, exemplar, stats, window, inside=inside, trees=trees)

    step = COVER_STEP * spacing(stats) if stats.count_density > 0 else None
    r_tex, _ = largest_empty_disc(arr, protos, window, region.shape, step=step, geoms=geoms)
    r_ex, _ = largest_empty_disc(exemplar.motifs, protos, exemplar.region, exemplar.region, step=step)
    order = measure_likeness(exemplar, stats, arr, inside)
    return Score(
        window=kind_of_window,
        window_area=float(window.area),
        motifs=int(inside.sum()),
        spacing=finite_or_none(spacing(stats)),
        **dataclasses.asdict(conflicts),
        density_ratio=density_ratio,
        density_windows=len(windows),
        density_cv=finite_or_none(float(windows.std()) / mean) if len(windows) >= 2 and mean > 0 else None,
        density_min_ratio=finite_or_none(float(ratio.min())) if ratio is not None else None,
        density_max_ratio=finite_or_none(float(ratio.max())) if ratio is not None else None,
        kind_mix_tv=kind_mix_tv(arr, stats, window, inside=inside),
        orientation_outside=finite_or_none(orientation_outside(arr, stats, window, inside=inside)),
        gap_distance=found.gap_distance,
        gap_noise=found.gap_noise,
        pair_correlation_distance=found.pair_correlation_distance,
        kind_pairs=found.kind_pairs,
        repetition=rep.repetition,
        repetition_raw=rep.repetition_raw,
        repetition_vector=rep.repetition_vector,
        repetition_total=rep.repetition_total,
        repetition_total_vector=rep.repetition_total_vector,
        repetition_order_steps=rep.order_steps,
        empty_disc_radius=r_tex,
        exemplar_empty_disc_radius=r_ex,
        coverage=finite_or_none(r_tex / r_ex) if r_ex > 0 else None,
        neighbourhood_distance=order.distance,
        neighbourhood_tile=order.tile,
        neighbourhood_random=order.random,
        likeness=order.likeness,
    )
