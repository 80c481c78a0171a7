"""The swatch sheet of the regular tiles with growth beside patch: docs/growth-swatches.png (issue 13).

Every FGDC lithology and osm-carto area-fill tile that ``svgtile import`` accepts and that is
*regular* by the rule of tests/test_growth_regular.py (its ring shapes, Ijiri et al. 2008 §4, fall
into few classes: :func:`svgtile.engines.growth.connectivity.regularity` ≥ ``REGULAR``) is drawn
repeated, then synthesized three ways on 3 × 3 tiles (seed 1): ``auto`` (the default engine's
choice, named in the caption), ``patch`` with its defaults, and ``growth``; each caption carries
the texture's likeness L.  The same sheet as::

    svgtile swatches TILES… --engine auto --engine patch --engine growth --columns 2 -o sheet.svg --png

Needs ``../shared/data`` beside the repository and the ``png`` extra (resvg-py).  Run from the
repository root: ``python tools/make_growth_sheet.py`` (a few minutes).
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

from make_patterns_doc import DATA, DOCS, SEED, small_png  # noqa: E402

from svgtile.apps.load import load_exemplar  # noqa: E402
from svgtile.apps.preview import render_png  # noqa: E402
from svgtile.apps.swatches import read_names, swatch_sheet  # noqa: E402
from svgtile.engines.growth.connectivity import REGULAR, reference_rings, regularity  # noqa: E402
from svgtile.errors import SvgtileError  # noqa: E402

FOLDERS = (DATA / "fgdc-geologic-patterns" / "lithology", DATA / "osm-carto" / "patterns")
ENGINES = ("auto", "patch", "growth")


def regular_tiles() -> list[Path]:
    """The regular tiles of :data:`FOLDERS`, in folder and name order."""
    found = []
    for path in (p for folder in FOLDERS for p in sorted(folder.glob("*.svg"))):
        try:
            ex, _ = load_exemplar(str(path), as_tile=True, warn=lambda m: None)
        except SvgtileError:
            continue  # refused: not a texture of motifs
        if ex.cellular is None and ex.period is not None and regularity(reference_rings(ex)) >= REGULAR:
            found.append(path)
    return found


def main() -> None:
    tiles = regular_tiles()
    names = read_names(DATA / "fgdc-geologic-patterns" / "INDEX.csv")
    sheet = swatch_sheet(tiles, columns=2, seed=SEED, names=names, engines=ENGINES)
    (DOCS / "growth-swatches.png").write_bytes(small_png(render_png(sheet.text, 1600)))
    for group in sheet.patterns:
        figures = "  ".join(f"{s.engine}={s.likeness:.2f}" if s.likeness is not None else f"{s.engine}=–" for s in group)
        print(f"{group[0].path.stem}: {figures}  (auto chose {group[0].chosen})")


if __name__ == "__main__":
    main()
