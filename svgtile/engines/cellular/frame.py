"""The face's parameterisation (legakis2001 §3.2): a course frame (s, t), mapped both ways.

Courses run along ``s``; ``t`` counts across them (course ``j`` lies in ``j·h ≤ t < (j+1)·h``).
The paper requires of every parameterisation a *mapping* from parameter space to the world (to
place the cells made there) and a *projection* from the world to parameter space (to fill
occupancy maps); both frames here give both.

* :class:`RotatedFrame` — courses along a fixed bearing: a strike angle, or the unit's long axis.
  Anchored at the world origin, so two units with the same strike share their courses.
* :class:`FlowFrame` — courses following a flow field (:class:`~svgtile.core.flow.FlowField`,
  the ``--flow`` control): ``t`` is the least-squares potential whose gradient is the flow's
  normal, ``s`` the one whose gradient is the flow (on a grid of half a course), so the level
  lines of ``t`` — the course boundaries — run along the flow.  Projection interpolates the grid;
  mapping interpolates the grid's (s, t) back to the world (a Delaunay triangulation).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import shapely
from scipy.interpolate import LinearNDInterpolator, RegularGridInterpolator
from scipy.sparse.linalg import lsqr

from svgtile.core.flow import FlowField


@dataclass(frozen=True, eq=False)
class RotatedFrame:
    """Courses along the bearing ``angle`` (degrees, from +x towards +y), through the origin."""

    angle: float

    def project(self, xy: np.ndarray) -> np.ndarray:
        """(n, 2) world points -> (n, 2) parameters (s, t), user units."""
        c, s = math.cos(math.radians(self.angle)), math.sin(math.radians(self.angle))
        xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        return np.stack([xy[:, 0] * c + xy[:, 1] * s, -xy[:, 0] * s + xy[:, 1] * c], axis=1)

    def map(self, st: np.ndarray) -> np.ndarray:
        """(n, 2) parameters (s, t) -> (n, 2) world points, user units."""
        c, s = math.cos(math.radians(self.angle)), math.sin(math.radians(self.angle))
        st = np.asarray(st, dtype=np.float64).reshape(-1, 2)
        return np.stack([st[:, 0] * c - st[:, 1] * s, st[:, 0] * s + st[:, 1] * c], axis=1)

    def course_angle(self, xy: np.ndarray) -> np.ndarray:
        """(n,) the courses' bearing at ``xy``, degrees."""
        return np.full(len(np.asarray(xy).reshape(-1, 2)), float(self.angle))


def long_axis_angle(shape: shapely.Geometry) -> float:
    """Bearing of the unit's long axis, degrees in [0, 180): the long side of its minimum rotated
    rectangle."""
    rect = np.asarray(shapely.minimum_rotated_rectangle(shape).exterior.coords)[:3]
    a, b = rect[1] - rect[0], rect[2] - rect[1]
    v = a if np.hypot(*a) >= np.hypot(*b) else b
    return float(np.degrees(np.arctan2(v[1], v[0])) % 180.0)


class FlowFrame:
    """Courses following ``flow`` over ``shape`` (see the module docstring).

    Parameters
    ----------
    flow : the flow field
    shape : the face, user units
    step : grid spacing, user units (half a course height is fine enough: courses bend slowly)
    """

    def __init__(self, flow: FlowField, shape: shapely.Geometry, step: float) -> None:
        x0, y0, x1, y1 = shapely.bounds(shape)
        pad = 2 * step
        xs = np.arange(math.floor((x0 - pad) / step), math.ceil((x1 + pad) / step) + 1) * step
        ys = np.arange(math.floor((y0 - pad) / step), math.ceil((y1 + pad) / step) + 1) * step
        gx, gy = np.meshgrid(xs, ys, indexing="ij")
        nodes = np.stack([gx.ravel(), gy.ravel()], axis=1)
        d = flow.direction(nodes)
        normal = np.stack([-d[:, 1], d[:, 0]], axis=1)
        self.s = _potential(d, len(xs), len(ys), step)
        self.t = _potential(normal, len(xs), len(ys), step)
        # anchor both at the grid point nearest the world origin's projection: the lowest corner
        self._s = RegularGridInterpolator((xs, ys), self.s.reshape(len(xs), len(ys)), bounds_error=False, fill_value=None)
        self._t = RegularGridInterpolator((xs, ys), self.t.reshape(len(xs), len(ys)), bounds_error=False, fill_value=None)
        self._flow = flow
        st = np.stack([self.s, self.t], axis=1)
        self._inverse = LinearNDInterpolator(st, nodes)

    def project(self, xy: np.ndarray) -> np.ndarray:
        xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        return np.stack([self._s(xy), self._t(xy)], axis=1)

    def map(self, st: np.ndarray) -> np.ndarray:
        """(n, 2) parameters -> world points; NaN outside the grid."""
        return self._inverse(np.asarray(st, dtype=np.float64).reshape(-1, 2))

    def course_angle(self, xy: np.ndarray) -> np.ndarray:
        return self._flow.angle(np.asarray(xy, dtype=np.float64).reshape(-1, 2))


def _potential(g: np.ndarray, nx: int, ny: int, step: float) -> np.ndarray:
    """(nx·ny,) the potential φ on the grid whose gradient is closest to ``g`` (least squares,
    φ = 0 at node 0): Σ (φ_{i+1,j} − φ_{i,j} − h·ḡx)² + (φ_{i,j+1} − φ_{i,j} − h·ḡy)², ḡ the mean
    of ``g`` at the two nodes."""
    idx = np.arange(nx * ny).reshape(nx, ny)
    a, b = idx[:-1, :].ravel(), idx[1:, :].ravel()
    c, d = idx[:, :-1].ravel(), idx[:, 1:].ravel()
    m1, m2 = len(a), len(c)
    rows = np.r_[np.arange(m1), np.arange(m1), m1 + np.arange(m2), m1 + np.arange(m2), m1 + m2]
    cols = np.r_[b, a, d, c, 0]
    vals = np.r_[np.ones(m1), -np.ones(m1), np.ones(m2), -np.ones(m2), 1.0]
    A = sp.csr_matrix((vals, (rows, cols)), shape=(m1 + m2 + 1, nx * ny))
    rhs = np.r_[step * (g[a, 0] + g[b, 0]) / 2, step * (g[c, 1] + g[d, 1]) / 2, 0.0]
    return lsqr(A, rhs, atol=1e-10, btol=1e-10, iter_lim=20 * (nx + ny) + 200)[0]
