"""``svgtile score``: how well a texture reproduces its exemplar (figures of :mod:`svgtile.metrics`)."""

from __future__ import annotations

import json
from pathlib import Path

import click

from svgtile.apps.compare import format_score
from svgtile.cli.common import json_safe, load, warn_if_few
from svgtile.metrics import score as measure
from svgtile.svg.texture import read_texture


@click.command(name="score")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.argument("texture", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print machine-readable JSON.")
def score(exemplar, texture, as_json):
    """Measure how well TEXTURE (an SVG svgtile made from EXEMPLAR) reproduces EXEMPLAR.

    Figures are measured on the texture's interior (the region shrunk by one exemplar width):
    overlaps, distance-rule violators, density, kind mix, orientation, structure, repetition,
    coverage.  See the README for their definitions.
    """
    ex, stats = load(exemplar)
    arr, region = read_texture(texture, ex)
    result = measure(ex, stats, arr, region)
    warn_if_few(result.motifs, texture)
    if as_json:
        out = {"exemplar": Path(exemplar).name, "texture": Path(texture).name, **result.to_dict()}
        click.echo(json.dumps(json_safe(out), indent=2, allow_nan=False))
    else:
        click.echo(f"{Path(texture).name} against {Path(exemplar).name}: {len(arr)} motifs")
        click.echo(format_score(result))
