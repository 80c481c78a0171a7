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
from svgtile.apps.load import load_exemplar
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
    es = {}
    sc = None
    for name in (engine, "tile", "random"):
        arr = synthesize(ex, region, name, seed=seed, stats=st, boundary="centroid",
                         params=params if name == engine else None).arrangement  # fmt: skip
        es[name] = distance(arr, ex, st, region)
        if name == engine:
            sc, count = score(ex, st, arr, region), len(arr)
    return Figures(path.stem, regularity(reference_rings(ex)), count, likeness(es[engine], es["tile"], es["random"]),
                   es[engine], es["tile"], es["random"], sc.repetition, sc.overlaps_total, sc.violators_total,
                   sc.density_ratio)  # fmt: skip


def distance(arr, ex, st, region: Region) -> float:
    """E: the neighbourhood distance of ``arr`` to the tile ``ex`` on the motifs one tile width in
    from ``region``'s edge (1500 of them at most, fixed draws)."""
    inner = shapely.buffer(region.shape, -max(ex.period))
    centres = np.flatnonzero(shapely.contains_xy(inner, arr.xy[:, 0], arr.xy[:, 1]))
    return neighbourhood_distance(arr.xy, arr.kind, ex.motifs.xy, ex.motifs.kind, spacing=spacing(st), period=ex.period,
                                  centres=centres, sample=1500, rng=np.random.default_rng(0))  # fmt: skip


def baselines(ex, st, region: Region, seed: int = 1) -> tuple[float, float]:
    """(E_tile, E_random) of ``ex`` over ``region``: the two ends of the likeness scale."""
    return tuple(distance(synthesize(ex, region, name, seed=seed, stats=st, boundary="centroid").arrangement, ex, st,
                          region) for name in ("tile", "random"))  # fmt: skip
