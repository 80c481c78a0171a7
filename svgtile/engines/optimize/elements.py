"""Several samples per elongated element (Ma, Wei & Tong 2011 §3.1).

A rigid, compact motif is one sample at its centroid.  An elongated motif — a dash, a stroke,
a reed: its footprint's minimum rotated rectangle at least :data:`ELONGATED` times as long as
wide — is two samples, one near each end of its long axis, with sample ids 1 and 2, so that its
orientation is carried by sample positions: neighbourhoods see which way a dash lies, and the
least squares of §4.3 turn it with its neighbours.  After the assignment, the motif is placed at
the middle of its samples and turned so that its axis runs from its sample 1 to its sample 2 —
the paper's "output samples as control points for placing and orienting" the input element
(motifs stay rigid here: no deformation).

A sample's attribute is ``kind · 3 + sample id`` (id 0 for a compact motif's one sample), so the
kind term of eq. (1) also keeps the ends of a dash apart.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import Prototype, rotation

#: Length over width from which a footprint is sampled at both ends, when asked for
#: (``Settings.elongated``; off by default: see :func:`layout`).
ELONGATED = 2.5


@dataclass(frozen=True, eq=False)
class Layout:
    """Where each kind's samples lie on it.

    Attributes
    ----------
    ends : (K, 2) float, user units at scale 1 — for an elongated kind, the offset of its sample 2
        from its centroid in the motif's frame (sample 1 at the opposite offset); zero for a
        compact kind
    elongated : (K,) bool
    """

    ends: np.ndarray
    elongated: np.ndarray

    def samples(self, arr: Arrangement) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The samples of ``arr``: positions (S, 2) user units, attributes (S,) int, and the
        motif each belongs to (S,) int, motif by motif (a motif's samples in id order)."""
        two = self.elongated[arr.kind]
        count = np.where(two, 2, 1)
        owner = np.repeat(np.arange(len(arr)), count)
        first = np.r_[0, np.cumsum(count)[:-1]]
        sid = np.arange(len(owner)) - first[owner]  # 0, or 0 and 1 for a two-sample motif
        sid = np.where(two[owner], sid + 1, 0)
        off = np.einsum("sij,sj->si", rotation(arr.angle[owner]), self.ends[arr.kind[owner]])
        off *= arr.scale[owner, None]
        xy = arr.xy[owner] + np.where(sid[:, None] == 1, -off, np.where(sid[:, None] == 2, off, 0.0))
        return xy, arr.kind[owner] * 3 + sid, owner

    def poses(self, arr: Arrangement, xy: np.ndarray, owner: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each motif's centroid (n, 2) user units, the angle of its axis (n,) degrees, and
        whether it had two samples (n,) bool, from its samples' positions ``xy`` (S, 2)."""
        n = len(arr)
        count = np.bincount(owner, minlength=n)
        centre = np.stack([np.bincount(owner, xy[:, 0], n), np.bincount(owner, xy[:, 1], n)], -1) / count[:, None]
        two = count == 2
        angle = arr.angle.copy()
        if two.any():
            first = np.r_[0, np.cumsum(count)[:-1]][two]
            d = xy[first + 1] - xy[first]
            e = self.ends[arr.kind[two]]
            angle[two] = np.degrees(np.arctan2(d[:, 1], d[:, 0]) - np.arctan2(e[:, 1], e[:, 0]))
            angle[two] = (angle[two] + 180.0) % 360.0 - 180.0
        return centre, angle, two


def layout(protos: list[Prototype], threshold: float = ELONGATED) -> Layout | None:
    """The sample layout of every kind, or None when no kind is elongated (one sample each).

    An elongated kind's two samples sit on its long axis, half a width in from each end (the
    centres of the end caps of a stroke).

    Off by default (``threshold`` 0): measured on dashes in straight rows of several directions
    (tests/test_optimize_elements.py) the dashes lie along their rows a little better (median
    misalignment 6.9° → 5.9°), but a few dashes at patch seams turn far, the bundled exemplars'
    likeness (centroids only) drops (shale 1.05 → 0.92) and till's density falls below 0.9.
    """
    k = len(protos)
    ends = np.zeros((k, 2))
    elongated = np.zeros(k, dtype=bool)
    if threshold <= 0:
        return None
    for i, p in enumerate(protos):  # once per kind, not per motif
        shape = shapely.union_all([shapely.polygons(r) for r in p.rings])
        box = shapely.get_coordinates(shapely.minimum_rotated_rectangle(shape))[:4]
        a, b = box[1] - box[0], box[2] - box[1]
        long, short = (a, b) if np.hypot(*a) >= np.hypot(*b) else (b, a)
        length, width = float(np.hypot(*long)), float(np.hypot(*short))
        if width > 0 and length >= threshold * width:
            elongated[i] = True
            ends[i] = long / length * (length - width) / 2
    return Layout(ends, elongated) if elongated.any() else None
