"""Sand's repetition (issue 13): growth's figure, the exemplar's own, the spread of sand's rows in
both, and ideal lattices of sand's steps with i.i.d. jitter (benchmarks/README.md, "Why growth
on FGDC 619, 620 and 670 cannot meet the repetition gate").

Run from the repository root: ``python benchmarks/sand_repetition.py`` (300 × 300, seed 1).
"""

from __future__ import annotations

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile import analyze, read_exemplar
from svgtile.analysis.order import read_order
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import repetition, score
from svgtile.metrics.window import spacing


def spread(xy: np.ndarray, g: np.ndarray, tol: float) -> np.ndarray:
    """(2,): x / y spread of each motif's displacement to the motif nearest ``x + g`` (within ``tol``)."""
    d, j = cKDTree(xy).query(xy + g, distance_upper_bound=tol)
    ok = np.isfinite(d)
    return (xy[j[ok]] - xy[ok]).std(0)


def main() -> None:
    ex = read_exemplar("exemplars/sand.svg")
    st = analyze(ex)
    s = spacing(st)
    g1, g2 = (np.asarray(step.vector) for step in read_order(ex).steps)
    region = Region.rectangle(300, 300)
    arr = synthesize(ex, region, "growth", seed=1, stats=st, boundary="centroid").arrangement
    sc = score(ex, st, arr, region)
    own = repetition(ex.motifs, ex, st, ex.region)
    print(f"growth: repetition {sc.repetition:.3f} at {np.round(sc.repetition_vector, 2)}, L {sc.likeness:.3f}")
    print(f"exemplar: repetition {own.repetition:.3f} at {np.round(own.repetition_vector, 2)}")
    for k in (1, 2):
        print(f"{k} step(s) along the row: spread growth {np.round(spread(arr.xy, k * g1, 0.4 * s), 3)}, "
              f"exemplar {np.round(spread(ex.motifs.xy, k * g1, 0.4 * s), 3)}")  # fmt: skip
    jitter = spread(ex.motifs.xy, g1, 0.4 * s) / np.sqrt(2)  # per motif: a step is the difference of two
    i, j = np.meshgrid(np.arange(-40, 100), np.arange(-5, 70))
    base = i.ravel()[:, None] * g1 + j.ravel()[:, None] * g2
    for f in (1.0, 1.5, 2.0):
        xy = base + np.random.default_rng(1).normal(0, 1, base.shape) * jitter * f
        xy = xy[shapely.contains_xy(region.shape, xy[:, 0], xy[:, 1])]
        lat = Arrangement(np.zeros(len(xy), np.int64), xy, np.zeros(len(xy)), np.ones(len(xy)))
        sl = score(ex, st, lat, region)
        print(f"lattice, jitter {f} × the exemplar's: repetition {sl.repetition:.3f} L {sl.likeness:.3f} "
              f"violators {sl.violators_total}")  # fmt: skip


if __name__ == "__main__":
    main()
