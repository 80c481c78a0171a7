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
the best-voted first.  Where the mean breaks a rule, each of the bin's own predictions (its
position, its sample) is tried in its place, one element a bin at most (FGDC 601, 612, 613,
617: +0.01–0.03 of ρ; 605: −0.06).

Insertion is capped at the exemplar's density ρ (:func:`capped`): in world-anchored windows of
:data:`WINDOW` spacings, the best-voted elements are added only while the window's covered
fraction stays below ρ (renewal's insertion on a drawn exemplar, whose start is thinned by count:
while the window holds fewer motifs than the exemplar's per unit area).  Uncapped, every predicted hole was filled, and where the exemplar's
neighbourhoods predict more neighbours than its density holds — rows whose spacing along the row
is tighter than across, a drawn exemplar's dense clusters — the texture overfilled (FGDC 610:
density / ρ 1.44; bundled exemplars 1.06–1.31).  The cap is the count the paper's §4.1 start
would have had without seams; the predictions say only *where* the missing elements go.
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import Stats, footprint_areas
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius, rotation
from svgtile.core.region import Region
from svgtile.engines.optimize.samples import Samples
from svgtile.engines.optimize.search import Neighbourhoods
from svgtile.engines.windows import square_area, square_cells, square_windows

#: Predictions a bin needs before an element is inserted there.
VOTES = 2
#: Predictions nearer than this to an output element (spacings) are taken as that element.
TAKEN = 0.5
#: Side of the density windows of the cap, exemplar spacings: those of the start's thinning
#: (:func:`.init.thin`, two cells of 5 spacings).  Windows of 3 and 6 spacings left FGDC
#: 601 and 613 at 0.86–0.89 of ρ: a small window's cover varies as much as the exemplar's
#: does there, so capping each at ρ keeps their mean below it.
WINDOW = 10.0
_TIE = 75  # hash stream: ties between equally voted bins


def insert(arr: Arrangement, samples: Samples, hoods: Neighbourhoods, match: np.ndarray, slots: np.ndarray,
           exemplar: Exemplar, stats: Stats, region: Region, boundary: str, *,
           key: int, by_count: bool = False) -> tuple[Arrangement, np.ndarray]:  # fmt: skip
    """``arr`` with elements added where its neighbourhoods predict one and none stands.

    Parameters
    ----------
    arr : (n motifs) the output, with no conflict, kept by ``boundary``
    samples : the exemplar's samples (one per motif)
    hoods, match, slots : the search of ``arr``'s positions: its neighbourhoods, (n,) each
        element's exemplar sample and (n, k) the exemplar slot each neighbour is paired with
    key : the run's key
    by_count : cap each window at the exemplar's motifs per unit area, not ρ (:func:`capped`;
        renewal's insertion on a drawn exemplar, whose start is thinned by count)

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
    tree = cKDTree(arr.xy)  # the output's, for the holes here and the rules below
    empty = tree.query(at, distance_upper_bound=TAKEN * spacing)[0] == np.inf
    at, sample, src = at[empty], sample[empty], src[empty]
    if len(at) == 0:
        return none
    # world-anchored bins of half a spacing; a bin's votes, mean position and first sample
    ids, which = square_windows(at, TAKEN * spacing)
    votes = np.bincount(which, minlength=len(ids))
    order = np.lexsort((sample, src, which))  # within a bin: by the predicting element, then sample
    first = order[np.r_[0, np.flatnonzero(np.diff(which[order])) + 1]]
    xy = np.stack([np.bincount(which, weights=at[:, d]) for d in (0, 1)], -1) / votes[:, None]
    chosen = sample[first]
    good = votes >= VOTES
    if not good.any():
        return none
    turn = hoods.turn[src[first]]
    bin_of = np.arange(len(ids))
    # every prediction of a voted bin stands in for the bin's mean, after it, where the mean breaks a rule
    alt = good[which]
    bin_of = np.r_[bin_of, which[alt]]
    xy, chosen, turn = np.r_[xy, at[alt]], np.r_[chosen, sample[alt]], np.r_[turn, hoods.turn[src[alt]]]
    fallback = np.r_[np.zeros(len(ids)), np.ones(int(alt.sum()))]
    good = good[bin_of]
    bin_of, xy, chosen, turn, fallback = bin_of[good], xy[good], chosen[good], turn[good], fallback[good]
    ids, votes = ids[bin_of], votes[bin_of]
    angle = (samples.angle[chosen] + turn + 180.0) % 360.0 - 180.0
    new = Arrangement(samples.kind[chosen], xy, angle, samples.scale[chosen]).quantized(DECIMALS)
    kept = region.keep(new, exemplar.prototypes, boundary)
    new, ids, votes, chosen, bin_of, fallback = (new.take(kept), ids[kept], votes[kept], chosen[kept], bin_of[kept],
                                                 fallback[kept])  # fmt: skip
    if len(new) == 0:
        return none
    # the rules, against the output near the new elements and among them: the output stays
    reach = 2 * float(motif_radius(arr, exemplar.prototypes).max(initial=0.0)) + float(stats.distance.max(initial=0.0))
    near = np.unique(np.concatenate([np.zeros(0, np.int64), *map(np.asarray, tree.query_ball_point(
        new.xy, reach + float(motif_radius(new, exemplar.prototypes).max())))]).astype(np.int64))  # fmt: skip
    both = Arrangement.concat([arr.take(near), new])
    m = len(near)
    tie = cellrng.uniform(key, _TIE, ids[:, 0], ids[:, 1], chosen)
    priority = np.r_[np.zeros(m), -votes + 0.5 * tie + (votes.max() + 1) * fallback]
    prefer = np.r_[np.zeros(m), np.ones(len(new))]
    keep = cull(len(both), find_conflicts(both, exemplar.prototypes, stats.distance), priority, prefer)
    if not keep[:m].all():  # cannot happen: the output has no conflict among itself
        return none
    add = np.flatnonzero(keep[m:])
    # one element a bin: its best kept candidate
    add = add[np.lexsort((priority[m:][add], bin_of[add]))]
    add = add[np.r_[True, bin_of[add][1:] != bin_of[add][:-1]]] if len(add) else add
    add = add[capped(arr, new.take(add), -priority[m:][add], exemplar, stats, region, window=WINDOW * spacing,
                     by_count=by_count)]  # fmt: skip
    return Arrangement.concat([arr, new.take(add)]), chosen[add]


def capped(arr: Arrangement, new: Arrangement, rank: np.ndarray, exemplar: Exemplar, stats: Stats, region: Region,
           *, window: float, by_count: bool = False) -> np.ndarray:  # fmt: skip
    """(m,) bool: the elements of ``new`` added so that no window is filled past ρ (``by_count``:
    holds the exemplar's motifs per unit area, to the nearest motif, each motif counting 1).

    The plane is cut into world-anchored square windows of side ``window``; a window's room is
    ``ρ · area(window ∩ region)`` less the footprint area of the motifs of ``arr`` whose centroid
    lies in it (as :func:`svgtile.analysis.window.density` counts).  The elements of ``new`` in a
    window are taken by decreasing ``rank`` as long as each brings the window's covered fraction
    nearer to ρ (the room left before it is more than half its area); the first that would not
    ends the window's list.

    Parameters
    ----------
    arr : (n motifs) the output
    new : (m motifs) the candidates, no conflict with ``arr`` nor among themselves
    rank : (m,) float, the higher the sooner a candidate is taken (unique)
    window : side of the windows, user units
    by_count : the room in motifs (``area(window ∩ region)`` times the exemplar's motifs per unit
        area, less the motifs there), each candidate taking 1

    Returns
    -------
    (m,) bool, the candidates taken
    """
    m = len(new)
    if m == 0:
        return np.zeros(0, dtype=bool)
    ids, which = square_windows(new.xy, window)
    inside = square_area(ids, window, region)
    room = inside * (len(exemplar.motifs) / exemplar.region.area if by_count else stats.density)
    # the output's cover of those windows: its motifs' windows looked up among ``ids``; a motif
    # whose centroid lies outside the region (kept by the boundary mode) covers no window's
    # ``window ∩ region``, as the density figure counts
    cell = square_cells(arr.xy, window)
    pos = np.searchsorted(_keys(ids), _keys(cell))
    hit = (pos < len(ids)) & (_keys(ids)[np.minimum(pos, len(ids) - 1)] == _keys(cell))
    hit &= shapely.contains_xy(region.shape, arr.xy[:, 0], arr.xy[:, 1])
    covers = np.ones(int(hit.sum())) if by_count else footprint_areas(arr.take(np.flatnonzero(hit)), exemplar.prototypes)
    room -= np.bincount(pos[hit], weights=covers, minlength=len(ids))
    area = np.ones(m) if by_count else footprint_areas(new, exemplar.prototypes)
    order = np.lexsort((-rank, which))  # by window, best first
    w, a = which[order], area[order]
    start = np.r_[0, np.flatnonzero(np.diff(w)) + 1]
    before = np.cumsum(a) - a  # area added before this one, if all before it are taken
    before -= np.repeat(before[start], np.diff(np.r_[start, m]))
    nearer = room[w] - before > a / 2
    # a window's candidates are taken up to its first that would not bring it nearer to ρ
    short = np.cumsum(~nearer)
    short -= np.repeat(short[start] - ~nearer[start], np.diff(np.r_[start, m]))
    take = np.zeros(m, dtype=bool)
    take[order] = short == 0
    return take


def shrinking(arr: Arrangement, kind: np.ndarray, exemplar: Exemplar, stats: Stats, region: Region, *,
              window: float) -> np.ndarray:  # fmt: skip
    """(n,) bool: the elements of ``arr`` whose new ``kind`` (n,) has a smaller footprint than
    their present one, in a world-anchored window of side ``window`` whose cover (as
    :func:`capped` counts it) is below ρ.

    The non-penetration step (:func:`.controls.settle`) returns an element whose voted kind is
    larger and collides, and never one whose kind is smaller: every iteration the vote of eq. (5)
    then shrinks the covered area a little (FGDC 605: −0.02 to −0.07 of ρ per iteration, 606's
    one-off fragments turned into dots).  Where the window is already short, such changes are
    not taken; the windows are world-anchored, so the decision at a place does not depend on how
    far the region extends (a cap on the whole texture's figure would: an edit anywhere could
    turn it on or off everywhere).

    Parameters
    ----------
    arr : (n motifs) the output before the vote
    kind : (n,) int, the kinds the vote gave
    window : side of the windows, user units (:data:`WINDOW` spacings in the solver)
    """
    area = footprint_areas(arr, exemplar.prototypes)
    down = footprint_areas(Arrangement(kind, arr.xy, arr.angle, arr.scale), exemplar.prototypes) < area * (1 - 1e-9)
    if not down.any():
        return down
    ids, which = square_windows(arr.xy, window)
    room = stats.density * square_area(ids, window, region)
    inside = shapely.contains_xy(region.shape, arr.xy[:, 0], arr.xy[:, 1])
    cover = np.bincount(which[inside], weights=area[inside], minlength=len(ids))
    return down & (cover < room)[which]


def _keys(cells: np.ndarray) -> np.ndarray:
    """(c,) int64: one sortable key per integer cell ``(c, 2)`` (coordinates well within ±2³¹)."""
    return cells[:, 0] * (1 << 32) + cells[:, 1]
