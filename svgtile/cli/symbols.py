"""``svgtile symbols``: each kind of an exemplar as its own SVG, and a QGIS style that uses them."""

from __future__ import annotations

from pathlib import Path

import click

from svgtile.apps.gisout import write_symbols
from svgtile.cli.common import load
from svgtile.files import write_file
from svgtile.gis.symbols import qml_style

#: The style's file name in the output folder.
STYLE_NAME = "svgtile.qml"


@click.command(name="symbols")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "folder", required=True, type=click.Path(file_okay=False),
              help="The folder to write KIND.svg and svgtile.qml into (made if missing).")
@click.option("--import", "as_tile", is_flag=True, help="EXEMPLAR is a seamless pattern tile: import it first.")
def symbols_cmd(exemplar, folder, as_tile):
    """Write each motif kind of EXEMPLAR as FOLDER/KIND.svg, and FOLDER/svgtile.qml.

    Each SVG has a square page centred on the kind's anchor (the point of a GIS output), as wide
    as the 'size' field of a scale-1 motif.  svgtile.qml is a QGIS style for a layer written by
    svgtile synth -o X.gpkg (Layer Properties ▸ Symbology ▸ Style ▸ Load Style): an SVG marker whose
    file is FOLDER/KIND.svg, its size the 'size' field in map units, its rotation 'angle'.
    """
    ex, _ = load(exemplar, as_tile=as_tile)
    written = write_symbols(ex, folder, protect=(exemplar,))
    write_file(qml_style(str(Path(folder).resolve())), Path(folder) / STYLE_NAME, protect=(exemplar,))
    click.echo(f"svgtile: wrote {len(written)} symbols and {STYLE_NAME} in {folder}", err=True)
