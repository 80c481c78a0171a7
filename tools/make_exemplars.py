#!/usr/bin/env python3
"""Generate the bundled svgtile exemplars (``exemplars/*.svg`` and ``exemplars/README.md``).

Every exemplar is an original drawing (CC0) of a cartographic area pattern, modelled on -- not
copied from -- the FGDC lithology patterns and the openstreetmap-carto area fills.  Each one is a
set of non-overlapping motifs inside an input region, as required by the patch-based geometric
texture synthesis of AlMeraj et al. (2013, section 3.1).

Two encodings are written:

* symbol/use (all but one file): each motif kind is a ``<symbol>`` drawn around the origin and
  each motif a ``<use xlink:href="#kind" transform="translate(x y) rotate(a)"/>`` inside
  ``<g id="motifs">``; the input region is ``<rect id="region">`` or ``<circle id="region">``.
* plain: every motif is a top-level ``<polygon>`` or ``<g>`` with absolute coordinates, no ``<use>``.

Motifs are placed the way a cartographer draws them, not by dart throwing (which is what the
``random`` engine imitates, so a dart-thrown exemplar has no structure to lose): along offset
rows that continue across the edges, in tight groups (nests, clumps, split fragments, chains)
whose members keep a characteristic gap between *footprints* (interior of closed outlines plus
the stroke band), all with a hand-drawn irregularity (``rows``, ``group``, ``settle``).  Before
writing, every exemplar is checked: footprints are pairwise at least ``MIN_GAP`` apart and lie
inside the region; a square exemplar tiled 3 × 3 shows no seam (gaps across its sides are no
wider than inside it), and in the circle the outermost motifs keep only a small margin to it.

The output is deterministic (fixed seed per exemplar, at most 3 decimals per number).
Run from anywhere:  python3 tools/make_exemplars.py [--out DIR]
Requires numpy and shapely (>= 2.1, for ``shapely.dwithin``).
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import LineString, Point, Polygon
from shapely.geometry.base import BaseGeometry
from shapely.ops import unary_union

INK = "#231f20"  # FGDC-style ink (as in the USGS Inkscape conversion)
BLACK = "#000"
MIN_GAP = 0.4  # hard lower bound on the distance between two motif footprints
PLACE_GAP = 0.5  # lower bound used while placing (a little slack over MIN_GAP)
QUAD_SEGS = 16  # shapely buffer resolution (circle error < 0.2 % of the radius)
BEZIER_SAMPLES = 16  # samples per cubic segment when flattening paths for footprints


# --------------------------------------------------------------------------- numbers


def fmt(value: float) -> str:
    """Format a number with at most 3 decimals, no trailing zeros and no ``-0``."""
    text = f"{value:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def r3(value: float) -> float:
    """Round to the precision that is written to the file."""
    return float(fmt(value))


def r3pts(points) -> tuple[tuple[float, float], ...]:
    """Round a sequence of points to file precision."""
    return tuple((r3(x), r3(y)) for x, y in points)


# --------------------------------------------------------------------------- shapes


@dataclass(frozen=True)
class Shape:
    """One SVG primitive of a motif, with its presentation attributes.

    ``pts`` holds the vertices (line, polyline, polygon), the centre (circle, ellipse) or the
    cubic Bezier points ``P0 C1 C2 P1 C1 C2 P2 ...`` of a closed path; ``size`` holds the radius
    (circle) or radii (ellipse).  ``fill``/``stroke`` are colours or None.
    """

    tag: str
    pts: tuple[tuple[float, float], ...]
    size: tuple[float, ...] = ()
    fill: str | None = None
    stroke: str | None = INK
    width: float = 0.35
    cap: str = "round"

    # ---- geometry

    def outline(self) -> BaseGeometry:
        """The bare geometry (no stroke): a polygon for closed shapes, a line otherwise."""
        if self.tag == "circle":
            return Point(self.pts[0]).buffer(self.size[0], quad_segs=QUAD_SEGS * 2)
        if self.tag == "ellipse":
            disc = Point(0, 0).buffer(1.0, quad_segs=QUAD_SEGS * 2)
            disc = affinity.scale(disc, self.size[0], self.size[1], origin=(0, 0))
            return affinity.translate(disc, *self.pts[0])
        if self.tag == "polygon":
            return Polygon(self.pts)
        if self.tag == "path":
            return Polygon(flatten_bezier(self.pts))
        if len(set(self.pts)) == 1:  # zero-length line: a dot
            return Point(self.pts[0])
        return LineString(self.pts)

    def footprint(self) -> BaseGeometry:
        """Interior of closed outlines plus half the stroke width on each side."""
        geom = self.outline()
        if not self.stroke:
            return geom
        if isinstance(geom, Point) and self.cap != "round":
            raise ValueError("a zero-length line needs round caps to be visible")
        cap = "round" if self.cap == "round" else "flat"
        return geom.buffer(self.width / 2, quad_segs=QUAD_SEGS, cap_style=cap, join_style="round")

    # ---- transformation

    def moved(self, x: float, y: float, angle: float) -> Shape:
        """This shape rotated by ``angle`` degrees about the origin, then translated (rounded)."""
        if self.tag == "ellipse":
            raise ValueError("ellipses are only used inside symbols")
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        pts = r3pts((x + c * px - s * py, y + s * px + c * py) for px, py in self.pts)
        return Shape(self.tag, pts, self.size, self.fill, self.stroke, self.width, self.cap)

    # ---- SVG

    def svg(self) -> str:
        """The SVG element, styled with presentation attributes."""
        p = self.pts
        if self.tag == "circle":
            geo = f'cx="{fmt(p[0][0])}" cy="{fmt(p[0][1])}" r="{fmt(self.size[0])}"'
        elif self.tag == "ellipse":
            geo = (
                f'cx="{fmt(p[0][0])}" cy="{fmt(p[0][1])}" '
                f'rx="{fmt(self.size[0])}" ry="{fmt(self.size[1])}"'
            )
        elif self.tag == "line":
            geo = f'x1="{fmt(p[0][0])}" y1="{fmt(p[0][1])}" x2="{fmt(p[1][0])}" y2="{fmt(p[1][1])}"'
        elif self.tag in ("polyline", "polygon"):
            geo = 'points="' + " ".join(f"{fmt(x)},{fmt(y)}" for x, y in p) + '"'
        elif self.tag == "path":
            geo = f'd="{bezier_path_data(p)}"'
        else:
            raise ValueError(self.tag)
        style = f'fill="{self.fill or "none"}"'
        if self.stroke:
            style += f' stroke="{self.stroke}" stroke-width="{fmt(self.width)}"'
            if self.tag in ("line", "polyline"):
                style += f' stroke-linecap="{self.cap}"'
            if self.tag in ("polyline", "polygon", "path"):
                style += ' stroke-linejoin="round"'
        else:
            style += ' stroke="none"'
        return f"<{self.tag} {geo} {style}/>"


def flatten_bezier(pts) -> list[tuple[float, float]]:
    """Sample a closed chain of cubic Bezier segments ``P0 C1 C2 P1 ...`` into a ring."""
    arr = np.asarray(pts, dtype=float)
    t = np.linspace(0.0, 1.0, BEZIER_SAMPLES, endpoint=False)[:, None]
    ring = []
    for i in range(0, len(arr) - 1, 3):
        p0, c1, c2, p1 = arr[i : i + 4]
        seg = (
            ((1 - t) ** 3) * p0 + 3 * ((1 - t) ** 2) * t * c1 + 3 * (1 - t) * t**2 * c2 + t**3 * p1
        )
        ring.extend(map(tuple, seg))
    return ring


def bezier_path_data(pts) -> str:
    """Path data ``M P0 C C1 C2 P1 ... Z`` for a closed chain of cubic segments."""

    def xy(p):
        return f"{fmt(p[0])} {fmt(p[1])}"

    parts = [f"M{xy(pts[0])}"]
    for i in range(1, len(pts) - 1, 3):
        parts.append(f"C{xy(pts[i])} {xy(pts[i + 1])} {xy(pts[i + 2])}")
    return " ".join(parts) + "Z"


# ---- shape constructors (all coordinates rounded to file precision)


def circle(cx, cy, r, **style) -> Shape:
    return Shape("circle", r3pts([(cx, cy)]), (r3(r),), **style)


def ellipse(cx, cy, rx, ry, **style) -> Shape:
    return Shape("ellipse", r3pts([(cx, cy)]), (r3(rx), r3(ry)), **style)


def line(x1, y1, x2, y2, **style) -> Shape:
    return Shape("line", r3pts([(x1, y1), (x2, y2)]), **style)


def dot(x, y, diameter, **style) -> Shape:
    """A dot drawn the FGDC way: a zero-length line with round caps."""
    return Shape("line", r3pts([(x, y), (x, y)]), width=r3(diameter), cap="round", **style)


def polyline(points, **style) -> Shape:
    return Shape("polyline", r3pts(points), **style)


def polygon(points, **style) -> Shape:
    return Shape("polygon", r3pts(points), **style)


def smooth_closed(points, **style) -> Shape:
    """A closed smooth outline through ``points`` (Catmull-Rom spline written as cubic Beziers)."""
    p = np.asarray(points, dtype=float)
    n = len(p)
    chain = [p[0]]
    for i in range(n):
        prev, cur, nxt, nxt2 = p[i - 1], p[i], p[(i + 1) % n], p[(i + 2) % n]
        chain += [cur + (nxt - prev) / 6, nxt - (nxt2 - cur) / 6, nxt]
    return Shape("path", r3pts(chain), **style)


# --------------------------------------------------------------------------- kinds & motifs


@dataclass
class Kind:
    """A motif kind: an id, a short description and its shapes drawn around the origin."""

    id: str
    label: str
    shapes: list[Shape]
    # orientation law: ("fixed", 0, 0) | ("uniform", lo, hi) | ("normal", sd, clip), degrees
    angles: tuple[str, float, float] = ("fixed", 0.0, 0.0)
    group: bool = False  # plain encoding: wrap the shapes in a <g> even if there is one shape
    footprint: BaseGeometry = field(init=False)
    radius: float = field(init=False)

    def __post_init__(self):
        self.footprint = unary_union([s.footprint() for s in self.shapes])
        coords = shapely.get_coordinates(self.footprint)
        self.radius = float(np.hypot(coords[:, 0], coords[:, 1]).max())

    def size_text(self) -> str:
        """Unrotated footprint size (stroke included), e.g. ``"4.4 × 2.8"``."""
        x0, y0, x1, y1 = self.footprint.bounds
        return f"{x1 - x0:.1f} × {y1 - y0:.1f}"

    def sample_angle(self, rng: np.random.Generator) -> float:
        """Draw a placement rotation (degrees) from this kind's orientation law."""
        law, a, b = self.angles
        if law == "uniform":
            return rng.uniform(a, b)
        if law == "normal":
            return float(np.clip(rng.normal(0.0, a), -b, b))
        return 0.0


@dataclass(frozen=True)
class Motif:
    """A placed instance: kind, translation and rotation (degrees, clockwise on screen)."""

    kind: Kind
    x: float
    y: float
    angle: float

    def footprint(self) -> BaseGeometry:
        fp = affinity.rotate(self.kind.footprint, self.angle, origin=(0, 0))
        return affinity.translate(fp, self.x, self.y)


# --------------------------------------------------------------------------- regions


@dataclass(frozen=True)
class Region:
    """A square ``[0, size]^2`` or a circle of radius ``size/2`` inscribed in it."""

    shape: str  # "square" | "circle"
    size: float

    def margin(self, geom: BaseGeometry) -> float:
        """Signed distance from ``geom`` to the region boundary (negative when sticking out)."""
        if self.shape == "square":
            x0, y0, x1, y1 = geom.bounds
            return min(x0, self.size - x1, y0, self.size - y1)
        c = self.size / 2
        pts = shapely.get_coordinates(geom)
        return c - float(np.hypot(pts[:, 0] - c, pts[:, 1] - c).max())

    def inset(self, motif: Motif, margin: float) -> Motif | None:
        """``motif`` moved just far enough inward (square: along x and y; circle: radially) to
        keep ``margin`` from the boundary -- how a drafter finishes a row at the region's edge;
        None if it does not fit."""
        fp = motif.footprint()
        x, y = motif.x, motif.y
        if self.shape == "square":
            x0, y0, x1, y1 = fp.bounds
            x += max(0.0, margin - x0) - max(0.0, margin - (self.size - x1))
            y += max(0.0, margin - y0) - max(0.0, margin - (self.size - y1))
        else:
            c = self.size / 2
            theta = math.atan2(y - c, x - c)
            for _ in range(4):  # the footprint is not round: converge in a few steps
                moved = affinity.translate(fp, x - motif.x, y - motif.y)
                shift = min(0.0, self.margin(moved) - margin - 0.002)
                x, y = x + shift * math.cos(theta), y + shift * math.sin(theta)
        out = Motif(motif.kind, r3(x), r3(y), motif.angle)
        return out if self.margin(out.footprint()) >= margin - 1e-9 else None

    def side_of(self, geom: BaseGeometry) -> list[str]:
        """Names of the boundary parts a motif is closest to (for the edge-margin check)."""
        cx, cy = geom.centroid.x, geom.centroid.y
        if self.shape == "square":
            x0, y0, x1, y1 = geom.bounds
            d = {"left": x0, "top": y0, "right": self.size - x1, "bottom": self.size - y1}
            best = min(d.values())
            return [k for k, v in d.items() if v <= best + 1e-9]
        sector = int(
            ((math.degrees(math.atan2(cy - self.size / 2, cx - self.size / 2)) + 360) % 360) // 45
        )
        return [f"sector{sector}"]

    def sides(self) -> list[str]:
        if self.shape == "square":
            return ["left", "top", "right", "bottom"]
        return [f"sector{i}" for i in range(8)]

    def svg(self) -> str:
        s = fmt(self.size)
        if self.shape == "square":
            return f'<rect id="region" x="0" y="0" width="{s}" height="{s}" fill="none" stroke="none"/>'
        c = fmt(self.size / 2)
        return f'<circle id="region" cx="{c}" cy="{c}" r="{c}" fill="none" stroke="none"/>'

    def describe(self) -> str:
        if self.shape == "square":
            return f'square {fmt(self.size)} × {fmt(self.size)} (`<rect id="region">`)'
        return (
            f"circle of radius {fmt(self.size / 2)} centred at ({fmt(self.size / 2)}, "
            f'{fmt(self.size / 2)}) (`<circle id="region">`)'
        )


# --------------------------------------------------------------------------- placement
#
# A cartographer does not scatter motifs at random: they are drawn along rows (offset from row
# to row), around a few centres (clumps, satellites) or in pairs, by eye, so that spacing is
# characteristic but never exact.  A layout function builds that intent as *candidates* --
# (kind id, x, y, angle, gap) in order -- with ``rows`` and ``around``; ``settle`` then inks
# them in that order the way a drafter would: a motif that would run over the region's edge is
# nudged inside, one that would touch an earlier one is left out.


@dataclass(frozen=True)
class Cand:
    """A motif the layout intends to draw: kind, centre, rotation (degrees) and the clear
    distance it wants to its neighbours (two motifs keep the mean of theirs)."""

    kind: str
    x: float
    y: float
    angle: float
    gap: float


def steps(rng: np.random.Generator, n: int, total: float, spread: float) -> np.ndarray:
    """``n`` positive steps of relative spread ``spread`` (uniform ±) that sum to ``total``:
    spacing judged by eye along a row, closed on itself so the pattern tiles."""
    s = 1.0 + rng.uniform(-spread, spread, n)
    return s / s.sum() * total


def rows(
    rng: np.random.Generator,
    size: float,
    row_gap: float,
    pitch,
    *,
    spread: float = 0.25,
    row_spread: float = 0.12,
    wobble: float = 0.0,
    stagger: float = 0.5,
) -> list[tuple[float, float, int, int]]:
    """Centres along offset rows across a ``size`` square, as (x, y, row, index in row).

    Rows are about ``row_gap`` apart (relative spread ``row_spread``); along a row the centres
    follow ``pitch`` -- a number, or a callable ``pitch(row, k) -> float`` giving the distance
    from motif k of the row to motif k + 1 -- scaled by ``1 ± spread`` and closed to the square's width, so
    both the rows and the positions along them continue across the edges when the exemplar is
    tiled.  Each row starts ``stagger`` of a pitch after the one above (plus a little), and each
    centre sits ``wobble`` (standard deviation) off its row line: the hand-drawn offset rows of
    FGDC 607, 620 or the OSM marsh fill.
    """
    n_rows = max(2, round(size / row_gap))
    n_rows += n_rows % 2 if stagger else 0
    ys = np.cumsum(steps(rng, n_rows, size, row_spread)) - size / n_rows / 2
    out = []
    start = rng.uniform(0, 1)
    for r, y in enumerate(ys):
        nominal: list[float] = []
        while True:
            step = pitch(r, len(nominal)) if callable(pitch) else pitch
            if sum(nominal) + 0.5 * step > size:
                break
            nominal.append(step)
        xs = np.concatenate([[0.0], np.cumsum(steps(rng, len(nominal), size, spread)[:-1])])
        x0 = (start + r * stagger + rng.uniform(-0.12, 0.12)) * size / len(nominal)
        for i, x in enumerate(xs):
            out.append((float((x + x0) % size), float(y + rng.normal(0, wobble)), r, i))
    return out


def around(
    rng: np.random.Generator, x: float, y: float, reach: float, n: int, spread: float = 0.3
) -> list[tuple[float, float]]:
    """``n`` centres about ``reach`` from (x, y) at roughly even angles: a clump or satellites."""
    theta = rng.uniform(0, 2 * math.pi) + 2 * math.pi * np.arange(n) / n
    theta = theta + rng.uniform(-0.35, 0.35, n) * (2 * math.pi / max(n, 3))
    dist = reach * (1 + rng.uniform(-spread, spread, n) / 2)
    return [(x + d * math.cos(t), y + d * math.sin(t)) for t, d in zip(theta, dist, strict=True)]


def group(
    rng: np.random.Generator,
    kinds: list[Kind],
    x: float,
    y: float,
    gap: float,
    *,
    angles: list[float] | None = None,
    spread: float = 0.1,
    keep: float = 0.0,
    theta: float | None = None,
    box: float | None = None,
) -> list[Cand]:
    """A tight group drawn around (x, y): the first motif there, each next one pushed against
    the ones before it from an evenly turning direction until its footprint is ``gap``
    (± ``spread``) from theirs -- pebbles in a nest, a clump of bushes, a split clast.
    ``keep`` is the candidates' own gap (see :class:`Cand`); ``theta`` (radians) fixes the
    first direction, so a group of two or three becomes a chain along it (rows, bedding).
    With ``box`` the whole group is moved inside the square [0, box]² (0.4 from its sides), so
    the region's edge does not break it up."""
    out: list[Cand] = []
    union = None
    theta0 = rng.uniform(0, 2 * math.pi) if theta is None else theta
    wiggle = 0.3 if theta is None else 0.08
    for n, kind in enumerate(kinds):
        angle = kind.sample_angle(rng) if angles is None else angles[n]
        fp0 = affinity.rotate(kind.footprint, angle, origin=(0, 0))
        if union is None:
            px, py = x, y
        else:
            t = (
                theta0
                + 2 * math.pi * (n - 1) / max(1, len(kinds) - 1)
                + rng.uniform(-wiggle, wiggle)
            )
            want = gap * (1 + rng.uniform(-spread, spread))
            lo, hi = 0.0, 30.0
            for _ in range(18):  # bisection on the distance from the group centre
                mid = (lo + hi) / 2
                fp = affinity.translate(fp0, x + mid * math.cos(t), y + mid * math.sin(t))
                lo, hi = (mid, hi) if fp.distance(union) < want else (lo, mid)
            px, py = x + hi * math.cos(t), y + hi * math.sin(t)
        out.append(Cand(kind.id, px, py, angle, keep))
        placed = affinity.translate(fp0, px, py)
        union = placed if union is None else union.union(placed)
    if box is not None:
        x0, y0, x1, y1 = union.bounds
        sx = max(0.0, 0.4 - x0) - max(0.0, x1 - (box - 0.4))
        sy = max(0.0, 0.4 - y0) - max(0.0, y1 - (box - 0.4))
        out = [Cand(c.kind, c.x + sx, c.y + sy, c.angle, c.gap) for c in out]
    return out


def cand(rng: np.random.Generator, kind: Kind, x: float, y: float, gap: float, angle=None) -> Cand:
    """A candidate of ``kind`` at (x, y); its angle drawn from the kind's law unless given."""
    return Cand(kind.id, x, y, kind.sample_angle(rng) if angle is None else angle, gap)


def pick(rng: np.random.Generator, weights: dict[str, float]) -> str:
    """A kind id drawn with the given weights."""
    ids = list(weights)
    p = np.array([weights[i] for i in ids], dtype=float)
    return ids[rng.choice(len(ids), p=p / p.sum())]


def settle(region: Region, kinds: dict[str, Kind], cands: list[Cand], margin: float) -> list[Motif]:
    """Ink the candidates in order: nudge each inside the region (at least ``margin`` from its
    boundary) and keep it only if it clears every motif kept so far by its gap."""
    placed = _Placed()
    for c in cands:
        kind = kinds[c.kind]
        motif = region.inset(Motif(kind, r3(c.x), r3(c.y), round(c.angle, 2)), margin)
        if motif is None:
            continue
        fp = motif.footprint()
        if placed.clear(motif, fp, c.gap):
            placed.add(motif, fp, c.gap)
    return placed.motifs


class _Placed:
    """The motifs kept so far, with what the gap test needs."""

    def __init__(self):
        self.motifs: list[Motif] = []
        self.fps: list[BaseGeometry] = []
        self.centres: list[tuple[float, float]] = []
        self.radii: list[float] = []
        self.gaps: list[float] = []

    def add(self, motif: Motif, fp: BaseGeometry, gap: float) -> None:
        self.motifs.append(motif)
        self.fps.append(fp)
        self.centres.append((motif.x, motif.y))
        self.radii.append(motif.kind.radius)
        self.gaps.append(gap)

    def clear(self, motif: Motif, fp: BaseGeometry, gap: float) -> bool:
        """True if ``fp`` keeps the required gaps to every kept footprint."""
        if not self.motifs:
            return True
        c = np.asarray(self.centres)
        need = np.maximum(PLACE_GAP, (gap + np.asarray(self.gaps)) / 2)
        reach = motif.kind.radius + np.asarray(self.radii) + need
        near = np.flatnonzero(np.hypot(c[:, 0] - motif.x, c[:, 1] - motif.y) < reach)
        if len(near) == 0:
            return True
        shapely.prepare(fp)
        return not shapely.dwithin(fp, np.asarray(self.fps, dtype=object)[near], need[near]).any()


# --------------------------------------------------------------------------- validation


@dataclass
class Report:
    """Measured statistics of one exemplar."""

    counts: dict[str, int]
    min_gap: float
    median_gap: float
    min_margin: float
    side_margins: dict[str, float]
    angle_ranges: dict[str, tuple[float, float]]


def require(ok: bool, message: str) -> None:
    """Fail loudly (also under ``python -O``) when an exemplar invariant is violated."""
    if not ok:
        raise ValueError(message)


def validate(name: str, region: Region, items: list[tuple[str, float, BaseGeometry]]) -> Report:
    """Check the exemplar invariants and return its statistics (raises ValueError).

    ``items`` are (kind id, rotation, footprint) per motif, built from the rounded values that
    are written to the file.
    """
    fps = [fp for _, _, fp in items]
    n = len(fps)
    require(25 <= n <= 100, f"{name}: {n} motifs (want 25-100)")
    tree = shapely.STRtree(fps)
    nn = np.full(n, np.inf)
    for i, fp in enumerate(fps):
        # candidates within a generous window; exact distance for those
        for j in tree.query(fp.buffer(12.0)):
            if j != i:
                nn[i] = min(nn[i], fp.distance(fps[j]))
    min_gap = float(nn.min())
    require(min_gap >= MIN_GAP, f"{name}: footprints only {min_gap:.3f} apart")
    margins = [region.margin(fp) for fp in fps]
    require(min(margins) >= MIN_GAP / 2, f"{name}: motif too close to / outside the region")
    side = dict.fromkeys(region.sides(), math.inf)
    for fp, mg in zip(fps, margins, strict=True):
        for s in region.side_of(fp):
            side[s] = min(side[s], mg)
    median_gap = float(np.median(nn))
    worst = max(side.values())
    if region.shape == "circle":
        # the outermost motifs must hug every sector: about half the typical gap, no wide band
        require(
            worst <= 0.75 * median_gap,
            f"{name}: a boundary part has an empty band of {worst:.2f} (median gap {median_gap:.2f})",
        )
    else:
        require_seamless(name, region, fps, nn, np.asarray(margins))
    counts: dict[str, int] = {}
    angles: dict[str, list[float]] = {}
    for kind_id, angle, _ in items:
        counts[kind_id] = counts.get(kind_id, 0) + 1
        angles.setdefault(kind_id, []).append(angle)
    return Report(
        counts,
        min_gap,
        median_gap,
        min(margins),
        side,
        {k: (min(v), max(v)) for k, v in angles.items()},
    )


def require_seamless(
    name: str, region: Region, fps: list[BaseGeometry], nn: np.ndarray, margins: np.ndarray
) -> None:
    """Tiled 3 × 3, a square exemplar must show no seam: the motifs along its sides, with their
    neighbours across the sides, have no larger nearest gaps than the exemplar's inner motifs.

    ``nn`` are the nearest footprint gaps within the exemplar alone, ``margins`` each motif's
    distance to the boundary.  (For clumped or row patterns the typical gap between clumps or
    rows, not the gap within them, sets how close to a side the outermost motifs must be.)
    """
    size = region.size
    shifts = [(dx, dy) for dx in (-size, 0, size) for dy in (-size, 0, size)]
    tiled = [affinity.translate(fp, dx, dy) for dx, dy in shifts for fp in fps]
    tree = shapely.STRtree(tiled)
    _idx, torus = tree.query_nearest(fps, return_distance=True, exclusive=True, all_matches=False)
    inner = margins > 2 * float(np.median(nn))
    require(inner.sum() >= 5, f"{name}: too few motifs away from the sides to judge the seams")
    limit = 1.2 * float(nn[inner].max())
    edge = ~inner
    require(
        float(torus[edge].max()) <= limit,
        f"{name}: tiling leaves a seam: a gap of {torus[edge].max():.2f} across a side "
        f"(the largest inner gap is {nn[inner].max():.2f})",
    )
    require(
        float(np.median(torus[edge])) <= 1.25 * float(np.median(nn[inner])),
        f"{name}: tiling leaves a seam: gaps across the sides are wider than inside",
    )


# --------------------------------------------------------------------------- SVG output

XML_HEAD = '<?xml version="1.0" encoding="UTF-8"?>\n'
NOTICE = (
    "<!-- svgtile exemplar: original drawing, CC0 1.0 (public domain dedication). "
    "Generated by tools/make_exemplars.py -->\n"
)


def svg_open(region: Region, title: str) -> list[str]:
    s = fmt(region.size)
    return [
        XML_HEAD
        + NOTICE
        + '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
        f'width="{s}" height="{s}" viewBox="0 0 {s} {s}">',
        f"  <title>{title}</title>",
    ]


def svg_symbols(region: Region, title: str, kinds: list[Kind], motifs: list[Motif]) -> str:
    """The symbol/use encoding."""
    out = svg_open(region, title)
    out.append("  <defs>")
    for kind in kinds:
        out.append(f'    <symbol id="{kind.id}" overflow="visible">')
        out += [f"      {shape.svg()}" for shape in kind.shapes]
        out.append("    </symbol>")
    out.append("  </defs>")
    out.append(f"  {region.svg()}")
    out.append('  <g id="motifs">')
    for m in motifs:
        out.append(
            f'    <use xlink:href="#{m.kind.id}" '
            f'transform="translate({fmt(m.x)} {fmt(m.y)}) rotate({fmt(m.angle)})"/>'
        )
    out += ["  </g>", "</svg>", ""]
    return "\n".join(out)


def absolute_shapes(motif: Motif) -> list[Shape]:
    """The motif's shapes in absolute (rounded) coordinates, as a plain drawing stores them."""
    return [s.moved(motif.x, motif.y, motif.angle) for s in motif.kind.shapes]


def svg_plain(region: Region, title: str, motifs: list[Motif]) -> str:
    """The plain encoding: one top-level element (or <g>) per motif, absolute coordinates."""
    out = svg_open(region, title)
    out.append(f"  {region.svg()}")
    for m in motifs:
        shapes = absolute_shapes(m)
        if len(shapes) == 1 and not m.kind.group:
            out.append(f"  {shapes[0].svg()}")
        else:
            out.append("  <g>")
            out += [f"    {s.svg()}" for s in shapes]
            out.append("  </g>")
    out += ["</svg>", ""]
    return "\n".join(out)


# --------------------------------------------------------------------------- the exemplars


@dataclass
class Exemplar:
    """Everything needed to draw, check, write and document one exemplar."""

    name: str
    title: str
    depicts: str
    modelled_on: str
    region: Region
    structure: str  # what a cartographer draws: rows, clumps, pairs … (for the README)
    kinds: list[Kind]
    layout: Callable[[np.random.Generator, float], list[Cand]]  # (rng, region size) -> intent
    seed: int
    margin: float
    plain: bool = False

    def build(self) -> tuple[str, list[Motif], Report]:
        """Place, validate and serialise; returns (svg text, motifs, report)."""
        rng = np.random.default_rng(self.seed)
        by_id = {k.id: k for k in self.kinds}
        motifs = settle(self.region, by_id, self.layout(rng, self.region.size), self.margin)
        if self.plain:
            # check the geometry exactly as written: absolute, rounded shapes
            items = [
                (m.kind.id, m.angle, unary_union([s.footprint() for s in absolute_shapes(m)]))
                for m in motifs
            ]
            text = svg_plain(self.region, self.title, motifs)
        else:
            items = [(m.kind.id, m.angle, m.footprint()) for m in motifs]
            text = svg_symbols(self.region, self.title, self.kinds, motifs)
        return text, motifs, validate(self.name, self.region, items)


def pts(text: str) -> list[tuple[float, float]]:
    """Parse SVG-style point lists ``"x,y x,y ..."`` (compact hand-drawn coordinates)."""
    return [tuple(float(v) for v in pair.split(",")) for pair in text.split()]


def pebble_outline(sx: float, sy: float, wobble: list[float]) -> list[tuple[float, float]]:
    """Control points of a rounded pebble: an ellipse with per-vertex radial wobble."""
    n = len(wobble)
    return [
        ((1 + w) * sx * math.cos(2 * math.pi * i / n), (1 + w) * sy * math.sin(2 * math.pi * i / n))
        for i, w in enumerate(wobble)
    ]


FREE = ("uniform", 0, 360)  # orientation law: free rotation


def gravel() -> Exemplar:
    pen = {"stroke": INK, "width": 0.35}
    oblong = pebble_outline(2.2, 1.35, [0.0, 0.08, -0.05, 0.1, -0.04, 0.06, -0.08])
    kinds = [
        Kind(
            "pebble-round",
            "near-circular pebble outline (ellipse)",
            [ellipse(0, 0, 1.7, 1.3, **pen)],
            FREE,
        ),
        Kind(
            "pebble-oblong",
            "oblong, slightly irregular pebble outline (smooth path)",
            [smooth_closed(oblong, **pen)],
            FREE,
        ),
    ]
    return Exemplar(
        name="gravel",
        title="Gravel or conglomerate: rounded pebble outlines",
        depicts="gravel / conglomerate: scattered rounded pebbles drawn as thin outlines",
        modelled_on="FGDC 601 *Gravel or conglomerate (1st option)* and 602 "
        "(pebble outlines only, no dots)",
        structure="pebbles in nests of two or three (gaps about 0.8) at sites on loose "
        "offset rows about 10 apart, each nest of one shape (round or oblong)",
        region=Region("square", 60),
        kinds=kinds,
        layout=lambda rng, size: gravel_layout(rng, size, {k.id: k for k in kinds}),
        seed=601,
        margin=0.4,
    )


def gravel_layout(rng, size, kinds) -> list[Cand]:
    out = []
    mix = {"pebble-round": 1, "pebble-oblong": 1}
    for x, y, _r, _i in rows(rng, size, 10.0, 10.5, spread=0.15, wobble=0.6):
        n = int(pick(rng, {"2": 2, "3": 3}))
        out += group(rng, [kinds[pick(rng, mix)]] * n, x, y, 0.8, keep=0.6, box=size)
    return out


def sand() -> Exemplar:
    dot_shape = circle(0, 0, 0.4, fill=BLACK, stroke=None)
    return Exemplar(
        name="sand",
        title="Massive sand or sandstone: small dots",
        depicts="sand / sandstone: evenly scattered small dots",
        modelled_on="FGDC 607 *Massive sand or sandstone*",
        structure="dots on offset rows 5 apart, about 5.5 apart along a row, each a little off "
        "its place (a hand-stippled lattice)",
        region=Region("square", 50),
        kinds=[Kind("dot", 'filled dot, diameter 0.8 (`<circle r="0.4">`)', [dot_shape])],
        layout=lambda rng, size: [
            Cand("dot", x, y, 0.0, 2.0)
            for x, y, _r, _i in rows(rng, size, 5.0, 5.6, spread=0.18, wobble=0.3)
        ],
        seed=607,
        margin=0.4,
    )


def shale() -> Exemplar:
    pen = {"stroke": BLACK, "width": 0.4, "cap": "butt"}
    law = ("normal", 1.0, 3.0)  # sd 1°, clipped to ±3°
    kinds = [
        Kind(
            "dash-long",
            "horizontal dash, length 5 (butt caps)",
            [line(-2.5, 0, 2.5, 0, **pen)],
            law,
        ),
        Kind(
            "dash-short",
            "horizontal dash, length 2.6 (butt caps)",
            [line(-1.3, 0, 1.3, 0, **pen)],
            law,
        ),
    ]
    return Exemplar(
        name="shale",
        title="Shale: short horizontal dashes",
        depicts="shale / clay shale: short horizontal dashes in loose layers "
        "(strongly oriented, all within ±3°)",
        modelled_on="FGDC 620 *Clay or clay shale* (here jittered instead of in strict rows)",
        structure="dashes end to end along rows 3.6 apart, a short one after one to three "
        "long ones, each row offset from the one above (brickwork)",
        region=Region("square", 48),
        kinds=kinds,
        layout=lambda rng, size: shale_layout(rng, size, {k.id: k for k in kinds}),
        seed=620,
        margin=0.4,
    )


def shale_layout(rng, size, kinds) -> list[Cand]:
    seqs: dict[int, list[str]] = {}
    half = {"dash-long": 2.5, "dash-short": 1.3}

    def kind_at(r: int, k: int) -> str:
        seq = seqs.setdefault(r, [])
        while len(seq) <= k:
            run = [] if seq and seq[-1] == "dash-short" else ["dash-long"] * int(rng.integers(1, 4))
            seq += [*run, "dash-short"] if run else ["dash-long"]
        return seq[k]

    def pitch(r: int, k: int) -> float:
        return half[kind_at(r, k)] + 2.2 + half[kind_at(r, k + 1)]

    return [
        cand(rng, kinds[kind_at(r, i)], x, y, 0.9)
        for x, y, r, i in rows(rng, size, 3.6, pitch, spread=0.2, wobble=0.2, stagger=0.4)
    ]


def breccia() -> Exemplar:
    pen = {"stroke": INK, "width": 0.35}
    kinds = [
        Kind(
            "fragment-triangle",
            "angular triangular fragment",
            [polygon(pts("-1.9,1.3 2.3,0.8 -0.3,-1.9"), **pen)],
            FREE,
        ),
        Kind(
            "fragment-quad",
            "angular four-sided fragment",
            [polygon(pts("-2.2,-0.8 1.5,-1.5 2.1,1 -1.2,1.4"), **pen)],
            FREE,
        ),
        Kind(
            "fragment-notched",
            "angular fragment with a re-entrant notch",
            [polygon(pts("-2.3,-0.5 -0.6,-1.7 2,-1.3 1,0.1 2.2,1.4 -1,1.5"), **pen)],
            FREE,
        ),
    ]
    return Exemplar(
        name="breccia",
        title="Breccia: angular fragments",
        depicts="breccia: angular rock fragments (outlines) at arbitrary rotations",
        modelled_on="FGDC 605 *Breccia (1st option)* (fragments only, no dots)",
        region=Region("square", 60),
        kinds=kinds,
        structure="fragments of one shape in groups of two or three (a broken clast whose pieces "
        "lie close, gaps about 0.8) at sites on offset rows about 10 apart",
        layout=lambda rng, size: groups_layout(
            rng,
            size,
            {k.id: k for k in kinds},
            row_gap=10.0,
            pitch=10.5,
            reach=0.8,
            sizes={2: 2, 3: 3},
            weights={"fragment-triangle": 1, "fragment-quad": 1, "fragment-notched": 1},
        ),
        seed=605,
        margin=0.4,
    )


def groups_layout(rng, size, kinds, *, row_gap, pitch, reach, sizes, weights) -> list[Cand]:
    """Groups of one kind (sizes: group size -> weight), ``reach`` apart within, at sites on
    offset rows."""
    out = []
    n_of = {str(k): v for k, v in sizes.items()}
    for x, y, _r, _i in rows(rng, size, row_gap, pitch, spread=0.2, wobble=0.6):
        n = int(pick(rng, n_of))
        out += group(rng, [kinds[pick(rng, weights)]] * n, x, y, reach, keep=0.6, box=size)
    return out


def breccia_plain() -> Exemplar:
    pen = {"stroke": BLACK, "width": 0.3}
    kinds = [
        Kind(
            "shard",
            "sharp triangular shard, a top-level `<polygon>`",
            [polygon(pts("-2.4,0.9 2.2,0.6 -0.4,-1.3"), **pen)],
            FREE,
        ),
        Kind(
            "block",
            "irregular four-sided block, a top-level `<polygon>`",
            [polygon(pts("-1.7,-1.2 1.8,-1.5 1.3,1.4 -1.6,1.1"), **pen)],
            FREE,
        ),
        Kind(
            "clast-with-crystal",
            "five-sided clast with a small filled crystal inside, "
            "a `<g>` of a `<polygon>` and a `<circle>`",
            [
                polygon(pts("-2.2,-0.6 -0.2,-1.8 2.1,-0.9 1.4,1.5 -1.3,1.4"), **pen),
                circle(0.3, 0.1, 0.45, fill=BLACK, stroke=None),
            ],
            FREE,
            group=True,
        ),
    ]
    return Exemplar(
        name="breccia-plain",
        title="Volcanic breccia, drawn as plain shapes (no symbol/use)",
        depicts="breccia drawn the way most real files are: every fragment is its own "
        "absolutely positioned element, no `<symbol>`/`<use>`; identical shapes recur at "
        "different rotations and positions, so the kinds can be recovered up to "
        "rotation + translation",
        modelled_on="FGDC 714 *Volcanic breccia and tuff* and 606 *Breccia (2nd option)*",
        region=Region("square", 56),
        kinds=kinds,
        structure="split fragments: pairs of the same shape, the second turned about half "
        "round (gap about 0.8), at sites on offset rows about 9 apart",
        layout=lambda rng, size: breccia_plain_layout(rng, size, {k.id: k for k in kinds}),
        seed=714,
        margin=0.4,
        plain=True,
    )


def breccia_plain_layout(rng, size, kinds) -> list[Cand]:
    out = []
    for x, y, _r, _i in rows(rng, size, 9.0, 9.5, spread=0.15, wobble=0.5):
        k = kinds[pick(rng, {"shard": 1.1, "block": 1, "clast-with-crystal": 0.9})]
        a = k.sample_angle(rng)
        turned = a + 180 + rng.uniform(-20, 20)  # the other half of a split fragment
        out += group(rng, [k, k], x, y, 0.8, angles=[a, turned], keep=0.6, box=size)
    return out


def marsh() -> Exemplar:
    pen = {"stroke": BLACK, "width": 0.3}
    upright = ("uniform", -10, 10)
    tuft3 = [
        line(-1.7, 1.1, 1.7, 1.1, **pen),
        polyline(pts("0,1.1 0.05,-0.3 -0.05,-1.7"), **pen),
        polyline(pts("-0.6,1.1 -0.95,0 -1.5,-0.9"), **pen),
        polyline(pts("0.6,1.1 0.95,0 1.5,-0.9"), **pen),
    ]
    tuft5 = [line(-2.2, 1.1, 2.2, 1.1, **pen)]
    for x, top, lean in [
        (-1.3, -0.1, -0.9),
        (-0.65, -1.1, -0.45),
        (0, -1.9, 0.0),
        (0.65, -1.1, 0.45),
        (1.3, -0.1, 0.9),
    ]:
        blade = [(x, 1.1), (x + lean * 0.4, (1.1 + top) / 2), (x + lean, top)]
        tuft5.append(polyline(blade, **pen))
    kinds = [
        Kind("tuft-small", "grass tuft: 3 blades on a short ground line", tuft3, upright),
        Kind("tuft-large", "grass tuft: 5 fanned blades on a ground line", tuft5, upright),
    ]
    return Exemplar(
        name="marsh",
        title="Marsh: upright grass tufts",
        depicts="marsh / wetland: upright grass tufts on short ground lines (angles within ±10°)",
        modelled_on="openstreetmap-carto `generating_patterns/marsh.svg` (two tuft variants) "
        "and the topographic marsh symbol",
        region=Region("square", 60),
        kinds=kinds,
        structure="tufts of one size side by side in twos and threes (gap about 0.9), the "
        "groups along offset rows about 7.5 apart",
        layout=lambda rng, size: marsh_layout(rng, size, {k.id: k for k in kinds}),
        seed=1004,
        margin=0.4,
    )


def marsh_layout(rng, size, kinds) -> list[Cand]:
    out = []
    for x, y, _r, _i in rows(rng, size, 7.5, 11.0, spread=0.15, wobble=0.3):
        k = kinds[pick(rng, {"tuft-small": 1.2, "tuft-large": 1})]
        n = int(pick(rng, {"2": 3, "3": 1}))
        out += group(
            rng,
            [k] * n,
            x,
            y,
            0.9,
            theta=0.0 if rng.random() < 0.5 else math.pi,
            keep=0.6,
            box=size,
        )
    return out


def scrub() -> Exemplar:
    pen = {"stroke": BLACK, "width": 0.3}
    upright = ("uniform", -6, 6)
    stick = [
        line(-1.5, 1.4, 1.5, 1.4, **pen),
        line(0, 1.4, 0, -1.6, **pen),
        polyline(pts("0,0.8 -0.95,0.05 -1.3,-1"), **pen),
        polyline(pts("0,0.8 0.95,0.05 1.3,-1"), **pen),
    ]
    crown = [
        smooth_closed(
            pts("-1.4,0.2 -1.5,-0.8 -0.7,-1.5 0.2,-1.7 1.1,-1.2 1.5,-0.3 0.9,0.45 0,0.5"), **pen
        ),
        line(0, 0.5, 0, 1.5, **pen),
        line(-1.1, 1.5, 1.1, 1.5, **pen),
    ]
    kinds = [
        Kind(
            "bush-stick",
            "stick bush: stem with two upturned branches on a ground line",
            stick,
            upright,
        ),
        Kind("bush-round", "round bush: closed crown outline on a short stem", crown, upright),
    ]
    return Exemplar(
        name="scrub",
        title="Scrub: small bush symbols",
        depicts="scrub / heath: small upright bush symbols (angles within ±6°)",
        modelled_on="openstreetmap-carto `generating_patterns/scrub.svg` (stick bush) and the "
        "Temaki `shrub` icon (round crown)",
        region=Region("square", 60),
        kinds=kinds,
        structure="clumps of three to five bushes of one kind (gaps about 0.8) at sites on "
        "offset rows about 12 apart",
        layout=lambda rng, size: scrub_layout(rng, size, {k.id: k for k in kinds}),
        seed=2005,
        margin=0.4,
    )


def scrub_layout(rng, size, kinds) -> list[Cand]:
    out = []
    for x, y, _r, _i in rows(rng, size, 12.0, 12.5, spread=0.2, wobble=0.8):
        k = kinds[pick(rng, {"bush-stick": 3, "bush-round": 2})]
        out += group(rng, [k] * int(rng.integers(3, 6)), x, y, 0.8, keep=0.6, box=size)
    return out


def till() -> Exemplar:
    pen = {"stroke": INK, "width": 0.35}
    clast = pebble_outline(2.1, 1.35, [0.05, -0.06, 0.12, 0.0, -0.1, 0.08, -0.03, 0.1])
    kinds = [
        Kind("clast", "rounded clast outline (smooth path)", [smooth_closed(clast, **pen)], FREE),
        Kind("ring", "small pebble ring (circle r = 0.75)", [circle(0, 0, 0.75, **pen)]),
        Kind(
            "dash",
            "short dash (length 3.2, round caps), within ±40° of horizontal",
            [line(-1.6, 0, 1.6, 0, **pen)],
            ("uniform", -40, 40),
        ),
        Kind(
            "dot",
            "dot: zero-length line with round caps, diameter 0.7 (FGDC style)",
            [dot(0, 0, 0.7, stroke=INK)],
        ),
    ]
    return Exemplar(
        name="till",
        title="Till or diamicton: clasts, rings, dashes and dots",
        depicts="glacial till / diamicton: unsorted mixture of large clasts, small pebble "
        "rings, short dashes and dots",
        modelled_on="FGDC 681 *Till or diamicton (1st option)* and 682 (2nd option)",
        region=Region("square", 50),
        kinds=kinds,
        structure="large clasts on a coarse offset lattice (about 16 apart), each with one or "
        "two pebble rings close by; dashes on the rows between the clasts; dots on fine offset "
        "rows filling the rest",
        layout=lambda rng, size: till_layout(rng, size, {k.id: k for k in kinds}),
        seed=681,
        margin=0.4,
    )


def till_layout(rng, size, kinds) -> list[Cand]:
    out = []
    coarse = rows(rng, size, 16.7, 16.7, spread=0.15, wobble=1.0)
    for x, y, _r, _i in coarse:  # large motifs first, as a drafter would draw them
        out.append(cand(rng, kinds["clast"], x, y, 0.8))
        for px, py in around(rng, x, y, 4.0, int(rng.integers(1, 3)), spread=0.15):
            out.append(cand(rng, kinds["ring"], px, py, 0.8))
    for x, y, _r, _i in coarse:
        out.append(cand(rng, kinds["dash"], (x + 8.3) % size, (y + 8.3) % size, 2.0))
    out += [
        cand(rng, kinds["dot"], x, y, 2.6)
        for x, y, _r, _i in rows(rng, size, 5.0, 5.4, spread=0.2, wobble=0.4)
    ]
    return out


def boulders() -> Exemplar:
    pen = {"stroke": INK, "width": 0.5, "fill": "#bdbdbd"}
    large = (
        "3.9,1.2 3,2.4 1,2.5 -1.2,2.5 -3.3,2.3 -4,0.9 -3.4,-1 -1.8,-2.5 0.6,-2.9 2.6,-2 3.8,-0.5"
    )
    medium = "2.9,-0.4 2.6,1 2.1,2 0.2,2.2 -1.6,2 -2.8,1.1 -2.7,-0.6 -1.9,-1.9 -0.3,-2.1 1.4,-1.7"
    small = "1.9,0.4 1,1.5 -0.6,1.5 -1.9,0.6 -1.7,-0.8 -0.4,-1.5 1.2,-1.2"
    kinds = [
        Kind(
            "boulder-large",
            "large boulder with a flat base and a bulging top (smooth blob)",
            [smooth_closed(pts(large), **pen)],
            FREE,
        ),
        Kind(
            "boulder-medium",
            "medium, blocky boulder with two facets (smooth blob)",
            [smooth_closed(pts(medium), **pen)],
            FREE,
        ),
        Kind(
            "boulder-small",
            "small rounded boulder (smooth blob)",
            [smooth_closed(pts(small), **pen)],
            FREE,
        ),
    ]
    return Exemplar(
        name="boulders",
        title="Boulders: filled grey blobs with dark outline",
        depicts="boulder field / blockfield: large and small rounded boulders, grey fill with "
        "a dark outline",
        modelled_on="the Temaki `boulder1`–`boulder3` icons and the filled blobs of FGDC 681",
        region=Region("square", 80),
        kinds=kinds,
        structure="boulders of the three sizes mixed along offset rows about 9.4 apart, about "
        "10 apart along a row (a blockfield drawn boulder by boulder)",
        layout=lambda rng, size: boulders_layout(rng, size, {k.id: k for k in kinds}),
        seed=3001,
        margin=0.4,
    )


def boulders_layout(rng, size, kinds) -> list[Cand]:
    out = []
    mix = {"boulder-large": 1, "boulder-medium": 1.2, "boulder-small": 1.4}
    for x, y, _r, _i in rows(rng, size, 9.4, 10.0, spread=0.15, wobble=0.6):
        out.append(cand(rng, kinds[pick(rng, mix)], x, y, 1.2))
    return out


def chert_nodules() -> Exemplar:
    pen = {"stroke": INK, "width": 0.35}
    bedding = ("uniform", -12, 12)
    lens = "1.8,0.05 0.9,0.6 -0.5,0.7 -1.8,0.1 -0.8,-0.55 0.7,-0.6"
    kinked = "2.2,0.3 1.2,0.9 -0.3,0.5 -1.6,1 -2.3,0.1 -1.2,-0.8 0.4,-0.6 1.7,-0.7"
    kinds = [
        Kind(
            "nodule-ellipse",
            "elongate chert nodule (ellipse)",
            [ellipse(0, 0, 2.6, 0.9, **pen)],
            bedding,
        ),
        Kind(
            "nodule-lens",
            "lens-shaped chert nodule with blunt tips (smooth path)",
            [smooth_closed(pts(lens), **pen)],
            bedding,
        ),
        Kind(
            "nodule-irregular",
            "irregular, kinked chert nodule (smooth path)",
            [smooth_closed(pts(kinked), **pen)],
            bedding,
        ),
    ]
    by = {k.id: k for k in kinds}
    return Exemplar(
        name="chert-nodules",
        title="Chert nodules in a circular input region",
        depicts="chert nodules: lens-shaped and elliptical nodules roughly parallel to bedding "
        "(angles within ±12°), drawn inside a CIRCULAR input region",
        modelled_on="the chert nodules of FGDC 639 *Cherty limestone (1st option)* and 648 "
        "*Cherty dolostone* (without the limestone brick lines)",
        region=Region("circle", 68),
        kinds=kinds,
        structure="nodules strung along bedding rows about 5 apart, about 8 apart along a row, "
        "rows offset from one another, inside the circle",
        layout=lambda rng, size: [
            cand(
                rng,
                by[pick(rng, {"nodule-ellipse": 2, "nodule-lens": 3, "nodule-irregular": 0.7})],
                x,
                y,
                1.0,
            )
            for x, y, _r, _i in rows(rng, size, 5.0, 8.0, spread=0.18, wobble=0.3)
            if math.hypot(x - size / 2, y - size / 2) < size / 2 - 0.8
        ],
        seed=639,
        margin=0.4,
    )


EXEMPLARS = [
    gravel,
    sand,
    shale,
    breccia,
    breccia_plain,
    marsh,
    scrub,
    till,
    boulders,
    chert_nodules,
]


# --------------------------------------------------------------------------- README

README_HEAD = """\
# Bundled exemplars

Small hand-drawn-style exemplars for svgtile: each file is a set of non-overlapping motifs inside
an input region (a square, or a circle for `chert-nodules.svg`), the input expected by the
patch-based geometric texture synthesis of AlMeraj et al. (2013).

**License: CC0 1.0 Universal (public domain dedication).** These are our own original drawings,
generated by [`tools/make_exemplars.py`](../tools/make_exemplars.py). They are *modelled on* (not
copied from) the FGDC-STD-013-2006 geologic lithology patterns (US federal work, public domain)
and the openstreetmap-carto area fills (CC0); no coordinates were taken from those files.

Do not edit the SVGs by hand: change the script and run `python3 tools/make_exemplars.py`
(numpy + shapely); the output is deterministic.

## Format

All files but `breccia-plain.svg` use `<symbol>`/`<use>`:

```xml
<defs>
  <symbol id="KIND" overflow="visible"> …shapes drawn around the origin… </symbol>
</defs>
<rect id="region" x="0" y="0" width="60" height="60" fill="none" stroke="none"/>
<g id="motifs">
  <use xlink:href="#KIND" transform="translate(X Y) rotate(DEG)"/>
</g>
```

* The symbol id is the motif kind; the `translate` is the motif position and `rotate` its
  orientation (degrees, clockwise on screen, about the symbol origin).
* Shapes are styled with presentation attributes (`fill`, `stroke`, `stroke-width`,
  `stroke-linecap`, `stroke-linejoin`); ink is `#000` or `#231f20`, boulders have a grey fill.
* A motif's *footprint* is the interior of its closed outlines (filled or not) plus the stroke
  band (round caps add discs at line ends; a zero-length round-capped line is a dot). In every
  file any two footprints are at least 0.4 units apart and every footprint lies inside the
  region; a square exemplar tiled 3 × 3 shows no seam (rows and groups continue across its
  sides), and in the circle the outermost motifs keep about half the typical gap to it. The
  generator asserts all of this.
* Each exemplar has the structure a cartographer draws -- offset rows, nests, clumps, split
  fragments, chains along bedding -- with hand-drawn irregularity, not a dart-thrown scatter
  (which is what the `random` engine makes); "Structure" below says what each one is.
* Numbers have at most 3 decimals.

`breccia-plain.svg` is the "real world" encoding: no `<symbol>`/`<use>`; each motif is a
top-level `<polygon>` or `<g>` with absolute coordinates.

| file | kinds | motifs | region | min gap |
|---|---|---|---|---|
"""


def readme(entries: list[tuple[Exemplar, Report]]) -> str:
    """The exemplars/README.md text: overview table plus one section per exemplar."""
    rows = []
    for ex, rep in entries:
        rows.append(
            f"| `{ex.name}.svg` | {len(rep.counts)} | {sum(rep.counts.values())} | "
            f"{ex.region.shape} {fmt(ex.region.size)} | {rep.min_gap:.2f} |"
        )
    parts = [README_HEAD + "\n".join(rows) + "\n"]
    for ex, rep in entries:
        kinds = "\n".join(
            f"  - `{k.id}` × {rep.counts.get(k.id, 0)} — {k.label}; "
            f"{k.size_text()} units; {angle_text(k, rep)}"
            for k in ex.kinds
        )
        encoding = "plain shapes without `<symbol>`/`<use>`" if ex.plain else "`<symbol>`/`<use>`"
        parts.append(
            f"\n## {ex.name}.svg\n\n"
            f"* **Depicts:** {ex.depicts}.\n"
            f"* **Modelled on:** {ex.modelled_on}.\n"
            f"* **Structure:** {ex.structure}.\n"
            f"* **Kinds and motif counts** ({sum(rep.counts.values())} motifs, {encoding}):\n{kinds}\n"
            f"* **Input region:** {ex.region.describe()}.\n"
            f"* **Spacing:** footprint gaps ≥ {rep.min_gap:.2f} (median nearest-neighbour gap "
            f"{rep.median_gap:.2f}); the motif closest to each side of the boundary is "
            f"{rep.min_margin:.2f}–{max(rep.side_margins.values()):.2f} from it.\n"
            f"\n<!-- preview:{ex.name} -->\n"
        )
    return "".join(parts)


def angle_text(kind: Kind, rep: Report) -> str:
    """Human description of the orientations used for a kind."""
    law = kind.angles[0]
    lo, hi = rep.angle_ranges.get(kind.id, (0.0, 0.0))
    if law == "fixed":
        return "not rotated"
    if law == "uniform" and kind.angles[2] - kind.angles[1] >= 360:
        return "free rotation (0–360°)"
    return f"rotation {fmt(lo)}° … {fmt(hi)}°"


# --------------------------------------------------------------------------- main


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = Path(__file__).resolve().parent.parent
    parser.add_argument("--out", type=Path, default=root / "exemplars", help="output directory")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    entries = []
    for make in EXEMPLARS:
        ex = make()
        text, _motifs, rep = ex.build()
        (args.out / f"{ex.name}.svg").write_text(text, encoding="utf-8")
        entries.append((ex, rep))
        counts = ", ".join(f"{k}={v}" for k, v in rep.counts.items())
        print(
            f"{ex.name:15s} n={sum(rep.counts.values()):3d} min_gap={rep.min_gap:.3f} "
            f"median_gap={rep.median_gap:.2f} margins={rep.min_margin:.2f}.."
            f"{max(rep.side_margins.values()):.2f}  [{counts}]"
        )
    (args.out / "README.md").write_text(readme(entries), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
