"""``svgtile synth``: one texture, from an exemplar, over a rectangle or a shape of a map."""

from __future__ import annotations

import secrets
from pathlib import Path

import click

from svgtile.apps.load import MAX_MOTIFS, check_motif_count
from svgtile.apps.mapread import read_controls, synth_region
from svgtile.apps.preview import render_png
from svgtile.cli.common import (
    Stderr,
    engine_options,
    engine_params,
    load,
    output_format,
    parse_size,
    png_width,
    progress_line,
    warn,
)
from svgtile.core.region import BOUNDARY_MODES
from svgtile.engines import synthesize
from svgtile.errors import ParameterError
from svgtile.files import check_output, same_file, write_file
from svgtile.gis.geojson import exemplar_placements
from svgtile.svg.writer import fmt, result_document


@click.command(name="synth")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, help="Output file, its format by its suffix: .svg (or - for standard output), .geojson (one point per motif: kind, angle, scale, for GIS) or .png (a picture, 2 pixels per user unit, 64 to 8192 pixels wide; needs the 'png' extra).")
@click.option("--size", default=None,
              help="Output size WIDTHxHEIGHT in the exemplar's user units, e.g. 800x600 (one number: a square).")
@click.option("--region", "region_spec", default=None, metavar="MAP.svg#ID|FILE.geojson",
              help="Fill this shape instead of a --size rectangle: an element (closed shape or group) of another SVG, holes by its fill rule, or the polygons of a GeoJSON file (FILE.geojson#ID: one feature).")
@click.option("--avoid", multiple=True, metavar="MAP.svg#ID",
              help="Keep every motif clear of these labels, lines or shapes (texts by their box, lines by their stroke, grown by --avoid-margin). Repeatable.")
@click.option("--avoid-margin", type=float, default=2.0, show_default=True,
              help="Clear space around --avoid zones, user units.")
@click.option("--flow", multiple=True, metavar="MAP.svg#ID|FILE.geojson",
              help="Turn motifs along these strokes (a flow field interpolated between them; the way each stroke was drawn is the way motifs point). Repeatable. Engines that honour it: growth.")
@click.option("--barrier", multiple=True, metavar="MAP.svg#ID|FILE.geojson",
              help="Lines no motif crosses and growth does not cross (a fault, a river); each side is filled on its own. Repeatable. Engines that honour it: growth.")
@click.option("--grow-within", multiple=True, metavar="MAP.svg#ID|FILE.geojson",
              help="Grow motifs only inside these shapes or brush strokes (a stroke's width is the brush). Repeatable. Engines that honour it: growth.")
@engine_options
@click.option("--boundary", type=click.Choice(BOUNDARY_MODES), default="clip", show_default=True,
              help="At the region's edge: inside = only whole motifs; centroid = motifs whose centre is inside; clip = cut motifs at the edge; none = let them stick out.")
@click.option("--seed", type=click.IntRange(min=0), default=None,
              help="Random seed; the same exemplar, options and seed give the same file. Without it a seed is chosen and printed.")
@click.option("--force", is_flag=True, help=f"Run even when the estimated motif count exceeds {MAX_MOTIFS:,}.")
@click.option("--import", "as_tile", is_flag=True,
              help="EXEMPLAR is a seamless pattern tile (FGDC, OSM fill …): import it first, as 'svgtile import' does.")
@click.pass_context
def synth(ctx, exemplar, output, size, region_spec, avoid, avoid_margin, flow, barrier, grow_within, engine, boundary,
          seed, force, as_tile, **values):  # fmt: skip
    """Synthesize a texture like EXEMPLAR and write it (SVG, GeoJSON points or PNG, by -o's suffix).

    EXEMPLAR is an SVG whose motifs are <use> clones of <symbol>s (or plain shapes); the element
    with id="region" (else the viewBox) is the area the motifs were drawn in.
    """
    region = synth_region(parse_size(size) if size is not None else None, region_spec, avoid, avoid_margin)
    where = f"--size {size}" if size is not None else f"--region {region_spec}"
    params = engine_params(ctx, engine, values)  # checked before the work
    controls = read_controls(flow, barrier, grow_within)
    kind = output_format(output)
    if output != "-" and same_file(output, exemplar):
        raise ParameterError(f"{output}: refusing to overwrite the exemplar")
    check_output(output, protect=(exemplar,))  # fail before the work, not after
    ex, stats = load(exemplar, as_tile=as_tile)
    check_motif_count(ex, stats, region, where, limit=float("inf") if force else MAX_MOTIFS, forceable=True)
    if seed is None:
        seed = secrets.randbelow(2**31)
        click.echo(f"svgtile: seed {seed}", err=True)
    result = synthesize(ex, region, engine, seed=seed, stats=stats, boundary=boundary, progress=progress_line(),
                        params=params, controls=controls)  # fmt: skip
    Stderr.clear()
    if len(result) == 0:
        warn(f"no motif fits in {size or region_spec} with --boundary {boundary}; writing an empty texture")
    x0, y0, x1, y1 = region.bounds
    where_meta = {"region": region_spec} if region_spec else {"size": f"{fmt(x1 - x0)}x{fmt(y1 - y0)}"}
    if kind == "geojson":
        data = exemplar_placements(ex, result.arrangement)
    else:
        data = result_document(result, exemplar=Path(exemplar).name, **where_meta)
        if kind == "png":
            data = render_png(data, png_width(x1 - x0))
    write_file(data, output, protect=(Path(exemplar),))
