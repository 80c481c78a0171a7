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
  still conflicts to its previous state.  The previous state had no conflict, so this ends
  with none, keeps every motif, and the output keeps every invariant of every engine.
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


def _troubled(arr: Arrangement, moved: np.ndarray, exemplar: Exemplar, stats: Stats, region: Region,
              boundary: str) -> np.ndarray:  # fmt: skip
    """(n,) bool: moved elements that conflict, or that the boundary mode would drop."""
    bad = np.zeros(len(arr), dtype=bool)
    if not moved.any():
        return bad
    c = find_conflicts(arr, exemplar.prototypes, stats.distance)
    bad[c.i] = bad[c.j] = True
    sel = np.flatnonzero(moved)
    bad[sel[~region.keep(arr.take(sel), exemplar.prototypes, boundary)]] = True
    return bad & moved


def settle(prev: Arrangement, new: Arrangement, exemplar: Exemplar, stats: Stats, region: Region,
           boundary: str) -> tuple[Arrangement, int]:  # fmt: skip
    """``new`` with no overlaps, no distance-rule violations and nothing the boundary drops.

    Parameters
    ----------
    prev : the previous arrangement, free of conflicts and kept by the boundary mode
    new : the same elements after an assignment (same order)

    Returns
    -------
    the settled arrangement, and how many elements were returned to their previous state
    """
    cur = new
    same = lambda a: ((a.kind == prev.kind) & (a.xy == prev.xy).all(axis=1)  # noqa: E731
                      & (a.angle == prev.angle) & (a.scale == prev.scale))  # fmt: skip
    for _ in range(RELAX_STEPS):
        bad = _troubled(cur, ~same(cur), exemplar, stats, region, boundary)
        if not bad.any():
            return cur, 0
        xy = cur.xy.copy()
        xy[bad] = (cur.xy[bad] + prev.xy[bad]) / 2
        cur = Arrangement(cur.kind, np.round(xy, DECIMALS), cur.angle, cur.scale)
    back = 0
    while True:
        bad = _troubled(cur, ~same(cur), exemplar, stats, region, boundary)
        if not bad.any():
            return cur, back
        back += int(bad.sum())
        kind, xy, angle, scale = cur.kind.copy(), cur.xy.copy(), cur.angle.copy(), cur.scale.copy()
        kind[bad], xy[bad], angle[bad], scale[bad] = prev.kind[bad], prev.xy[bad], prev.angle[bad], prev.scale[bad]
        cur = Arrangement(kind, xy, angle, scale)
