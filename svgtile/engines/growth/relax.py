"""Relaxation of the grown motifs towards their reference ring shapes (Ijiri et al. 2008, §5.5).

Each grown motif i copies a reference ring: its neighbours should sit at ``x_i + R_θi r_j^i``.
Relaxation moves the grown motifs to minimise eq. (5),

    Σ_i Σ_{j ∈ w(x_i)} ‖x_j − (x_i + r_j^i)‖²,

subject to eq. (6), x_k = x_k⁰ for the constrained motifs: the first motif grown, the motifs of
neighbouring cells grown before (they are held where they are) and motifs near a barrier.  The
correspondence j ↔ r_j^i is the placed motif nearest to each desired ring position, within
r_short — a motif that lost or gained an edge during growth simply has fewer terms, as the paper
uses the current neighbourhood where the topology changed.

The problem is a sparse linear least-squares problem, one for x and one for y with the same
matrix; the constraints are eliminated (their columns move to the right-hand side — the
Lagrange system of the paper reduced to its unknowns) and the normal equations ``AᵀA x = Aᵀb``
are solved with a sparse direct solver.  A small pull λ·‖x − x⁰‖² keeps parts with no
constrained motif (and the null space of a lone motif) in place.

On a drawn exemplar of rows a third term holds each grown motif on its row line
(:mod:`.rows`): ``ROW_WEIGHT · (x_i · n − u_i)²`` with ``n`` the unit vector across the rows and
``u_i`` the line nearest the motif plus its exemplar motif's offset from its line.  The problem
is then solved in the rows' frame (along, across), where the term touches only the across
coordinate: the same matrix for along, the matrix plus ``ROW_WEIGHT`` on the diagonal across.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve
from scipy.spatial import cKDTree

from svgtile.engines.growth import kernel
from svgtile.engines.growth.connectivity import Rings
from svgtile.engines.growth.rows import ROW_WEIGHT, RowLines

#: Weight of the pull towards the current positions (relative to one ring term).
PULL = 1e-3


def relax(rings: Rings, xy: np.ndarray, ring: np.ndarray, theta: np.ndarray, first: int,
          held: np.ndarray | None = None, *, rows: RowLines | None = None) -> np.ndarray:  # fmt: skip
    """Relaxed positions of the grown motifs (eq. 5–6).

    Parameters
    ----------
    rings : the reference ring shapes
    xy : (n, 2) float array, user units — every motif: ``first`` fixed ones, then the grown ones
    ring, theta : (n − first,) int and float arrays — each grown motif's reference ring and the
        rotation applied to it (radians)
    first : how many leading motifs of ``xy`` are fixed; the first grown one is fixed too
    held : (n − first,) bool array, optional — grown motifs also held (near a barrier)
    rows : the exemplar's row lines, optional — hold the grown motifs on them (module docstring)

    Returns
    -------
    (n − first, 2) float array: the grown motifs' new positions
    """
    n = len(xy)
    g = n - first
    if g <= 1:
        return xy[first:].copy()
    i, want = kernel.ring_slots(rings.rel, rings.size, np.asarray(ring, np.int64), np.cos(theta), np.sin(theta), first)
    dist, j = cKDTree(xy).query(xy[i] + want, distance_upper_bound=rings.short_length / 2)
    ok = np.isfinite(dist) & (j != i)
    i, j, want = i[ok], j[ok], want[ok]
    fixed = np.zeros(n, bool)
    fixed[: first + 1] = True
    if held is not None:
        fixed[first:] |= held
    free = np.flatnonzero(~fixed)
    if not len(free) or not len(i):
        return xy[first:].copy()
    col = np.full(n, -1)
    col[free] = np.arange(len(free))
    if rows is not None:
        return _relax_on_rows(rows, rings.element[ring], xy, i, j, want, fixed, free, col, first)
    # row e: x_j − x_i = want_e; fixed ends move to the right-hand side
    b = want.copy()
    b -= np.where(fixed[j, None], xy[j], 0.0)
    b += np.where(fixed[i, None], xy[i], 0.0)
    N, rhs = _normal_equations(col[i], col[j], b, len(free))
    rhs += PULL * xy[free]
    out = xy.copy()
    out[free] = spsolve(N, rhs)  # one factorisation for both coordinates
    return out[first:]


def _relax_on_rows(rows: RowLines, sub: np.ndarray, xy: np.ndarray, i: np.ndarray, j: np.ndarray,
                   want: np.ndarray, fixed: np.ndarray, free: np.ndarray, col: np.ndarray, first: int,
                   ) -> np.ndarray:  # fmt: skip
    """:func:`relax` with the row term, solved in the rows' frame (arguments as set up there;
    ``sub``: (n − first,) int, the exemplar motif each grown motif copies)."""
    frame = np.stack([rows.along, rows.across])  # rows: the frame's axes, so q = xy @ frame.T
    q = xy @ frame.T
    b = want @ frame.T
    b -= np.where(fixed[j, None], q[j], 0.0)
    b += np.where(fixed[i, None], q[i], 0.0)
    N, rhs = _normal_equations(col[i], col[j], b, len(free))
    rhs += PULL * q[free]
    out = q.copy()
    out[free, 0] = spsolve(N, rhs[:, 0])
    target = rows.target(xy[free], sub[free - first])
    out[free, 1] = spsolve((N + ROW_WEIGHT * sp.identity(len(free), format="csc")).tocsc(),
                           rhs[:, 1] + ROW_WEIGHT * target)  # fmt: skip
    return (out @ frame)[first:]


def _normal_equations(ci: np.ndarray, cj: np.ndarray, b: np.ndarray, f: int) -> tuple[sp.csc_matrix, np.ndarray]:
    """``AᵀA + λI`` and ``Aᵀb`` of the rows ``x_cj − x_ci = b`` over ``f`` unknowns, assembled
    directly (−1 marks a fixed end, whose term is already in ``b``).

    ``A`` has +1 at ``cj`` and −1 at ``ci`` in each row, so ``AᵀA`` counts on its diagonal the rows
    each unknown is in and holds −(rows joining p and q) off it: the values, the structure (in
    the canonical order ``spsolve`` sorts a matrix into) and the summation order of ``Aᵀb`` that
    the ``scipy.sparse`` products give, bit for bit, without building ``A`` (tests/test_growth_kernel.py).

    Parameters
    ----------
    ci, cj : (e,) int arrays — each row's unknowns (−1: fixed)
    b : (e, 2) float array, user units
    f : number of unknowns
    """
    data, indices, indptr, rhs = kernel.normal_equations(np.asarray(ci, np.int64), np.asarray(cj, np.int64),
                                                         np.ascontiguousarray(b, np.float64), f, PULL)  # fmt: skip
    N = sp.csc_matrix((data, indices, indptr), shape=(f, f))
    return N, rhs
