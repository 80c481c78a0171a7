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

Motifs are placed by dart throwing until saturation, with a per-motif jittered gap between
*footprints* (interior of closed outlines plus the stroke band), so the spacing is even but not
regular.  Before writing, every exemplar is checked: footprints are pairwise at least
``MIN_GAP`` apart, lie inside the region and keep only a small margin to its boundary.

The output is deterministic (fixed seed per exemplar, at most 3 decimals per number).
Run from anywhere:  python3 tools/make_exemplars.py [--out DIR]
Requires numpy and shapely (>= 2.1, for ``shapely.dwithin``).
"""

from __future__ import annotations

import argparse
import math
import sys
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

    def margin(self, geom: BaseGeometry, stretch_y: float = 1.0) -> float:
        """Signed distance from ``geom`` to the region boundary (negative when sticking out).

        With ``stretch_y`` the distances to the top and bottom sides of a square are divided by
        it (the placement metric of layered exemplars).
        """
        if self.shape == "square":
            x0, y0, x1, y1 = geom.bounds
            return min(x0, self.size - x1, y0 / stretch_y, (self.size - y1) / stretch_y)
        c = self.size / 2
        pts = shapely.get_coordinates(geom)
        return c - float(np.hypot(pts[:, 0] - c, pts[:, 1] - c).max())

    def snap(
        self, motif: Motif, target: float, rng: np.random.Generator, stretch_y: float = 1.0
    ) -> Motif:
        """Move ``motif`` towards a random side (square) or radially (circle) so that its margin
        becomes ``target``: the way a hand drawer fills the region right up to its edge."""
        fp = motif.footprint()
        x, y = motif.x, motif.y
        if self.shape == "square":
            x0, y0, x1, y1 = fp.bounds
            side = rng.integers(4)
            if side == 0:
                x += target - x0
            elif side == 1:
                x += self.size - target - x1
            elif side == 2:
                y += target * stretch_y - y0
            else:
                y += self.size - target * stretch_y - y1
        else:
            c = self.size / 2
            theta = math.atan2(y - c, x - c)
            for _ in range(4):  # the footprint is not round: converge in a few steps
                shift = self.margin(affinity.translate(fp, x - motif.x, y - motif.y)) - target
                x, y = x + shift * math.cos(theta), y + shift * math.sin(theta)
        return Motif(motif.kind, r3(x), r3(y), motif.angle)

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


@dataclass(frozen=True)
class Phase:
    """One drawing pass: kinds (with weights) placed until ``count`` or saturation.

    ``gap`` is the nominal clear distance between footprints; each motif gets its own gap
    ``gap * U(1 - jitter, 1 + jitter)`` and two motifs keep at least the mean of their gaps.
    """

    weights: dict[str, float]
    gap: float
    count: int | None = None
    jitter: float = 0.4
    max_fail: int = 8000
    edge_bias: float = 0.2  # share of candidates pushed against the region boundary


def place(
    region: Region,
    kinds: dict[str, Kind],
    phases: list[Phase],
    margin: float,
    rng: np.random.Generator,
    stretch_y: float = 1.0,
) -> list[Motif]:
    """Dart-throw motifs phase by phase, keeping footprint gaps and the boundary margin.

    ``stretch_y`` > 1 measures the gaps in a space squeezed vertically by that factor, so vertical
    gaps come out larger than horizontal ones (a layered look); the true gap never drops below
    ``PLACE_GAP``.  A share of the candidates is snapped to the boundary with a margin of
    ``margin + U(0, gap)``, so that the outermost motifs sit about half a gap from the edge
    without lining up along it.
    """
    placed = _Placed(stretch_y)
    for phase in phases:
        ids = list(phase.weights)
        prob = np.array([phase.weights[i] for i in ids], dtype=float)
        prob /= prob.sum()
        count, fails = 0, 0
        while fails < phase.max_fail and (phase.count is None or count < phase.count):
            kind = kinds[ids[rng.choice(len(ids), p=prob)]]
            motif = Motif(
                kind,
                r3(rng.uniform(0, region.size)),
                r3(rng.uniform(0, region.size)),
                round(kind.sample_angle(rng), 2),
            )
            gap = phase.gap * rng.uniform(1 - phase.jitter, 1 + phase.jitter)
            if rng.random() < phase.edge_bias:
                target = margin + 0.002 + rng.uniform(0, phase.gap)
                motif = region.snap(motif, target, rng, stretch_y)
            fp = motif.footprint()
            if region.margin(fp, stretch_y) < margin or not placed.clear(motif, fp, gap):
                fails += 1
                continue
            placed.add(motif, fp, gap)
            count, fails = count + 1, 0
    return placed.motifs


class _Placed:
    """The motifs placed so far, with what the gap test needs."""

    def __init__(self, stretch_y: float):
        self.stretch_y = stretch_y
        self.motifs: list[Motif] = []
        self.true: list[BaseGeometry] = []  # footprints
        self.metric: list[BaseGeometry] = []  # footprints squeezed by 1/stretch_y
        self.centres: list[tuple[float, float]] = []
        self.radii: list[float] = []
        self.gaps: list[float] = []

    def squeeze(self, geom: BaseGeometry) -> BaseGeometry:
        return affinity.scale(geom, 1.0, 1.0 / self.stretch_y, origin=(0, 0))

    def add(self, motif: Motif, fp: BaseGeometry, gap: float) -> None:
        self.motifs.append(motif)
        self.true.append(fp)
        self.metric.append(self.squeeze(fp))
        self.centres.append((motif.x, motif.y))
        self.radii.append(motif.kind.radius)
        self.gaps.append(gap)

    def clear(self, motif: Motif, fp: BaseGeometry, gap: float) -> bool:
        """True if ``fp`` keeps the required gaps to every placed footprint."""
        if not self.motifs:
            return True
        c = np.asarray(self.centres)
        need = np.maximum(PLACE_GAP, (gap + np.asarray(self.gaps)) / 2)
        reach = (motif.kind.radius + np.asarray(self.radii) + need) * max(1.0, self.stretch_y)
        near = np.flatnonzero(np.hypot(c[:, 0] - motif.x, c[:, 1] - motif.y) < reach)
        if len(near) == 0:
            return True
        squeezed = self.squeeze(fp)
        shapely.prepare(squeezed)
        if shapely.dwithin(squeezed, np.asarray(self.metric, dtype=object)[near], need[near]).any():
            return False
        shapely.prepare(fp)
        return not shapely.dwithin(fp, np.asarray(self.true, dtype=object)[near], PLACE_GAP).any()


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
    require(25 <= n <= 90, f"{name}: {n} motifs (want 25-90)")
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
    # the outermost motifs must hug every side: about half the typical gap, never a wide band
    require(
        worst <= 0.75 * median_gap,
        f"{name}: a boundary part has an empty band of {worst:.2f} (median gap {median_gap:.2f})",
    )
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
    kinds: list[Kind]
    phases: list[Phase]
    seed: int
    margin: float
    stretch_y: float = 1.0
    plain: bool = False

    def build(self) -> tuple[str, list[Motif], Report]:
        """Place, validate and serialise; returns (svg text, motifs, report)."""
        rng = np.random.default_rng(self.seed)
        by_id = {k.id: k for k in self.kinds}
        motifs = place(self.region, by_id, self.phases, self.margin, rng, self.stretch_y)
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
        region=Region("square", 60),
        kinds=kinds,
        phases=[Phase({"pebble-round": 1, "pebble-oblong": 1}, gap=3.4)],
        seed=601,
        margin=1.3,
    )


def sand() -> Exemplar:
    dot_shape = circle(0, 0, 0.4, fill=BLACK, stroke=None)
    return Exemplar(
        name="sand",
        title="Massive sand or sandstone: small dots",
        depicts="sand / sandstone: evenly scattered small dots",
        modelled_on="FGDC 607 *Massive sand or sandstone*",
        region=Region("square", 50),
        kinds=[Kind("dot", 'filled dot, diameter 0.8 (`<circle r="0.4">`)', [dot_shape])],
        phases=[Phase({"dot": 1}, gap=4.0, jitter=0.3)],
        seed=607,
        margin=1.6,
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
        region=Region("square", 56),
        kinds=kinds,
        phases=[Phase({"dash-long": 3, "dash-short": 1}, gap=2.2, jitter=0.35)],
        seed=620,
        margin=0.9,
        stretch_y=1.7,
    )


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
        phases=[
            Phase({"fragment-triangle": 1, "fragment-quad": 1, "fragment-notched": 1}, gap=2.8)
        ],
        seed=605,
        margin=1.1,
    )


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
        phases=[Phase({"shard": 1, "block": 1, "clast-with-crystal": 1}, gap=2.7)],
        seed=714,
        margin=1.1,
        plain=True,
    )


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
    return Exemplar(
        name="marsh",
        title="Marsh: upright grass tufts",
        depicts="marsh / wetland: upright grass tufts on short ground lines (angles within ±10°)",
        modelled_on="openstreetmap-carto `generating_patterns/marsh.svg` (two tuft variants) "
        "and the topographic marsh symbol",
        region=Region("square", 60),
        kinds=[
            Kind("tuft-small", "grass tuft: 3 blades on a short ground line", tuft3, upright),
            Kind("tuft-large", "grass tuft: 5 fanned blades on a ground line", tuft5, upright),
        ],
        phases=[Phase({"tuft-small": 1, "tuft-large": 1}, gap=3.4)],
        seed=1004,
        margin=1.3,
    )


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
    return Exemplar(
        name="scrub",
        title="Scrub: small bush symbols",
        depicts="scrub / heath: small upright bush symbols (angles within ±6°)",
        modelled_on="openstreetmap-carto `generating_patterns/scrub.svg` (stick bush) and the "
        "Temaki `shrub` icon (round crown)",
        region=Region("square", 60),
        kinds=[
            Kind(
                "bush-stick",
                "stick bush: stem with two upturned branches on a ground line",
                stick,
                upright,
            ),
            Kind("bush-round", "round bush: closed crown outline on a short stem", crown, upright),
        ],
        phases=[Phase({"bush-stick": 3, "bush-round": 2}, gap=3.6)],
        seed=2005,
        margin=1.4,
    )


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
        phases=[  # large motifs first, dots fill the rest (as a drafter would draw it)
            Phase({"clast": 1}, gap=3.6, count=6, max_fail=2000),
            Phase({"dash": 1}, gap=2.4, count=12, max_fail=2000),
            Phase({"ring": 1}, gap=2.2, count=8, max_fail=2000),
            Phase({"dot": 1}, gap=4.4, jitter=0.35),
        ],
        seed=681,
        margin=1.2,
    )


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
        phases=[
            Phase({"boulder-large": 1, "boulder-medium": 1.3}, gap=3.2, count=34),
            Phase({"boulder-small": 1}, gap=2.8, count=22),
        ],
        seed=3001,
        margin=1.2,
    )


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
    return Exemplar(
        name="chert-nodules",
        title="Chert nodules in a circular input region",
        depicts="chert nodules: lens-shaped and elliptical nodules roughly parallel to bedding "
        "(angles within ±12°), drawn inside a CIRCULAR input region",
        modelled_on="the chert nodules of FGDC 639 *Cherty limestone (1st option)* and 648 "
        "*Cherty dolostone* (without the limestone brick lines)",
        region=Region("circle", 68),
        kinds=kinds,
        phases=[Phase({"nodule-ellipse": 2, "nodule-lens": 2, "nodule-irregular": 1}, gap=2.6)],
        seed=639,
        margin=1.1,
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
  file any two footprints are at least 0.4 units apart, every footprint lies inside the region,
  and the outermost motifs keep only about half the typical gap to the region boundary (so the
  exemplar can be tiled without seams). The generator asserts all of this.
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
