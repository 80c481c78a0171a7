"""Where the optimize engine loses density on a refilled tile: stage by stage, and where in the cells.

For each FGDC tile named (imported as ``svgtile import`` does; 2 × 2 tiles, seed 1, as
benchmarks/optimize_sets.py): density / ρ of the start (Ma, Wei & Tong 2011 §4.1, the patches),
then each iteration's insertion (:mod:`svgtile.engines.optimize.insert`: candidates the cap was
offered and took), kind vote (§4.3, eq. (5); the votes ``shrinking`` refused) and settling (votes
and moves the non-penetration step returned); then per kind the count a tile and share of ρ,
exemplar against output; and the density by distance from the start's seams (bands of a tenth
of the cell: 0.0 is the band along the seams, 0.4 the cell's middle).  Density is counted as the
score counts it (footprint area of the motifs whose centroid lies in the region, over its area).

    .venv/bin/python benchmarks/optimize_density_trace.py 617 619 620 621 626 641 642

Needs ``../shared/data`` beside the checkout (or ``$SVGTILE_SHARED_DATA``).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import shapely

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from test_optimize_sets import SETS  # noqa: E402

import svgtile.engines.optimize.init as init_mod  # noqa: E402
import svgtile.engines.optimize.insert as insert_mod  # noqa: E402
import svgtile.engines.optimize.solver as solver_mod  # noqa: E402
from svgtile import analyze  # noqa: E402
from svgtile.analysis.stats import footprint_areas  # noqa: E402
from svgtile.core.region import Region  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402
from svgtile.svg.reader import parse_exemplar  # noqa: E402
from svgtile.tiles.importer import import_tile  # noqa: E402


def trace(stem: str) -> None:
    t = import_tile(SETS["fgdc"] / f"{stem}.svg")
    x0, y0, w, h = t.box
    ex = parse_exemplar(t.text, source=stem)
    stats = analyze(ex)
    region = Region.rectangle(2 * w, 2 * h, x0, y0)
    area, rho, log, cell = region.shape.area, stats.density, [], []

    def dens(arr) -> float:
        inside = shapely.contains_xy(region.shape, arr.xy[:, 0], arr.xy[:, 1])
        return float(footprint_areas(arr, ex.prototypes)[inside].sum() / area / rho)

    originals = (init_mod.patch_start, solver_mod.settle, solver_mod.insert, solver_mod.shrinking, insert_mod.capped)
    patch_start, settle, insert, shrinking, capped = originals

    def spy_start(*a, **k):
        out = patch_start(*a, **k)
        arr = out[0] if isinstance(out, tuple) else out
        cell.append(k["cell"])
        log.append(f"start: {len(arr)} motifs, density / rho {dens(arr):.3f}")
        return out

    def spy_settle(prev, new, *a, **k):
        out = settle(prev, new, *a, **k)
        log.append(f"  vote {dens(prev):.3f} -> {dens(new):.3f} ({(new.kind != prev.kind).sum()} kinds changed), "
                   f"settled {dens(out[0]):.3f} ({(out[0].kind != new.kind).sum()} returned)")  # fmt: skip
        return out

    def spy_insert(arr, *a, **k):
        out = insert(arr, *a, **k)
        log.append(f"  insert +{len(out[0]) - len(arr)}: {dens(arr):.3f} -> {dens(out[0]):.3f}")
        return out

    def spy_capped(arr, new, *a, **k):
        out = capped(arr, new, *a, **k)
        log.append(f"    cap: {len(new)} offered, {int(out.sum())} taken")
        return out

    def spy_shrinking(*a, **k):
        out = shrinking(*a, **k)
        log.append(f"    shrinking votes refused: {int(out.sum())}")
        return out

    init_mod.patch_start, solver_mod.settle, solver_mod.insert = spy_start, spy_settle, spy_insert
    solver_mod.shrinking, insert_mod.capped = spy_shrinking, spy_capped
    try:
        arr = synthesize(ex, region, "optimize", seed=1, stats=stats).arrangement
    finally:
        init_mod.patch_start, solver_mod.settle, solver_mod.insert, solver_mod.shrinking, insert_mod.capped = originals
    sp = stats.spacing
    c = cell[0] if cell else float("nan")
    print(f"== {stem}: period {ex.period}, {len(ex.motifs)} motifs, {len(ex.prototypes)} kinds, spacing {sp:.2f}, "
          f"cell {c:.2f} ({c / sp:.1f} spacings), density / rho {dens(arr):.3f}")  # fmt: skip
    print("\n".join(log))
    tiles = area / (w * h)
    ek, ok = (np.bincount(a.kind, minlength=len(ex.prototypes)) for a in (ex.motifs, arr))
    ea, oa = footprint_areas(ex.motifs, ex.prototypes), footprint_areas(arr, ex.prototypes)
    print("  kind: a tile, exemplar / output; share of rho, exemplar / output")
    for k in np.flatnonzero(ek + ok):
        print(f"   {k}: {ek[k]} / {ok[k] / tiles:.1f}; {ea[ex.motifs.kind == k].sum() / (w * h) / rho:.3f} / "
              f"{oa[arr.kind == k].sum() / area / rho:.3f}")  # fmt: skip
    if cell:
        f = np.abs((arr.xy / c + 0.5) % 1.0 - 0.5).min(axis=1)  # 0 on a seam, 0.5 at a cell's centre
        bins = np.linspace(0, 0.5, 6)
        got, _ = np.histogram(f, bins, weights=oa)
        share = np.diff(1 - (1 - 2 * bins) ** 2)  # each band's share of the plane
        print("  density / rho by distance from the seams (cells):",
              " ".join(f"{b:.1f}: {g / (area * s) / rho:.2f}" for b, g, s in zip(bins[:-1], got, share, strict=True)))  # fmt: skip


if __name__ == "__main__":
    for stem in sys.argv[1:]:
        trace(stem)
