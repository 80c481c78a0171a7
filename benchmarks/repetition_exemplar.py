"""Issue 13 (rep13): the repetition figure against the exemplar's own share, on its known answers.

Prints ``repetition`` (new: excess over what the exemplar shows) and ``repetition_order`` (the
figure before: excess over chance at the single mode) for: exemplars scored against themselves;
growth on sand and marsh (300 × 300, seeds 1–3) and on FGDC 619, 620, 670 (5 × 5 tiles, seed 1);
the tile and random engines on FGDC tiles (5 × 5 tiles, seed 1).

Run from the repository root: ``python benchmarks/repetition_exemplar.py``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from svgtile import analyze, read_exemplar
from svgtile.apps.load import load_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import repetition, score

FGDC = (
    Path(os.environ.get("SVGTILE_DATA") or "../shared/data")
    / "fgdc-geologic-patterns"
    / "lithology"
)


def line(label, r):
    print(f"{label:34s} new {r.repetition:.3f} (P_tex {r.repetition_raw:.3f}, P_ex {r.repetition_exemplar or 0:.3f})"
          f"  old {r.repetition_order:.3f}  v={tuple(round(v, 2) for v in r.repetition_vector or ())}", flush=True)  # fmt: skip


def fgdc(name):
    return load_exemplar(str(FGDC / f"{name}.svg"), as_tile=True, warn=lambda m: None)


which = sys.argv[1:] or ["self", "grow", "tile"]
if "self" in which:
    for name in ("sand", "marsh", "gravel", "till", "boulders"):
        ex = read_exemplar(f"exemplars/{name}.svg")
        line(f"self {name}", repetition(ex.motifs, ex, analyze(ex), ex.region))
    for name in ("603", "605", "607", "619", "620", "670", "626", "611"):
        ex, st = fgdc(name)
        line(f"self fgdc/{name}", repetition(ex.motifs, ex, st, ex.region))
if "grow" in which:
    for name in ("sand", "marsh"):
        ex = read_exemplar(f"exemplars/{name}.svg")
        st = analyze(ex)
        for seed in (1, 2, 3):
            region = Region.rectangle(300, 300)
            arr = synthesize(
                ex, region, "growth", seed=seed, stats=st, boundary="centroid"
            ).arrangement
            line(f"growth {name} seed {seed}", score(ex, st, arr, region))
    for name in ("619", "620", "670"):
        ex, st = fgdc(name)
        w, h = ex.period
        region = Region.rectangle(5 * w, 5 * h)
        arr = synthesize(ex, region, "growth", seed=1, stats=st, boundary="centroid").arrangement
        line(f"growth fgdc/{name}", score(ex, st, arr, region))
if "tile" in which:
    for name in ("603", "605", "607", "611", "619", "620", "626", "670"):
        ex, st = fgdc(name)
        w, h = ex.period
        region = Region.rectangle(5 * w, 5 * h)
        for eng in ("tile", "random"):
            arr = synthesize(ex, region, eng, seed=1, stats=st, boundary="centroid").arrangement
            line(f"{eng} fgdc/{name}", score(ex, st, arr, region))
