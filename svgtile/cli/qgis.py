"""``svgtile qgis``: install the QGIS Processing plugin, and the fill command it runs."""

from __future__ import annotations

from pathlib import Path

import click

from svgtile.apps import qgis as qg
from svgtile.apps.gisout import (
    check_style,
    filled_exemplars,
    map_parts,
    write_placements,
    write_style,
)
from svgtile.apps.load import MAX_MOTIFS
from svgtile.apps.mapfill import default_jobs
from svgtile.apps.mapread import AVOID_MARGIN
from svgtile.cli.common import POINT_FORMATS, engine_options, output_format, spec_files, warn
from svgtile.core.region import BOUNDARY_MODES
from svgtile.engines import get_engine, make_params
from svgtile.errors import ParameterError, SvgtileError
from svgtile.files import check_output

_PROFILE = click.option(
    "--profile", type=click.Path(file_okay=False), default=None,
    help="The QGIS user profile folder (the one holding python/plugins). Default: the 'default' "
         "profile in the platform's usual place (Linux: ~/.local/share/QGIS/QGIS3/profiles/default).",
)  # fmt: skip


@click.group(name="qgis")
def qgis() -> None:
    """The QGIS Processing plugin: Processing toolbox ▸ svgtile ▸ Fill polygons with texture."""


@qgis.command()
@_PROFILE
def install(profile):
    """Install (and enable) the plugin for this svgtile (and this Python) in a QGIS profile.

    Installing again updates it. Restart QGIS to see the algorithm in the Processing toolbox.
    """
    target = qg.install(profile)
    click.echo(f"svgtile: installed the QGIS plugin in {target}")


@qgis.command()
@_PROFILE
def uninstall(profile):
    """Remove the plugin from a QGIS profile."""
    target = qg.uninstall(profile)
    click.echo(f"svgtile: removed the QGIS plugin from {target}")


@qgis.command()
@click.argument("layer", metavar="LAYER")
@click.option("-o", "--output", required=True, help="The point layer: .gpkg, .shp, .fgb or .geojson (in LAYER's CRS).")
@click.option("--exemplar", type=click.Path(dir_okay=False), default=None, help="One exemplar for every polygon.")
@click.option("--styles", "styles_file", type=click.Path(dir_okay=False), default=None,
              help="An exemplar table: a styles file (as for svgtile map) whose classes --class-field names.")
@click.option("--class-field", default=None, help="The field holding each polygon's class.")
@engine_options
@click.option("--boundary", type=click.Choice(BOUNDARY_MODES), default="inside", show_default=True,
              help="How motifs meet the polygons' edges and holes (markers cannot be cut: inside keeps them whole).")
@click.option("--unit", type=click.FloatRange(min=0, min_open=True), default=1.0, show_default=True,
              help="Map units per exemplar user unit (with --exemplar).")
@click.option("--seed", type=click.IntRange(min=0), required=True, help="Random seed.")
@click.option("--avoid", multiple=True, metavar="LAYER", help="A layer every motif keeps clear of. Repeatable.")
@click.option("--avoid-margin", type=click.FloatRange(min=0), default=AVOID_MARGIN, show_default=True,
              help="Clear space around --avoid features, map units.")
@click.option("--with-style", is_flag=True, help="Also write OUT.qml and OUT-symbols/ (see svgtile synth --help).")
@click.option("--jobs", type=click.IntRange(min=1), default=None, help="Polygons filled at once [default: the usable cores].")
def fill(layer, output, exemplar, styles_file, class_field, engine, boundary, unit, seed, avoid, avoid_margin,
         with_style, jobs, **values):  # fmt: skip
    """Fill every polygon of LAYER (a GIS layer spec: FILE.gpkg#LAYER, FILE.shp …) and write the motifs as points.

    What the QGIS plugin runs; usable on its own.  Engine options the chosen engine does not have
    are refused; with --styles the table's parameters are used instead.
    """
    if output_format(output, ("geojson", "gis")) not in POINT_FORMATS or output == "-":
        raise ParameterError(f"{output}: give a GIS file (.gpkg, .shp, .fgb, .geojson)")
    given = {k: v for k, v in values.items() if v is not None}
    params = make_params(get_engine(engine), given) if exemplar else None
    inputs = (*(Path(p) for p in (exemplar, styles_file) if p), *spec_files((layer, *avoid)))
    check_output(output, protect=inputs)
    if with_style:
        check_style(output, protect=inputs)
    result, crs = qg.fill(layer, exemplar=exemplar, styles_file=styles_file, class_field=class_field, engine=engine,
                          params={} if params is None else {k: getattr(params, k) for k in given}, boundary=boundary,
                          unit=unit, seed=seed, avoid=avoid, avoid_margin=avoid_margin, jobs=jobs or default_jobs(),
                          max_motifs=MAX_MOTIFS)  # fmt: skip
    for message in result.warnings:
        warn(message)
    for ident, message in result.errors.items():
        warn(f"polygon {ident} not filled: {message}")
    if result.errors and len(result.errors) == len(result.regions):
        raise SvgtileError(f"no polygon was filled ({next(iter(result.errors.values()))}); nothing written", source=layer)
    exemplars = filled_exemplars(result)
    write_placements(map_parts(result, exemplars), output, crs=crs, protect=inputs)
    if with_style:  # one exemplar: one symbols folder, whatever the class field says
        write_style(output, exemplars if styles_file else {None: next(iter(exemplars.values()))}, protect=inputs)
    if result.errors:
        raise SvgtileError(f"{len(result.errors)} of {len(result.regions)} polygons failed (see the warnings); "
                           f"the others were written", source=str(output))  # fmt: skip
