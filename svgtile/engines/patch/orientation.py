"""Orientations in the patch engine: motifs of a turned copy (almeraj2013 §3.2) and new
orientations from each kind's arc (§3.5)."""

from __future__ import annotations

import numpy as np

from svgtile.analysis.stats import Stats, in_arcs
from svgtile.core.arrangement import DECIMALS, Arrangement


def turn(kind: np.ndarray, angle: np.ndarray, theta: np.ndarray, stats: Stats | None) -> np.ndarray:
    """Orientations, degrees, of motifs whose copy is turned by ``theta`` (all arrays (n,)).

    The paper turns every motif back by −θ, so the copy's rotation does not carry the
    orientations out of the exemplar's (§3.2); that changes the gaps between elongated motifs,
    whose positions turn but whose orientations do not.  Where ``angle + theta`` is still in the
    kind's exemplar arc (§3.5; e.g. any orientation of a kind drawn at all angles), turning the
    motif with its copy keeps the orientations inside the arcs *and* the copy rigid, so its gaps
    are the exemplar's.  Other motifs (and all of them without ``stats``) keep ``angle``.
    """
    if stats is None:
        return angle
    turned = (angle + theta + 180.0) % 360.0 - 180.0
    return np.where(in_arcs(turned, kind, stats, tol=0.0), turned, angle)


# ----------------------------------------------------------------------------- §3.5


def vary_orientations(arr: Arrangement, stats: Stats, u: np.ndarray) -> Arrangement:
    """New orientations, uniform in each kind's exemplar arc (almeraj2013 §3.5).

    A motif's position is its centroid, so changing its angle rotates it about its centroid.

    Parameters
    ----------
    u : (n,) floats in [0, 1), one per motif.
    """
    angle = stats.arc_start[arr.kind] + u * stats.arc_width[arr.kind]
    return arr.with_angle((angle + 180.0) % 360.0 - 180.0).quantized(DECIMALS)
