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
4. **pick** — each part of the periodic pattern is kept once (the copy whose lowest piece
   lies in the central tile) and moved by whole periods so its centroid is in the tile;
   **repeat** — parts that recur at the same offset and relative rotation in every copy are one
   motif though they do not touch (a tuft of blades, a diatom's two valves, FGDC 710's three
   strokes), unless that offset is a lattice step (:func:`_repeat_groups`);
5. **classify** — motifs identical up to rotation and translation share a kind
   (:func:`svgtile.exemplar.match_kinds`, the rule of plain exemplars);
6. **write** — one ``<symbol>`` per kind (the first motif, redrawn as polylines around its
   centroid), one ``<use>`` per motif, and the tile as ``<rect id="region">`` with
   ``svgtile:period``, so that analysis measures distances across the tile's edges.

The result is an exemplar SVG text that :func:`svgtile.exemplar.parse_exemplar` reads back to
the same motifs.  Grouping follows the perceptual rule of AlMeraj et al. 2013 §3.1 that an
element is what the eye sees as one motif; the footprint is the one of :mod:`svgtile.core.footprint`.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from svgtile.core.footprint import rotation
from svgtile.errors import ExemplarError
from svgtile.svg.dialect import PERIOD_ATTR, SVG_NS, XLINK_NS
from svgtile.svg.kinds import match_kinds
from svgtile.svg.tilepieces import TilePieces, parse_tile
from svgtile.svg.writer import fmt, fmt_array

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
#: Repetition rule (stage 4b): two parts are one motif when the offset between them (in the first
#: part's frame, with their relative rotation) recurs, within this share of the larger kind's radius …
REPEAT_TOLERANCE = 0.05
#: … and this many degrees of relative rotation …
REPEAT_TURN = 3.0
#: … for at least this share of the parts of either kind (swamp's rarer arrangement: 0.45) …
REPEAT_SHARE = 0.25
#: … and at least this many times.  Each part is compared with this many nearest parts.
MIN_REPEATS, NEIGHBOURS = 3, 12
#: A recurring offset that pairs more than this share of its parts twice is a lattice step (every
#: part of a lattice has a neighbour both at +v and at −v), not a motif.
AMBIGUOUS = 0.1
#: Motifs so joined must stand apart: the nearest part outside a motif lies farther than this many
#: times its longest link (a single-linkage gap; the osm-carto marsh, reed, bog, mangrove and swamp
#: tufts have ≥ 1.5, the near-lattices of FGDC 710, 711 and 716 about 1.0) …
SEPARATION = 1.3
#: … for all but this share of the motifs.
CROWDED = 0.1
#: Centred footprints whose outline points agree on a grid of this share of their radius are taken
#: as copies without the rotation search of :func:`svgtile.exemplar.match_kinds` (a speed-up only).
COPY_GRID = 0.02
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

    # 4. one copy per part: the component whose lowest piece lies in the central tile
    order = np.lexsort((base, comp))
    first = order[np.r_[True, comp[order][1:] != comp[order][:-1]]]
    chosen = first[copy[first] == CENTRE]
    part_of = np.full(len(block), -1)
    part_of[np.isin(comp, comp[chosen])] = np.searchsorted(np.sort(comp[chosen]), comp[np.isin(comp, comp[chosen])])
    members = np.flatnonzero(part_of >= 0)
    part = part_of[members]
    n_parts = len(chosen)
    part_fp = _group_union(block[members], part, n_parts)
    mb = shapely.bounds(part_fp)
    span = (mb[:, 2:] - mb[:, :2]) / period
    if (span > 1.0 + 1e-9).any():
        worst = int(np.argmax(span.max(axis=1)))
        raise TileRefused(
            f"not discrete motifs: a group of {int((part == worst).sum())} piece(s) spans "
            f"{span[worst].max():.2g} times the tile, so the pattern is continuous",
            source=tile.source,
        )
    pxy = shapely.get_coordinates(shapely.centroid(part_fp))
    pmove = -np.floor((pxy - origin) / period) * period
    pxy = pxy + pmove

    # 4b. parts that always occur together at the same offset are one motif
    part_paint = _paints(tile, idx, base[members], part, n_parts)
    pcentred = _moved(part_fp, pmove - pxy)
    pkind, pangle = _kinds(pcentred, part_paint)
    order = _symmetry(pcentred[np.unique(pkind, return_index=True)[1]])
    motif_of, join = _repeat_groups(pxy, pkind, pangle, _radii(pcentred), period, origin, order)
    n_motifs = int(motif_of.max(initial=-1)) + 1
    motif = motif_of[part]
    footprint = _group_union(_moved(part_fp, pmove + join), motif_of, n_motifs) if n_motifs < n_parts else _moved(part_fp, pmove)
    cxy = shapely.get_coordinates(shapely.centroid(footprint))
    move = -np.floor((cxy - origin) / period) * period
    centred = _moved(footprint, -cxy)
    cxy = cxy + move

    # 5. kinds up to rotation
    paints = _paints(tile, idx, base[members], motif, n_motifs)
    kind, angle = _kinds(centred, paints)
    # number kinds by size of their motif counts (most common first), stable
    counts = np.bincount(kind)
    rank = np.argsort(np.argsort(-counts, kind="stable"), kind="stable")
    kind = rank[kind]

    # 6. the drawing of each kind: its first motif's pieces around its centroid
    offset = OFFSETS[copy[members]] * period + shift[base[members]] + pmove[part] + join[part] + move[motif]
    text = _write(tile, idx, kind, cxy, angle, motif, base[members], offset)
    wrapped = np.zeros(n_motifs, dtype=bool)
    np.logical_or.at(wrapped, motif, (copy[members] != CENTRE) | (join[part] != 0).any(axis=1))
    return ImportedTile(
        tile.source, tile.box, kind, cxy, angle, np.bincount(motif, minlength=n_motifs), wrapped,
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


def _kinds(centred: np.ndarray, paints: list[tuple]) -> tuple[np.ndarray, np.ndarray]:
    """:func:`svgtile.exemplar.match_kinds` of centred footprints, run once per set of plain copies.

    Footprints with the same paint whose outline points coincide on a grid of :data:`COPY_GRID`
    × their radius (far inside :data:`KIND_TOLERANCE`) are copies: only the first of each set is
    matched up to rotation, and the others take its kind and angle.  Returns (n,) kinds numbered
    in order of first appearance and (n,) angles, degrees.
    """
    radius = _radii(centred)
    coords, index = shapely.get_coordinates(centred, return_index=True)
    step = COPY_GRID * np.maximum(radius, 1e-12)
    cells = np.round(coords / step[index, None]).astype(np.int64)
    start = np.r_[0, np.cumsum(np.bincount(index, minlength=len(centred)))]
    # the cells are relative to each radius, so the radius itself (on a log scale) is in the key
    size = np.round(np.log(np.maximum(radius, 1e-12)) / np.log1p(COPY_GRID)).astype(np.int64)
    keys = [(paints[g], int(size[g]), cells[start[g] : start[g + 1]].tobytes()) for g in range(len(centred))]
    rep: dict[tuple, int] = {}
    first = np.array([rep.setdefault(key, g) for g, key in enumerate(keys)], dtype=np.int64)
    reps = np.unique(first)
    kind, angle = match_kinds([centred[g] for g in reps], [paints[g] for g in reps], KIND_TOLERANCE)
    at = np.searchsorted(reps, first)
    return kind[at], angle[at]


def _paints(tile: TilePieces, idx: np.ndarray, piece: np.ndarray, group: np.ndarray, count: int) -> list[tuple]:
    """(count,) sorted tuples of the distinct paints of each group's pieces (``piece`` indexes
    ``idx``; ``group`` is each piece's group)."""
    sets: list[set] = [set() for _ in range(count)]
    for g, b in zip(group.tolist(), piece.tolist(), strict=True):
        sets[g].add(tile.paint[idx[b]])
    return [tuple(sorted(s)) for s in sets]


def _radii(geoms: np.ndarray) -> np.ndarray:
    """(n,) farthest outline point of each geometry from the origin."""
    coords, index = shapely.get_coordinates(geoms, return_index=True)
    out = np.zeros(len(geoms))
    np.maximum.at(out, index, np.hypot(coords[:, 0], coords[:, 1]))
    return out


def _repeat_groups(
    xy: np.ndarray, kind: np.ndarray, angle: np.ndarray, radius: np.ndarray, period: np.ndarray, origin: np.ndarray,
    order: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
    """Join parts that always occur together: the motifs of a tile whose parts do not touch.

    A tuft of separate blades (osm-carto marsh) or a shape beside a dot (swamp) is drawn as parts
    that neither touch nor pair up as parallel strokes, but a motif is copied whole, so the offset
    from one of its parts to another — taken in the first part's frame, with their relative
    rotation — is the same in every copy, while offsets between separate motifs scatter (Gestalt
    common fate / the repetition AlMeraj et al. 2013 §3.1 look for).  Offsets to the
    :data:`NEIGHBOURS` nearest parts (across the tile's edges) are clustered per ordered pair of
    part kinds, within :data:`REPEAT_TOLERANCE` of the larger kind's radius and
    :data:`REPEAT_TURN` degrees; a cluster holding at least :data:`REPEAT_SHARE` of either kind's
    parts (and :data:`MIN_REPEATS`) is a *recurring offset*, and its pairs are links.

    A part with rotational symmetry (a dash, a cross) has its angle only up to that symmetry, so
    offsets from it are taken in its frame with their direction folded into one sector of the
    symmetry; offsets from a round part (a dot) are taken in its partner's frame (in the tile's
    if both are round), and relative rotations are folded the same way: rotated copies of an
    L-and-dot motif still share one offset.

    A regular lattice makes every neighbour offset recur, so a recurring offset is kept only if it
    is one-to-one (at most :data:`AMBIGUOUS` of its parts have a partner both ways, as every
    lattice point has at +v and −v), and the joined groups must be finite (not reach their own
    repeat) and stand apart (the nearest outside part farther than
    :data:`SEPARATION` times the group's longest link, for all but :data:`CROWDED` of them); while
    they do not, the longest recurring offset is dropped.

    Parameters
    ----------
    xy : (n, 2) part centroids inside the tile, user units
    kind : (n,) part kinds; angle : (n,) degrees, each part's rotation from its kind's first part
    radius : (n,) each part's farthest outline point from its centroid, user units
    period, origin : (2,) the tile's size and corner
    order : (k,) each kind's order of rotational symmetry (1 none, 0 round; see
        :func:`_symmetry`); default all 1

    Returns
    -------
    group : (n,) motif of each part, numbered from 0 by each motif's first part
    join : (n, 2) whole periods moving each part next to the other parts of its motif
    """
    n = len(xy)
    alone = (np.arange(n), np.zeros((n, 2)))
    if n < 2 * MIN_REPEATS:
        return alone
    pos = np.mod(xy - origin, period)
    pos[pos >= period] = 0.0
    k = min(NEIGHBOURS, n - 1)
    dist, nb = cKDTree(pos, boxsize=period).query(pos, k=k + 1)
    i, j, dist = np.repeat(np.arange(n), k), nb[:, 1:].ravel(), dist[:, 1:].ravel()
    ok = (j < n) & (j != i)
    i, j, dist = i[ok], j[ok], dist[ok]
    d = _min_image(pos[j] - pos[i], period)
    order = np.ones(int(kind.max()) + 1, dtype=np.int64) if order is None else np.asarray(order)
    # each part's angle is known up to its symmetry's sector (360° / order; a round part: none)
    sector_of = np.where(order > 0, 360.0 / np.maximum(order, 1), 0.0)
    sector_i, sector_j = sector_of[kind[i]], sector_of[kind[j]]
    # the frame of the offset: the first part's, else (round) its partner's, else (both round)
    # the tile's, whose copies then must not be turned
    length_d = np.hypot(d[:, 0], d[:, 1])
    frame = np.where(sector_i > 0, angle[i], np.where(sector_j > 0, angle[j], 0.0))
    sector = np.where(sector_i > 0, sector_i, np.where(sector_j > 0, sector_j, 360.0))
    direction = np.mod(np.degrees(np.arctan2(d[:, 1], d[:, 0])) - frame, sector)
    t = np.radians(direction)
    local = np.c_[length_d * np.cos(t), length_d * np.sin(t)]
    kind_radius = np.zeros(len(order))
    np.maximum.at(kind_radius, kind, radius)
    scale = REPEAT_TOLERANCE * np.maximum(kind_radius[kind[i]], kind_radius[kind[j]])
    # the relative rotation is known up to the sectors of both parts (their gcd; none if round)
    fold = np.where((sector_i > 0) & (sector_j > 0), np.gcd(sector_i.astype(np.int64), sector_j.astype(np.int64)), 0)
    turn = np.where(fold > 0, np.mod(angle[j] - angle[i], np.where(fold > 0, fold, 360.0)), 0.0)
    turn = np.where(turn > fold / 2, turn - fold, turn)
    # in these coordinates two links repeat each other when no coordinate differs by more than 1
    feat = np.c_[local / np.maximum(scale, 1e-12)[:, None], turn / REPEAT_TURN, 3.0 * kind[i], 3.0 * kind[j]]
    links = cKDTree(feat)
    support = _support(feat)
    per_kind = np.bincount(kind)
    need = np.maximum(MIN_REPEATS, REPEAT_SHARE * np.maximum(per_kind[kind[i]], per_kind[kind[j]]))
    recurring = np.flatnonzero(support >= need)
    if len(recurring) == 0:
        return alone

    # recurring links into clusters, the best-supported offset first (a few dozen clusters)
    cluster = np.full(len(i), -1)
    count = 0
    for r in recurring[np.argsort(-support[recurring], kind="stable")]:
        if cluster[r] >= 0:
            continue
        near = np.asarray(links.query_ball_point(feat[r], r=1.0, p=np.inf), dtype=np.int64)
        near = near[(cluster[near] < 0) & (support[near] >= need[near])]
        cluster[near] = count
        count += 1
    use = cluster >= 0
    ci, a, b, length, step = cluster[use], i[use], j[use], dist[use], d[use]

    # one-to-one: a part with two partners under one offset is a lattice point
    # a pair seen from both sides (i -> j and j -> i) counts once
    key = ci * n * n + np.minimum(a, b) * n + np.maximum(a, b)
    _, unique = np.unique(key, return_index=True)
    ends = np.r_[ci[unique] * n + a[unique], ci[unique] * n + b[unique]]
    node, times = np.unique(ends, return_counts=True)
    twice = node[times > 1]
    involved = np.bincount(node // n, minlength=count)
    ambiguous = np.bincount(twice // n, minlength=count)
    fine = ambiguous <= AMBIGUOUS * involved
    keep = fine[ci] & ~np.isin(ci * n + a, twice) & ~np.isin(ci * n + b, twice)
    ci, a, b, length, step = ci[keep], a[keep], b[keep], length[keep], step[keep]
    if len(ci) == 0:
        return alone
    size = np.zeros(count)
    np.maximum.at(size, ci, length)
    active = np.unique(ci)
    active = active[np.argsort(size[active], kind="stable")]
    while len(active):
        on = np.isin(ci, active)
        graph = coo_matrix((np.ones(int(on.sum())), (a[on], b[on])), shape=(n, n))
        m, group = connected_components(graph, directed=False)
        root = np.full(m, n)
        np.minimum.at(root, group, np.arange(n))
        rel = _min_image(pos - pos[root[group]], period)
        wraps = np.zeros(m, dtype=bool)
        np.logical_or.at(wraps, group[a[on]], np.abs(rel[b[on]] - rel[a[on]] - step[on]).max(axis=1) > 1e-6 * period.max())
        longest = np.zeros(m)
        np.maximum.at(longest, group[a[on]], length[on])
        outside = np.full(m, np.inf)
        apart = group[i] != group[j]
        np.minimum.at(outside, group[i[apart]], dist[apart])
        multi = np.bincount(group, minlength=m) > 1
        crowded = multi & (outside <= SEPARATION * longest)
        if not wraps.any() and crowded.sum() <= CROWDED * multi.sum():
            join = np.round((pos[root[group]] + rel - pos) / period) * period
            return group, join
        active = active[:-1]
    return alone


def _support(feat: np.ndarray) -> np.ndarray:
    """(m,) how many of the rows of ``feat`` (m, f) lie within 1 of each row (max norm, itself
    included).

    The links of a lattice all sit at a few points, so counting pairs of links directly costs
    O(m²); rows are counted instead as distinct points on a grid of 0.1 with their
    multiplicities, so the count is exact to that grid and costs O(distinct points × neighbours).
    """
    cell, inverse, weight = np.unique(np.round(feat * 10.0).astype(np.int64), axis=0, return_inverse=True, return_counts=True)
    centres = cell / 10.0
    tree = cKDTree(centres)
    pairs = tree.sparse_distance_matrix(tree, 1.0 + 1e-9, p=np.inf, output_type="ndarray")
    same = pairs["i"] == pairs["j"]
    count = np.bincount(pairs["i"][~same], weights=weight[pairs["j"][~same]], minlength=len(cell)) + weight
    return count[inverse.reshape(-1)]


def _symmetry(centred: np.ndarray) -> np.ndarray:
    """(k,) order of rotational symmetry of each centred footprint: 0 if round (it matches
    itself turned by any angle), else the largest of 6, 4, 3, 2 it matches itself turned by
    360° / order, else 1; within :data:`KIND_TOLERANCE` / 2 × its radius."""
    radius = np.maximum(_radii(centred), 1e-12)
    order = np.ones(len(centred), dtype=np.int64)
    undecided = np.ones(len(centred), dtype=bool)
    for m, turn in ((0, 37.0), (6, 60.0), (4, 90.0), (3, 120.0), (2, 180.0)):
        at = np.flatnonzero(undecided)
        rot = rotation(turn).T
        turned = shapely.transform(centred[at], lambda p, rot=rot: p @ rot)
        same = at[shapely.hausdorff_distance(centred[at], turned) <= 0.5 * KIND_TOLERANCE * radius[at]]
        order[same] = m
        undecided[same] = False
    return order


def _min_image(d: np.ndarray, period: np.ndarray) -> np.ndarray:
    """(k, 2) offsets moved by whole periods to their shortest form."""
    return d - np.round(d / period) * period


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
