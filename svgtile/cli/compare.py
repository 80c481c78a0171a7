"""``svgtile compare``: every engine on one region, one table (and PNG previews)."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import click

from svgtile.apps.compare import compare as run_compare
from svgtile.apps.compare import format_table
from svgtile.apps.load import MAX_MOTIFS, check_motif_count, check_work
from svgtile.apps.preview import contact_sheet, render_png, require_renderer
from svgtile.cli.common import Stderr, json_safe, load, parse_size, warn_if_few
from svgtile.core.region import Region
from svgtile.errors import ExemplarError, OutputError
from svgtile.files import check_paths, read_input, write_file
from svgtile.svg.writer import fmt, svg_document

#: Pixels per user unit of the contact sheet are chosen so a texture panel is this wide.
SHEET_PANEL = 320
#: … and at least this many, so that motifs can be seen on a large region.
MIN_SCALE = 2.0


@click.command(name="compare")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("--size", required=True, help="Output size WIDTHxHEIGHT in the exemplar's user units, e.g. 1000x1000.")
@click.option("--engines", default="patch,tile,random", show_default=True, help="Comma-separated engines, one column each.")
@click.option("--seed", type=click.IntRange(min=0), default=1, show_default=True, help="Random seed, the same for every engine.")
@click.option("--png", "png_dir", type=click.Path(file_okay=False),
              help="Also write each texture as SVG and PNG into this folder, and a contact sheet: the exemplar beside every texture.")
@click.option("--json", "as_json", is_flag=True, help="Print machine-readable JSON.")
@click.option("--import", "as_tile", is_flag=True,
              help="EXEMPLAR is a seamless pattern tile (FGDC, OSM fill …): import it first, as 'svgtile import' does.")
def compare(exemplar, size, engines, seed, png_dir, as_json, as_tile):
    """Synthesize EXEMPLAR with each engine and print their figures side by side."""
    width, height = parse_size(size)
    names = [e.strip() for e in engines.split(",") if e.strip()]
    if png_dir is not None:
        folder = Path(png_dir)
        if folder.exists() and not folder.is_dir():
            raise OutputError("is a file, not a folder", source=png_dir)
        require_renderer()
        planned = [folder / f"{n}.{suffix}" for n in (*names, "contact-sheet") for suffix in ("svg", "png")]
        check_paths([exemplar], planned)  # before any of them is written
    ex, stats = load(exemplar, as_tile=as_tile)
    region = Region.rectangle(width, height)
    estimate = check_motif_count(ex, stats, region, f"--size {size}", limit=MAX_MOTIFS)  # every engine holds them
    check_work(estimate, names, f"--size {size}")
    results = run_compare(ex, stats, region, engines=names, seed=seed)
    Stderr.clear()
    warn_if_few(min(r.score.motifs for r in results), f"--size {size}")
    if png_dir is not None:
        _write_previews(Path(png_dir), Path(exemplar), ex, region, results, seed, imported=as_tile)
    if as_json:
        out = {"exemplar": Path(exemplar).name, "size": f"{fmt(width)}x{fmt(height)}", "seed": seed,
               "engines": {r.engine: r.score.to_dict() for r in results}}  # fmt: skip
        click.echo(json.dumps(json_safe(out), indent=2, allow_nan=False))
    else:
        click.echo(f"{Path(exemplar).name} on {fmt(width)} x {fmt(height)}, seed {seed}")
        for r in results:  # as svgtile score says it (and --json's "sampled")
            if r.score.sample is not None:
                click.echo(f"sampled ({r.engine}): {r.score.sample.describe()} (structure: nearest gaps, "
                           "pair correlation)")  # fmt: skip
        click.echo(format_table(results))


def _write_previews(folder: Path, path: Path, ex, region, results, seed: int, *, imported: bool = False) -> None:
    """``ENGINE.svg``/``.png`` per texture and ``contact-sheet.svg``/``.png`` in ``folder``; each
    texture's run record says ``imported="tile"`` when the exemplar was imported (``--import``),
    as ``synth --import``'s does, so that ``svgtile score`` imports it too."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"cannot create the folder ({exc.strerror or exc})", source=str(folder)) from None
    x0, y0, x1, y1 = region.bounds
    scale = max(MIN_SCALE, SHEET_PANEL / max(x1 - x0, y1 - y0))
    ex_text = _svg_text(read_input(path, error=ExemplarError))
    panels = [(f"exemplar {path.stem}", ex_text)]
    for r in results:
        meta = {"engine": r.engine, "seed": seed, "exemplar": path.name, "motifs": len(r.arrangement),
                **({"imported": "tile"} if imported else {})}  # fmt: skip
        text = svg_document(ex, r.arrangement, region, boundary="clip", params=meta)
        write_file(text, folder / f"{r.engine}.svg", protect=(path,))
        png = render_png(text, round(scale * (x1 - x0)))
        write_file(png, folder / f"{r.engine}.png", protect=(path,))
        panels.append((r.engine, text))
    sheet, width = contact_sheet(panels, scale)
    write_file(sheet, folder / "contact-sheet.svg", protect=(path,))
    write_file(render_png(sheet, width), folder / "contact-sheet.png", protect=(path,))


def _svg_text(data: bytes) -> str:
    """The exemplar as text for the contact sheet: as is when UTF-8 (most files), else
    re-serialised by ElementTree, which reads any encoding the exemplar reader reads."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return ET.tostring(ET.fromstring(data), encoding="unicode")
