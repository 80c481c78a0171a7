"""Controls (Ma, Wei & Tong 2011 §5) and the interleaved non-penetration step.

* Local orientation (§5, eq. (7)): with a flow field, each output neighbourhood is turned into
  the exemplar's frame by the field's angle at its element before it is compared, predictions are
  turned back, and motifs take their sample's angle plus the field's (:func:`local_turn`).
* Domain shape (§5, eq. (6)): each candidate exemplar neighbourhood, shifted onto the output
  element (and turned by eq. (7)), costs ``λ`` for each of its samples that falls outside the
  output region (:class:`DomainTerm`), so elements at the region's edge take exemplar samples
  from a like edge.  ``c`` is exact (inside or not, by the region's shape) rather than the
  paper's rasterised map, and is asked only for elements near the edge: for the others every
  candidate's neighbourhood lies inside and the term is 0.  The region stays a hard constraint
  besides: an element that would leave what the boundary mode keeps is moved back
  (:func:`settle`).
* Non-penetration: the paper runs physics sub-steps; :func:`settle` instead relaxes each
  conflicting element halfway back to where it was, a few times, and finally returns whatever
  still conflicts to its previous state.  A conflict counts only if the previous state did not
  have it, so this ends with no new one, keeps every motif, and an engine's output (which has
  none) keeps every invariant of every engine.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import find_conflicts, pair_conflicts, slack
from svgtile.core.exemplar import Exemplar
from svgtile.core.flow import FlowField
from svgtile.core.footprint import motif_radius, rotation
from svgtile.core.region import Region
from svgtile.engines.optimize.samples import Samples

#: Halfway-back relaxation sub-steps before conflicting elements are returned to their place.
RELAX_STEPS = 1


class DomainTerm:
    """Eq. (6) of Ma, Wei & Tong 2011 against the output region, for the search (§4.2, §5).

    ``c(s_o, s_i) = Σ_{s'_i ∈ n(s_i)} |1 − c(p(s_o) + R(θ)(p(s'_i) − p(s_i)))|²`` with ``c`` 1
    inside the region and 0 outside, ``n(s_i)`` the sample's ``k`` nearest neighbours (the output
    neighbourhood's size) and ``θ`` the local orientation of eq. (7).

    Parameters
    ----------
    region : the output region
    samples : the exemplar's samples
    k : neighbours of each exemplar sample shifted onto the output
    """

    def __init__(self, region: Region, samples: Samples, k: int) -> None:
        self.rel = np.nan_to_num(samples.rel[:, :k] * samples.spacing, nan=0.0)  # (m, k, 2) user units
        reach = float(np.hypot(*self.rel.reshape(-1, 2).T).max(initial=0.0))
        self.shape = region.shape
        # elements deeper inside than every shifted neighbourhood reaches: the term is 0 for them
        self.deep = shapely.buffer(region.shape, -reach * (1 + 1e-9) - 10.0**-DECIMALS)
        shapely.prepare(self.deep)

    def near_edge(self, xy: np.ndarray) -> np.ndarray:
        """(e,) int: the elements of ``xy`` (n, 2) for which the term may not be 0."""
        return np.flatnonzero(~shapely.contains_xy(self.deep, xy[:, 0], xy[:, 1]))

    def costs(self, xy: np.ndarray, turn: np.ndarray, cand: np.ndarray) -> np.ndarray:
        """(e, C) float: the number of each candidate's shifted samples outside the region.

        Parameters
        ----------
        xy : (e, 2) float, user units; turn : (e,) degrees; cand : (e, C) int samples
        """
        rel = np.einsum("eij,eckj->ecki", rotation(turn), self.rel[cand])
        q = xy[:, None, None, :] + rel
        inside = shapely.contains_xy(self.shape, q[..., 0], q[..., 1])
        return (~inside).sum(axis=-1).astype(np.float64)


def local_turn(flow: FlowField | None, xy: np.ndarray) -> np.ndarray:
    """(n,) degrees: θ of eq. (7), the field's direction at each element (0 without a field)."""
    if flow is None or len(xy) == 0:
        return np.zeros(len(xy))
    return flow.angle(xy)


def conflict_codes(arr: Arrangement, exemplar: Exemplar, stats: Stats) -> tuple[np.ndarray, np.ndarray]:
    """The conflicting pairs of ``arr``: codes ``i·n + j`` (``i < j``), (p,) int, and whether
    each overlaps, (p,) bool."""
    c = find_conflicts(arr, exemplar.prototypes, stats.distance)
    return c.i.astype(np.int64) * len(arr) + c.j, c.overlap


def flawed(arr: Arrangement, exemplar: Exemplar, stats: Stats,
           conflicts: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:  # fmt: skip
    """(n,) bool: elements in a distance-rule violation (not an overlap) — a start that is not
    an engine's output, such as a jittered lattice, whose elements must pass each other by.
    ``conflicts`` is :func:`conflict_codes` of ``arr`` if already known."""
    codes, overlap = conflicts or conflict_codes(arr, exemplar, stats)
    out = np.zeros(len(arr), dtype=bool)
    out[codes[~overlap] // len(arr)] = out[codes[~overlap] % len(arr)] = True
    return out


def _local_update(arr: Arrangement, changed: np.ndarray, codes: np.ndarray, overlap: np.ndarray,
                  exemplar: Exemplar, stats: Stats, paths: tuple[cKDTree, float]) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """The conflicts of ``arr`` from those before ``changed`` (n,) bool elements changed.

    Only pairs with a changed end are tested again: each changed element against the elements
    whose bounding discs come within its distance rule (:func:`svgtile.core.footprint.
    near_pairs`' bound), by :func:`svgtile.core.conflicts.pair_conflicts`, the tests of
    :func:`svgtile.core.conflicts.find_conflicts` — pairs of two unchanged neighbours of a
    changed element are not tested again.  ``paths`` is a k-d tree of points every element
    stays within a distance of (the middles of the segments from the previous to the new
    positions, and the largest half-length plus rounding), built once per :func:`settle`.
    """
    n = len(arr)
    protos = exemplar.prototypes
    radius = motif_radius(arr, protos)
    eps = slack(protos)
    idx = np.flatnonzero(changed)
    reach = 2 * float(radius.max()) + float(stats.distance.max()) + eps
    tree, spread = paths
    pairs = cKDTree(arr.xy[idx]).sparse_distance_matrix(tree, reach + spread, output_type="ndarray")
    i, j = idx[pairs["i"]], pairs["j"].astype(np.int64)
    centre = np.hypot(*(arr.xy[i] - arr.xy[j]).T)
    near = (i != j) & (centre - radius[i] - radius[j] < stats.distance[arr.kind[i], arr.kind[j]] + eps)
    # a pair of two changed elements comes twice: keep it once
    i, j = i[near], j[near]
    once = ~changed[j] | (i < j)
    c = pair_conflicts(arr, protos, stats.distance, i[once], j[once])
    keep = ~(changed[codes // n] | changed[codes % n])
    return np.r_[codes[keep], c.i * n + c.j], np.r_[overlap[keep], c.overlap]


def settle(prev: Arrangement, new: Arrangement, exemplar: Exemplar, stats: Stats, region: Region,
           boundary: str, known: np.ndarray, lax: np.ndarray) -> tuple[Arrangement, np.ndarray]:  # fmt: skip
    """``new`` with no conflict that ``prev`` did not have and nothing the boundary drops.

    A moved element is *troubled* when it is in a conflict ``prev`` did not have (bar a
    violation between two ``lax`` elements) or the boundary mode would drop it.  Troubled
    elements go halfway back :data:`RELAX_STEPS` times, then all the way back until none is
    left; after the first round, conflicts are searched again only around what changed.

    Parameters
    ----------
    prev : the previous arrangement, kept by the boundary mode
    new : the same elements after an assignment (same order)
    known : (p,) int, the conflict codes of ``prev`` (:func:`conflict_codes`; none for an
        engine's output)
    lax : (n,) bool, elements that may break the distance rule among themselves (:func:`flawed`
        of the start; none for an engine's output)

    Returns
    -------
    the settled arrangement, and its conflict codes
    """
    n = len(new)
    cur = new
    codes, overlap = conflict_codes(cur, exemplar, stats)
    # every position a relaxation round gives lies on the segment from prev to new (rounded)
    half = np.hypot(*(new.xy - prev.xy).T) / 2
    paths = cKDTree((prev.xy + new.xy) / 2), float(half.max(initial=0.0)) + 10.0**-DECIMALS
    dropped = np.zeros(n, dtype=bool)
    changed = np.ones(n, dtype=bool)
    step = 0
    while True:
        moved = ((cur.kind != prev.kind) | (cur.xy != prev.xy).any(axis=1) | (cur.angle != prev.angle)
                 | (cur.scale != prev.scale))  # fmt: skip
        check = np.flatnonzero(changed & moved)
        dropped[changed] = False
        dropped[check[~region.keep(cur.take(check), exemplar.prototypes, boundary)]] = True
        i, j = codes // n, codes % n
        new_pair = ~np.isin(codes, known) & (overlap | ~(lax[i] & lax[j]))
        bad = dropped.copy()
        bad[i[new_pair]] = bad[j[new_pair]] = True
        bad &= moved
        if not bad.any():
            return cur, np.sort(codes)
        kind, xy, angle, scale = cur.kind.copy(), cur.xy.copy(), cur.angle.copy(), cur.scale.copy()
        if step < RELAX_STEPS:
            xy[bad] = np.round((cur.xy[bad] + prev.xy[bad]) / 2, DECIMALS)
        else:
            kind[bad], xy[bad], angle[bad], scale[bad] = prev.kind[bad], prev.xy[bad], prev.angle[bad], prev.scale[bad]
        cur = Arrangement(kind, xy, angle, scale)
        changed = bad
        codes, overlap = _local_update(cur, changed, codes, overlap, exemplar, stats, paths)
        step += 1
