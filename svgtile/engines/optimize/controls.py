"""Controls (Ma, Wei & Tong 2011 §5) and the interleaved non-penetration step.

* Local orientation (§5, eq. (7)): with a flow field, each output neighbourhood is turned into
  the exemplar's frame by the field's angle at its element before it is compared, predictions are
  turned back, and motifs take their sample's angle plus the field's (:func:`local_turn`).
* Domain shape (§5, eq. (6)): the region is a hard constraint here — an element that would leave
  what the boundary mode keeps is moved back (see :func:`settle`); output neighbourhoods at the
  region's edge are one-sided and so match exemplar samples at the exemplar's edge, which is the
  paper's constrained selection for a non-repeating exemplar.
* Non-penetration: the paper runs physics sub-steps; :func:`settle` instead relaxes each
  conflicting element halfway back to where it was, a few times, and finally returns whatever
  still conflicts to its previous state.  A conflict counts only if the previous state did not
  have it, so this ends with no new one, keeps every motif, and an engine's output (which has
  none) keeps every invariant of every engine.
"""

from __future__ import annotations

import numpy as np

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.flow import FlowField
from svgtile.core.region import Region

#: Halfway-back relaxation sub-steps before conflicting elements are returned to their place.
RELAX_STEPS = 2


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


def flawed(arr: Arrangement, exemplar: Exemplar, stats: Stats) -> np.ndarray:
    """(n,) bool: elements in a distance-rule violation (not an overlap) — a start that is not
    an engine's output, such as a jittered lattice, whose elements must pass each other by."""
    codes, overlap = conflict_codes(arr, exemplar, stats)
    out = np.zeros(len(arr), dtype=bool)
    out[codes[~overlap] // len(arr)] = out[codes[~overlap] % len(arr)] = True
    return out


def _troubled(arr: Arrangement, moved: np.ndarray, known: np.ndarray, lax: np.ndarray, exemplar: Exemplar,
              stats: Stats, region: Region, boundary: str) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """(n,) bool: moved elements in a conflict the previous state did not have (``known``) —
    bar a violation between two ``lax`` elements — or that the boundary mode would drop; and
    the conflict codes of ``arr``."""
    n = len(arr)
    bad = np.zeros(n, dtype=bool)
    if not moved.any():
        return bad, known
    codes, overlap = conflict_codes(arr, exemplar, stats)
    i, j = codes // n, codes % n
    new = ~np.isin(codes, known) & (overlap | ~(lax[i] & lax[j]))
    bad[i[new]] = bad[j[new]] = True
    sel = np.flatnonzero(moved)
    bad[sel[~region.keep(arr.take(sel), exemplar.prototypes, boundary)]] = True
    return bad & moved, codes


def settle(prev: Arrangement, new: Arrangement, exemplar: Exemplar, stats: Stats, region: Region,
           boundary: str, known: np.ndarray, lax: np.ndarray) -> tuple[Arrangement, np.ndarray]:  # fmt: skip
    """``new`` with no conflict that ``prev`` did not have and nothing the boundary drops.

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
    the settled arrangement, and its conflict codes (a subset of ``known``, with the pairs a move
    has broken up removed)
    """
    cur = new
    same = lambda a: ((a.kind == prev.kind) & (a.xy == prev.xy).all(axis=1)  # noqa: E731
                      & (a.angle == prev.angle) & (a.scale == prev.scale))  # fmt: skip
    for _ in range(RELAX_STEPS):
        bad, codes = _troubled(cur, ~same(cur), known, lax, exemplar, stats, region, boundary)
        if not bad.any():
            return cur, codes
        xy = cur.xy.copy()
        xy[bad] = (cur.xy[bad] + prev.xy[bad]) / 2
        cur = Arrangement(cur.kind, np.round(xy, DECIMALS), cur.angle, cur.scale)
    while True:
        bad, codes = _troubled(cur, ~same(cur), known, lax, exemplar, stats, region, boundary)
        if not bad.any():
            return cur, codes
        kind, xy, angle, scale = cur.kind.copy(), cur.xy.copy(), cur.angle.copy(), cur.scale.copy()
        kind[bad], xy[bad], angle[bad], scale[bad] = prev.kind[bad], prev.xy[bad], prev.angle[bad], prev.scale[bad]
        cur = Arrangement(kind, xy, angle, scale)
