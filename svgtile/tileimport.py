"""Turning a seamless pattern tile into an exemplar (``svgtile import``).

Map symbol sets (FGDC lithology patterns, OSM area fills, well-log tiles) are drawn as one tile of
plain paths that repeats seamlessly; one element may hold many motifs, one motif may be several
elements, and motifs crossing the tile's edge are cut there.  The pipeline, stage by stage:

1. **pieces** — :func:`svgtile.exemplar.read_tile` flattens the tile into drawn subpaths with
   their footprints (stroke bands; zero-length round-capped lines are dots of the stroke's
   diameter) and drops frame/background rectangles equal to the tile;
2. **wrap** — every piece is moved by whole periods so that its centre lies in the tile, and
   pieces that are then identical (explicit periodic copies, duplicates) are dropped;
3. **group** — pieces are joined into motifs on a 3 × 3 block of tiles, so that motifs cut at
   an edge are reassembled: footprints that touch or overlap belong together, and so do two
   pieces closer than :data:`JOIN_RATIO` times the smaller one's size (729's pairs of parallel
   lines); a group that reaches its own repeat is a continuous line or hatching, and the pattern
   is refused (:class:`TileRefused`);
4. **pick** — each motif of the periodic pattern is kept once (the copy whose lowest piece
   lies in the central tile) and moved by whole periods so its centroid is in the tile;
5. **classify** — motifs identical up to rotation and translation share a kind
   (:func:`svgtile.exemplar.match_kinds`, the rule of plain exemplars);
6. **write** — one ``<symbol>`` per kind (the first motif, redrawn as polylines around its
   centroid), one ``<use>`` per motif, and the tile as ``<rect id="region">`` with
   ``svgtile:period``, so that analysis measures distances across the tile's edges.

The result is an exemplar SVG text that :func:`svgtile.exemplar.parse_exemplar` reads back to
the same motifs.  Grouping follows the perceptual rule of AlMeraj et al. 2013 §3.1 that an
element is what the eye sees as one motif; the footprint is the one of :mod:`svgtile.footprint`.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from .errors import ExemplarError
from .exemplar import PERIOD_ATTR, SVG_NS, XLINK_NS, TilePieces, match_kinds, parse_tile
from .output import fmt, fmt_array

#: Two parallel straight strokes closer than this share of the shorter one's length belong to one
#: motif, as the two lines of each FGDC 729 motif do (gaps 0.16–0.21 of the length there).
JOIN_RATIO = 0.3
#: … when their directions differ by less than this many degrees …
PARALLEL = 10.0
#: … their lengths by less than this ratio …
SIMILAR_LENGTH = 0.6
#: … and each is straight: no point farther from its chord than this share of its length.
STRAIGHTNESS = 0.05
#: Shape tolerance for kinds (see :func:`svgtile.exemplar.match_kinds`): hand-digitised symbol
#: sets repeat a motif with a few percent of variation (FGDC 730 has 3 of 43 rectangles 7 % larger).
KIND_TOLERANCE = 0.08
#: Gaps below this share of the tile's size count as touching (coordinates are rounded in files).
TOUCH = 2e-4
#: Coordinates are compared at this many decimals when dropping duplicate pieces (relative to the
#: tile size, 1e-5 of it).
DUPLICATE_DECIMALS = 5
#: The 3 × 3 block of tiles, central tile (0, 0) at index 4.
OFFSETS = np.array([(i, j) for j in (-1, 0, 1) for i in (-1, 0, 1)], dtype=np.float64)
CENTRE = 4


class TileRefused(ExemplarError):
    """The tile is not an arrangement of discrete motifs (hatching, continuous lines, a fill)."""


@dataclass(frozen=True, eq=False)
class ImportedTile:
    """A pattern tile as an exemplar.

    Attributes
    ----------
    source : str
    box : (x, y, width, height) of the tile, user units
    kind : (n,) int array, each motif's kind
    xy : (n, 2) float array, each motif's footprint centroid, inside the tile
    angle : (n,) float array, degrees, rotation of the kind's symbol onto the motif
    pieces : (n,) int array, how many drawn subpaths make each motif
    wrapped : (n,) bool array, the motif was cut at the tile's edge and reassembled
    text : str, the exemplar SVG
    notes : tuple of str, what was dropped or ignored
    """

    source: str
    box: tuple[float, float, float, float]
    kind: np.ndarray
    xy: np.ndarray
    angle: np.ndarray
    pieces: np.ndarray
    wrapped: np.ndarray
    text: str
    notes: tuple[str, ...]

    @property
    def kinds(self) -> int:
        return int(self.kind.max(initial=-1)) + 1

    def __len__(self) -> int:
        return len(self.kind)


def import_tile(path: str | Path) -> ImportedTile:
    """Import the pattern tile SVG at ``path`` (see the module docstring).

    Raises
    ------
    TileRefused
        The pattern is not made of discrete motifs; the message says why.
    ExemplarError
        The file cannot be read as a tile.
    """
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise ExemplarError(f"cannot read file ({exc.strerror or exc})", source=str(path)) from None
    return import_pieces(parse_tile(data, source=str(path)))


def import_pieces(tile: TilePieces) -> ImportedTile:
    """Group, classify and write the pieces of a tile (stages 2–6 of the module docstring)."""
    notes = list(tile.warnings)
    if tile.frames:
        notes.append(f"dropped {len(tile.frames)} frame/background element(s) equal to the tile")
    if len(tile.footprint) == 0:
        if tile.filled_frame:
            raise TileRefused("a solid fill: the tile is one filled rectangle, with no motifs", source=tile.source)
        raise TileRefused("the tile draws nothing", source=tile.source)
    x0, y0, w, h = tile.box
    period = np.array([w, h])
    origin = np.array([x0, y0])

    # 2. wrap pieces into the tile and drop duplicates
    bounds = shapely.bounds(tile.footprint)
    centre = (bounds[:, :2] + bounds[:, 2:]) / 2
    shift = -np.floor((centre - origin) / period) * period
    keep = _unique_pieces(tile, shift)
    if (~keep).any():
        notes.append(f"dropped {int((~keep).sum())} piece(s) repeating others by whole periods")
    idx = np.flatnonzero(keep)
    geoms, shift = _moved(tile.footprint[idx], shift[idx]), shift[idx]
    n = len(idx)

    # 3. group on the 3 x 3 block
    block = _moved(np.tile(geoms, 9), np.repeat(OFFSETS * period, n, axis=0))
    base = np.tile(np.arange(n), 9)
    copy = np.repeat(np.arange(9), n)
    lines = _Lines.of(tile, idx, np.tile(shift, (9, 1)) + np.repeat(OFFSETS * period, n, axis=0), 9)
    comp = _components(block, lines, scale=float(max(w, h)))
    _refuse_continuous(tile, idx, comp, base, copy)

    # 4. one copy per motif: the component whose lowest piece lies in the central tile
    order = np.lexsort((base, comp))
    first = order[np.r_[True, comp[order][1:] != comp[order][:-1]]]
    chosen = first[copy[first] == CENTRE]
    motif_of = np.full(len(block), -1)
    motif_of[np.isin(comp, comp[chosen])] = np.searchsorted(np.sort(comp[chosen]), comp[np.isin(comp, comp[chosen])])
    members = np.flatnonzero(motif_of >= 0)
    motif = motif_of[members]
    footprint = _group_union(block[members], motif, len(chosen))
    mb = shapely.bounds(footprint)
    span = (mb[:, 2:] - mb[:, :2]) / period
    if (span > 1.0 + 1e-9).any():
        worst = int(np.argmax(span.max(axis=1)))
        raise TileRefused(
            f"not discrete motifs: a group of {int((motif == worst).sum())} piece(s) spans "
            f"{span[worst].max():.2g} times the tile, so the pattern is continuous",
            source=tile.source,
        )
    cxy = shapely.get_coordinates(shapely.centroid(footprint))
    move = -np.floor((cxy - origin) / period) * period
    cxy = cxy + move

    # 5. kinds up to rotation
    centred = _moved(footprint, -cxy + move)
    paints = [tuple(sorted({tile.paint[idx[b]] for b in base[members[motif == m]]})) for m in range(len(chosen))]
    kind, angle = match_kinds(list(centred), paints, KIND_TOLERANCE)
    # number kinds by size of their motif counts (most common first), stable
    counts = np.bincount(kind)
    rank = np.argsort(np.argsort(-counts, kind="stable"), kind="stable")
    kind = rank[kind]

    # 6. the drawing of each kind: its first motif's pieces around its centroid
    offset = OFFSETS[copy[members]] * period + shift[base[members]] + move[motif]
    text = _write(tile, idx, kind, cxy, angle, motif, base[members], offset)
    wrapped = np.zeros(len(chosen), dtype=bool)
    np.logical_or.at(wrapped, motif, copy[members] != CENTRE)
    return ImportedTile(
        tile.source, tile.box, kind, cxy, angle, np.bincount(motif, minlength=len(chosen)), wrapped,
        text, tuple(notes),
    )  # fmt: skip


# ----------------------------------------------------------------------------- stages


def _moved(geoms: np.ndarray, by: np.ndarray) -> np.ndarray:
    """Each geometry translated by its own vector; ``by`` is (n, 2)."""
    coords, index = shapely.get_coordinates(geoms, return_index=True)
    return shapely.set_coordinates(shapely.transform(geoms, lambda c: c), coords + by[index])


def _unique_pieces(tile: TilePieces, shift: np.ndarray) -> np.ndarray:
    """(n,) bool: the first of each set of pieces identical after wrapping into the tile."""
    decimals = DUPLICATE_DECIMALS - int(np.ceil(np.log10(max(tile.box[2], tile.box[3]))))
    seen: set = set()
    keep = np.zeros(len(tile.points), dtype=bool)
    for i, (pts, paint) in enumerate(zip(tile.points, tile.paint, strict=True)):
        key = (paint, bool(tile.closed[i]), np.round(pts + shift[i], decimals).tobytes())
        if key not in seen:
            seen.add(key)
            keep[i] = True
    return keep


def _components(geoms: np.ndarray, lines: _Lines, *, scale: float) -> np.ndarray:
    """(m,) component label of each footprint: joined when they touch or overlap (gap below
    :data:`TOUCH` × ``scale``), or when they are a pair of parallel strokes (:meth:`_Lines.paired`)."""
    touch = TOUCH * scale
    reach = max(touch, JOIN_RATIO * float(lines.length.max(initial=0.0)))
    tree = shapely.STRtree(geoms)
    i, j = tree.query(geoms, predicate="dwithin", distance=reach)
    keep = i < j
    i, j = i[keep], j[keep]
    gap = shapely.distance(geoms[i], geoms[j])
    join = (gap <= touch) | lines.paired(i, j, gap)
    m = len(geoms)
    graph = coo_matrix((np.ones(int(join.sum())), (i[join], j[join])), shape=(m, m))
    return connected_components(graph, directed=False)[1]


@dataclass(frozen=True)
class _Lines:
    """Straight open strokes among the pieces, for the parallel-pair rule (Gestalt proximity and
    parallelism: FGDC 729 draws each motif as two parallel lines that do not touch).

    Attributes (one row per piece of the 3 × 3 block, m rows)
    ----------
    straight : (m,) bool, an open subpath whose points lie within :data:`STRAIGHTNESS` × its
        length of its chord
    mid : (m, 2) float, chord midpoint, user units
    direction : (m, 2) float, unit chord direction
    length : (m,) float, chord length, user units
    """

    straight: np.ndarray
    mid: np.ndarray
    direction: np.ndarray
    length: np.ndarray

    @classmethod
    def of(cls, tile: TilePieces, idx: np.ndarray, moves: np.ndarray, reps: int) -> _Lines:
        """Features of pieces ``idx`` of ``tile``, repeated ``reps`` times, the copies moved by
        ``moves`` (reps · n, 2)."""
        first = np.array([tile.points[p][0] for p in idx]).reshape(-1, 2)
        last = np.array([tile.points[p][-1] for p in idx]).reshape(-1, 2)
        chord = last - first
        length = np.hypot(chord[:, 0], chord[:, 1])
        direction = chord / np.maximum(length, 1e-12)[:, None]
        deviation = np.array([
            float(np.abs(_cross(tile.points[p] - first[k], direction[k])).max()) if len(tile.points[p]) > 2 else 0.0
            for k, p in enumerate(idx)
        ])  # fmt: skip
        straight = ~tile.closed[idx] & (length > 0) & (deviation <= STRAIGHTNESS * length)
        mid = np.tile((first + last) / 2, (reps, 1)) + moves
        return cls(np.tile(straight, reps), mid, np.tile(direction, (reps, 1)), np.tile(length, reps))

    def paired(self, i: np.ndarray, j: np.ndarray, gap: np.ndarray) -> np.ndarray:
        """(p,) bool: are pieces i and j two parallel strokes side by side?

        Both straight, directions within :data:`PARALLEL` degrees, lengths within
        :data:`SIMILAR_LENGTH`, gap below :data:`JOIN_RATIO` × the shorter, and each one's midpoint
        within the other's extent along the stroke.
        """
        li, lj = self.length[i], self.length[j]
        cos = np.abs(np.sum(self.direction[i] * self.direction[j], axis=1))
        along_i = np.abs(np.sum((self.mid[j] - self.mid[i]) * self.direction[i], axis=1))
        along_j = np.abs(np.sum((self.mid[i] - self.mid[j]) * self.direction[j], axis=1))
        return (
            self.straight[i] & self.straight[j]
            & (cos >= np.cos(np.radians(PARALLEL)))
            & (np.minimum(li, lj) >= SIMILAR_LENGTH * np.maximum(li, lj))
            & (gap <= JOIN_RATIO * np.minimum(li, lj))
            & (along_i <= li / 2) & (along_j <= lj / 2)
        )  # fmt: skip


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """z of the cross products of (k, 2) vectors ``a`` with the (2,) vector ``b``."""
    return a[:, 0] * b[1] - a[:, 1] * b[0]


def _refuse_continuous(tile: TilePieces, idx: np.ndarray, comp: np.ndarray, base: np.ndarray, copy: np.ndarray) -> None:
    """Refuse the tile if a group of pieces joins its own repeat (an endless line or hatching)."""
    n = len(idx)
    central = np.unique(comp[copy == CENTRE])
    pairs = np.unique(comp * n + base)
    per_comp = np.bincount(pairs // n, minlength=comp.max() + 1)
    size = np.bincount(comp, minlength=comp.max() + 1)
    endless = central[per_comp[central] < size[central]]
    if len(endless) == 0:
        return
    pieces = np.unique(base[np.isin(comp, endless)])
    total = len(idx)
    what = _describe_endless(tile, idx[pieces])
    raise TileRefused(
        f"not discrete motifs: {len(pieces)} of {total} drawn piece(s) join their own repeat across "
        f"the tile's edge ({what}), so the pattern is continuous lines or hatching",
        source=tile.source,
    )


def _describe_endless(tile: TilePieces, pieces: np.ndarray) -> str:
    lengths = np.array([float(np.hypot(*np.ptp(tile.points[p], axis=0))) for p in pieces])
    longest = float(lengths.max(initial=0.0))
    w, h = tile.box[2], tile.box[3]
    if longest >= 0.9 * min(w, h):
        return f"the longest runs {longest / max(w, h):.2g} tile widths"
    return "short pieces touching end to end"


def _group_union(geoms: np.ndarray, group: np.ndarray, count: int) -> np.ndarray:
    """(count,) union of the footprints of each group, holes filled (the motif footprint)."""
    parts, index = shapely.get_parts(geoms, return_index=True)
    order = np.argsort(group[index], kind="stable")
    polys = shapely.polygons(shapely.get_exterior_ring(parts[order]))
    multi = shapely.multipolygons(polys, indices=group[index][order])
    # buffer(0) unions a multipolygon's overlapping parts
    merged = shapely.buffer(multi, 0)
    parts, index = shapely.get_parts(merged, return_index=True)
    polys = shapely.polygons(shapely.get_exterior_ring(parts))
    out = shapely.multipolygons(polys, indices=index)
    single = shapely.get_num_geometries(out) == 1
    out[single] = shapely.get_geometry(out[single], 0)
    assert len(out) == count
    return out


# ----------------------------------------------------------------------------- writing


def _write(
    tile: TilePieces,
    idx: np.ndarray,
    kind: np.ndarray,
    xy: np.ndarray,
    angle: np.ndarray,
    motif: np.ndarray,
    piece: np.ndarray,
    offset: np.ndarray,
) -> str:
    """The exemplar SVG: a symbol per kind, a ``<use>`` per motif, the tile as the region.

    ``motif``, ``piece`` and ``offset`` list every member piece of every motif: the motif it is
    in, its index into ``idx`` and the translation (m, 2) that brings it to the motif's place.
    """
    x0, y0, w, h = tile.box
    box = " ".join(fmt_array(np.array([x0, y0, w, h])))
    root = ET.Element(f"{{{SVG_NS}}}svg", {"viewBox": box, "width": fmt(w), "height": fmt(h)})
    desc = ET.SubElement(root, f"{{{SVG_NS}}}desc")
    desc.text = (
        f"Imported by svgtile from {Path(tile.source).name}: {len(kind)} motif(s) of "
        f"{int(kind.max()) + 1} kind(s); the region repeats with period {fmt(w)} x {fmt(h)}."
    )
    defs = ET.SubElement(root, f"{{{SVG_NS}}}defs")
    for k in range(int(kind.max()) + 1):
        rep = int(np.flatnonzero(kind == k)[0])
        symbol = ET.SubElement(defs, f"{{{SVG_NS}}}symbol", {"id": f"kind-{k + 1}", "overflow": "visible"})
        sel = np.flatnonzero(motif == rep)
        # pieces of one element drawn in one place form one path (holes keep their fill rule)
        groups: dict[tuple, list[int]] = {}
        for s in sel:
            p = idx[piece[s]]
            groups.setdefault((int(tile.element[p]), *np.round(offset[s], 9)), []).append(s)
        for members in groups.values():
            p0 = idx[piece[members[0]]]
            d = " ".join(_path_data(tile.points[idx[piece[s]]] + offset[s] - xy[rep], bool(tile.closed[idx[piece[s]]])) for s in members)
            attrs = {name: _paint_value(name, value) for name, value in tile.paint[p0]}
            attrs["d"] = d
            ET.SubElement(symbol, f"{{{SVG_NS}}}path", dict(sorted(attrs.items())))
    ET.SubElement(root, f"{{{SVG_NS}}}rect", {
        "id": "region", "x": fmt(x0), "y": fmt(y0), "width": fmt(w), "height": fmt(h),
        "fill": "none", PERIOD_ATTR: f"{fmt(w)} {fmt(h)}",
    })  # fmt: skip
    group = ET.SubElement(root, f"{{{SVG_NS}}}g", {"id": "motifs"})
    xs, ys, angles = fmt_array(xy[:, 0]), fmt_array(xy[:, 1]), fmt_array(angle)
    for k, x, y, a in zip(kind.tolist(), xs, ys, angles, strict=True):
        transform = f"translate({x} {y})" + (f" rotate({a})" if a != "0" else "")
        ET.SubElement(group, f"{{{SVG_NS}}}use", {f"{{{XLINK_NS}}}href": f"#kind-{k + 1}", "transform": transform})
    ET.indent(root, space=" ")
    return ET.tostring(root, encoding="unicode", xml_declaration=False) + "\n"


def _path_data(pts: np.ndarray, closed: bool) -> str:
    """Path data of a polyline; a single point is a zero-length line (a dot with round caps)."""
    if len(pts) == 1:
        pts = np.vstack([pts, pts])
    v = fmt_array(pts.ravel())
    coords = [f"{v[2 * i]} {v[2 * i + 1]}" for i in range(len(pts))]
    return "M" + coords[0] + " L" + " ".join(coords[1:]) + (" Z" if closed else "")


def _paint_value(name: str, value: str) -> str:
    """A paint value as plain SVG: QGIS ``param(name) default`` becomes its default."""
    text = value.strip()
    if text.startswith("param("):
        rest = text.split(")", 1)[1].strip()
        return rest or ("none" if name == "fill" else "#000000")
    return text
