"""The base mesh of a map unit (legakis2001 §3.1): corners, edges with labels, the face.

On a map, a unit polygon is the paper's model in 2-D: its *face* is the polygon (holes are holes,
as the paper's window in a wall), its *edges* are the runs of boundary between corners, every
ring included, and its *corners* are the vertices where the boundary turns by more than a
threshold.  A ring that never turns that sharply (a lake's shore) is one closed edge without
corners.  Rings are oriented with the face on their left, so the left normal of every edge points
into the face and the sign of the turn at a corner says convex (left turn) or reflex (right turn).

Edges carry *labels* (§3.1: "stored as strings, attached to features"): an edge takes the name of
a labelled map line (a fault, a coastline, a unit contact) that runs along most of it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
import shapely.ops

from svgtile.core.cells import geometry_array

#: An edge is labelled when at least this share of its length lies near the labelled line …
LABEL_SHARE = 0.5


@dataclass(frozen=True, eq=False)
class BaseMesh:
    """Corners, edges and the face of one map unit.

    Attributes
    ----------
    face : shapely Polygon or MultiPolygon, user units
    rings : list of (m, 2) float arrays, each ring's vertices (not closed), face on the left
    corner_ring, corner_vertex : (c,) int arrays, the ring and vertex index of each corner
    corner_xy : (c, 2) float array, user units
    corner_turn : (c,) float array, degrees, the boundary's turn there: > 0 convex, < 0 reflex
    edge_ring : (e,) int array, the ring of each edge
    edge_start, edge_end : (e,) float arrays, arc lengths on the ring where the edge runs (the
        end may exceed the ring's length for the edge that wraps past the ring's start)
    edges : (e,) object array of LineStrings, each edge's geometry from corner to corner
    labels : (e,) object array of str, each edge's label ("" for none)
    """

    face: shapely.Geometry
    rings: list[np.ndarray]
    corner_ring: np.ndarray
    corner_vertex: np.ndarray
    corner_xy: np.ndarray
    corner_turn: np.ndarray
    edge_ring: np.ndarray
    edge_start: np.ndarray
    edge_end: np.ndarray
    edges: np.ndarray
    labels: np.ndarray

    @property
    def ring_length(self) -> np.ndarray:
        """(r,) length of each ring, user units."""
        return np.array([float(np.hypot(*np.diff(np.vstack([r, r[:1]]), axis=0).T).sum()) for r in self.rings])

    def edge_direction(self) -> np.ndarray:
        """(e,) each edge's chord direction, degrees in [0, 180) (an axis, not a heading)."""
        xy0 = shapely.get_coordinates(shapely.get_point(self.edges, 0))
        xy1 = shapely.get_coordinates(shapely.get_point(self.edges, -1))
        d = xy1 - xy0
        return np.degrees(np.arctan2(d[:, 1], d[:, 0])) % 180.0


def base_mesh(face: shapely.Geometry, *, corner_angle: float = 30.0, tolerance: float = 0.0,
              labels: dict[str, shapely.Geometry] | None = None, label_distance: float = 0.0) -> BaseMesh:  # fmt: skip
    """The base mesh of ``face`` (§3.1).

    Parameters
    ----------
    face : the unit, user units
    corner_angle : degrees; a vertex where the boundary turns by more than this is a corner
    tolerance : user units; the rings are simplified by this much first (digitising noise and
        collinear vertices make no corners)
    labels : name -> line (or polygonal) geometry; an edge of which at least :data:`LABEL_SHARE`
        lies within ``label_distance`` of a geometry takes its name (the first such, by name)
    label_distance : user units
    """
    face = shapely.orient_polygons(shapely.simplify(face, tolerance) if tolerance > 0 else face)
    rings = []
    for poly in shapely.get_parts(face):
        for ring in [poly.exterior, *poly.interiors]:
            xy = np.asarray(ring.coords)[:-1]
            keep = np.r_[True, np.hypot(*np.diff(xy, axis=0).T) > 1e-12]
            rings.append(xy[keep])
    c_ring, c_vertex, c_turn = [], [], []
    e_ring, e_start, e_end, e_geom = [], [], [], []
    for r, xy in enumerate(rings):
        seg = np.roll(xy, -1, axis=0) - xy  # segment i runs from vertex i to i + 1
        heading = np.arctan2(seg[:, 1], seg[:, 0])
        turn = np.degrees((heading - np.roll(heading, 1) + np.pi) % (2 * np.pi) - np.pi)  # at vertex i
        arc = np.r_[0.0, np.cumsum(np.hypot(seg[:, 0], seg[:, 1]))]
        length = arc[-1]
        corners = np.flatnonzero(np.abs(turn) > corner_angle)
        c_ring += [r] * len(corners)
        c_vertex += corners.tolist()
        c_turn += turn[corners].tolist()
        if len(corners) == 0:
            starts, ends = np.array([0.0]), np.array([length])
        else:
            starts = arc[corners]
            ends = np.r_[arc[corners[1:]], arc[corners[0]] + length]
        closed = np.vstack([xy, xy[:1]])
        ring_line = shapely.LineString(closed)
        for a, b in zip(starts.tolist(), ends.tolist(), strict=True):
            e_ring.append(r)
            e_start.append(a)
            e_end.append(b)
            e_geom.append(_piece(ring_line, a, b, length))
    edges = geometry_array(e_geom)
    names = np.full(len(edges), "", dtype=object)
    for name in sorted(labels or {}):
        near = shapely.buffer(labels[name], max(label_distance, 1e-9))
        share = shapely.length(shapely.intersection(edges, near)) / np.maximum(shapely.length(edges), 1e-12)
        names[(share >= LABEL_SHARE) & (names == "")] = name
    corner_xy = np.array([rings[r][v] for r, v in zip(c_ring, c_vertex, strict=True)]).reshape(-1, 2)
    return BaseMesh(face, rings, np.array(c_ring, np.int64), np.array(c_vertex, np.int64), corner_xy,
                    np.array(c_turn), np.array(e_ring, np.int64), np.array(e_start), np.array(e_end), edges,
                    names)  # fmt: skip


def _piece(ring: shapely.LineString, a: float, b: float, length: float) -> shapely.LineString:
    """The part of a closed ring from arc length ``a`` to ``b`` (``b`` may pass the ring's start)."""
    if b <= length + 1e-12:
        return shapely.ops.substring(ring, a, min(b, length))
    first = np.asarray(shapely.ops.substring(ring, a, length).coords)
    second = np.asarray(shapely.ops.substring(ring, 0.0, b - length).coords)
    return shapely.LineString(np.vstack([first, second[1:]]))


def point_at(ring: np.ndarray, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points and inward unit normals at arc lengths ``s`` of a ring (§3.2: an edge by arc length).

    Parameters
    ----------
    ring : (m, 2) float array, the ring's vertices, face on the left
    s : (k,) float array, arc lengths (taken modulo the ring's length)

    Returns
    -------
    xy : (k, 2) float array, user units
    normal : (k, 2) float array, unit vectors into the face (the left normal of the segment)
    """
    seg = np.roll(ring, -1, axis=0) - ring
    seglen = np.hypot(seg[:, 0], seg[:, 1])
    arc = np.r_[0.0, np.cumsum(seglen)]
    s = np.asarray(s, dtype=np.float64) % arc[-1]
    i = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(ring) - 1)
    u = ((s - arc[i]) / seglen[i])[:, None]
    tangent = seg[i] / seglen[i, None]
    return ring[i] + u * seg[i], np.stack([-tangent[:, 1], tangent[:, 0]], axis=1)

