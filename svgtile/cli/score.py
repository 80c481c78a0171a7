"""``svgtile score``: how well a texture reproduces its exemplar (figures of :mod:`svgtile.metrics`)."""

from __future__ import annotations

import gc
import json
from contextlib import contextmanager
from pathlib import Path

import click

from svgtile.apps.compare import format_score
from svgtile.cli.common import json_safe, load
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
    with _no_cycle_collection():
        arr, region = read_texture(texture, ex)
        result = measure(ex, stats, arr, region)
    if as_json:
        out = {"exemplar": Path(exemplar).name, "texture": Path(texture).name, **result.to_dict()}
        click.echo(json.dumps(json_safe(out), indent=2, allow_nan=False))
    else:
        click.echo(f"{Path(texture).name} against {Path(exemplar).name}: {len(arr)} motifs")
        click.echo(format_score(result))


@contextmanager
def _no_cycle_collection():
    """CPython's cyclic collector paused: reading and measuring a large texture makes hundreds
    of thousands of objects that hold no reference cycles (the strings of the ``<use>`` scan,
    one shapely footprint per motif), and the collector would walk them all again and again."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()
