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

A large texture (more than :data:`~svgtile.metrics.window.SAMPLE_ABOVE` motifs in its window)
has its *structure* figures — :data:`SAMPLED`: nearest gaps and pair correlation, which need
every motif's footprint and k-d trees of every motif of each kind — measured on the motifs of a
few sample windows spread over the window (:func:`~svgtile.metrics.window.sample_windows`).
Every other figure stays exact over every motif: the counts a user relies on as guarantees
(overlaps, violators, motifs), the amounts (density, kind mix, orientation), and the figures
that already measure a fixed sample of the whole window (repetition, the neighbourhood
distance and L: bit for bit what ``exact=True`` gives).  The largest empty disc, a maximum a
sample would miss, is searched over the whole window on a raster twice as coarse, refined once
more: the same guarantee (:func:`~svgtile.metrics.coverage.largest_empty_disc`: a lower bound
within ``step / 4**levels / √2``, now half as large), more centres measured exactly.  How far
the sampled figures lie from the exact ones on large textures of the bundled exemplars is
:data:`SAMPLE_BOUND` (benchmarks/README.md, "`svgtile score` on sample windows").

``score(…, exact=True)`` (``svgtile score --exact``) measures everything on every motif.

``score(…, pool=…)`` measures the figures that look at footprints (conflicts, empty discs) in
an executor's worker while it measures the others; ``svgtile score`` hands it a forked worker
process, which has scanned part of the texture's ``<use>`` lines
(:func:`svgtile.svg.texture.start_reading`) and measures the baselines (``baselines=`` a future)
while this process scans the rest and measures the first figures.  Each
figure is the same function of the same inputs either way, so the score is the same bit for bit.

References
----------
AlMeraj, Kaplan & Asente 2013, Patch-based geometric texture synthesis (../shared/papers/).
"""

from __future__ import annotations

import dataclasses
import math
from concurrent.futures import Executor, Future
from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.analysis.stats import Stats
from svgtile.analysis.window import measured_window
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import world_footprints
from svgtile.core.region import Region
from svgtile.core.worker import worker_result, worker_submit
from svgtile.metrics import window as _window
from svgtile.metrics.amounts import density, kind_mix_noise, kind_mix_tv, window_densities
from svgtile.metrics.coverage import (
    COVER_LEVELS,
    COVER_STEP,
    Footprints,
    exemplar_empty_disc,
    largest_empty_disc,
)
from svgtile.metrics.likeness import measure as measure_likeness
from svgtile.metrics.pattern import KindPair, kind_trees, repetition, structure
from svgtile.metrics.rules import Conflicts, conflict_counts, orientation_outside
from svgtile.metrics.window import (
    SAMPLE_HALO,
    Sample,
    finite_or_none,
    in_window,
    sample_windows,
    spacing,
)

#: The documented bound of ``|sampled − exact|`` for a large texture (the empty disc's radius:
#: relative to the exact one): the largest deviations measured
#: (``benchmarks/score_sample_deviation.py``, patch textures of about 115,000 motifs of the six
#: bundled exemplars, seeds 1 and 2 (marsh: 1), and the 163,356 interior motifs of benchmarks/README.md's
#: 3000² gravel texture; samples of about 20,000) were 0.016, 0.002, 0.008 and 0.32 %, rounded
#: up.  A sample of m motifs deviates about √(SAMPLE_MOTIFS / m) times as much (the test's).
SAMPLE_BOUND = {
    "gap_distance": 0.02,
    "gap_noise": 0.005,
    "pair_correlation_distance": 0.01,
    "empty_disc_radius": 0.005,
}

#: The figures a large texture has measured on its sample windows (:class:`Score`'s fields).
SAMPLED = ("gap_distance", "gap_noise", "pair_correlation_distance", "kind_pairs")


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
        Total variation distance ``½ Σ_c |f'_c − f_c|`` of the frequencies of the kinds' shape
        classes in ``I`` (:attr:`~svgtile.analysis.stats.Stats.classes`: kinds drawn a few times
        each are counted with the rare kinds of like shape, issue 12.3; every other kind is its
        own class), in [0, 1]; 0 is right, 1 if ``I`` holds no motif.
    kind_mix_tv_kinds : float or None
        The same per kind, each one-off fragment on its own; None when no kinds are pooled
        (then it equals ``kind_mix_tv``).
    kind_mix_noise : float or None
        What ``kind_mix_tv_kinds`` is on average for a fair draw of ``motifs`` motifs from the
        exemplar's exact mix (:func:`~svgtile.metrics.amounts.kind_mix_noise`); a per-kind TV
        near it is chance, not a skew.  None when no kinds are pooled.
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
        Excess of motifs repeated at one of the texture's most common displacements over what
        the exemplar itself shows there (or chance, if more), in [0, 1]: ≈ 1 for a tiling of
        irregular content, ≈ 0 for random placement, a faithful texture of a lattice or of
        rows, or the exemplar itself; lower is better.
    repetition_raw : float or None
        The texture's share of motifs repeated at that displacement.
    repetition_vector : (float, float) or None
        That displacement, user units.
    repetition_exemplar : float or None
        The exemplar's own share there (0: the exemplar cannot show that displacement).
    repetition_order : float or None
        Excess over chance at the single most common displacement the exemplar's exact order
        does not explain (``repetition`` before issue 13, blind to what the exemplar shows).
    repetition_order_vector : (float, float) or None
        Its displacement, user units.
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
        The same for the exemplar: centred in and inside its input region; for a repeating tile,
        centred in the tile and measured across its edges, among the copies around it
        (:func:`~svgtile.metrics.coverage.exemplar_empty_disc`), user units.
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
    sample : Sample or None
        Where the figures :data:`SAMPLED` were measured when the texture is large; None when
        every figure was measured on every motif.  In the JSON (``"sampled"``, after
        ``motifs``) only when not None.
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
    kind_mix_tv_kinds: float | None
    kind_mix_noise: float | None
    orientation_outside: float | None
    gap_distance: float | None
    gap_noise: float | None
    pair_correlation_distance: float | None
    kind_pairs: tuple[KindPair, ...]
    repetition: float | None
    repetition_raw: float | None
    repetition_vector: tuple[float, float] | None
    repetition_exemplar: float | None
    repetition_order: float | None
    repetition_order_vector: tuple[float, float] | None
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
    sample: Sample | None = None

    def to_dict(self) -> dict:
        """The figures as plain JSON-able data: a dict in field order, tuples as lists; the
        sample, if any, as ``"sampled"`` after ``"motifs"`` with the figures it measured."""
        out = _plain(self)
        sample = out.pop("sample")
        if sample is None:
            return out
        keys = list(out)
        at = keys.index("motifs") + 1
        sample["figures"] = list(SAMPLED)
        return {**{k: out[k] for k in keys[:at]}, "sampled": sample, **{k: out[k] for k in keys[at:]}}


def _plain(value):
    if dataclasses.is_dataclass(value):
        return {f.name: _plain(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, tuple | list):
        return [_plain(v) for v in value]
    return value


def score(
    exemplar: Exemplar, stats: Stats, arrangement: Arrangement, region: Region, *, exact: bool = False,
    sample_above: int | None = None, sample_motifs: int | None = None, pool: Executor | None = None,
    baselines: tuple[float, float] | Future | None = None,
) -> Score:  # fmt: skip
    """All figures of a texture against its exemplar.

    Parameters
    ----------
    exemplar : the parsed exemplar
    stats : its analysis
    arrangement : the texture, n motifs, user units
    region : the output region the texture fills
    exact : measure every figure on every motif, however large the texture
    sample_above, sample_motifs : a texture with more than ``sample_above`` motifs in its window
        (default :data:`~svgtile.metrics.window.SAMPLE_ABOVE`) has the figures :data:`SAMPLED`
        measured on sample windows holding about ``sample_motifs`` motifs (default
        :data:`~svgtile.metrics.window.SAMPLE_MOTIFS`; :func:`~svgtile.metrics.window.sample_windows`)
    pool : an executor (``svgtile score``: one worker process) to measure the figures of
        :func:`_footprint_figures` in — the conflicts and the empty discs — while this thread
        measures the others; None: all here.  The figures are the same.
    baselines : ``(E_tile, E_random)`` if already known (:func:`~svgtile.metrics.likeness.baseline_distances`),
        or a future of them (``pool``'s), waited for where they are needed, after the structure
        and repetition figures (measured here if its worker died)

    Returns
    -------
    Score
    """
    arr = arrangement
    protos = exemplar.prototypes
    window, kind_of_window = measured_window(exemplar, region)
    inside = in_window(arr, window)
    plan = None if exact else sample_windows(
        window, arr.xy, inside, above=sample_above if sample_above is not None else _window.SAMPLE_ABOVE,
        motifs=sample_motifs if sample_motifs is not None else _window.SAMPLE_MOTIFS,
    )  # fmt: skip
    step = COVER_STEP * spacing(stats) if stats.count_density > 0 else None
    sampled = plan is not None
    geoms = None if sampled or pool is not None else world_footprints(arr, protos)
    apart = (exemplar, stats, arr, window, region.shape, inside, step, sampled)
    far = worker_submit(pool, _footprint_figures, *apart)
    trees = kind_trees(arr, len(protos))
    if not sampled:
        found = structure(exemplar, stats, arr, window, geoms=geoms, inside=inside, trees=trees)
        sample = None
    else:
        boxes, sample = plan
        sub = arr.take(_near_boxes(arr, boxes, SAMPLE_HALO * _rarest_spacing(stats)))
        found = structure(exemplar, stats, sub, boxes, inside=in_window(sub, boxes), trees=kind_trees(sub, len(protos)))
    rep = repetition(arr, exemplar, stats, window, inside=inside, trees=trees, room=region.shape)
    if isinstance(baselines, Future):
        baselines = worker_result(baselines)
    order = measure_likeness(exemplar, stats, arr, inside, baselines=baselines)
    density_ratio = (
        finite_or_none(density(arr, exemplar, window, inside=inside) / stats.density) if stats.density > 0 else None
    )
    windows = window_densities(arr, exemplar, window)
    mean = float(windows.mean()) if len(windows) else 0.0
    ratio = windows / stats.density if stats.density > 0 and len(windows) else None
    conflicts, r_tex, r_ex = worker_result(far) or _footprint_figures(*apart, geoms=geoms)
    motifs = int(inside.sum())
    # per kind only where rare kinds are pooled into classes; the two readings agree otherwise
    pooled = len(np.unique(stats.kind_classes)) < len(stats.frequency)
    return Score(
        window=kind_of_window,
        window_area=float(window.area),
        motifs=motifs,
        spacing=finite_or_none(spacing(stats)),
        **dataclasses.asdict(conflicts),
        density_ratio=density_ratio,
        density_windows=len(windows),
        density_cv=finite_or_none(float(windows.std()) / mean) if len(windows) >= 2 and mean > 0 else None,
        density_min_ratio=finite_or_none(float(ratio.min())) if ratio is not None else None,
        density_max_ratio=finite_or_none(float(ratio.max())) if ratio is not None else None,
        kind_mix_tv=kind_mix_tv(arr, stats, window, inside=inside),
        kind_mix_tv_kinds=kind_mix_tv(arr, stats, window, inside=inside, classes=False) if pooled else None,
        kind_mix_noise=kind_mix_noise(motifs, stats.frequency) if pooled else None,
        orientation_outside=finite_or_none(orientation_outside(arr, stats, window, inside=inside)),
        gap_distance=found.gap_distance,
        gap_noise=found.gap_noise,
        pair_correlation_distance=found.pair_correlation_distance,
        kind_pairs=found.kind_pairs,
        repetition=rep.repetition,
        repetition_raw=rep.repetition_raw,
        repetition_vector=rep.repetition_vector,
        repetition_exemplar=rep.repetition_exemplar,
        repetition_order=rep.repetition_order,
        repetition_order_vector=rep.repetition_order_vector,
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
        sample=sample,
    )


def _footprint_figures(
    exemplar: Exemplar, stats: Stats, arr: Arrangement, window: shapely.Geometry, shape: shapely.Geometry,
    inside: np.ndarray, step: float | None, sampled: bool, *, geoms: np.ndarray | None = None,
) -> tuple[Conflicts, float, float]:  # fmt: skip
    """The figures :func:`score` may measure in another process: the conflicts and the largest
    empty discs of the texture and of the exemplar, which look at the motifs' footprints (about
    half of the figures' work; the other figures need neither).

    ``window`` is the measuring window, ``shape`` the region's, ``inside`` (n,) bool the motifs
    in the window, ``step`` the empty disc's raster step (user units), ``sampled`` whether the
    texture is large enough to be sampled (then footprints are built only where a figure looks,
    :class:`~svgtile.metrics.coverage.Footprints`, and the disc is searched on a raster twice as
    coarse), ``geoms`` every motif's footprint if already built.
    """
    protos = exemplar.prototypes
    if sampled:
        # footprints built only for the pairs the k-d tree bounds of the conflict search leave
        # open and for the motifs near the empty disc's candidate centres
        geoms = Footprints(arr, protos)
        disc = {"step": 2 * step if step is not None else None, "geoms": geoms, "levels": COVER_LEVELS + 1}
    else:
        geoms = world_footprints(arr, protos) if geoms is None else geoms
        disc = {"step": step, "geoms": geoms}
    conflicts = conflict_counts(arr, protos, stats, inside, geoms)
    r_tex, _ = largest_empty_disc(arr, protos, window, shape, **disc)
    r_ex = exemplar_empty_disc(exemplar, step=step)
    return conflicts, r_tex, r_ex


def _rarest_spacing(stats: Stats) -> float:
    """Mean spacing ``1 / sqrt(f_i λ)`` of the exemplar's rarest kind, user units."""
    lam = float(stats.frequency[stats.frequency > 0].min()) * stats.count_density
    return 1.0 / math.sqrt(lam) if lam > 0 else 0.0


def _near_boxes(arr: Arrangement, boxes: shapely.Geometry, halo: float) -> np.ndarray:
    """(m,) int: the motifs centred within ``halo`` of the sample windows (rectangles), and in them."""
    bounds = shapely.bounds(shapely.get_parts(boxes))
    x, y = arr.xy[:, 0, None], arr.xy[:, 1, None]
    near = (x >= bounds[:, 0] - halo) & (x <= bounds[:, 2] + halo) & (y >= bounds[:, 1] - halo) & (y <= bounds[:, 3] + halo)
    return np.flatnonzero(near.any(axis=1))
