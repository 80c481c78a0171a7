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

import functools

import numpy as np
import shapely

from svgtile.core.footprint import Prototype

#: At most this many discs per prototype.
MOST = 12

#: Discs per motif tried against the other motif of a pair (those nearest to its centroid).
PAIR = 2

#: Candidate disc centres per prototype part: a grid of about this many points over its box.
GRID = 1500


@functools.cache
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
    # (candidates, outline points): how far each outline point lies outside each candidate disc
    outside = np.hypot(c[:, None, 0] - outline[None, :, 0], c[:, None, 1] - outline[None, :, 1]) - r[:, None]
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
    wa, sa = _nearest(xy_a, angle_a, scale_a, ca, ra, xy_b)  # (p, m, 2), (p, m)
    wb, sb = _nearest(xy_b, angle_b, scale_b, cb, rb, xy_a)
    d = np.hypot(wa[:, :, None, 0] - wb[:, None, :, 0], wa[:, :, None, 1] - wb[:, None, :, 1])
    d -= sa[:, :, None] + sb[:, None, :]
    return d.reshape(len(xy_a), -1).min(axis=1)


def _nearest(xy, angle, scale, centre, radius, to) -> tuple[np.ndarray, np.ndarray]:
    """World centres (p, m, 2) and radii (p, m) of the :data:`PAIR` discs (local ``centre`` (d, 2),
    ``radius`` (d,)) of motifs at ``xy``, ``angle``, ``scale`` whose edges come nearest to the
    points ``to`` (p, 2): the discs worth trying against the other motif.  Chosen in the local
    frame (``to`` turned back), by repeated arg-minima."""
    if len(radius) <= PAIR:
        pick = np.broadcast_to(np.arange(len(radius)), (len(xy), len(radius)))
    else:
        a = np.radians(angle)
        c, s = np.cos(a), np.sin(a)
        dx, dy = to[:, 0] - xy[:, 0], to[:, 1] - xy[:, 1]
        lx, ly = (c * dx + s * dy) / scale, (c * dy - s * dx) / scale  # Rᵀ (to − xy) / scale
        gap = np.hypot(centre[None, :, 0] - lx[:, None], centre[None, :, 1] - ly[:, None]) - radius[None, :]
        rows = np.arange(len(xy))
        pick = np.empty((len(xy), PAIR), dtype=np.int64)
        for n in range(PAIR):
            pick[:, n] = gap.argmin(axis=1)
            gap[rows, pick[:, n]] = np.inf
    local = centre[pick]  # (p, m, 2)
    a = np.radians(angle)
    c, s = (np.cos(a) * scale)[:, None], (np.sin(a) * scale)[:, None]
    out = np.empty(local.shape)
    out[:, :, 0] = c * local[:, :, 0] - s * local[:, :, 1] + xy[:, 0, None]
    out[:, :, 1] = s * local[:, :, 0] + c * local[:, :, 1] + xy[:, 1, None]
    return out, scale[:, None] * radius[pick]
