"""Likeness of the growth engine on a repeating tile, against the tile and random baselines
(shared by tests/test_growth_regular.py and benchmarks/growth_likeness.py).

L = (E_random − E) / (E_random − E_tile), E the neighbourhood distance of Ma, Wei & Tong 2011
(:func:`svgtile.analysis.neighbourhood.neighbourhood_distance`) on the motifs of the interior
(one exemplar width in from the edge); repetition, conflicts and the density ratio from
:func:`svgtile.metrics.score`.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from svgtile.analysis.neighbourhood import likeness, neighbourhood_distance
from svgtile.analysis.stats import analyze
from svgtile.apps.load import load_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.connectivity import reference_rings, regularity
from svgtile.metrics import score
from svgtile.metrics.window import spacing

#: ``shared/data`` beside the checkout (CI), or beside the folder of worktrees (development).
SHARED = next((p / "shared" / "data" for p in Path(__file__).resolve().parents[2:4] if (p / "shared" / "data").is_dir()),
              Path(__file__).resolve().parents[2] / "shared" / "data")  # fmt: skip
#: The candidate tiles: every FGDC lithology pattern and osm-carto area fill.
CANDIDATES = sorted((SHARED / "fgdc-geologic-patterns" / "lithology").glob("*.svg")) + sorted(
    (SHARED / "osm-carto" / "patterns").glob("*.svg"))  # fmt: skip


@dataclass(frozen=True)
class Figures:
    name: str
    regularity: float
    motifs: int
    likeness: float
    e: float
    e_tile: float
    e_random: float
    repetition: float | None
    overlaps: int
    violators: int
    density_ratio: float | None


def measure(path: Path, *, periods: int = 4, seed: int = 1, engine: str = "growth", **params) -> Figures:
    """Figures of ``engine`` (the growth engine unless told) with ``params`` on ``path`` (imported
    as a tile) over ``periods`` × ``periods`` tile periods (at least 200 user units a side)."""
    ex, st = load_exemplar(str(path), as_tile=True, warn=lambda m: None)
    w, h = ex.period
    n = max(periods, int(np.ceil(200 / min(w, h))))
    region = Region.rectangle(n * w, n * h)
    inner = shapely.buffer(region.shape, -max(w, h))
    s = spacing(st)
    es = {}
    sc = None
    for name in (engine, "tile", "random"):
        arr = synthesize(ex, region, name, seed=seed, stats=st, boundary="centroid",
                         params=params if name == engine else None).arrangement  # fmt: skip
        centres = np.flatnonzero(shapely.contains_xy(inner, arr.xy[:, 0], arr.xy[:, 1]))
        es[name] = neighbourhood_distance(arr.xy, arr.kind, ex.motifs.xy, ex.motifs.kind, spacing=s, period=ex.period,
                                            centres=centres, sample=1500, rng=np.random.default_rng(0))  # fmt: skip
        if name == engine:
            sc, count = score(ex, st, arr, region), len(arr)
    return Figures(path.stem, regularity(reference_rings(ex)), count, likeness(es[engine], es["tile"], es["random"]),
                   es[engine], es["tile"], es["random"], sc.repetition, sc.overlaps_total, sc.violators_total,
                   sc.density_ratio)  # fmt: skip


def tile_rows(exemplar, gap: float) -> np.ndarray:
    """(m,) int: the row of each of a repeating tile's motifs — motifs whose y lie within ``gap``
    user units of the next form one row (the FGDC tiles' rows run along x)."""
    y = exemplar.motifs.xy[:, 1]
    order = np.argsort(y, kind="stable")
    row = np.empty(len(y), np.int64)
    row[order] = np.r_[0, np.cumsum(np.diff(y[order]) > gap)]
    return row


def shuffled_rows(exemplar, region: Region, *, rng: np.random.Generator) -> Arrangement:
    """The tile's rows over ``region`` with every row copy moved along x by its own uniform shift
    in [0, w): each row keeps the tile's exact content (its along-row steps), and no two rows keep
    the relation they have in the tile, so nothing repeats at the tile's period across rows.

    The best a texture keeping the tile's rows can do against the repetition figure: what the
    figure still finds in it is the rows' own along-row steps (tests/test_growth_regular.py).
    Motifs are not checked for conflicts (a probe of the figure, not a texture).
    """
    ex = exemplar.motifs
    w, h = exemplar.period
    row = tile_rows(exemplar, 0.5 * spacing(analyze(exemplar)))
    x0, y0, x1, y1 = region.shape.bounds
    ia = np.arange(np.floor((x0 - w) / w), np.ceil(x1 / w) + 1)
    ib = np.arange(np.floor((y0 - h) / h), np.ceil(y1 / h) + 1)
    shift = rng.uniform(0, w, (len(ib), row.max() + 1))
    B, A, S = np.meshgrid(np.arange(len(ib)), ia, np.arange(len(ex)), indexing="ij")
    xy = np.c_[(ex.xy[S, 0] + A * w + shift[B, row[S]]).ravel(), (ex.xy[S, 1] + ib[B] * h).ravel()]
    keep = shapely.contains_xy(region.shape, xy[:, 0], xy[:, 1])
    s = S.ravel()[keep]
    return Arrangement(ex.kind[s], xy[keep], ex.angle[s], ex.scale[s])
