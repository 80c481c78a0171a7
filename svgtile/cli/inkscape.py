"""``svgtile inkscape``: install the Inkscape extension, and the fill command it runs."""

from __future__ import annotations

from pathlib import Path

import click

from svgtile.apps import inkscape as ink
from svgtile.cli.main import MAX_MOTIFS, _load
from svgtile.core.region import BOUNDARY_MODES
from svgtile.engines import ENGINES
from svgtile.engines.patch.engine import PatchParams
from svgtile.errors import ParameterError

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
@click.option("--engine", type=click.Choice(sorted(ENGINES)), default="patch")
@click.option("--grid", type=click.Choice(["square", "hex"]), default="square")
@click.option("--overlap", type=float, default=PatchParams.overlap)
@click.option("--max-rotation", type=float, default=PatchParams.max_rotation)
@click.option("--vary-orientation", is_flag=True)
@click.option("--boundary", type=click.Choice(BOUNDARY_MODES), default="clip")
@click.option("--seed", type=click.IntRange(min=0), required=True)
def fill(exemplar, containers, out_dir, engine, grid, overlap, max_rotation, vary_orientation, boundary, seed):
    """(For the extension.) Fill every container of CONTAINERS (JSON) with a texture like EXEMPLAR.

    Writes OUT_DIR/texture-<i>.svg per container; see svgtile.apps.inkscape.
    """
    if not 0.0 <= overlap <= 0.5:
        raise ParameterError(f"overlap must be between 0 and 0.5, not {overlap:g}")
    if not 0.0 <= max_rotation <= 180.0:
        raise ParameterError(f"max rotation must be between 0 and 180 degrees, not {max_rotation:g}")
    params = dict(grid=grid, overlap=overlap, max_rotation=max_rotation,
                  vary_orientation=vary_orientation, boundary=boundary)  # fmt: skip
    ink.fill(Path(exemplar), Path(containers), Path(out_dir), engine=engine, seed=seed,
             max_motifs=MAX_MOTIFS, params=params, load=_load)  # fmt: skip
