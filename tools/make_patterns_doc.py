"""Import every pattern tile of the shared symbol sets and write docs/patterns.md (issue 4).

For each tile: ``svgtile import`` (motifs, kinds, or the reason it is refused), then a texture of
3 × 3 tile sizes synthesized with the default engine, ``auto`` (seed 1; the engine it chose is in
the table), and its figures from :func:`svgtile.metrics.score` (likeness L among them: on a
3 × 3 texture, one tile of interior, a rough figure).  A bedded or brick tile imported as cells
(the cellular engine) reports its cells and, in the density and L columns, the linework figures
ink and S (:mod:`svgtile.metrics.linework`); the motif figures do not apply to it.  Also renders the FGDC swatch sheet to docs/fgdc-swatches.png
(the same as ``svgtile swatches <lithology dir> -o sheet.svg --png``).

Needs ``../shared/data`` beside the repository and the ``png`` extra (resvg-py).  Run from the
repository root: ``python tools/make_patterns_doc.py`` (a few minutes).
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

from svgtile import Region, analyze
from svgtile.apps.linework import measure_tile
from svgtile.apps.preview import render_png
from svgtile.apps.swatches import collect, read_names, swatch_sheet
from svgtile.engines import synthesize
from svgtile.errors import SvgtileError
from svgtile.metrics import score
from svgtile.svg.reader import parse_exemplar
from svgtile.tiles.importer import import_tile

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data"
DOCS = ROOT / "docs"
SETS = [
    ("FGDC lithology", DATA / "fgdc-geologic-patterns" / "lithology"),
    ("OSM carto patterns", DATA / "osm-carto" / "patterns"),
    ("OSM carto symbols (sanitised)", DATA / "osm-carto" / "symbols"),
    ("Equinor lithology", DATA / "equinor-lithology" / "svg"),
]
TILES = 3
SEED = 1


def row(path: Path, names: dict[str, str]) -> dict:
    out = {"pattern": path.stem, "name": names.get(path.stem, "")}
    try:
        imported = import_tile(path)
    except SvgtileError as exc:
        out["refused"] = str(exc).removeprefix(f"{path}: ")
        return out
    ex = parse_exemplar(imported.text, source=str(path))
    stats = analyze(ex)
    x0, y0, w, h = imported.box
    region = Region.rectangle(TILES * w, TILES * h, x0, y0)
    made = synthesize(ex, region, "auto", seed=SEED, stats=stats)
    arr = made.arrangement
    out.update(engine=made.engine)
    if made.cells is not None:
        out.update(motifs=len(imported), kinds=imported.kinds, wrapped=int(imported.wrapped.sum()), texture=len(arr),
                   cells=len(made.cells.cells))  # fmt: skip
        lw = measure_tile(path, seed=SEED)  # the linework figure: the motif figures do not apply
        if lw is not None:
            out.update(ink=lw.ink, structure=lw.structure)
        return out
    figures = score(ex, stats, arr, region)
    out.update(
        motifs=len(imported), kinds=imported.kinds, wrapped=int(imported.wrapped.sum()), texture=len(arr),
        overlaps=figures.overlaps_total, violators=figures.violators_total,
        density=figures.density_ratio, kind_mix=figures.kind_mix_tv, kind_mix_kinds=figures.kind_mix_tv_kinds,
        coverage=figures.coverage,
        likeness=figures.likeness, exemplar_overlaps=stats.overlaps,
    )  # fmt: skip
    return out


def fmt(v, digits=2) -> str:
    return "–" if v is None else f"{v:.{digits}f}"


def _per_kind(v) -> str:
    """The per-kind kind-mix TV after the one over shape classes, where kinds pool."""
    return "" if v is None else f" · {fmt(v)}"


def table(rows: list[dict]) -> list[str]:
    lines = [
        "| pattern | name | motifs | kinds | cut & reassembled | result | engine | texture motifs | overlaps | violators | density ratio (cells: ink) | kind-mix TV (· per kind, where kinds pool into shape classes) | coverage | likeness L (cells: S) |",
        "|---|---|--:|--:|--:|---|---|--:|--:|--:|--:|--:|--:|--:|",
    ]
    for r in rows:
        if "refused" in r:
            lines.append(f"| {r['pattern']} | {r['name']} | | | | refused: {r['refused']} | | | | | | | | |")
        elif "cells" in r:
            lines.append(
                f"| {r['pattern']} | {r['name']} | {r['motifs']} | {r['kinds']} | {r['wrapped']} | accepted as cells | "
                f"{r['engine']} | {r['texture']} in {r['cells']} cells | | | {fmt(r.get('ink'))} | | | {fmt(r.get('structure'))} |"
            )
        else:
            lines.append(
                f"| {r['pattern']} | {r['name']} | {r['motifs']} | {r['kinds']} | {r['wrapped']} | accepted | "
                f"{r['engine']} | {r['texture']} | {r['overlaps']} | {r['violators']} | {fmt(r['density'])} | "
                f"{fmt(r['kind_mix'])}{_per_kind(r.get('kind_mix_kinds'))} | {fmt(r['coverage'])} | {fmt(r['likeness'])} |"
            )
    return lines


def main() -> None:
    DOCS.mkdir(exist_ok=True)
    fgdc_names = read_names(DATA / "fgdc-geologic-patterns" / "INDEX.csv")
    equinor = {}
    sections, summary = [], []
    for title, folder in SETS:
        files = collect([str(folder)])
        names = fgdc_names if "FGDC" in title else equinor
        rows = [row(p, names) for p in files]
        accepted = [r for r in rows if "refused" not in r]
        clean = [r for r in accepted if r.get("overlaps", 0) == 0 and r.get("violators", 0) == 0]
        summary.append(
            f"| {title} | {len(rows)} | {len(accepted)} | {len(clean)} | {len(rows) - len(accepted)} |"
        )
        sections += [f"## {title}", "", *table(rows), ""]
        with open(DOCS / f"patterns-{folder.parent.name}-{folder.name}.csv", "w", newline="") as handle:
            keys = sorted({k for r in rows for k in r})
            writer = csv.DictWriter(handle, keys)
            writer.writeheader()
            writer.writerows(rows)
        print(title, len(rows), "accepted", len(accepted), "clean", len(clean))
    head = (ROOT / "tools" / "patterns_head.md").read_text()
    text = head.replace("<!-- summary -->", "\n".join(
        ["| set | tiles | accepted | of which 0 overlaps and 0 violators | refused |", "|---|--:|--:|--:|--:|", *summary]
    ))
    (DOCS / "patterns.md").write_text(text + "\n" + "\n".join(sections))
    sheet = swatch_sheet(collect([str(SETS[0][1])]), columns=6, seed=SEED, names=fgdc_names)
    (DOCS / "fgdc-swatches.png").write_bytes(small_png(render_png(sheet.text, 1500)))


def small_png(data: bytes) -> bytes:
    """The sheet as a 16-grey palette PNG (under 1 MB for the docs), if Pillow is installed."""
    try:
        from PIL import Image
    except ImportError:
        return data
    out = io.BytesIO()
    Image.open(io.BytesIO(data)).convert("L").quantize(16).save(out, "PNG", optimize=True)
    return out.getvalue()


if __name__ == "__main__":
    main()
