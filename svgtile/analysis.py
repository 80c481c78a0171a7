"""What synthesis must reproduce: distance matrix, density, orientation arcs, kind frequencies.

Implements the exemplar analysis of almeraj2013: the minimum-distance matrix ``d_ij`` of §3.1, the
density ρ of §3.4 and the smallest orientation arc per kind of §3.5.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from .arrangement import Arrangement
from .exemplar import Exemplar
from .footprint import Prototype, motif_radius, near_pairs, overlapping, world_footprints


@dataclass(frozen=True, eq=False)
class Stats:
    """Exemplar statistics.

    Attributes
    ----------
    distance : (k, k) float array, user units
        ``d_ij``: the smallest footprint distance between an instance of kind i and one of kind j.
    measured : (k, k) bool array
        False where the exemplar has no such pair and ``distance`` holds the fallback
        (see :func:`distance_matrix`).
    density : float
        ρ, the fraction of the input region covered by motif footprints (area sum / region area).
    count_density : float
        Motifs per square user unit in the input region.
    arc_start, arc_width : (k,) float arrays, degrees
        Each kind's smallest arc of orientations ``[start, start + width]`` (§3.5).
    frequency : (k,) float array
        Fraction of the motifs that are of each kind.
    overlaps : int
        Pairs of exemplar motifs whose footprints share area (the paper assumes none).
    """

    distance: np.ndarray
    measured: np.ndarray
    density: float
    count_density: float
    arc_start: np.ndarray
    arc_width: np.ndarray
    frequency: np.ndarray
    overlaps: int


def analyze(exemplar: Exemplar) -> Stats:
    """Compute :class:`Stats` for an exemplar."""
    motifs, protos = exemplar.motifs, exemplar.prototypes
    k = len(protos)
    distance, measured, overlaps = distance_matrix(motifs, protos)
    area = footprint_areas(motifs, protos)
    region_area = exemplar.region.area
    start, width = orientation_arcs(motifs.angle, motifs.kind, k)
    counts = np.bincount(motifs.kind, minlength=k)
    return Stats(
        distance=distance,
        measured=measured,
        density=float(area.sum() / region_area),
        count_density=len(motifs) / region_area,
        arc_start=start,
        arc_width=width,
        frequency=counts / counts.sum(),
        overlaps=overlaps,
    )


def footprint_areas(arr: Arrangement, protos: list[Prototype]) -> np.ndarray:
    """(n,) footprint area of each motif, square user units."""
    return np.array([p.area for p in protos])[arr.kind] * arr.scale**2


def distance_matrix(arr: Arrangement, protos: list[Prototype]) -> tuple[np.ndarray, np.ndarray, int]:
    """The symmetric matrix ``d_ij`` of almeraj2013 §3.1, exactly.

    ``d_ij`` is the minimum footprint distance over all pairs of an instance of kind i and a
    different instance of kind j.  Candidate pairs come from :func:`near_pairs` with a reach that
    doubles until every kind pair that has instances found a pair within it; a pair found within
    the reach is the true minimum, since every closer pair passes the bounding-disc filter.

    A kind pair the exemplar cannot measure (a kind with one instance has no i–i pair) falls back
    to the smaller of the two kinds' smallest measured distances to any kind, and to 0 when
    nothing was measured at all: the rule then never forbids what the exemplar shows elsewhere.

    Returns
    -------
    distance : (k, k) float array
    measured : (k, k) bool array
    overlaps : int, number of pairs whose footprints share area.
    """
    k = len(protos)
    geoms = world_footprints(arr, protos)
    radius = motif_radius(arr, protos)
    counts = np.bincount(arr.kind, minlength=k)
    possible = np.outer(counts, counts) - np.diag(counts) > 0
    distance = np.full((k, k), np.inf)
    span = float(np.ptp(arr.xy, axis=0).max()) if len(arr) else 0.0
    reach = max(float(radius.max(initial=0.0)), 1e-9)
    overlaps = 0
    while True:
        i, j = near_pairs(arr.xy, radius, reach)
        dist = shapely.distance(geoms[i], geoms[j])
        found = dist < reach
        ki, kj = arr.kind[i][found], arr.kind[j][found]
        np.minimum.at(distance, (ki, kj), dist[found])
        np.minimum.at(distance, (kj, ki), dist[found])
        if np.isfinite(distance[possible]).all() or reach > 2 * (span + 2 * radius.max(initial=0.0)):
            overlaps = int(overlapping(geoms, i, j, dist).sum())
            break
        reach *= 2
    measured = np.isfinite(distance)
    row_min = np.where(measured, distance, np.inf).min(axis=1)
    fallback = np.minimum.outer(row_min, row_min)
    fallback[~np.isfinite(fallback)] = 0.0
    distance = np.where(measured, distance, fallback)
    return distance, measured, overlaps


def orientation_arcs(angle: np.ndarray, kind: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Smallest arc of the circle holding every orientation of each kind (almeraj2013 §3.5).

    Parameters
    ----------
    angle : (n,) float array, degrees.
    kind : (n,) int array.
    k : number of kinds.

    Returns
    -------
    start : (k,) float array, degrees in [-180, 180); the arc runs counter-clockwise from here.
    width : (k,) float array, degrees in [0, 360).  A kind without instances gets width 0.
    """
    start = np.zeros(k)
    width = np.zeros(k)
    for c in range(k):
        a = np.sort(np.mod(angle[kind == c], 360.0))
        if len(a) == 0:
            continue
        gaps = np.diff(np.append(a, a[0] + 360.0))
        g = int(np.argmax(gaps))
        start[c] = (a[(g + 1) % len(a)] + 180.0) % 360.0 - 180.0
        width[c] = max(0.0, 360.0 - gaps[g])
    return start, width


def in_arcs(angle: np.ndarray, kind: np.ndarray, stats: Stats, tol: float = 1e-6) -> np.ndarray:
    """(n,) bool: does each motif's orientation lie in its kind's arc?"""
    offset = np.mod(angle - stats.arc_start[kind] + tol, 360.0)
    return offset <= stats.arc_width[kind] + 2 * tol
