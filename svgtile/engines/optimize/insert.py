"""Insertion: elements the neighbourhoods predict where no output element stands (issue 14).

Ma, Wei & Tong 2011 keep the element count of their initialisation (§4): every output element
is matched (§4.2) and moved (§4.3), none is added.  Where the start is sparse — patches cut from
an irregular tile meet at seams that lose motifs to culling — the count never recovers.  Here
each matched element ``s_o → s_i`` also predicts, by eq. (3), the exemplar neighbours of ``s_i``
that no output neighbour was paired with (among its ``k`` nearest, the ring that the output's
``k``-neighbourhood should hold): ``p = p(s_o) + R(θ)(p(s'_i) − p(s_i))``.  Predictions that
land where no output element stands are gathered in world-anchored bins of half a spacing; a
bin predicted by at least :data:`VOTES` elements gets one element, at the mean of its
predictions, of the kind, angle and scale of its first prediction's sample — and is kept only
if it breaks no rule (no overlap, no distance-rule violation, kept by the boundary mode),
the best-voted first.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from svgtile.analysis.stats import Stats
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius, rotation
from svgtile.core.region import Region
from svgtile.engines.optimize.samples import Samples
from svgtile.engines.optimize.search import Neighbourhoods

#: Predictions a bin needs before an element is inserted there.
VOTES = 2
#: Predictions nearer than this to an output element (spacings) are taken as that element.
TAKEN = 0.5
_TIE = 75  # hash stream: ties between equally voted bins


def insert(arr: Arrangement, samples: Samples, hoods: Neighbourhoods, match: np.ndarray, slots: np.ndarray,
           exemplar: Exemplar, stats: Stats, region: Region, boundary: str, *,
           key: int) -> tuple[Arrangement, np.ndarray]:  # fmt: skip
    """``arr`` with elements added where its neighbourhoods predict one and none stands.

    Parameters
    ----------
    arr : (n motifs) the output, with no conflict, kept by ``boundary``
    samples : the exemplar's samples (one per motif)
    hoods, match, slots : the search of ``arr``'s positions: its neighbourhoods, (n,) each
        element's exemplar sample and (n, k) the exemplar slot each neighbour is paired with
    key : the run's key

    Returns
    -------
    the arrangement, ``arr`` first, then the inserted elements; and (m,) int, the exemplar
    sample each inserted element stands for (its match for the next search)
    """
    n, k = slots.shape
    none = (arr, np.zeros(0, dtype=np.int64))
    if n == 0:
        return none
    # exemplar slots among the k nearest of each element's match that no output neighbour took
    taken = np.zeros((n, samples.rel.shape[1]), dtype=bool)
    rows = np.repeat(np.arange(n), k)
    ok = (slots >= 0).ravel()
    taken[rows[ok], slots.ravel()[ok]] = True
    free = ~taken[:, :k] & (samples.nindex[match, :k] >= 0)
    src, slot = np.nonzero(free)
    if len(src) == 0:
        return none
    rel = samples.rel[match[src], slot] * samples.spacing
    at = arr.xy[src] + np.einsum("eij,ej->ei", rotation(hoods.turn[src]), rel)
    sample = samples.nindex[match[src], slot]
    spacing = samples.spacing
    empty = cKDTree(arr.xy).query(at, distance_upper_bound=TAKEN * spacing)[0] == np.inf
    at, sample, src = at[empty], sample[empty], src[empty]
    if len(at) == 0:
        return none
    # world-anchored bins of half a spacing; a bin's votes, mean position and first sample
    cell = np.floor(at / (TAKEN * spacing)).astype(np.int64)
    ids, which, votes = np.unique(cell, axis=0, return_inverse=True, return_counts=True)
    which = which.ravel()
    order = np.lexsort((sample, src, which))  # within a bin: by the predicting element, then sample
    first = order[np.r_[0, np.flatnonzero(np.diff(which[order])) + 1]]
    xy = np.stack([np.bincount(which, weights=at[:, d]) for d in (0, 1)], -1) / votes[:, None]
    chosen = sample[first]
    good = votes >= VOTES
    if not good.any():
        return none
    ids, votes, xy, chosen = ids[good], votes[good], xy[good], chosen[good]
    turn = hoods.turn[src[first]][good]
    angle = (samples.angle[chosen] + turn + 180.0) % 360.0 - 180.0
    new = Arrangement(samples.kind[chosen], xy, angle, samples.scale[chosen]).quantized(DECIMALS)
    kept = region.keep(new, exemplar.prototypes, boundary)
    new, ids, votes, chosen = new.take(kept), ids[kept], votes[kept], chosen[kept]
    if len(new) == 0:
        return none
    # the rules, against the output near the new elements and among them: the output stays
    reach = 2 * float(motif_radius(arr, exemplar.prototypes).max(initial=0.0)) + float(stats.distance.max(initial=0.0))
    near = np.unique(np.concatenate([np.zeros(0, np.int64), *map(np.asarray, cKDTree(arr.xy).query_ball_point(
        new.xy, reach + float(motif_radius(new, exemplar.prototypes).max())))]).astype(np.int64))  # fmt: skip
    both = Arrangement.concat([arr.take(near), new])
    m = len(near)
    tie = cellrng.uniform(key, _TIE, ids[:, 0], ids[:, 1])
    priority = np.r_[np.zeros(m), -votes + 0.5 * tie]
    prefer = np.r_[np.zeros(m), np.ones(len(new))]
    keep = cull(len(both), find_conflicts(both, exemplar.prototypes, stats.distance), priority, prefer)
    add = keep[m:]
    if not keep[:m].all():  # cannot happen: the output has no conflict among itself
        return none
    return Arrangement.concat([arr, new.take(add)]), chosen[add]
