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

Everything is vectorised over references × shifts × ring slots: one call costs a few small
numpy operations whatever the exemplar.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from svgtile.engines.growth.connectivity import Rings


@dataclass(frozen=True)
class Weights:
    """Weights of eq. (2).

    The paper uses w1 = w2 = 1, w3 = 100 on hand-made irregular references.  On a repeating tile
    each element's ring is the only faithful continuation, and the sub-id term (1 when a target
    neighbour and the reference neighbour it is matched with are the same exemplar motif) would
    forbid exactly that; so w3 defaults to 0 and is a library setting.
    """

    distance: float = 1.0
    kind: float = 1.0
    subid: float = 0.0


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
    t = len(tar)
    ok = rings.size >= t
    if want >= 0:
        ok &= rings.kind == want
    cand = np.flatnonzero(ok)
    if not len(cand):
        return []
    M = rings.rel.shape[1]
    size = rings.size[cand]
    if t == 0:
        theta = flow_angle if rotation == "flow" else 0.0
        return [(int(r), 0, theta, 0.0) for r in cand[np.argsort(noise[cand])[:top]]]
    shift = np.arange(M)
    ref = rings.rolled[cand, :, :t]  # (c, M, t, 2): reference slot k + i for target neighbour i
    if rotation == "fit":
        dot = (ref * tar).sum(-1).sum(-1)
        cross = (ref[..., 0] * tar[:, 1] - ref[..., 1] * tar[:, 0]).sum(-1)
        theta = np.arctan2(cross, dot)  # (c, M), eq. (4)
    else:
        theta = np.full((len(cand), M), flow_angle if rotation == "flow" else 0.0)
    c, s = np.cos(theta)[..., None], np.sin(theta)[..., None]
    rx = c * ref[..., 0] - s * ref[..., 1]
    ry = s * ref[..., 0] + c * ref[..., 1]
    err = weights.distance * np.hypot(rx - tar[:, 0], ry - tar[:, 1]).sum(-1) / rings.mean_length
    if weights.kind:
        err = err + weights.kind * (rings.rolled_kind[cand, :, :t] != tkind).sum(-1)
    if weights.subid:
        err = err + weights.subid * (rings.rolled_sub[cand, :, :t] == tsub).sum(-1)
    err = np.where(shift[None, :] < size[:, None], err, np.inf)
    err = err + 1e-9 * noise[cand][:, None]  # ties: a reproducible random reference
    flat = err.ravel()
    best = np.argsort(flat)[:top] if top > 1 else np.array([np.argmin(flat)])
    out = []
    for f in best:
        i, k = divmod(int(f), M)
        if np.isfinite(err[i, k]):
            out.append((int(cand[i]), k, float(theta[i, k]), float(err[i, k])))
    return out
