"""Turning a seamless pattern tile into an exemplar (``svgtile import``).

Map symbol sets (FGDC lithology patterns, OSM area fills, well-log tiles) are drawn as one tile of
plain paths that repeats seamlessly; one element may hold many motifs, one motif may be several
elements, and motifs crossing the tile's edge are cut there.  The pipeline, stage by stage:

1. **pieces** — :func:`svgtile.svg.tilepieces.read_tile` flattens the tile into drawn subpaths with
   their footprints (stroke bands; zero-length round-capped lines are dots of the stroke's
   diameter) and drops frame/background rectangles equal to the tile;
2. **wrap** — every piece is moved by whole periods so that its centre lies in the tile, and
   pieces that are then identical (explicit periodic copies, duplicates) are dropped;
3. **group** — pieces are joined into motifs on a 3 × 3 block of tiles, so that motifs cut at
   an edge are reassembled: footprints that touch or overlap belong together, and so do two
   pieces closer than :data:`JOIN_RATIO` times the smaller one's size (729's pairs of parallel
   lines), and pieces of one icon (an element, ``<g>`` or ``<use>`` expansion spanning at most
   :data:`ICON_SPAN` of the tile) closer than :data:`ELEMENT_JOIN` times the pattern's spacing
   (an icon drawn as one ``<path>`` or one group stays whole); a group that reaches its own
   repeat is a continuous line or hatching, and the pattern is refused (:class:`TileRefused`);
4. **pick** — each part of the periodic pattern is kept once (the copy whose lowest piece
   lies in the central tile) and moved by whole periods so its centroid is in the tile;
   **repeat** — parts that recur at the same offset and relative rotation in every copy are one
   motif though they do not touch (a tuft of blades, a diatom's two valves, FGDC 710's three
   strokes), unless that offset is a lattice step (:func:`svgtile.tiles.repeat.repeat_groups`);
5. **classify** — motifs identical up to rotation and translation share a kind
   (:func:`svgtile.svg.kinds.match_kinds`, the rule of plain exemplars);
6. **write** — one ``<symbol>`` per kind (the first motif, redrawn as polylines around its
   centroid), one ``<use>`` per motif, and the tile as ``<rect id="region">`` with
   ``svgtile:period``, so that analysis measures distances across the tile's edges;
7. **own overlaps** — no two motifs of the exemplar overlap as analysis measures them: a motif
   that would only through its kind's drawing keeps its own, motifs whose outlines overlap are
   joined, or the notes say why not (:mod:`svgtile.tiles.overlaps`).

The result is an exemplar SVG text that :func:`svgtile.svg.reader.parse_exemplar` reads back to
the same motifs.  Grouping follows the perceptual rule of AlMeraj et al. 2013 §3.1 that an
element is what the eye sees as one motif; the footprint is the one of :mod:`svgtile.core.footprint`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from svgtile.errors import ExemplarError
from svgtile.files import read_input
from svgtile.svg.kinds import match_kinds
from svgtile.svg.tilepieces import TilePieces, parse_tile
from svgtile.tiles.overlaps import merge_motifs, own_overlaps, separate_kinds
from svgtile.tiles.refusals import LeftOut, TileRefused
from svgtile.tiles.repeat import radii, repeat_groups, symmetry_orders
from svgtile.tiles.write import exemplar_text

__all__ = ["ImportedTile", "LeftOut", "TileRefused", "import_bedded", "import_pieces", "import_tile"]

#: Two parallel straight strokes closer than this share of the shorter one's length belong to one
#: motif, as the two lines of each FGDC 729 motif do (gaps 0.16–0.21 of the length there).
JOIN_RATIO = 0.3
#: … when their directions differ by less than this many degrees …
PARALLEL = 10.0
#: … their lengths by less than this ratio …
SIMILAR_LENGTH = 0.6
#: … and each is straight: no point farther from its chord than this share of its length.
STRAIGHTNESS = 0.05
#: Shape tolerance for kinds (see :func:`svgtile.svg.kinds.match_kinds`): hand-digitised symbol
#: sets repeat a motif with a few percent of variation (FGDC 730 has 3 of 43 rectangles 7 % larger).
KIND_TOLERANCE = 0.08
#: Subpaths of one element (an icon drawn as one ``<path>``: osm-carto's dog-park paw is a pad and
#: four toes, the Muslim graveyard's crescent and star) closer than this share of the pattern's
#: spacing, ``√(tile area / pieces)``, are one motif.  Icons measured 0.04–0.06; the dashes FGDC
#: 303-K and 305-K draw all in one path stand 0.25–0.31 apart, and stay apart.  The same share
#: holds for the shapes of one ``<g>`` or ``<use>``: osm-carto swamp's two trees in one def stand
#: 0.07 apart (0.95 units at a spacing of 12.8).
ELEMENT_JOIN = 0.15
#: … when the element or group is an icon: its pieces span at most this share of the tile each way.
ICON_SPAN = 0.5
#: Gaps below this share of the tile's size count as touching (coordinates are rounded in files).
TOUCH = 2e-4
#: … and so do gaps below this share of the smaller piece's size (the square root of its box's
#: area): FGDC 626 draws two pieces 0.014 units apart (1.7 % of the smaller), which the redrawn
#: symbols then made overlap.
TOUCH_SIZE = 0.05
#: Pairs of pieces (on the 3 × 3 block) whose boxes come within joining reach, at most: the real
#: tiles of ../shared/data have at most some 250,000 (FGDC 661: 3,137 motifs drawn over each other),
#: and the grouping costs about 50 µs a pair.
MAX_NEAR_PIECES = 1_000_000
#: Coordinates are compared at this many decimals when dropping duplicate pieces (relative to the
#: tile size, 1e-5 of it).
DUPLICATE_DECIMALS = 5
#: Centred footprints whose outline points agree on a grid of this share of their radius are taken
#: as copies without the rotation search of :func:`svgtile.svg.kinds.match_kinds` (a speed-up only).
COPY_GRID = 0.02
#: Rounds of joining overlapping motifs (:func:`svgtile.tiles.overlaps.merge_motifs`) before
#: the importer gives up and says so in its notes.
MERGE_ROUNDS = 3
#: The 3 × 3 block of tiles, central tile (0, 0) at index 4.
OFFSETS = np.array([(i, j) for j in (-1, 0, 1) for i in (-1, 0, 1)], dtype=np.float64)
CENTRE = 4


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
    cellular : dict or None, the cellular description of a bedded or brick tile
        (:mod:`svgtile.tiles.cellular`); the motifs are then those set in its cells
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
    cellular: dict | None = None

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
    data = read_input(path, error=ExemplarError)
    tile = parse_tile(data, source=str(path))
    try:
        return import_pieces(tile)
    except TileRefused as refused:  # bedded or brick tiles: courses of cells (issue 15)
        return import_bedded(tile, refused)


def import_bedded(tile: TilePieces, refused: TileRefused) -> ImportedTile:
    """The tile as a cellular exemplar (:func:`svgtile.tiles.cellular.import_cellular`), or
    ``refused`` raised again if it is not bedded."""
    from svgtile.tiles.cellular import import_cellular

    text, desc, motifs, notes = import_cellular(tile, refused, import_pieces)
    if motifs is None or len(motifs) == 0:
        empty = np.zeros(0, np.int64)
        return ImportedTile(tile.source, tile.box, empty, np.zeros((0, 2)), np.zeros(0), empty,
                            np.zeros(0, dtype=bool), text, (*tile.warnings, *notes), desc)  # fmt: skip
    return ImportedTile(motifs.source, motifs.box, motifs.kind, motifs.xy, motifs.angle, motifs.pieces, motifs.wrapped,
                        text, (*motifs.notes, *notes), desc)  # fmt: skip


def import_pieces(tile: TilePieces) -> ImportedTile:
    """Group, classify and write the pieces of a tile (stages 2–6 of the module docstring)."""
    notes = list(tile.warnings)
    if tile.frames:
        ground = f" (its colour {tile.ground} kept as the ground)" if tile.ground else ""
        notes.append(f"dropped {len(tile.frames)} frame/background element(s) equal to the tile{ground}")
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
    shift = shift_all = -np.floor((centre - origin) / period) * period
    first = _unique_pieces(tile, shift)
    keep = first == np.arange(len(first))
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
    # subpaths of one element (an icon drawn as one <path>) in one copy, and the spacing of pieces
    element = _icon_places(tile, first, np.round(shift_all / period).astype(np.int64), idx, copy)
    spacing = float(np.sqrt(w * h / n))
    comp = _components(block, lines, scale=float(max(w, h)), element=element, near=ELEMENT_JOIN * spacing,
                       source=tile.source)
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
    order = symmetry_orders(pcentred[np.unique(pkind, return_index=True)[1]], KIND_TOLERANCE)
    motif_of, join = repeat_groups(pxy, pkind, pangle, radii(pcentred), period, origin, order)
    for round_ in range(MERGE_ROUNDS + 1):
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
        text = exemplar_text(tile, idx, kind, cxy, angle, motif, base[members], offset)

        # 7. no two motifs of the exemplar overlap (svgtile.tiles.overlaps)
        if len(own_overlaps(text, source=tile.source)[0]) == 0:
            break

        def clashes(k: np.ndarray, a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
            return own_overlaps(exemplar_text(tile, idx, k, cxy, a, motif, base[members], offset), source=tile.source)  # noqa: B023

        kinds_before, as_read = int(kind.max()) + 1, (kind, angle, text)
        kind, angle, left = separate_kinds(kind, angle, clashes, lambda m: _kinds(centred[m], [paints[g] for g in m]))  # noqa: B023
        text = exemplar_text(tile, idx, kind, cxy, angle, motif, base[members], offset)
        if int(kind.max()) + 1 > kinds_before and not left:
            notes.append(f"{int(kind.max()) + 1 - kinds_before} kind(s) added: motifs a few percent off their "
                         f"kind's shape would overlap a neighbour drawn as it, and keep their own drawing")  # fmt: skip
        if not left:
            break
        pairs, pair_shift = clashes(kind, angle)
        merged = merge_motifs(motif_of, join, move, pairs, pair_shift)
        why = merged if isinstance(merged, str) else None
        if why is None:
            new_of, new_join = merged
            fp = _group_union(_moved(part_fp, pmove + new_join), new_of, int(new_of.max()) + 1)
            b = shapely.bounds(fp)
            if ((b[:, 2:] - b[:, :2]) / period > 1.0 + 1e-9).any():
                why = "joined they would span more than the tile"
        if why is None and round_ == MERGE_ROUNDS:
            why = f"they still overlap after {MERGE_ROUNDS} rounds of joining"
        if why is not None:
            notes.append(f"{left} pair(s) of motifs overlap in the exemplar (their outlines, drawn to the "
                         f"analysis' tolerance, meet) and are not joined: {why}")  # fmt: skip
            kind, angle, text = as_read  # own drawings would not have helped: the kinds as matched
            break
        notes.append(f"joined {len(pairs)} pair(s) of motifs whose outlines overlap into one motif each")
        motif_of, join = merged
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
    """(n,) int: for each piece, the first piece identical to it after wrapping into the tile
    (itself for the pieces kept)."""
    decimals = DUPLICATE_DECIMALS - int(np.ceil(np.log10(max(tile.box[2], tile.box[3]))))
    seen: dict = {}
    first = np.arange(len(tile.points))
    for i, (pts, paint) in enumerate(zip(tile.points, tile.paint, strict=True)):
        key = (paint, bool(tile.closed[i]), np.round(pts + shift[i], decimals).tobytes())
        first[i] = seen.setdefault(key, i)
    return first


def _icons(tile: TilePieces, idx: np.ndarray) -> np.ndarray:
    """(n,) int for the pieces ``idx``: the *icon* each piece belongs to, or -1.

    An icon is an element (an icon drawn as one ``<path>``) or a drawn group (a ``<g>``, a
    ``<use>`` expansion: an icon of a symbol set drawn as several shapes) whose pieces together
    span at most :data:`ICON_SPAN` of the tile each way; a piece belongs to the outermost icon
    that holds it.  An element or group that spans the tile is a pattern drawn in one path or one
    group (FGDC 305-K's dashes, osm-carto's flattened jsdotpattern fills, the one ``<g>`` of
    every FGDC tile), whose subpaths are motifs of their own.
    """
    bounds = shapely.bounds(tile.footprint)
    n = len(tile.element)
    chains = tile.groups if len(tile.groups) == n else [()] * n
    n_el = int(tile.element.max(initial=-1)) + 1
    out = np.full(n, -1)
    # holders innermost to outermost: the element, then each enclosing group (ids after the elements)
    for level in range(max((len(c) for c in chains), default=0) + 1):
        if level == 0:
            holder = tile.element.astype(np.int64)
        else:
            holder = np.array([n_el + c[-level] if len(c) >= level else -1 for c in chains], dtype=np.int64)
        held = holder >= 0
        k = int(holder.max(initial=-1)) + 1
        lo, hi = np.full((k, 2), np.inf), np.full((k, 2), -np.inf)
        np.minimum.at(lo, holder[held], bounds[held, :2])
        np.maximum.at(hi, holder[held], bounds[held, 2:])
        icon = np.zeros(n, dtype=bool)
        icon[held] = ((hi - lo) / np.array(tile.box[2:]) <= ICON_SPAN).all(axis=1)[holder[held]]
        out[icon] = holder[icon]
    return out[idx]


def _icon_places(tile: TilePieces, first: np.ndarray, wrap: np.ndarray, idx: np.ndarray, copy: np.ndarray) -> np.ndarray:
    """(9 n,) int label of each piece of the 3 × 3 block: pieces of one icon (:func:`_icons`) as
    drawn in one place share a label, wherever wrapping into the tile moved them; every other
    piece has a label of its own (negative).

    Parameters
    ----------
    first : (all,) int, the first piece identical to each after wrapping (:func:`_unique_pieces`)
    wrap : (all, 2) int, whole periods that moved each piece into the tile
    idx : (n,) int, the pieces kept
    copy : (9 n,) int, the block's tile of each piece (``OFFSETS`` row)

    An icon drawn again a period away (jsdotpattern's explicit periodic copies) is the same icon:
    a dropped duplicate ties its icon to the kept piece's, at the offset between their places.
    """
    n = len(idx)
    icon = _icons(tile, np.arange(len(first)))
    k = int(icon.max(initial=-1)) + 1
    if k == 0:
        return -1 - np.arange(9 * n)
    # each icon's offset (whole periods) into the frame of the first icon it is tied to
    root, off = np.arange(k), np.zeros((k, 2), dtype=np.int64)
    dup = np.flatnonzero((first != np.arange(len(first))) & (icon >= 0) & (icon[first] >= 0))
    ties: dict[int, list[tuple[int, np.ndarray]]] = {}
    for p in dup.tolist():  # one tie per dropped duplicate: a plain walk of a small graph
        a, b, d = int(icon[p]), int(icon[first[p]]), wrap[p] - wrap[first[p]]
        ties.setdefault(a, []).append((b, -d))
        ties.setdefault(b, []).append((a, d))
    done = np.zeros(k, dtype=bool)
    for start in sorted(ties):
        if done[start]:
            continue
        done[start], todo = True, [start]
        while todo:
            a = todo.pop()
            for b, d in ties[a]:
                if not done[b]:
                    done[b], root[b], off[b] = True, root[start], off[a] + d
                    todo.append(b)
    base = np.tile(np.arange(n), 9)
    own = icon[idx][base]
    place = wrap[idx][base] + OFFSETS[copy].astype(np.int64) - off[np.maximum(own, 0)]
    rows = np.column_stack([root[np.maximum(own, 0)], place])
    label = np.unique(rows, axis=0, return_inverse=True)[1].ravel()
    return np.where(own >= 0, label, -1 - np.arange(len(base)))


def _components(geoms: np.ndarray, lines: _Lines, *, scale: float, source: str, element: np.ndarray | None = None,
                near: float = 0.0) -> np.ndarray:  # fmt: skip
    """(m,) component label of each footprint: joined when they touch or overlap (gap below
    :data:`TOUCH` × ``scale`` or :data:`TOUCH_SIZE` × the smaller one's size), when they are a pair of parallel strokes (:meth:`_Lines.paired`),
    or when they are subpaths of one element (``element``, (m,) int) closer than ``near``."""
    touch = TOUCH * scale
    reach = max(touch, JOIN_RATIO * float(lines.length.max(initial=0.0)), near)
    tree = shapely.STRtree(geoms)
    b = shapely.bounds(geoms)
    boxed = tree.query(shapely.box(b[:, 0] - reach, b[:, 1] - reach, b[:, 2] + reach, b[:, 3] + reach))
    if boxed.shape[1] > MAX_NEAR_PIECES:  # boxes only: cheap, and an upper bound of the work below
        raise TileRefused(f"not discrete motifs: its pieces are drawn over each other throughout "
                          f"({boxed.shape[1] // 9:,} near pairs per tile)", source=source)  # fmt: skip
    i, j = tree.query(geoms, predicate="dwithin", distance=reach)
    keep = i < j
    i, j = i[keep], j[keep]
    gap = shapely.distance(geoms[i], geoms[j])
    r = np.sqrt(shapely.area(shapely.envelope(geoms)))
    seen_touching = gap <= np.maximum(touch, TOUCH_SIZE * np.minimum(r[i], r[j]))
    join = seen_touching | lines.paired(i, j, gap)
    if element is not None:
        join |= (element[i] == element[j]) & (gap <= near)
    m = len(geoms)
    graph = coo_matrix((np.ones(int(join.sum())), (i[join], j[join])), shape=(m, m))
    return connected_components(graph, directed=False)[1]


def _kinds(centred: np.ndarray, paints: list[tuple]) -> tuple[np.ndarray, np.ndarray]:
    """:func:`svgtile.svg.kinds.match_kinds` of centred footprints, run once per set of plain copies.

    Footprints with the same paint whose outline points coincide on a grid of :data:`COPY_GRID`
    × their radius (far inside :data:`KIND_TOLERANCE`) are copies: only the first of each set is
    matched up to rotation, and the others take its kind and angle.  Returns (n,) kinds numbered
    in order of first appearance and (n,) angles, degrees.
    """
    radius = radii(centred)
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


