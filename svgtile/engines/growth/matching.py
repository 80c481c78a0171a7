"""Finding the best-matching reference element for a seed (Ijiri et al. 2008, §5.2–5.3).

The seed's placed neighbours (its target ring, counter-clockwise from the element on the ring's
open side) are compared with every reference ring of at least as many neighbours (§5.2: a
reference ring smaller than the target is ignored), under every cyclic shift of the reference
— matching without skipping or flipping — with the error of eq. (2):

    error = Σ_i  w1 · |t_i − R_θ r_(k+i)| / l  +  w2 · [kind differs]  +  w3 · [sub-id equal]

(positions are divided by the exemplar's mean edge length l so that w1 = w2 = 1 weigh a
mismatch of one edge length like one wrong kind), minimised over the shifts (eq. 3) and the
references (eq. 1).  The rotation R_θ depends on the mode (§5.3): none (θ = 0), fit (the θ of
eq. (4) in closed form: the 2-D orthogonal Procrustes angle of the matched pairs, as in the
shape matching of Müller et al. 2005), or flow (θ = the flow field's angle at the seed).

The loop over references × shifts × ring slots is compiled (:func:`svgtile.engines.growth.kernel.match`,
called once per seed by the growth loop); :func:`best_match` is its entry from Python.
"""

from __future__ import annotations

import numpy as np

from svgtile.engines.growth import Weights, kernel
from svgtile.engines.growth.connectivity import Rings

#: The rotation modes of §5.3 by name.
ROTATION_MODES = {"none": kernel.NONE, "fit": kernel.FIT, "flow": kernel.FLOW}


def best_match(rings: Rings, tar: np.ndarray, tkind: np.ndarray, tsub: np.ndarray, *, want: int,
               rotation: str, flow_angle: float, weights: Weights, noise: np.ndarray,
               top: int = 1) -> list[tuple[int, int, float, float]]:  # fmt: skip
    """The reference ring, shift and rotation that best fit a seed's placed neighbours.

    Parameters
    ----------
    rings : the reference ring shapes
    tar : (t, 2) float array, user units — the target neighbours relative to the seed, in ring
        order (:func:`svgtile.engines.growth.connectivity.ring_of`)
    tkind, tsub : (t,) int arrays — their kinds and sub-ids
    want : the kind the seed must become, or −1 for any (§5.1's seed symbol id)
    rotation : ``none``, ``fit`` or ``flow`` (§5.3)
    flow_angle : radians, the flow's direction at the seed (``flow`` mode)
    weights : eq. (2)'s weights
    noise : (r,) float array in [0, 1) — breaks ties between equally good references (a
        world-anchored hash, so the choice is reproducible)
    top : how many of the best (reference, shift) pairs to return

    Returns
    -------
    list of up to ``top`` tuples ``(ring, shift, theta, error)``, best first (empty when no
    reference qualifies): ``ring`` indexes ``rings``, ``shift`` is k, the reference slot matched
    with the first target neighbour, ``theta`` the rotation applied to the reference ring
    (radians), ``error`` the error of eq. (3)
    """
    if rotation not in ROTATION_MODES:
        raise ValueError(f"rotation must be one of {', '.join(ROTATION_MODES)}, not {rotation!r}")
    out_r, out_k = np.empty(top, np.int64), np.empty(top, np.int64)
    out_theta, out_err = np.empty(top), np.empty(top)
    got = kernel.match(rings.rel, rings.size, rings.kind, rings.nkind, rings.nsub, rings.mean_length,
                       np.ascontiguousarray(tar, float).reshape(-1, 2), np.asarray(tkind, np.int64),
                       np.asarray(tsub, np.int64), want, ROTATION_MODES[rotation], float(flow_angle),
                       weights.distance, weights.kind, weights.subid, np.asarray(noise, float), top,
                       out_r, out_k, out_theta, out_err)  # fmt: skip
    return [(int(out_r[i]), int(out_k[i]), float(out_theta[i]), float(out_err[i])) for i in range(got)]
