"""Growth on the 20 regular tiles with and without row phases (issue 13; svgtile/engines/growth/phases.py).

Run from the repository root: ``python benchmarks/growth_row_phases.py [SEED …]`` (default seed 1).
For each tile of tests/test_growth_regular.py ``REGULAR_TILES`` (4 periods, at least 200 units a
side, as tests/growth_measure.py): whether :func:`row_phases` reads it, and growth's likeness L,
density ratio, repetition and its vector (:func:`svgtile.metrics.score`), the share of motifs with
a same-kind partner one tile height up (``at (0, h)``, within 0.01 spacing) and the first
across-row mode with the along-row ones left out (``row_probes.successive_modes``).  On a tile with
row phases also: growth with them off (what growth did before) and the probe ``markov_rows`` on the
same region (its motifs not checked for conflicts).  A tile without row phases grows by the
unchanged code path, so before = after there.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import numpy as np
from growth_measure import baselines, distance
from row_probes import markov_rows, successive_modes
from test_growth_regular import REGULAR_TILES, at_step

from svgtile.analysis.neighbourhood import likeness
from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.engines.growth.phases import row_phases
from svgtile.metrics import score
from svgtile.metrics.window import spacing


def figures(arr, ex, st, region, base) -> str:
    s = score(ex, st, arr, region)
    h = ex.period[1]
    modes = successive_modes(arr, ex, st, region, 6)
    across = next(((v, g) for v, g in modes if g is not None and abs(g[1]) > 0.5 * spacing(st)), None)
    vec = "—" if s.repetition_vector is None else f"({s.repetition_vector[0]:.2f}, {s.repetition_vector[1]:.2f})"
    acr = "—" if across is None else f"{across[0]:.3f} ({across[1][0]:.2f}, {across[1][1]:.2f})"
    return (f"L {likeness(distance(arr, ex, st, region), *base):.3f} | density {s.density_ratio:.3f} | repetition "
            f"{s.repetition:.3f} {vec} | at (0, h) {at_step(arr, (0.0, h), 0.01 * spacing(st)):.3f} | across {acr} | "
            f"overlaps/violators {s.overlaps_total}/{s.violators_total}")  # fmt: skip


def main(argv: list[str]) -> None:
    seeds = [int(a) for a in argv] or [1]
    for name, path in sorted(REGULAR_TILES.items()):
        ex, st = load_exemplar(str(path), as_tile=True, warn=lambda m: None)
        w, h = ex.period
        n = max(4, int(np.ceil(200 / min(w, h))))
        region = Region.rectangle(n * w, n * h)
        phased = row_phases(ex, 1, st.distance) is not None
        for seed in seeds:
            base = baselines(ex, st, region, seed)
            t = time.perf_counter()
            arr = synthesize(ex, region, "growth", seed=seed, stats=st, boundary="centroid").arrangement
            dt = time.perf_counter() - t
            print(f"{name} seed {seed} row phases {'yes' if phased else 'no'} | growth {figures(arr, ex, st, region, base)}"
                  f" | {len(arr)} motifs {dt:.1f} s", flush=True)  # fmt: skip
            if phased:
                old = synthesize(ex, region, "growth", seed=seed, stats=st, boundary="centroid",
                                 params={"row_phases": False}).arrangement  # fmt: skip
                print(f"{name} seed {seed} before | {figures(old, ex, st, region, base)}", flush=True)
                probe = markov_rows(ex, st, region, rng=np.random.default_rng(seed))
                print(f"{name} seed {seed} markov_rows | {figures(probe, ex, st, region, base)}", flush=True)
            if not phased:
                break  # one seed: these tiles grow as before


if __name__ == "__main__":
    main(sys.argv[1:])
