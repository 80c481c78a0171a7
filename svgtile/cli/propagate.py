"""``svgtile propagate``: an edit of a few motifs of a texture, applied to every motif like them
(Ma, Wei & Tong 2011 §6.3, :func:`svgtile.engines.optimize.edit.propagate`)."""

from __future__ import annotations

from pathlib import Path

import click

from svgtile.cli.common import load, warn
from svgtile.engines.optimize.edit import propagate
from svgtile.errors import ParameterError
from svgtile.files import check_output, same_file, write_file
from svgtile.svg.texture import read_texture
from svgtile.svg.writer import svg_document


@click.command(name="propagate")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.argument("texture", type=click.Path(dir_okay=False))
@click.argument("edited", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, help="The texture with the edit propagated (.svg, or - for standard output).")
@click.option("--threshold", type=click.FloatRange(min=0), default=0.05, show_default=True,
              help="How alike a motif's surroundings must be to an edited motif's to take its edit (neighbourhood distance, squared exemplar spacings).")
def propagate_cmd(exemplar, texture, edited, output, threshold):
    """Apply the edit made in EDITED (a copy of TEXTURE with a few motifs moved, turned or swapped)
    to every motif of TEXTURE whose surroundings are like an edited motif's.

    TEXTURE was synthesized from EXEMPLAR by svgtile; EDITED is TEXTURE edited, motifs neither
    added nor removed. Changes that would make motifs overlap or crowd are left out.
    """
    inputs = (Path(exemplar), Path(texture), Path(edited))
    if output != "-" and any(same_file(output, p) for p in inputs):
        raise ParameterError(f"{output}: refusing to overwrite an input file")
    check_output(output, protect=inputs)
    ex, stats = load(exemplar)
    arr, region = read_texture(texture, ex)
    changed, _ = read_texture(edited, ex)
    out, users, taken = propagate(arr, changed, ex, stats, region, threshold=threshold)
    if users == 0:
        warn(f"{edited}: no motif differs from {texture}; writing it unchanged")
    click.echo(f"svgtile: {users} motifs edited, the edit propagated to {taken} more", err=True)
    params = {"propagated": taken, "edited": users, "threshold": threshold, "motifs": len(out)}
    write_file(svg_document(ex, out, region, boundary="none", params=params), output, protect=inputs)
