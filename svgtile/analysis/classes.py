"""Kinds as classes: motifs drawn once or a few times each, grouped by shape (issue 12.3).

A hand-drawn breccia (FGDC 605) draws each angular fragment once; an exact-match classifier
(:func:`svgtile.svg.kinds.match_kinds`) then makes every fragment its own kind, and the distance
rule of AlMeraj et al. 2013 §3.1 measures ``d_ij`` between *those two fragments* — wherever the
exemplar happened to put them.  Two fragments 30 units apart in the exemplar may then never come
closer than 30 units in the texture, and most fragments are culled (605: density / ρ 0.31).

A kind drawn two to four times is no better measured: FGDC's dash fields (681, 714, 715: till,
dashes of a few lengths amid dots) draw most dash lengths twice or three times, and ``d_ii`` is
then the gap of one pair of dashes (26.6 units for a dash of 714 drawn twice, whose shape class
keeps 1.1; 19.0 against 1.0 on average over its 23 rare kinds) and ``d_ij`` to another rare dash
the gap of a handful of pairs.  The texture could then place those
dashes only where the rule, wider than any gap the exemplar shows between dashes of that shape,
left room: 714 came out at density / ρ 0.86 and 715 at 0.76, short of exactly those kinds.  The dash
fields 684–686 draw dash lengths 5 to 14 times, and the rarer of those still kept 3.5–6.6 units
where the common dashes keep 1–2.  A kind needs :data:`RARE_BELOW` instances before its own pairs
stand for the rule.

Here kinds with fewer than :data:`RARE_BELOW` instances are grouped into classes by shape — size
(area, by factors of two), elongation (the aspect of the minimum rotated rectangle) and
angularity (the isoperimetric quotient 4πA/P² of the outline; :func:`shape_classes`) — and the
distance rule is pooled per class pair: ``d_ij`` becomes the smallest distance the exemplar shows
between *any* member of i's class and any member of j's (:func:`pooled_distance`).  Pooling only
lowers a distance, so the exemplar's own motifs still keep the rule.  Kinds drawn
:data:`RARE_BELOW` times or more are classes of their own, so exemplars without rare kinds are
unchanged.  Each motif keeps its own kind and symbol in the output.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

from svgtile.core.footprint import Prototype

#: Kinds drawn fewer times than this are pooled into shape classes (their own few pairs do not
#: measure a distance rule).  Chosen on the whole set (FGDC, osm-carto, Equinor; benchmarks/README.md,
#: "dens12"): below 5 (the junction rule's :data:`svgtile.analysis.stats.GAP_MIN_SAMPLES`) left the
#: dash fields 684–686 at 0.72–0.75 ρ, short of kinds drawn 5–11 times; 13 brings them to 0.90 with
#: the mean likeness unchanged; from 20 on the bundled breccia changes.
RARE_BELOW = 13
#: Two kinds are alike when their areas differ by less than this factor …
SIZE_FACTOR = 2.0
#: … their elongations (long / short side of the minimum rotated rectangle) by less than this …
ELONGATION_FACTOR = 1.6
#: … and both are angular or both round: isoperimetric quotient below this is angular (a square
#: is 0.785, a disc 1).
ROUND = 0.8


def shape_features(protos: list[Prototype]) -> np.ndarray:
    """(k, 3) float array: log2 area (user units²), elongation (≥ 1), isoperimetric quotient."""
    out = np.zeros((len(protos), 3))
    for i, p in enumerate(protos):
        geom = shapely.union_all([shapely.Polygon(r) for r in p.rings]) if p.rings else shapely.Point(0, 0)
        rect = shapely.minimum_rotated_rectangle(geom)
        xy = shapely.get_coordinates(rect)
        sides = np.hypot(*np.diff(xy[:3], axis=0).T) if len(xy) >= 3 else np.array([1.0, 1.0])
        long, short = float(sides.max()), float(max(sides.min(), 1e-12))
        perimeter = float(shapely.length(geom))
        q = 4 * math.pi * geom.area / perimeter**2 if perimeter > 0 else 1.0
        out[i] = (math.log2(max(p.area, 1e-12)), long / short, q)
    return out


def shape_classes(protos: list[Prototype], counts: np.ndarray) -> np.ndarray:
    """(k,) int class of each kind: rare kinds (fewer than :data:`RARE_BELOW` instances) share a
    class with rare kinds of like shape (area within :data:`SIZE_FACTOR`, elongation within
    :data:`ELONGATION_FACTOR`, both angular or both round), chained by single linkage; every
    other kind is its own class.

    Parameters
    ----------
    protos : the kinds' prototypes
    counts : (k,) int, motifs of each kind in the exemplar
    """
    k = len(protos)
    cls = np.arange(k)
    counts = np.asarray(counts)
    once = np.flatnonzero((counts >= 1) & (counts < RARE_BELOW))
    if len(once) < 2:
        return cls
    f = shape_features([protos[i] for i in once])
    # single linkage: like shapes chain into one class (fixed bins would split a class at an edge)
    size = np.abs(f[:, None, 0] - f[None, :, 0]) <= math.log2(SIZE_FACTOR)
    elong = np.abs(np.log(f[:, None, 1] / f[None, :, 1])) <= math.log(ELONGATION_FACTOR)
    angular = (f[:, None, 2] >= ROUND) == (f[None, :, 2] >= ROUND)
    group = connected_components(csr_matrix(size & elong & angular), directed=False)[1]
    lead = np.array([once[np.flatnonzero(group == g)[0]] for g in range(int(group.max()) + 1)])
    cls[once] = lead[group]
    return np.unique(cls, return_inverse=True)[1].ravel()


def pooled_distance(distance: np.ndarray, measured: np.ndarray, cls: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``d_ij`` pooled per class pair: the smallest measured distance between any member of i's
    class and any of j's; pairs of classes never measured keep their own value.

    Parameters
    ----------
    distance, measured : (k, k) arrays (:func:`svgtile.analysis.stats.distance_matrix`)
    cls : (k,) int classes (:func:`shape_classes`)

    Returns
    -------
    distance : (k, k) float array, user units
    measured : (k, k) bool array
    """
    c = int(cls.max(initial=-1)) + 1
    pooled = np.full((c, c), np.inf)
    ii, jj = np.nonzero(measured)
    np.minimum.at(pooled, (cls[ii], cls[jj]), distance[ii, jj])
    out = pooled[cls[:, None], cls[None, :]]
    have = np.isfinite(out)
    return np.where(have, out, distance), measured | have
