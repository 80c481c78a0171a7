"""``svgtile synth``: one texture, from an exemplar, over a rectangle or a shape of a map."""

from __future__ import annotations

import secrets
import sys
from pathlib import Path

import click

from svgtile.apps.gisout import check_style, write_placements, write_style
from svgtile.apps.load import MAX_MOTIFS, MAX_WORK_SECONDS, check_motif_count, check_work
from svgtile.apps.mapfill import default_jobs
from svgtile.apps.mapread import read_controls, synth_region
from svgtile.apps.preview import render_png
from svgtile.apps.tiled import synthesize_to_file
from svgtile.cli.common import (
    AUTO,
    POINT_FORMATS,
    Stderr,
    auto_params,
    default_boundary,
    engine_options,
    engine_params,
    honoured_by,
    load,
    output_format,
    parse_size,
    png_width,
    progress_line,
    spec_files,
    warn,
)
from svgtile.core.region import BOUNDARY_MODES
from svgtile.engines import get_engine, synthesize
from svgtile.engines.base import draws_cells
from svgtile.errors import ParameterError, SvgtileError
from svgtile.files import check_output, same_file, write_file
from svgtile.gis.geojson import exemplar_placements
from svgtile.gis.layers import common_crs, is_gis
from svgtile.runners.schedule import check_scheduler
from svgtile.runners.tiling import is_tiled
from svgtile.svg.writer import fmt, result_document


@click.command(name="synth")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, help="Output file, its format by its suffix: .svg (or - for standard output), .png (a picture, 2 pixels per user unit, 64 to 8192 pixels wide; needs the 'png' extra), or one point per motif for GIS (kind, angle, scale, size): .gpkg, .shp, .fgb or .geojson, in --region's CRS.")
@click.option("--size", default=None,
              help="Output size WIDTHxHEIGHT in the exemplar's user units, e.g. 800x600 (one number: a square).")
@click.option("--region", "region_spec", default=None, metavar="MAP.svg#ID|FILE.gpkg[#LAYER[:FID|?WHERE]]",
              help="Fill this shape instead of a --size rectangle: an element (closed shape or group) of another SVG, holes by its fill rule, or the polygons of a GIS layer (.gpkg, .shp, .fgb, .geojson; FILE#LAYER:FID one feature, FILE#LAYER?WHERE those an SQL condition selects, FILE.geojson#ID the feature with that id).")
@click.option("--avoid", multiple=True, metavar="MAP.svg#ID",
              help="Keep every motif clear of these labels, lines or shapes (texts by their box, lines by their stroke, grown by --avoid-margin). Repeatable.")
@click.option("--avoid-margin", type=float, default=2.0, show_default=True,
              help="Clear space around --avoid zones, user units.")
@click.option("--flow", multiple=True, metavar="MAP.svg#ID|FILE.geojson",
              help="Turn motifs along these strokes (a flow field interpolated between them; the way each stroke was drawn is the way motifs point). Repeatable. Engines that honour it: " + honoured_by("flow") + ".")
@click.option("--barrier", multiple=True, metavar="MAP.svg#ID|FILE.geojson",
              help="Lines no motif crosses and growth does not cross (a fault, a river); each side is filled on its own. Repeatable. Engines that honour it: " + honoured_by("barriers") + ".")
@click.option("--grow-within", multiple=True, metavar="MAP.svg#ID|FILE.geojson",
              help="Grow motifs only inside these shapes or brush strokes (a stroke's width is the brush). Repeatable. Engines that honour it: " + honoured_by("grow_within") + ".")
@engine_options(auto=True)
@click.option("--boundary", type=click.Choice(BOUNDARY_MODES), default=None,
              help="At the region's edge: inside = only whole motifs; centroid = motifs whose centre is inside; clip = cut motifs at the edge; none = let them stick out. [default: clip; inside for GIS point outputs, whose markers cannot be cut]")
@click.option("--with-style", is_flag=True,
              help="With a GIS output: also write OUT.qml (a QGIS style QGIS loads with the layer) and OUT-symbols/ (each kind as an SVG), so QGIS draws the texture at once.")
@click.option("--refine", type=click.IntRange(min=0), default=0, show_default=True, metavar="N",
              help="Then improve any engine's texture by N iterations of optimisation (Ma, Wei & Tong 2011): every motif's surroundings pulled towards the exemplar's.")
@click.option("--seed", type=click.IntRange(min=0), default=None,
              help="Random seed; the same exemplar, options and seed give the same file. Without it a seed is chosen and printed.")
@click.option("--force", is_flag=True, help=f"Run even when the estimated motif count exceeds {MAX_MOTIFS:,} or the "
              f"estimated work {MAX_WORK_SECONDS:.0f} s.")
@click.option("--scheduler", default=None, metavar="local|processes|ADDRESS",
              help="Run the region as tiles on Dask: local = Dask's local scheduler, processes = a LocalCluster of --jobs workers, or a cluster's address (tcp://host:8786). The output is the same as without it.")
@click.option("--tile-size", type=click.FloatRange(min=0, min_open=True), default=None, metavar="SIZE",
              help="Cut the region into world-anchored tiles of this side, user units, run on Dask (--scheduler, default local); the output is the same. An engine that is not tile-exact (patch, random) runs whole.")
@click.option("--jobs", type=click.IntRange(min=1), default=None,
              help="With --scheduler local or processes: worker processes [default: the usable cores].")
@click.option("--import", "as_tile", is_flag=True,
              help="EXEMPLAR is a seamless pattern tile (FGDC, OSM fill …): import it first, as 'svgtile import' does.")
@click.pass_context
def synth(ctx, exemplar, output, size, region_spec, avoid, avoid_margin, flow, barrier, grow_within, engine, boundary,
          with_style, refine, seed, force, scheduler, tile_size, jobs, as_tile, **values):  # fmt: skip
    """Synthesize a texture like EXEMPLAR and write it (SVG, PNG or GIS points, by -o's suffix).

    EXEMPLAR is an SVG whose motifs are <use> clones of <symbol>s (or plain shapes); the element
    with id="region" (else the viewBox) is the area the motifs were drawn in.
    """
    # before the region is cut by its avoid zones: an avoid layer in another CRS would mislead that
    crs = common_crs(region_spec, [a for a in avoid if is_gis(a)])  # checked for any output
    region = synth_region(parse_size(size) if size is not None else None, region_spec, avoid, avoid_margin)
    where = f"--size {size}" if size is not None else f"--region {region_spec}"
    params = engine_params(ctx, engine, values)  # checked before the work
    controls = read_controls(flow, barrier, grow_within)
    kind = output_format(output)
    boundary = default_boundary(kind, boundary)
    if with_style and (kind not in POINT_FORMATS or output == "-"):
        raise ParameterError("--with-style goes with a GIS output file (.gpkg, .shp, .fgb, .geojson)")
    if output != "-" and same_file(output, exemplar):
        raise ParameterError(f"{output}: refusing to overwrite the exemplar")
    # every input file is protected: the exemplar, and the files of --region and --avoid
    inputs = (Path(exemplar), *spec_files((region_spec or "", *avoid)))
    check_output(output, protect=inputs)  # fail before the work, not after
    if with_style:
        check_style(output, protect=inputs)
    ex, stats = load(exemplar, as_tile=as_tile)
    estimate = check_motif_count(ex, stats, region, where, limit=float("inf") if force else MAX_MOTIFS, forceable=True)
    limit = float("inf") if force else MAX_WORK_SECONDS
    if engine == AUTO:
        def affordable(name: str) -> bool:  # one worker: the cheaper guess, as a tiled run may not be
            try:
                check_work(estimate, name, where, refine=refine, limit=limit)
            except ParameterError:
                return False
            return True

        engine, params = auto_params(ex, stats, params, controls.given(), affordable=affordable)
    cellular = draws_cells(get_engine(engine))
    # the work is shared among workers only when the region is really cut into tiles
    split = is_tiled(ex, engine, tile_size, params=params, refine=refine)
    check_work(estimate, engine, where, refine=refine, workers=(jobs or default_jobs()) if split else 1,
               limit=limit, forceable=True, params=params)  # fmt: skip
    if seed is None:
        seed = secrets.randbelow(2**31)
        click.echo(f"svgtile: seed {seed}", err=True)
    if cellular and with_style:
        raise ParameterError(f"{output}: --with-style styles motif points, not a cellular texture's cells")
    if (scheduler is not None or tile_size is not None) and cellular:
        # the tiled writers draw motifs only, and a cellular engine is not tile-exact anyway
        click.echo(f"svgtile: engine {engine!r} draws cells, which tiles cannot carry: running the region whole here",
                   err=True)  # fmt: skip
        scheduler = tile_size = None
    if scheduler is not None or tile_size is not None:
        if controls.given():
            raise ParameterError("--flow, --barrier and --grow-within do not go with --scheduler or --tile-size yet")
        _tiled(output, kind, ex, stats, region, engine, seed=seed, boundary=boundary, params=params, refine=refine,
               tile_size=tile_size, scheduler=scheduler or "local", jobs=jobs, where=where, region_spec=region_spec,
               exemplar_path=exemplar, size=size, crs=crs, protect=inputs, as_tile=as_tile)  # fmt: skip
        if with_style:
            write_style(output, {None: ex}, protect=inputs)
        return
    result = synthesize(ex, region, engine, seed=seed, stats=stats, boundary=boundary, progress=progress_line(),
                        params=params, refine=refine, controls=controls)  # fmt: skip
    Stderr.clear()
    if len(result) == 0 and (result.cells is None or len(result.cells) == 0):
        warn(f"no motif fits in {size or region_spec} with --boundary {boundary}; writing an empty texture")
    where_meta = _where_meta(region, region_spec, as_tile)
    if kind in POINT_FORMATS and result.cells is not None:  # cells are polygons: GeoJSON or SVG
        if not (output == "-" or str(output).lower().endswith(".geojson")) or crs is not None:
            raise ParameterError(f"{output}: a cellular texture's cells are written to .svg or .geojson without a CRS")
        write_file(exemplar_placements(ex, result.arrangement, cells=result.cells), output, protect=inputs)
        return
    if kind in POINT_FORMATS:
        write_placements([(ex, result.arrangement, None, None)], output, crs=crs, protect=inputs)
        if with_style:
            write_style(output, {None: ex}, protect=inputs)
        return
    data = result_document(result, exemplar=Path(exemplar).name, **where_meta)
    if kind == "png":
        x0, _, x1, _ = region.bounds
        data = render_png(data, png_width(x1 - x0))
    write_file(data, output, protect=inputs)


def _where_meta(region, region_spec: str | None, as_tile: bool) -> dict[str, str]:
    """The run record's say on where and from what: ``region`` (the --region spec) or ``size``,
    and ``imported="tile"`` when EXEMPLAR was imported first (``--import``), so that ``svgtile
    score EXEMPLAR TEXTURE`` imports it too."""
    x0, y0, x1, y1 = region.bounds
    where = {"region": region_spec} if region_spec else {"size": f"{fmt(x1 - x0)}x{fmt(y1 - y0)}"}
    return {**where, "imported": "tile"} if as_tile else where


def _tiled(output, kind, ex, stats, region, engine, *, seed, boundary, params, refine, tile_size, scheduler, jobs,
           where, region_spec, exemplar_path, size, crs, protect, as_tile) -> None:  # fmt: skip
    """``synth --scheduler``: the region's tiles on Dask, written as they finish (same bytes)."""
    check_scheduler(scheduler)
    if kind == "png" or (kind == "gis" and not str(output).lower().endswith(".geojson")) or crs is not None:
        raise ParameterError(f"{output}: --scheduler writes .svg or .geojson without a CRS (write those, then convert)")
    where_meta = _where_meta(region, region_spec, as_tile)

    def on_plan(tiles) -> None:
        if tile_size is not None and len(tiles) == 1 and tiles[0].whole:
            why = f"--refine {refine} is" if refine else f"engine {engine!r} is"
            click.echo(f"svgtile: {why} not tile-exact (its reach is unbounded): running the region whole", err=True)

    run = synthesize_to_file(output, kind, ex, stats, region, engine, seed=seed, boundary=boundary, params=params,
                             refine=refine, tile_size=tile_size, where={"exemplar": Path(exemplar_path).name, **where_meta},
                             scheduler=scheduler, workers=jobs or default_jobs(), bar=sys.stderr.isatty() and output != "-",
                             protect=protect, on_plan=on_plan)  # fmt: skip
    Stderr.clear()
    for tile, message in run.errors.items():
        warn(f"{tile} not filled: {message}")
    if run.motifs == 0 and not run.errors:
        warn(f"no motif fits in {size or region_spec} with --boundary {boundary}; writing an empty texture")
    if run.errors:
        raise SvgtileError(f"{len(run.errors)} of {len(run.tiles)} tiles failed (see the warnings); the others were written",
                           source=str(output))  # fmt: skip
