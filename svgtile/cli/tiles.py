"""``svgtile import`` (a pattern tile to an exemplar) and ``svgtile swatches`` (a legend sheet)."""

from __future__ import annotations

from pathlib import Path

import click

from svgtile.apps.load import MAX_MOTIFS
from svgtile.cli.common import parse_size, warn
from svgtile.engines import AUTO, ENGINES
from svgtile.errors import ParameterError, SvgtileError
from svgtile.files import check_output, same_file, write_file
from svgtile.tiles.importer import import_tile


@click.command(name="import")
@click.argument("tile", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, help="Output exemplar SVG file, or - for standard output.")
def import_cmd(tile, output):
    """Turn a seamless pattern TILE (FGDC, OSM, well-log fills …) into an exemplar.

    Frame and background rectangles are dropped (a background painted in a plain colour is kept as
    the ground the texture is painted on), zero-length round-capped lines become dots,
    motifs cut at the tile's edge are reassembled, touching strokes and parallel pairs of strokes
    are grouped into motifs, and motifs identical up to rotation share a <symbol>.  Hatching,
    continuous lines and solid fills are refused with the reason, unless they are bedded (rows of
    lines, joints, motifs in cells): those become cellular patterns for ``--engine cellular``.
    """
    if output != "-" and same_file(output, tile):
        raise ParameterError(f"{output}: refusing to overwrite the tile")
    check_output(output, protect=(tile,))
    imported = import_tile(tile)
    for note in imported.notes:
        warn(f"{tile}: {note}")
    write_file(imported.text, output, protect=(Path(tile),))
    cells = imported.cellular
    bedded = "" if cells is None else (f"a cellular pattern (courses of {cells['course']:g}, "
                                       f"{len(cells.get('lines', ()))} bedding line(s) per repeat) with ")  # fmt: skip
    click.echo(
        f"svgtile: {tile}: {bedded}{len(imported)} motif(s) of {imported.kinds} kind(s), "
        f"{int(imported.wrapped.sum())} reassembled across the tile's edge",
        err=True,
    )


@click.command(name="swatches")
@click.argument("inputs", nargs=-1, required=True, type=click.Path(exists=True))
@click.option("-o", "--output", required=True, help="Output SVG sheet, or - for standard output.")
@click.option("--size", default=None,
              help="Area of each swatch, WIDTHxHEIGHT in the tile's user units (one number: a square). Default: 3 x 3 tiles.")
@click.option("--columns", type=click.IntRange(min=1), default=4, show_default=True, help="Patterns per row.")
@click.option("--names", type=click.Path(dir_okay=False), default=None,
              help="CSV with a name column and a code (file stem) or file column, e.g. the FGDC INDEX.csv.")
@click.option("--seed", type=click.IntRange(min=0), default=1, show_default=True, help="Random seed of every synthesis.")
@click.option("--png", "png", is_flag=True, help="Also write OUTPUT with .png (needs the 'png' extra: resvg-py).")
@click.option("--png-width", type=click.IntRange(min=100, max=20000), default=1600, show_default=True,
              help="Width of the PNG, pixels.")
@click.option("--engine", "engines", multiple=True, type=click.Choice([AUTO, *ENGINES]),
              help=f"Engine of the textures; give it several times for textures side by side, each captioned "
                   f"with its engine and likeness L (e.g. --engine patch --engine growth). Default: {AUTO}.")
def swatches_cmd(inputs, output, size, columns, names, seed, png, png_width, engines):
    """A legend sheet of pattern tiles: per pattern its name, the tile repeated, and a texture
    synthesized from it, side by side at one scale (or why the tile was refused).

    INPUTS are tile SVG files or directories of them.
    """
    from svgtile.apps.preview import render_png
    from svgtile.apps.swatches import collect, read_names, swatch_sheet

    files = collect(inputs)
    if not files:
        raise ParameterError("no .svg files among the inputs")
    if png and output == "-":
        raise ParameterError("--png needs a file name for --output")
    png_path = Path(output).with_suffix(".png") if png else None
    if png_path is not None and png_path == Path(output):
        raise ParameterError(f"{output}: the SVG sheet and the PNG would be the same file")
    check_output(output, protect=tuple(files))
    if png_path is not None:
        check_output(str(png_path), protect=tuple(files))
    swatch = parse_size(size) if size is not None else None
    table = read_names(names) if names else None
    engines = tuple(dict.fromkeys(engines)) or (AUTO,)  # an engine named twice is drawn once
    sheet = swatch_sheet(files, swatch=swatch, columns=columns, seed=seed, names=table, max_motifs=MAX_MOTIFS,
                         engines=engines)  # fmt: skip
    if sheet.accepted == 0:  # a sheet of refusals is no legend; the exit code says nothing was made
        reasons = "; ".join(f"{g[0].path.name}: {g[0].refused}" for g in sheet.patterns[:3])
        raise SvgtileError(f"none of the {len(files)} pattern(s) could be synthesized ({reasons}"
                           f"{' …' if len(files) > 3 else ''}); nothing written", source=str(output))  # fmt: skip
    if png_path is not None:
        write_file(render_png(sheet.text, png_width), png_path, protect=tuple(files))
    write_file(sheet.text, output, protect=tuple(files))
    click.echo(f"svgtile: {sheet.accepted} of {len(files)} pattern(s) synthesized, {sheet.refused} refused", err=True)

