"""The regular FGDC/osm-carto tiles and the growth engine's figures on them (issue 13).

Run from the repository root: ``python benchmarks/growth_likeness.py --select`` lists the tiles
the rule of tests/test_growth_regular.py picks (regularity ≥ REGULAR among every tile
``svgtile import`` accepts); without ``--select`` it also measures each (L, repetition, density
ratio, conflicts: tests/growth_measure.py).
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from growth_measure import CANDIDATES, measure

from svgtile.apps.load import load_exemplar
from svgtile.engines.growth.connectivity import REGULAR, reference_rings, regularity
from svgtile.errors import SvgtileError


def main(argv: list[str]) -> None:
    for path in CANDIDATES:
        try:
            ex, _ = load_exemplar(str(path), as_tile=True, warn=lambda m: None)
        except SvgtileError:
            continue  # not a texture of motifs (hatches, continuous lines); cells: the cellular engine's
        if ex.period is None or ex.cellular is not None or regularity(reference_rings(ex)) < REGULAR:
            continue
        if "--select" in argv:
            print(path.stem, flush=True)
            continue
        f = measure(path)
        print(f"{f.name}: L={f.likeness:.3f} repetition={f.repetition:.3f} density={f.density_ratio:.3f} "
              f"overlaps={f.overlaps} violators={f.violators} regularity={f.regularity:.2f}", flush=True)  # fmt: skip


if __name__ == "__main__":
    main(sys.argv[1:])
