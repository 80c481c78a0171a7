"""``svgtile inkscape``: install the Inkscape extension, and the fill command it runs."""

from __future__ import annotations

from pathlib import Path

import click

from svgtile.apps import inkscape as ink
from svgtile.apps.load import MAX_MOTIFS
from svgtile.cli.common import engine_options, load
from svgtile.core.region import BOUNDARY_MODES
from svgtile.engines import get_engine, make_params

_USER_DIR = click.option(
    "--user-dir", type=click.Path(file_okay=False), default=None,
    help="Inkscape's user data folder (the one holding extensions/). Default: what "
         "'inkscape --user-data-directory' says, else the platform's usual place.",
)  # fmt: skip


@click.group(name="inkscape")
def inkscape() -> None:
    """The Inkscape extension: Extensions ▸ Render ▸ svgtile ▸ Fill with Texture…"""


@inkscape.command()
@_USER_DIR
def install(user_dir):
    """Install the extension for this svgtile (and this Python) into Inkscape.

    Installing again updates it. Restart Inkscape to see the menu entry.
    """
    target = ink.install(user_dir)
    click.echo(f"svgtile: installed the Inkscape extension in {target}")


@inkscape.command()
@_USER_DIR
def uninstall(user_dir):
    """Remove the extension from Inkscape."""
    target = ink.uninstall(user_dir)
    click.echo(f"svgtile: removed the Inkscape extension from {target}")


@inkscape.command(hidden=True)
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.argument("containers", type=click.Path(dir_okay=False))
@click.option("--out-dir", required=True, type=click.Path(file_okay=False, exists=True))
@engine_options
@click.option("--boundary", type=click.Choice(BOUNDARY_MODES), default="clip")
@click.option("--seed", type=click.IntRange(min=0), required=True)
def fill(exemplar, containers, out_dir, engine, boundary, seed, **values):
    """(For the extension.) Fill every container of CONTAINERS (JSON) with a texture like EXEMPLAR.

    Writes OUT_DIR/texture-<i>.svg per container; see svgtile.apps.inkscape.  The dialog shows
    every engine's parameters and the extension passes them all: those the chosen engine does not
    have are left out here (the dialog's help says which engine each is for).
    """
    own = get_engine(engine).Params.public_names()
    params = make_params(engine, {k: v for k, v in values.items() if k in own and v is not None})
    ink.fill(Path(exemplar), Path(containers), Path(out_dir), engine=engine, seed=seed, boundary=boundary,
             max_motifs=MAX_MOTIFS, params=params, load=load)  # fmt: skip
