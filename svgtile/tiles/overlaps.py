"""An imported exemplar never overlaps itself (stage 7 of :mod:`svgtile.tiles.importer`).

Grouping (stage 3) joins every two pieces whose footprints touch or overlap, so the motifs of a
tile do not overlap as drawn.  The exemplar, though, draws each motif with its kind's symbol
(the kind's first motif, turned by the motif's angle), and kinds match up to
:data:`svgtile.tiles.importer.KIND_TOLERANCE`: a motif a few percent off its kind's first one
can then reach into a neighbour it only came near.  (The real tiles once listed here, Equinor
11026's pebble-and-dash chains and FGDC 614's lens beside a dot, came within a hair of their
neighbours, and their outlines, grown by the analysis' tolerance, met; the reader now draws such
outlines finer, :func:`svgtile.core.footprint.separated`, and they import without overlaps or
kinds of their own.)  Such a motif is not a copy that can stand in for
its kind in that place: it keeps a drawing of its own (:func:`separate_kinds`), and the
exemplar is checked again on the whole periodic pattern (:func:`own_overlaps`, the count that
:func:`svgtile.analysis.stats.periodic_distance_matrix` makes).  The rule is AlMeraj et al. 2013
§3.1's: an exemplar's motifs are what the eye sees as separate elements, so two of them never
share area.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import shapely

from svgtile.analysis.stats import periodic_block
from svgtile.core.footprint import motif_radius, near_pairs, overlapping, world_footprints
from svgtile.svg.reader import parse_exemplar

#: Rounds of :func:`separate_kinds` that match the separated motifs among themselves before the
#: ones still overlapping get a kind each (one round settles every real tile of ../shared/data).
ROUNDS = 3


def own_overlaps(text: str, *, source: str) -> tuple[np.ndarray, np.ndarray]:
    """The pairs of motifs of the exemplar SVG ``text`` whose footprints (their kinds' symbols,
    placed, as :mod:`svgtile.analysis.stats` measures them) share area in the periodic pattern.

    Returns
    -------
    pairs : (p, 2) int array, motif indices in ``<use>`` order, each pair of the pattern once
    shift : (p, 2) float array, user units: the copy of the second motif at its place + shift
        overlaps the first at its place (whole periods; 0 within the tile)
    """
    ex = parse_exemplar(text, source=source)
    arr, n = ex.motifs, len(ex.motifs)
    block = periodic_block(arr, ex.period) if ex.period is not None and n else arr
    geoms = world_footprints(block, ex.prototypes)
    i, j = near_pairs(block.xy, motif_radius(block, ex.prototypes), 1e-9)
    mine = i < n  # the tile's own motifs come first in the block
    i, j = i[mine], j[mine]
    hit = overlapping(geoms, i, j, shapely.distance(geoms[i], geoms[j]))
    a, b = i[hit], j[hit] % n
    shift = block.xy[j[hit]] - arr.xy[b]
    # one row per pair of the pattern: (a, b, s) and (b, a, -s) are the same pair
    swap = (a > b) | ((a == b) & ((shift[:, 0] < 0) | ((shift[:, 0] == 0) & (shift[:, 1] < 0))))
    a, b = np.where(swap, b, a), np.where(swap, a, b)
    shift = np.where(swap[:, None], -shift, shift)
    rows = np.unique(np.column_stack([a, b, np.round(shift, 9)]), axis=0)
    return rows[:, :2].astype(np.int64), rows[:, 2:]


def separate_kinds(
    kind: np.ndarray,
    angle: np.ndarray,
    clashes: Callable[[np.ndarray, np.ndarray], np.ndarray],
    match: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
) -> tuple[np.ndarray, np.ndarray, int]:
    """Give the motifs that overlap a neighbour only through their kind's drawing kinds of their own.

    Parameters
    ----------
    kind, angle : (n,) int and (n,) float arrays, degrees: the motifs' kinds and symbol angles;
        a kind is drawn as its first motif (angle 0 there)
    clashes : ``(kind, angle) -> (pairs, shift)`` of the overlapping motifs (:func:`own_overlaps`
        of the exemplar written with those kinds)
    match : ``(motifs) -> (kind, angle)`` of the given motif indices matched among themselves
        (numbered from 0 in order of first appearance, angles relative to the first of each)

    Returns
    -------
    kind, angle : the new kinds (the separated motifs' kinds numbered after the old ones) and angles
    left : int, overlapping pairs that remain, both drawn as themselves (0 on every real tile)
    """
    kind, angle = kind.copy(), angle.copy()
    for round_ in range(ROUNDS + 1):
        pairs = clashes(kind, angle)[0]
        first = np.unique(kind, return_index=True)[1]
        is_rep = np.zeros(len(kind), dtype=bool)
        is_rep[first] = True
        stand_ins = np.unique(pairs[~is_rep[pairs]]) if len(pairs) else np.zeros(0, dtype=np.int64)
        if len(stand_ins) == 0:
            return kind, angle, len(pairs)
        if round_ < ROUNDS:
            new_kind, new_angle = match(stand_ins)
        else:  # the last round: each its own drawing
            new_kind, new_angle = np.arange(len(stand_ins)), np.zeros(len(stand_ins))
        kind[stand_ins] = int(kind.max()) + 1 + new_kind
        angle[stand_ins] = new_angle
    return kind, angle, len(clashes(kind, angle)[0])


def merge_motifs(
    motif_of: np.ndarray, join: np.ndarray, move: np.ndarray, pairs: np.ndarray, shift: np.ndarray
) -> tuple[np.ndarray, np.ndarray] | str:
    """Join overlapping motifs into one motif each.

    Parameters
    ----------
    motif_of : (parts,) int array, each part's motif
    join : (parts, 2) float array, user units: the move that brings each part to its motif
    move : (n, 2) float array, user units: whole periods that bring each motif into the tile
    pairs, shift : (p, 2) int and (p, 2) float arrays from :func:`own_overlaps`

    Returns
    -------
    (motif_of, join) of the joined motifs (numbered in order of their first motif), or a sentence
    saying why they cannot be joined: a motif that overlaps its own repeat is a continuous pattern.
    """
    n = len(move)
    where = np.full((n, 2), np.nan)  # each motif's place in its joined motif, relative to the root's
    root = np.arange(n)
    edges: dict[int, list[tuple[int, np.ndarray]]] = {}
    for (a, b), s in zip(pairs.tolist(), shift, strict=True):  # a handful of pairs: a plain graph walk
        edges.setdefault(a, []).append((b, s))
        edges.setdefault(b, []).append((a, -s))
    for start in sorted(edges):
        if not np.isnan(where[start, 0]):
            continue
        where[start] = 0.0
        todo = [start]
        while todo:
            a = todo.pop()
            for b, s in edges[a]:
                at = where[a] + s
                if np.isnan(where[b, 0]):
                    where[b], root[b] = at, start
                    todo.append(b)
                elif not np.allclose(where[b], at, atol=1e-6 * float(np.abs(move).max(initial=1.0) + 1.0)):
                    return "a motif would join its own repeat"
    where = np.nan_to_num(where)
    _, new_of = np.unique(root[motif_of], return_inverse=True)
    new_join = join + (move + where)[motif_of] - move[root[motif_of]]
    return new_of, new_join
