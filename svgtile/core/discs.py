"""Inscribed discs of a footprint: a few discs inside each prototype's outline, so that a pair of
motifs can often be found surely too close (or overlapping) without building their footprints.

One inscribed disc about the centroid (:attr:`svgtile.core.footprint.Prototype.inner`) decides
little for thin or concave motifs (marsh tufts, scrub, shale dashes: radius 0.13–0.21 against a
bounding radius of 2.1–2.5): their centroids lie in a thin stroke or outside the footprint.  A
few discs along the strokes do: if a disc of one motif and a disc of the other come closer than
the distance rule (almeraj2013 §3.1), so do the footprints, since each disc lies inside its
footprint.  Used by :func:`svgtile.core.conflicts.cross_pairs` to decide pairs before GEOS; the
decisions are the exact test's (the discs are shrunk by a margin far above rounding, and a pair
the discs do not decide goes to GEOS as before).
"""

from __future__ import annotations

import weakref

import numpy as np
import shapely

from svgtile.core.footprint import Prototype

#: At most this many discs per prototype.
MOST = 12

#: Discs per motif tried against the other motif of a pair (those nearest to its centroid).
PAIR = 2

#: Candidate disc centres per prototype part: a grid of about this many points over its box.
GRID = 1500

#: The most (candidate, outline point) pairs a kind's greedy cover may weigh (one float64 matrix
#: of this many entries, ≈ 0.16 GB, and two or three like it): a kind of many parts (a path of
#: a hundred dots has ≈ 10⁵ candidates against ≈ 2 × 10³ outline points) gets no discs, and
#: its pairs are decided by GEOS as before the discs.
MAX_PAIRS = 20_000_000


#: inscribed_discs' results, per prototype while it lives (kinds are few; a process may read many
#: exemplars, so the prototypes are not kept alive by it).
_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def inscribed_discs(proto: Prototype, most: int = MOST) -> tuple[np.ndarray, np.ndarray]:
    """Discs inside ``proto``'s outline (its rings filled, each part alone), local frame.

    Greedy cover (candidates: grid points inside a part, each with its distance to the part's
    ring as radius): each step takes the candidate that brings the outline nearest to the discs
    (the largest sum over outline points of the decrease of their distance to the discs), until
    ``most`` discs are chosen or the outline lies within 2 % of the radius of the discs.  Each radius is shrunk by 1e-9 × (1 + radius) so that
    the discs stay inside the outline after a motif's rotation, scaling and translation.

    Returns
    -------
    centre : (d, 2) float array, user units (local frame, scale 1)
    radius : (d,) float array, > 0
    """
    key = (most,)
    cached = _CACHE.get(proto)
    if cached is None or key not in cached:
        _CACHE.setdefault(proto, {})[key] = _discs(proto, most)
    return _CACHE[proto][key]


def _discs(proto: Prototype, most: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`inscribed_discs`, computed."""
    cands, radii = [], []
    for ring in proto.rings:
        poly = shapely.polygons(ring)
        x0, y0, x1, y1 = poly.bounds
        step = max(np.sqrt((x1 - x0) * (y1 - y0) / GRID), 1e-12)
        gx, gy = np.meshgrid(np.arange(x0 + step / 2, x1, step), np.arange(y0 + step / 2, y1, step))
        pts = np.stack([gx.ravel(), gy.ravel()], -1)
        inside = shapely.contains_xy(poly, pts[:, 0], pts[:, 1])
        pts = pts[inside]
        cands.append(pts)
        radii.append(shapely.distance(shapely.points(pts), shapely.get_exterior_ring(poly)))
    c, r = np.concatenate(cands), np.concatenate(radii)
    r = r - 1e-9 * (1.0 + proto.radius)
    c, r = c[r > 0], r[r > 0]
    if not len(c):
        return np.zeros((0, 2)), np.zeros(0)
    outline = np.concatenate(
        [shapely.get_coordinates(shapely.segmentize(shapely.linearrings(ring), proto.radius / 40)) for ring in proto.rings]
    )  # fmt: skip
    if len(c) * len(outline) > MAX_PAIRS:  # a kind of many parts: no discs, GEOS decides its pairs
        return np.zeros((0, 2)), np.zeros(0)
    # (candidates, outline points): how far each outline point lies outside each candidate disc
    outside = (
        np.hypot(c[:, None, 0] - outline[None, :, 0], c[:, None, 1] - outline[None, :, 1])
        - r[:, None]
    )
    chosen: list[int] = []
    gap = np.full(len(outline), proto.radius)  # each outline point's distance to the chosen discs
    for _ in range(most):
        gain = (gap[None, :] - np.minimum(gap[None, :], outside)).sum(axis=1)
        best = int(np.argmax(gain))
        if gain[best] <= 0 or gap.max() <= 0.02 * proto.radius:
            break
        chosen.append(best)
        gap = np.minimum(gap, outside[best])
    return c[chosen], r[chosen]


def disc_gap(
    xy_a: np.ndarray, angle_a: np.ndarray, scale_a: np.ndarray, discs_a: tuple[np.ndarray, np.ndarray],
    xy_b: np.ndarray, angle_b: np.ndarray, scale_b: np.ndarray, discs_b: tuple[np.ndarray, np.ndarray],
) -> np.ndarray:  # fmt: skip
    """(p,) float: the least gap ``|c_a − c_b| − r_a − r_b`` between a disc of motif a and one of
    motif b (a of one kind, b of one kind), user units; +inf for a kind without discs.

    The footprint distance is at most this gap, so a pair whose gap is below ``reach`` (minus a
    margin for the rounding of world coordinates) is surely closer than ``reach``, and one whose
    gap is below minus that margin surely shares area.  Of each motif's discs the :data:`PAIR`
    nearest to the other's centroid are tried, pairwise.

    Parameters
    ----------
    xy_*, angle_*, scale_* : (p, 2), (p,) degrees, (p,) the motifs' placements
    discs_* : their kind's :func:`inscribed_discs`
    """
    (ca, ra), (cb, rb) = discs_a, discs_b
    if not len(ra) or not len(rb):
        return np.full(len(xy_a), np.inf)
    ta, tb = np.radians(angle_a), np.radians(angle_b)
    dx, dy = xy_b[:, 0] - xy_a[:, 0], xy_b[:, 1] - xy_a[:, 1]
    ax, ay, ar = _nearest(np.cos(ta), np.sin(ta), scale_a, ca, ra, dx, dy, xy_a)  # (p, m) each
    bx, by, br = _nearest(np.cos(tb), np.sin(tb), scale_b, cb, rb, -dx, -dy, xy_b)
    d = np.hypot(ax[:, :, None] - bx[:, None, :], ay[:, :, None] - by[:, None, :])
    d -= ar[:, :, None] + br[:, None, :]
    return d.reshape(len(xy_a), -1).min(axis=1)


def _nearest(cos, sin, scale, centre, radius, dx, dy, xy):
    """World centres (x and y, (p, m) each) and radii (p, m) of the :data:`PAIR` discs (local
    ``centre`` (d, 2), ``radius`` (d,)) of p motifs at ``xy`` (p, 2), turned by ``cos``, ``sin``,
    scaled by ``scale`` (p,) each, whose centres lie nearest to the other motif's centroid, at
    ``(dx, dy)`` from ``xy``: the discs worth trying against it.  Chosen in the local frame (the
    offset turned back), by repeated arg-minima of squared distances."""
    if len(radius) <= PAIR:
        pick = np.broadcast_to(np.arange(len(radius)), (len(xy), len(radius)))
    else:
        lx, ly = (
            (cos * dx + sin * dy) / scale,
            (cos * dy - sin * dx) / scale,
        )  # Rᵀ (x_other − xy) / scale
        q = (centre[None, :, 0] - lx[:, None]) ** 2 + (centre[None, :, 1] - ly[:, None]) ** 2
        rows = np.arange(len(xy))
        pick = np.empty((len(xy), PAIR), dtype=np.int64)
        for n in range(PAIR):
            pick[:, n] = q.argmin(axis=1)
            q[rows, pick[:, n]] = np.inf
    local = centre[pick]  # (p, m, 2)
    c, s = (cos * scale)[:, None], (sin * scale)[:, None]
    wx = c * local[:, :, 0] - s * local[:, :, 1] + xy[:, 0, None]
    wy = s * local[:, :, 0] + c * local[:, :, 1] + xy[:, 1, None]
    return wx, wy, scale[:, None] * radius[pick]
