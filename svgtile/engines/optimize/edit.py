"""Editing by example (Ma, Wei & Tong 2011 §6.3): an edit of a few motifs applied to all alike.

The user edits a copy of a texture — moves, turns or swaps the kind of a few motifs.  The edited
motifs are found by comparing the copy with the texture motif by motif (both in svgtile's
order: an editor that moves ``<use>`` elements keeps it).  Every other motif whose neighbourhood
is within ``threshold`` of an edited motif's by eq. (1) — the same distance the solver
minimises — takes the same change: the displacement turned into its own frame (relative to its
nearest neighbour's direction, so a change made in one row of a turned texture follows the
rows), the same turn, the same new kind.  The result then goes through the non-penetration step
(:func:`.controls.settle`): a propagated change that would make a motif overlap or break the
distance rule is taken back, so the output keeps every invariant.
"""

from __future__ import annotations

import numpy as np

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import rotation
from svgtile.core.region import Region
from svgtile.engines.optimize.controls import conflict_codes, flawed, settle
from svgtile.engines.optimize.match import best_candidates
from svgtile.engines.optimize.search import output_neighbourhoods
from svgtile.errors import ParameterError


def edited_motifs(texture: Arrangement, edited: Arrangement, *, tolerance: float = 1e-3) -> np.ndarray:
    """(n,) bool: the motifs the edit moved (more than ``tolerance`` user units), turned or swapped.

    Raises
    ------
    ParameterError
        The edit added or removed motifs.
    """
    if len(texture) != len(edited):
        raise ParameterError(f"the edited texture has {len(edited)} motifs and the texture {len(texture)}: "
                             "move, turn or swap motifs, but add or remove none")  # fmt: skip
    moved = np.hypot(*(edited.xy - texture.xy).T) > tolerance
    turned = np.abs((edited.angle - texture.angle + 180.0) % 360.0 - 180.0) > 1e-3
    return moved | turned | (edited.kind != texture.kind)


def _frame(xy: np.ndarray, index: np.ndarray) -> np.ndarray:
    """(n,) degrees: the direction of each motif's nearest neighbour (its local frame)."""
    d = xy[np.maximum(index[:, 0], 0)] - xy
    return np.degrees(np.arctan2(d[:, 1], d[:, 0]))


def propagate(texture: Arrangement, edited: Arrangement, exemplar: Exemplar, stats: Stats, region: Region, *,
              threshold: float = 0.05, neighbours: int = 6) -> tuple[Arrangement, int, int]:  # fmt: skip
    """Apply the edit of ``texture`` into ``edited`` to every motif with a similar neighbourhood.

    Parameters
    ----------
    texture : the texture as synthesized, n motifs
    edited : the same n motifs, some moved, turned or swapped by the user
    exemplar, stats : the texture's exemplar and its analysis (the distance rule)
    region : the texture's region
    threshold : largest eq. (1) distance, squared exemplar spacings, of a neighbourhood to an
        edited one for the edit to apply
    neighbours : k of the neighbourhoods

    Returns
    -------
    the result, how many motifs the user edited, how many took an edit from them
    """
    user = edited_motifs(texture, edited)
    src = np.flatnonzero(user)
    if len(src) == 0 or len(texture) < 2:
        return edited, len(src), 0
    spacing = float(np.sqrt(exemplar.region.area / max(len(exemplar.motifs), 1)))
    hoods = output_neighbourhoods(texture.xy, texture.kind, neighbours, spacing, np.zeros(len(texture)))
    frame = _frame(texture.xy, hoods.index)
    # each motif's neighbourhood in its own frame, against the edited motifs' (the "exemplar")
    turned = output_neighbourhoods(texture.xy, texture.kind, neighbours, spacing, frame)
    rel_e = np.ascontiguousarray(turned.rel[src])
    cand = np.tile(np.arange(len(src)), (len(texture), 1))
    best, cost = best_candidates(turned.rel, turned.kind, texture.kind, cand, rel_e, turned.kind[src],
                                 texture.kind[src], 1.0)  # fmt: skip
    take = (cost <= threshold) & ~user
    who = src[best[take]]
    # the user's displacement in the edited motif's frame, turned into the taking motif's
    local = np.einsum("nij,nj->ni", rotation(-frame[who]), edited.xy[who] - texture.xy[who])
    xy, kind, angle = edited.xy.copy(), edited.kind.copy(), edited.angle.copy()
    at = np.flatnonzero(take)
    xy[at] = texture.xy[at] + np.einsum("nij,nj->ni", rotation(frame[at]), local)
    angle[at] = texture.angle[at] + (edited.angle[who] - texture.angle[who])
    kind[at] = edited.kind[who]
    new = Arrangement(kind, xy, angle, edited.scale).quantized(DECIMALS)
    known, _ = conflict_codes(edited, exemplar, stats)
    out, _ = settle(edited, new, exemplar, stats, region, "none", known, flawed(edited, exemplar, stats))
    changed = int(((out.xy != edited.xy).any(axis=1) | (out.kind != edited.kind) | (out.angle != edited.angle)).sum())
    return out, len(src), changed
