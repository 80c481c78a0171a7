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

import weakref
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.core.arrangement import Arrangement
from svgtile.core.discs import disc_gap, inscribed_discs
from svgtile.core.footprint import Prototype, motif_radius, near_pairs, world_footprints

#: Slack on the distance rule, user units: positions are rounded to 1e-4 units for output, so
#: two motifs exactly d_ij apart in the exemplar may come up to ~1.5e-4 closer in a copy.
RULE_SLACK = 2e-4


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
    """Tolerance of the distance rule (output rounding of positions and angles), user units."""
    return RULE_SLACK + 1e-6 * max(p.radius for p in protos)


#: Conflicts are searched band by band of about this many motifs, so that only one band's
#: footprints are in memory at a time; the pairs found are exactly those of a single pass.
BAND_MOTIFS = 150_000


def find_conflicts(
    arr: Arrangement, protos: list[Prototype], distance: np.ndarray, geoms: np.ndarray | None = None, *,
    group: np.ndarray | None = None, junction: np.ndarray | None = None,
) -> Conflicts:  # fmt: skip
    """All overlapping or rule-violating pairs of ``arr``.

    Parameters
    ----------
    arr : Arrangement
    protos : kind prototypes
    distance : (k, k) float array, the ``d_ij`` matrix
    geoms : (n,) world footprints of ``arr`` if already built; otherwise they are built band by
        band (horizontal bands of :data:`BAND_MOTIFS` motifs plus a halo as wide as the largest
        possible conflict), and a pair is reported by the band of its lower motif only.
    group, junction : optional (n,) int array and (k, k) float array: two motifs of different
        groups (say, of different exemplar copies) must keep the larger of ``junction`` and
        ``distance`` apart (:func:`svgtile.analysis.stats.junction_distance`); a pair that keeps
        ``distance`` but not ``junction`` is a violation.
    """
    if (group is None) != (junction is None):
        raise ValueError("group and junction go together")
    if junction is not None:
        junction = np.maximum(distance, junction)  # the junction rule adds to the distance rule
    if geoms is not None or len(arr) <= BAND_MOTIFS:
        return _conflicts(arr, protos, distance, geoms, group, junction)
    widest = distance if junction is None else junction
    reach = 2 * motif_radius(arr, protos).max() + widest.max() + 2 * slack(protos)
    y = arr.xy[:, 1]
    edges = np.quantile(y, np.linspace(0, 1, len(arr) // BAND_MOTIFS + 2)[1:-1])
    band = np.searchsorted(edges, y, side="right")
    bounds = np.r_[-np.inf, edges, np.inf]
    parts = []
    for b in range(len(edges) + 1):
        sel = np.flatnonzero((y >= bounds[b] - reach) & (y < bounds[b + 1] + reach))
        c = _conflicts(arr.take(sel), protos, distance, None, None if group is None else group[sel], junction)
        gi, gj = sel[c.i], sel[c.j]
        mine = np.minimum(band[gi], band[gj]) == b
        parts.append(Conflicts(gi[mine], gj[mine], c.overlap[mine], c.violation[mine]))
    return Conflicts(*(np.concatenate([getattr(p, f) for p in parts]) for f in ("i", "j", "overlap", "violation")))


def _conflicts(arr, protos, distance, geoms, group, junction) -> Conflicts:
    """:func:`find_conflicts` in one pass."""
    eps = slack(protos)
    widest = distance if junction is None else junction
    i, j = near_pairs(arr.xy, motif_radius(arr, protos), widest + eps, arr.kind)
    return pair_conflicts(arr, protos, distance, i, j, geoms, group, junction)


def pair_conflicts(arr: Arrangement, protos: list[Prototype], distance: np.ndarray, i: np.ndarray,
                   j: np.ndarray, geoms: np.ndarray | None = None, group: np.ndarray | None = None,
                   junction: np.ndarray | None = None) -> Conflicts:  # fmt: skip
    """The conflicts among the candidate pairs ``(i, j)`` (p,) int of ``arr`` (distinct motifs,
    each pair once): :func:`find_conflicts`'s tests on given pairs, e.g. only those that touch
    the motifs that moved (the optimize engine's non-penetration step).  ``junction`` is
    already the larger of itself and ``distance``."""
    eps = slack(protos)
    i, j = np.asarray(i, np.int64).copy(), np.asarray(j, np.int64).copy()
    swap = i > j
    i[swap], j[swap] = j[swap], i[swap]
    # pairs whose inscribed discs overlap surely share area: no footprint needed
    inner = motif_radius(arr, protos, inner=True)
    discs = (inner[i] > 0) & (inner[j] > 0)
    bound = np.hypot(*(arr.xy[i] - arr.xy[j]).T) - inner[i] - inner[j]  # footprint distance is at most this
    sure = discs & (bound < 0)
    rule = distance[arr.kind[i], arr.kind[j]] - eps
    if junction is not None:
        apart = group[i] != group[j]
        rule[apart] = junction[arr.kind[i[apart]], arr.kind[j[apart]]] - eps
    # pairs whose outlines' extents along the line of their centroids leave more than the rule
    # between them surely keep it and cannot overlap: no footprint needed either
    open_ = ~sure
    open_[open_] = ~_surely_apart(arr, protos, i[open_], j[open_], np.maximum(rule[open_], 0.0))
    held = sure | open_
    i, j, sure, discs, bound, rule = (x[held] for x in (i, j, sure, discs, bound, rule))
    # a few inscribed discs per kind (svgtile.core.discs): two that overlap show the footprints
    # sharing area (violating a positive rule), two closer than the rule a violation
    gap = np.full(len(i), np.inf)
    gap[~sure], margin = _disc_gaps(arr, arr, protos, i[~sure], j[~sure])
    shared = ~sure & (gap < -margin)
    test = ~sure & ~shared
    need = np.unique(np.concatenate([i[test], j[test]]))
    if geoms is None:
        geoms = np.empty(len(arr), dtype=object)
        geoms[need] = world_footprints(arr.take(need), protos)
    # pairs whose inscribed discs come closer than the rule surely violate it: only overlap is open
    known = (discs & (bound < rule)) | (gap < rule - margin)
    close, share = _test_pairs(geoms[i[test]], geoms[j[test]], rule[test], known[test])
    violation, overlap = sure | (shared & (rule > 0)), sure | shared
    violation[test], overlap[test] = close, share
    keep = violation | overlap
    return Conflicts(i[keep], j[keep], overlap[keep], violation[keep])


#: Most vertex–pair products :func:`_surely_apart` holds in memory at once.
_SUPPORT_CHUNK = 1 << 22


def _surely_apart(
    arr: Arrangement, protos: list[Prototype], i: np.ndarray, j: np.ndarray, reach: np.ndarray,
    other: Arrangement | None = None,
) -> np.ndarray:  # fmt: skip
    """(p,) bool: pairs whose footprint distance is surely more than ``reach`` (p,), user units.

    ``i`` indexes ``arr``, ``j`` indexes ``other`` (default ``arr``).

    A footprint lies in the convex hull of its outline's vertices, so with ``u`` the unit vector
    from centroid i to centroid j and ``h(u)`` how far a footprint's vertices reach along ``u``,
    the footprint distance is at least ``|x_j − x_i| − h_i(u) − h_j(−u)``.  That bound must
    exceed ``reach`` by a margin far above the rounding of the coordinates (relative 1e-9), so
    a pair said apart is one GEOS would find farther than ``reach`` too.
    """
    apart = np.zeros(len(i), dtype=bool)
    if len(i) == 0:
        return apart
    other = arr if other is None else other
    d = other.xy[j] - arr.xy[i]
    length = np.hypot(d[:, 0], d[:, 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        u = d / length[:, None]
    extent = np.zeros(len(i))
    # a point set reaches along u as far as its convex hull's corners, a subset of its points
    # (tufts and scrub: 68 and 42 outline vertices, 22 and 17 corners)
    for ends, sign, side in ((i, 1.0, arr), (j, -1.0, other)):
        for k in np.unique(side.kind[ends]).tolist():
            at = np.flatnonzero(side.kind[ends] == k)
            local = _corners(protos[k])  # (v, 2)
            rows = max(1, _SUPPORT_CHUNK // len(local))
            for a in range(0, len(at), rows):
                sel = at[a : a + rows]
                turn = np.radians(side.angle[ends[sel]])
                cos, sin = np.cos(turn), np.sin(turn)
                wx, wy = sign * u[sel, 0], sign * u[sel, 1]
                # (R u) · v = v · (Rᵀ u), R the motif's rotation (svgtile.core.footprint.rotation)
                along = local[:, 0] * (cos * wx + sin * wy)[:, None] + local[:, 1] * (cos * wy - sin * wx)[:, None]
                extent[sel] += side.scale[ends[sel]] * along.max(axis=1)
    gap = length - extent
    margin = max(1e-9 * (1.0 + float(np.abs(x.xy).max()) + float(motif_radius(x, protos).max())) for x in (arr, other))
    apart = gap > reach * (1.0 + 1e-9) + margin
    return apart & (length > 0)


#: _corners' results, per prototype while it lives (as svgtile.core.discs keeps its discs).
_CORNERS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _corners(proto: Prototype) -> np.ndarray:
    """(v, 2) the corners of the convex hull of ``proto``'s outline vertices (a subset of them,
    the same floats), local frame."""
    if proto not in _CORNERS:
        points = shapely.multipoints(np.concatenate(proto.rings))
        _CORNERS[proto] = shapely.get_coordinates(shapely.convex_hull(points))
    return _CORNERS[proto]


def _test_pairs(
    a: np.ndarray, b: np.ndarray, reach: np.ndarray, known_close: np.ndarray | None = None, *,
    either: bool = False,
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Exact tests of footprint pairs: (closer than ``reach``, sharing area), each (p,) bool.

    ``known_close`` (p,) bool marks pairs already known to be closer than ``reach`` (by their
    inscribed discs), which skip the distance test.  With ``either`` only ``close | share`` is
    wanted: a pair found closer than a positive ``reach`` is not tested for shared area (its
    ``share`` is then False), which spares the two costliest GEOS predicates on most pairs.
    """
    positive = reach > 0
    close = np.zeros(len(a), dtype=bool)
    test = positive if known_close is None else positive & ~known_close
    close[test] = shapely.dwithin(a[test], b[test], reach[test])
    if known_close is not None:
        close |= known_close & positive
    # a pair no closer than a positive reach shares no area; one closer is a conflict already
    check = ~positive if either else close | ~positive
    share = np.zeros(len(a), dtype=bool)
    share[check] = shapely.intersects(a[check], b[check])
    if share.any():
        share[share] = ~shapely.touches(a[share], b[share])
    return close & positive, share


def cross_conflicts(
    new: Arrangement, old: Arrangement, protos: list[Prototype], distance: np.ndarray,
    tree: cKDTree | None = None, *, groups: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:  # fmt: skip
    """(len(new),) bool: does each new motif conflict with any motif of ``old`` (of its group,
    with ``groups``: see :func:`cross_pairs`)?"""
    a, _ = cross_pairs(new, old, protos, distance, tree, complete=False, groups=groups)
    bad = np.zeros(len(new), dtype=bool)
    bad[a] = True
    return bad


def cross_pairs(
    new: Arrangement, old: Arrangement, protos: list[Prototype], distance: np.ndarray,
    tree: cKDTree | None = None, *, complete: bool = True, groups: tuple[np.ndarray, np.ndarray] | None = None,
    hopeless: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Conflicting pairs ``(a, b)``: motif ``new[a]`` overlaps or is too close to ``old[b]``.

    ``tree`` is a k-d tree of ``old.xy`` if one is at hand.  Footprints are built only for the
    pairs that bounding and inscribed discs cannot decide.  With ``complete=False`` a new motif
    already known to conflict is not tested further (enough to tell which new motifs conflict).
    With ``groups`` ((len(new),) and (len(old),) int arrays) only pairs of one group are
    checked: several independent checks in one call, each pair's outcome the same as alone.

    ``hopeless`` (with ``complete``) maps conflicting pairs ``(a, b)`` known so far to the
    (len(new),) bool mask of new motifs the caller will reject whatever their other pairs; the
    pairs of those not yet decided are not tested (their pairs come out incomplete, the caller
    rejects them), those of the rest come out as without it, in the same order.  It is asked
    after the inscribed discs about the centroids and again after the few discs per kind.
    """
    none = np.zeros(0, np.int64)
    if len(new) == 0 or len(old) == 0:
        return none, none
    eps = slack(protos)
    r_new, r_old = motif_radius(new, protos), motif_radius(old, protos)
    tree = tree or cKDTree(old.xy)
    # one neighbour query per kind of new motif, each with the reach that kind can need
    parts = []
    r_kind = np.array([p.radius for p in protos])
    for k in np.unique(new.kind):
        idx = np.flatnonzero(new.kind == k)
        reach = r_new[idx].max() + float((r_kind * old.scale.max() + distance[k]).max()) + eps
        pairs = cKDTree(new.xy[idx]).sparse_distance_matrix(tree, reach, output_type="ndarray")
        parts.append((idx[pairs["i"]], pairs["j"].astype(np.int64), pairs["v"]))
    a, b, centre = (np.concatenate(x) for x in zip(*parts, strict=True))
    if groups is not None:
        same = groups[0][a] == groups[1][b]
        a, b, centre = a[same], b[same], centre[same]
    d_rule = distance[new.kind[a], old.kind[b]] - eps
    near = centre - r_new[a] - r_old[b] < d_rule + 2 * eps
    a, b, centre, d_rule = a[near], b[near], centre[near], d_rule[near]
    # inscribed discs give an upper bound of the footprint distance: below the rule, surely bad
    # (valid only when both centroids lie inside their footprints, i.e. both radii are positive)
    in_a, in_b = motif_radius(new, protos, inner=True)[a], motif_radius(old, protos, inner=True)[b]
    sure = (in_a > 0) & (in_b > 0) & (centre - in_a - in_b < np.maximum(d_rule, 0.0))
    known = np.zeros(len(new), dtype=bool)  # new motifs known to conflict
    known[a[sure]] = True
    todo = np.flatnonzero(~sure)
    if complete:
        if hopeless is not None:
            todo = todo[~hopeless(a[sure], b[sure])[a[todo]]]
        stages = [todo]
    else:
        # the nearest pair of each new motif first: a motif found in conflict needs no more
        # tests (most candidates conflict with their nearest neighbour, if at all)
        todo = todo[~known[a[todo]]]
        order = todo[np.lexsort((centre[todo], a[todo]))]
        first = np.r_[True, a[order][1:] != a[order][:-1]][: len(order)]
        stages = [order[first], order[~first]]
    bad = sure.copy()
    for at in stages:
        if not complete:
            at = at[~known[a[at]]]
        # a few inscribed discs per kind decide most pairs of thin, concave motifs as surely bad
        close = discs_close(new, old, protos, a[at], b[at], np.maximum(d_rule[at], 0.0))
        bad[at[close]] = True
        known[a[at[close]]] = True
        at = at[~known[a[at]]] if not complete else at[~close]
        if complete and hopeless is not None:
            at = at[~hopeless(a[bad], b[bad])[a[at]]]
        # outlines whose extents along the line of centroids leave more than the rule are apart
        at = at[~_surely_apart(new, protos, a[at], b[at], np.maximum(d_rule[at], 0.0), old)]
        if not len(at):
            continue
        used_a, a_local = np.unique(a[at], return_inverse=True)
        used_b, b_local = np.unique(b[at], return_inverse=True)
        close, share = _test_pairs(
            world_footprints(new.take(used_a), protos)[a_local], world_footprints(old.take(used_b), protos)[b_local],
            d_rule[at], either=True,
        )  # fmt: skip
        bad[at] = close | share
        known[a[at[bad[at]]]] = True
    rest = ~sure & bad  # in the order of the candidates, as GEOS alone finds them
    return np.r_[a[sure], a[rest]], np.r_[b[sure], b[rest]]


#: Most disc-pair distances :func:`_disc_gaps` holds in memory at once.
_DISC_CHUNK = 1 << 21


def _disc_gaps(new, old, protos, a, b) -> tuple[np.ndarray, float]:
    """(p,) the least gap between inscribed discs (:func:`svgtile.core.discs.disc_gap`) of each
    pair ``(new[a], old[b])``, and the margin (user units) a gap must stay below a distance to
    show the footprints surely closer than it (the rounding of world coordinates)."""
    gap = np.full(len(a), np.inf)
    if not len(a):
        return gap, 0.0
    margin = 1e-9 * (1.0 + float(max(np.abs(new.xy).max(), np.abs(old.xy).max())) + max(p.radius for p in protos))
    k = len(protos)
    pair_kind = new.kind[a] * k + old.kind[b]
    order = np.argsort(pair_kind, kind="stable")
    # the (kind, kind) groups the pairs hold, not all k² of them (a kind in no pair gets no discs)
    groups, starts = np.unique(pair_kind[order], return_index=True)
    ends = np.r_[starts[1:], len(order)]
    for g, start, end in zip(groups.tolist(), starts.tolist(), ends.tolist(), strict=True):
        da, db = inscribed_discs(protos[g // k]), inscribed_discs(protos[g % k])
        rows = max(1, _DISC_CHUNK // max(len(da[1]) * len(db[1]), 1))
        for lo in range(start, end, rows):
            at = order[lo : min(lo + rows, end)]
            i, j = a[at], b[at]
            gap[at] = disc_gap(new.xy[i], new.angle[i], new.scale[i], da, old.xy[j], old.angle[j], old.scale[j], db)
    return gap, margin


def discs_close(new, old, protos, a, b, reach) -> np.ndarray:
    """(p,) bool: pairs ``(new[a], old[b])`` that two inscribed discs (:mod:`svgtile.core.discs`)
    show closer than ``reach`` (p,) ≥ 0 — or sharing area, for ``reach`` 0 — surely."""
    gap, margin = _disc_gaps(new, old, protos, a, b)
    return gap < reach - margin


def cull(n: int, conflicts: Conflicts, priority: np.ndarray, prefer: np.ndarray | None = None) -> np.ndarray:
    """Remove motifs until no pair of ``conflicts`` has both ends kept, removing as few as it can.

    The kept set is the greedy maximal independent set of the conflict graph taken in order of
    increasing score: a motif is kept unless a lower-scored kept motif conflicts with it.  It is
    computed in parallel rounds (Luby 1986): every undecided motif that scores below all its
    undecided neighbours is kept and its neighbours are removed.  Every removed motif thus has a
    kept neighbour it conflicted with — nothing is removed in vain.

    Parameters
    ----------
    n : number of motifs.
    conflicts : the pairs to break.
    priority : (n,) float array; the higher is removed first.
    prefer : (n,) float array ≥ 0, optional; a motif with a larger value is removed first
        (e.g. 1 for motifs that violate the distance rule, almeraj2013 §3.3).

    Returns
    -------
    (n,) bool array: the motifs kept.
    """
    if prefer is not None:  # prefer dominates: one unit of it outweighs any spread of priority
        priority = priority + prefer * (np.ptp(priority) + 1.0 if len(priority) else 1.0)
    score = np.empty(n, dtype=np.int64)  # unique ranks: no ties
    score[np.argsort(priority, kind="stable")] = np.arange(n)
    keep = np.ones(n, dtype=bool)
    undecided = np.zeros(n, dtype=bool)
    i, j = conflicts.i, conflicts.j
    undecided[i] = undecided[j] = True
    while len(i):
        lowest = np.full(n, n)
        np.minimum.at(lowest, i, score[j])
        np.minimum.at(lowest, j, score[i])
        chosen = undecided & (score < lowest)
        undecided &= ~chosen
        loser = np.zeros(n, dtype=bool)
        loser[j[chosen[i]]] = loser[i[chosen[j]]] = True
        keep &= ~loser
        undecided &= ~loser
        live = undecided[i] & undecided[j]
        i, j = i[live], j[live]
    return keep


def resolve(
    arr: Arrangement, protos: list[Prototype], distance: np.ndarray, priority: np.ndarray, *,
    frequency: np.ndarray | None = None, balance_rounds: int = 4,
    group: np.ndarray | None = None, junction: np.ndarray | None = None,
) -> np.ndarray:  # fmt: skip
    """Overlap resolution then the distance rule (almeraj2013 §3.3, §3.1); returns the kept mask.

    First every overlapping pair loses one motif, preferring a motif that violates the distance
    rule against its non-overlapping neighbours; then the remaining violations are broken.  With
    ``group`` and ``junction`` (:func:`find_conflicts`), motifs of different groups are held to
    the junction rule.

    Large motifs meet more conflicts than small ones, so plain culling skews the kind mix.  Given
    the exemplar's kind ``frequency``, the culling is re-run ``balance_rounds`` times with a
    per-kind shift of the removal order, each time moving the kept frequencies towards the
    exemplar's (the conflicts are found once; re-culling is cheap).
    """
    found = find_conflicts(arr, protos, distance, group=group, junction=junction)
    n = len(arr)
    violator = np.zeros(n)
    side = found.violation & ~found.overlap
    violator[found.i[side]] = violator[found.j[side]] = 1.0
    over = _subset(found, found.overlap)
    k = len(protos)
    shift = np.zeros(k)
    for _ in range(balance_rounds if frequency is not None else 1):
        score = priority + shift[arr.kind]
        keep = cull(n, over, score, violator)
        keep &= cull(n, _subset(found, found.violation & keep[found.i] & keep[found.j]), score)
        if frequency is None or not keep.any():
            break
        kept = np.bincount(arr.kind[keep], minlength=k) / keep.sum()
        shift = np.clip(shift + 0.5 * np.log(np.maximum(kept, 1e-6) / np.maximum(frequency, 1e-6)), -1.0, 1.0)
    return keep


def _subset(c: Conflicts, mask: np.ndarray) -> Conflicts:
    return Conflicts(c.i[mask], c.j[mask], c.overlap[mask], c.violation[mask])
