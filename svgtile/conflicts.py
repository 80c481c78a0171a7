"""Overlaps and distance-rule violations, and removing motifs until there are none.

Shared by every engine and by the tests: a pair of motifs *overlaps* when their footprints share
area, and *violates the distance rule* (almeraj2013 §3.1) when their footprint distance is below
``d_ij`` for their kinds.  Culling removes motifs until no conflicting pair is left, in rounds: in
each round every motif that outranks all its remaining conflicting neighbours is removed (a
Luby-style independent set), so a chain A–B–C loses B alone, no per-motif Python loop is needed
and the outcome depends only on each motif's neighbourhood — which keeps textures stable under
edits elsewhere.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from .arrangement import Arrangement
from .footprint import Prototype, motif_radius, near_pairs, world_footprints

#: Slack on the distance rule, relative to the largest motif radius: distances are compared after
#: output rounding, and GEOS distances carry float noise.
RULE_SLACK = 1e-6


@dataclass(frozen=True, eq=False)
class Conflicts:
    """Conflicting pairs of an arrangement.

    Attributes
    ----------
    i, j : (p,) int arrays, ``i < j``
    overlap : (p,) bool array, footprints share area
    violation : (p,) bool array, distance below ``d_ij`` (overlaps included when ``d_ij > 0``)
    """

    i: np.ndarray
    j: np.ndarray
    overlap: np.ndarray
    violation: np.ndarray

    def __len__(self) -> int:
        return len(self.i)


def slack(protos: list[Prototype]) -> float:
    return RULE_SLACK * max(p.radius for p in protos)


#: Conflicts are searched band by band of about this many motifs, so that only one band's
#: footprints are in memory at a time; the pairs found are exactly those of a single pass.
BAND_MOTIFS = 150_000


def find_conflicts(
    arr: Arrangement, protos: list[Prototype], distance: np.ndarray, geoms: np.ndarray | None = None
) -> Conflicts:
    """All overlapping or rule-violating pairs of ``arr``.

    Parameters
    ----------
    arr : Arrangement
    protos : kind prototypes
    distance : (k, k) float array, the ``d_ij`` matrix
    geoms : (n,) world footprints of ``arr`` if already built; otherwise they are built band by
        band (horizontal bands of :data:`BAND_MOTIFS` motifs plus a halo as wide as the largest
        possible conflict), and a pair is reported by the band of its lower motif only.
    """
    if geoms is not None or len(arr) <= BAND_MOTIFS:
        return _conflicts(arr, protos, distance, geoms)
    reach = 2 * motif_radius(arr, protos).max() + distance.max() + 2 * slack(protos)
    y = arr.xy[:, 1]
    edges = np.quantile(y, np.linspace(0, 1, len(arr) // BAND_MOTIFS + 2)[1:-1])
    band = np.searchsorted(edges, y, side="right")
    bounds = np.r_[-np.inf, edges, np.inf]
    parts = []
    for b in range(len(edges) + 1):
        sel = np.flatnonzero((y >= bounds[b] - reach) & (y < bounds[b + 1] + reach))
        c = _conflicts(arr.take(sel), protos, distance, None)
        gi, gj = sel[c.i], sel[c.j]
        mine = np.minimum(band[gi], band[gj]) == b
        parts.append(Conflicts(gi[mine], gj[mine], c.overlap[mine], c.violation[mine]))
    return Conflicts(*(np.concatenate([getattr(p, f) for p in parts]) for f in ("i", "j", "overlap", "violation")))


def _conflicts(arr, protos, distance, geoms) -> Conflicts:
    """:func:`find_conflicts` in one pass."""
    eps = slack(protos)
    i, j = near_pairs(arr.xy, motif_radius(arr, protos), distance + eps, arr.kind)
    swap = i > j
    i[swap], j[swap] = j[swap], i[swap]
    # pairs whose inscribed discs overlap surely share area: no footprint needed
    inner = motif_radius(arr, protos, inner=True)
    sure = np.hypot(*(arr.xy[i] - arr.xy[j]).T) < inner[i] + inner[j]
    need = np.unique(np.concatenate([i[~sure], j[~sure]]))
    if geoms is None:
        geoms = np.empty(len(arr), dtype=object)
        geoms[need] = world_footprints(arr.take(need), protos)
    close, share = _test_pairs(geoms[i[~sure]], geoms[j[~sure]], distance[arr.kind[i], arr.kind[j]][~sure] - eps)
    violation, overlap = sure.copy(), sure.copy()
    violation[~sure], overlap[~sure] = close, share
    keep = violation | overlap
    return Conflicts(i[keep], j[keep], overlap[keep], violation[keep])


def _test_pairs(a: np.ndarray, b: np.ndarray, reach: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exact tests of footprint pairs: (closer than ``reach``, sharing area), each (p,) bool."""
    positive = reach > 0
    close = np.zeros(len(a), dtype=bool)
    close[positive] = shapely.dwithin(a[positive], b[positive], reach[positive])
    check = close | ~positive
    share = np.zeros(len(a), dtype=bool)
    share[check] = shapely.intersects(a[check], b[check])
    if share.any():
        share[share] = ~shapely.touches(a[share], b[share])
    return close & positive, share


def cross_conflicts(
    new: Arrangement, old: Arrangement, protos: list[Prototype], distance: np.ndarray,
    new_geoms: np.ndarray, tree: cKDTree | None = None,
) -> np.ndarray:  # fmt: skip
    """(len(new),) bool: does each new motif conflict with any motif of ``old``?

    ``tree`` is a k-d tree of ``old.xy`` if one is at hand; footprints of ``old`` are built only
    for the motifs near a new one.
    """
    bad = np.zeros(len(new), dtype=bool)
    if len(new) == 0 or len(old) == 0:
        return bad
    eps = slack(protos)
    r_new, r_old = motif_radius(new, protos), motif_radius(old, protos)
    tree = tree or cKDTree(old.xy)
    hits = tree.query_ball_point(new.xy, r_new + r_old.max() + distance.max() + eps)
    lengths = np.fromiter((len(h) for h in hits), dtype=np.int64, count=len(hits))
    if lengths.sum() == 0:
        return bad
    a = np.repeat(np.arange(len(new)), lengths)
    b = np.concatenate([np.asarray(h, dtype=np.int64) for h in hits if h])
    d_rule = distance[new.kind[a], old.kind[b]]
    gap = np.hypot(*(new.xy[a] - old.xy[b]).T) - r_new[a] - r_old[b]
    near = gap < d_rule + eps
    a, b, d_rule = a[near], b[near], d_rule[near]
    used, b_local = np.unique(b, return_inverse=True)
    old_geoms = world_footprints(old.take(used), protos)
    close, share = _test_pairs(new_geoms[a], old_geoms[b_local], d_rule - eps)
    np.logical_or.at(bad, a[close | share], True)
    return bad


def cull(n: int, conflicts: Conflicts, priority: np.ndarray, prefer: np.ndarray | None = None) -> np.ndarray:
    """Remove motifs until no pair of ``conflicts`` has both ends kept.

    Parameters
    ----------
    n : number of motifs.
    conflicts : the pairs to break.
    priority : (n,) float array in [0, 1); among equals the higher priority is removed first.
    prefer : (n,) float array ≥ 0, optional; a motif with a larger value is removed first
        (e.g. 1 for motifs that violate the distance rule, almeraj2013 §3.3).

    Returns
    -------
    (n,) bool array: the motifs kept.
    """
    keep = np.ones(n, dtype=bool)
    i, j = conflicts.i, conflicts.j
    score = priority + (0.0 if prefer is None else 2.0 * prefer)
    score = np.argsort(np.argsort(score, kind="stable"), kind="stable")  # unique ranks: no ties
    while len(i):
        live = keep[i] & keep[j]
        i, j = i[live], j[live]
        if len(i) == 0:
            break
        best_neighbour = np.full(n, -1)
        np.maximum.at(best_neighbour, i, score[j])
        np.maximum.at(best_neighbour, j, score[i])
        involved = np.zeros(n, dtype=bool)
        involved[i] = involved[j] = True
        keep &= ~(involved & (score > best_neighbour))
    return keep


def resolve(
    arr: Arrangement, protos: list[Prototype], distance: np.ndarray, priority: np.ndarray,
    geoms: np.ndarray | None = None,
) -> np.ndarray:  # fmt: skip
    """Overlap resolution then the distance rule (almeraj2013 §3.3, §3.1); returns the kept mask.

    First every overlapping pair loses one motif, preferring a motif that violates the distance
    rule against its non-overlapping neighbours; then the remaining violations are broken,
    removing first the motifs with the most violations.
    """
    found = find_conflicts(arr, protos, distance, geoms)
    n = len(arr)
    violator = np.zeros(n)
    side = found.violation & ~found.overlap
    violator[found.i[side]] = violator[found.j[side]] = 1.0
    over = _subset(found, found.overlap)
    keep = cull(n, over, priority, violator)
    rest = _subset(found, found.violation & keep[found.i] & keep[found.j])
    degree = np.bincount(np.concatenate([rest.i, rest.j]), minlength=n).astype(np.float64)
    return keep & cull(n, rest, priority, degree)


def _subset(c: Conflicts, mask: np.ndarray) -> Conflicts:
    return Conflicts(c.i[mask], c.j[mask], c.overlap[mask], c.violation[mask])
