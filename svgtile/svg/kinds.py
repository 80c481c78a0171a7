"""Plain motifs identical up to translation and rotation share a kind (almeraj2013 §3.1)."""

from __future__ import annotations

import math
import warnings
import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.core.exemplar import Exemplar
from svgtile.svg.dialect import (
    OWN_LOOK,
    SHAPE_TOLERANCE,
    SHAPES,
    cascade_style,
    inherited_items,
    is_rendered,
    local_tag,
    polygons_of,
)


@dataclass
class Shape:
    """A centred footprint with what plain-shape matching compares."""

    geom: shapely.Geometry
    coords: np.ndarray  # (v, 2) outline points
    r: np.ndarray  # (v,) their distances from the origin
    area: float
    radius: float
    axis: float | None  # principal axis, degrees (None: no clear axis)

    @classmethod
    def of(cls, geom: shapely.Geometry) -> Shape:
        coords = shapely.get_coordinates(geom)
        r = np.hypot(coords[:, 0], coords[:, 1])
        return cls(geom, coords, r, float(geom.area), float(r.max()), principal_axis(geom))


def paint_key(el: ET.Element, parent_style: dict[str, str]) -> tuple:
    """What besides shape tells two plain motifs apart: the effective paint of every leaf and the
    opacity, clip, mask and filter of every element, styles cascaded from ``el``'s parent."""
    keys = set()
    todo = [(el, parent_style)]
    while todo:
        node, inherited = todo.pop()
        style = cascade_style(node, inherited)
        look = tuple((k, style[k]) for k in OWN_LOOK if k in style)
        if local_tag(node.tag) in SHAPES:
            keys.add((inherited_items(style), look))
        elif look:
            keys.add(((), look))
        todo.extend((c, style) for c in node if is_rendered(c))
    return tuple(sorted(keys))


def principal_axis(geom: shapely.Geometry) -> float | None:
    """Direction (degrees, mod 180) of the major principal axis of ``geom`` about the origin, or
    None when the second moments are nearly isotropic (no axis to align)."""
    sxx = syy = sxy = 0.0
    for poly in polygons_of(geom):
        xy = shapely.get_coordinates(poly.exterior)
        x0, y0, x1, y1 = xy[:-1, 0], xy[:-1, 1], xy[1:, 0], xy[1:, 1]
        cross = x0 * y1 - x1 * y0
        sign = 1.0 if cross.sum() > 0 else -1.0  # ring orientation
        sxx += sign * float(np.sum(cross * (x0 * x0 + x0 * x1 + x1 * x1))) / 12
        syy += sign * float(np.sum(cross * (y0 * y0 + y0 * y1 + y1 * y1))) / 12
        sxy += sign * float(np.sum(cross * (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0))) / 24
    if math.hypot(sxx - syy, 2 * sxy) < 0.05 * (sxx + syy):
        return None
    return math.degrees(0.5 * math.atan2(2 * sxy, sxx - syy))


def rotated(geom: shapely.Geometry, angle: float) -> shapely.Geometry:
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    return shapely.transform(geom, lambda p: p @ np.array([[c, s], [-s, c]]))


def match_rotation(ref: Shape, shape: Shape, tolerance: float = SHAPE_TOLERANCE) -> float | None:
    """Angle (degrees) rotating ``ref`` onto ``shape`` (both centred), or None if not congruent.

    Candidates: no rotation (kept on ties, so symmetric motifs get angle 0), the alignment of the
    principal axes both ways, and the shape's farthest point onto each of the reference's far
    points; the best is accepted if its Hausdorff distance is within ``tolerance`` × the
    reference's radius.
    """
    tol = tolerance * ref.radius
    exact = 1e-6 * ref.radius
    candidates = [0.0]
    if ref.axis is not None and shape.axis is not None:
        turn = shape.axis - ref.axis
        candidates += [turn, turn + 180.0]
    p = shape.coords[int(np.argmax(shape.r))]
    far = ref.coords[ref.r >= ref.radius - tol]
    if len(far) > 24:
        far = far[np.linspace(0, len(far) - 1, 24).astype(int)]
    candidates += list(np.degrees(math.atan2(p[1], p[0]) - np.arctan2(far[:, 1], far[:, 0])))
    best_d, best_angle = math.inf, 0.0
    for angle in candidates:
        d = shapely.hausdorff_distance(rotated(ref.geom, angle), shape.geom)
        if d < best_d - exact:
            best_d, best_angle = d, float(angle)
        if best_d <= exact:
            break
    if best_d > tol:
        return None
    return (best_angle + 180.0) % 360.0 - 180.0


# ----------------------------------------------------------------------------- pattern tiles
#

def match_kinds(
    geoms: list[shapely.Geometry], paints: list[tuple], tolerance: float = SHAPE_TOLERANCE
) -> tuple[np.ndarray, np.ndarray]:
    """Kinds of centred footprints, identical up to rotation within ``tolerance``.

    The rule of plain exemplars (:meth:`DocumentReader._plain_kind`): a motif takes the kind of the first
    earlier one of the same paint whose shape it matches after a rotation: areas within
    2 × ``tolerance``, radii within ``tolerance`` and Hausdorff distance within ``tolerance`` ×
    radius.

    Parameters
    ----------
    geoms : n footprints, each centred on its centroid
    paints : n hashable paint keys
    tolerance : relative shape tolerance

    Returns
    -------
    kind : (n,) int array, numbered in order of first appearance
    angle : (n,) float array, degrees rotating the kind's first motif onto each motif
    """
    kind = np.zeros(len(geoms), dtype=np.int64)
    angle = np.zeros(len(geoms))
    reps: list[tuple[Shape, tuple]] = []
    for n, (geom, paint) in enumerate(zip(geoms, paints, strict=True)):
        shape = Shape.of(geom)
        for k, (ref, ref_paint) in enumerate(reps):
            if ref_paint != paint:
                continue
            if abs(ref.area - shape.area) > 2 * tolerance * ref.area:
                continue
            if abs(ref.radius - shape.radius) > tolerance * ref.radius:
                continue
            turn = match_rotation(ref, shape, tolerance)
            if turn is not None:
                kind[n], angle[n] = k, turn
                break
        else:
            kind[n] = len(reps)
            reps.append((shape, paint))
    return kind, angle


def warn_all(exemplar: Exemplar) -> None:
    """Issue the exemplar's warnings through :mod:`warnings` (the CLI shows them on stderr)."""
    for message in exemplar.warnings:
        warnings.warn(f"{exemplar.source}: {message}", stacklevel=2)


# ----------------------------------------------------------------------------- map geometry
#
