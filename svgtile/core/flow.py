"""A flow field drawn as strokes: the direction motifs and courses follow, everywhere in a region.

Ijiri, Měch, Igarashi & Miller 2008, §5.3 and §6 (the flow-field tool): the user draws strokes,
their tangents are interpolated over the whole domain by radial basis functions, and each
element's local x axis follows the interpolated direction.  The same field turns the copies of
the patch engine, the local frames of the optimize engine (Ma, Wei & Tong 2011 §5, eq. 7) and
the courses of the cellular engine (Legakis, Dorsey & Gortler 2001 §3.2): one module, so that
``--flow`` means the same thing to every engine that honours it.

Interpolation is of the *unit tangent* (cos θ, sin θ) sampled along the strokes, with scipy's
:class:`~scipy.interpolate.RBFInterpolator` (the polyharmonic kernel −r with a constant term,
which, unlike the thin-plate spline, stays solvable on samples of one straight stroke; a small
smoothing so that crossing strokes do not ring), then normalised back to unit length.  Where the interpolated
vector nearly vanishes (two strokes drawn in opposite directions side by side) the tangent of the
nearest stroke sample is used instead.  Stroke direction matters: a motif turned by the field
points the way its stroke was drawn.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from svgtile.errors import ParameterError

#: Interpolated tangents shorter than this are replaced by the nearest sample's.
_DEGENERATE = 1e-3
#: Each query is interpolated from at most this many nearest samples (a local RBF: cost linear
#: in the number of queries, not in their product with the samples).
_NEIGHBOURS = 64


@dataclass(frozen=True, eq=False)
class FlowField:
    """A smooth unit direction field interpolated from stroke tangents.

    Attributes
    ----------
    points : (m, 2) float array, user units — where tangents were sampled along the strokes
    tangents : (m, 2) float array — the unit tangents there
    """

    points: np.ndarray
    tangents: np.ndarray

    @classmethod
    def from_strokes(cls, strokes: Sequence[np.ndarray], *, spacing: float | None = None,
                     source: str = "--flow") -> FlowField:  # fmt: skip
        """The field of ``strokes``.

        Parameters
        ----------
        strokes : sequence of (k, 2) float arrays, user units — polylines in drawing order
        spacing : distance between tangent samples along a stroke, user units; default 1/50 of
            the strokes' overall extent
        source : how errors name where the strokes came from

        Raises
        ------
        ParameterError
            No stroke of non-zero length.
        """
        lines = [np.asarray(s, dtype=np.float64).reshape(-1, 2) for s in strokes]
        lines = [s for s in lines if len(s) >= 2 and np.all(np.isfinite(s))]
        seg = [np.diff(s, axis=0) for s in lines]
        if not lines or not any(np.hypot(*d.T).sum() > 0 for d in seg):
            raise ParameterError(f"{source}: no stroke of non-zero length to take a direction from")
        allpts = np.concatenate(lines)
        extent = float(np.ptp(allpts, axis=0).max()) or 1.0
        step = spacing if spacing and spacing > 0 else extent / 50.0
        pts, tans = [], []
        for s, d in zip(lines, seg, strict=True):
            length = np.hypot(d[:, 0], d[:, 1])
            keep = length > 0
            s0, d, length = s[:-1][keep], d[keep], length[keep]
            if not len(d):
                continue
            arc = np.concatenate([[0.0], np.cumsum(length)])
            at = np.linspace(0.0, arc[-1], max(2, int(np.ceil(arc[-1] / step)) + 1))
            i = np.clip(np.searchsorted(arc, at, side="right") - 1, 0, len(d) - 1)
            frac = ((at - arc[i]) / length[i])[:, None]
            pts.append(s0[i] + frac * d[i])
            tans.append(d[i] / length[i][:, None])
        points = np.concatenate(pts)
        tangents = np.concatenate(tans)
        points, first = np.unique(points, axis=0, return_index=True)  # RBF needs distinct sites
        return cls(points, tangents[first])

    @classmethod
    def uniform(cls, angle: float) -> FlowField:
        """A constant field at ``angle`` degrees (counter-clockwise from +x in user space)."""
        t = np.radians(angle)
        return cls(np.zeros((1, 2)), np.array([[np.cos(t), np.sin(t)]]))

    def direction(self, xy: np.ndarray) -> np.ndarray:
        """Unit directions at ``xy``.

        Parameters
        ----------
        xy : (n, 2) float array, user units

        Returns
        -------
        (n, 2) float array of unit vectors
        """
        xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        if len(self.points) < 2:  # one site: its tangent everywhere
            return self._nearest(xy)
        # imported here: scipy.interpolate costs every svgtile command ~0.2 s to import
        from scipy.interpolate import RBFInterpolator

        rbf = RBFInterpolator(self.points, self.tangents, kernel="linear", degree=0, smoothing=1e-3,
                              neighbors=min(_NEIGHBOURS, len(self.points)))  # fmt: skip
        v = rbf(xy) if len(xy) else np.zeros((0, 2))
        norm = np.hypot(v[:, 0], v[:, 1])
        bad = norm < _DEGENERATE
        v = v / np.where(bad, 1.0, norm)[:, None]
        if bad.any():
            v[bad] = self._nearest(xy[bad])
        return v

    def angle(self, xy: np.ndarray) -> np.ndarray:
        """Directions at ``xy`` as angles, (n,) float array, degrees in (−180, 180]."""
        v = self.direction(xy)
        return np.degrees(np.arctan2(v[:, 1], v[:, 0]))

    def _nearest(self, xy: np.ndarray) -> np.ndarray:
        _, i = cKDTree(self.points).query(xy)
        return self.tangents[np.asarray(i, dtype=np.intp)]
