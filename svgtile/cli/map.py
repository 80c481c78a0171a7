"""``svgtile map``: fill every classed unit of a map with its class's texture (issue 5 item 3)."""

from __future__ import annotations

import re
import secrets
import sys
from pathlib import Path

import click
import numpy as np

from svgtile.apps.load import MAX_MOTIFS, load_exemplar
from svgtile.apps.mapfill import MapFill, default_jobs, fill_map, read_styles
from svgtile.cli.common import Stderr, output_format, warn
from svgtile.engines import engines_with, public_params
from svgtile.errors import ParameterError, SvgtileError
from svgtile.files import check_output, same_file, write_file
from svgtile.gis import geojson
from svgtile.svg.writer import MapLayer, map_document, prefixed_defs


def _with_params(f):
    """Fill the list of engine parameters into the help (they come from the engines)."""
    f.__doc__ = f.__doc__ % {"params": ", ".join(f"{p.name} [{', '.join(engines_with(p.name))}]"
                                                 for p in public_params().values())}
    return f


@click.command(name="map")
@click.argument("map_file", metavar="MAP", type=click.Path(dir_okay=False))
@click.option("--styles", "styles_file", required=True, type=click.Path(dir_okay=False),
              help="TOML file mapping each class to an exemplar and its parameters (see the README).")
@click.option("-o", "--output", required=True,
              help="The filled map (.svg), or one point per motif for GIS (.geojson).")
@click.option("--avoid", multiple=True, metavar="ID|MAP.svg#ID",
              help="More labels, lines or shapes every texture keeps clear of (an id in MAP, or a spec). Repeatable.")
@click.option("--seed", type=click.IntRange(min=0), default=None,
              help="Random seed shared by every region (a class's own seed wins, and a top-level seed in the styles file is every class's). Without it one is chosen and printed.")
@click.option("--jobs", type=click.IntRange(min=1), default=None,
              help="Regions filled at once, in separate processes [default: the usable cores].")
@_with_params
def map_cmd(map_file, styles_file, output, avoid, seed, jobs):
    """Fill every unit of MAP (SVG or GeoJSON) whose class the styles file knows.

    A unit's class is its class attribute (or the attribute the styles file names) or its
    Inkscape label; in GeoJSON, the property the styles file names (default "class"). The output
    keeps the map and adds one texture group per unit, above the unit and below what follows it.
    A unit that fails is reported; the others are written, and the exit code is 1.

    \b
    The styles file (TOML), a table [classes.NAME] per class:
      exemplar = "FILE.svg"   the class's exemplar, relative to the styles file
      engine = "patch"        one of the engines (svgtile synth --help)
      seed = 7                this class's seed (else the run's)
      unit = 1.0              map units per exemplar user unit
      boundary = "clip"       inside, centroid, clip or none
    and any parameter of its engine, as in svgtile synth with _ for -.
    Keys at the top level are defaults for every class (an engine parameter only for the
    classes whose engine has it; a seed there is every class's), plus:
      avoid = ["labels"]      ids in the map (or MAP.svg#ID specs) every texture keeps clear of
      avoid_margin = 2        clear space around them, map units
      class_attribute = "data-unit"   SVG maps: the attribute naming a unit's class
      class_property = "unit"         GeoJSON maps: the property naming a feature's class

    Engine parameters: %(params)s.
    """
    kind = output_format(output, ("svg", "geojson"))
    styles = read_styles(styles_file)
    inputs = (Path(map_file), Path(styles_file), *(s.exemplar for s in styles.classes.values()))
    if output != "-" and any(same_file(output, p) for p in inputs):
        raise ParameterError(f"{output}: refusing to overwrite an input file")
    check_output(output, protect=inputs)
    own = {s.seed for s in styles.classes.values()}
    if seed is not None and None not in own:
        warn(f"--seed {seed} is not used: every class has a seed in {styles_file} (a top-level seed is every class's)")
    if seed is None and None in own:
        seed = secrets.randbelow(2**31)
        click.echo(f"svgtile: seed {seed}", err=True)
    # the metadata records the seeds used: one, or each class's where they differ
    used = {c: s.seed if s.seed is not None else seed for c, s in sorted(styles.classes.items())}
    used_text = str(next(iter(used.values()))) if len(set(used.values())) == 1 else " ".join(f"{c}={v}" for c, v in used.items())
    if seed is None:
        seed = 0  # every class has its own seed: the run's is never used
    result = fill_map(map_file, styles, seed=seed, avoid=avoid, jobs=jobs or default_jobs(), progress=_progress(),
                      max_motifs=MAX_MOTIFS)  # fmt: skip
    Stderr.clear()
    for message in result.warnings:
        warn(message)
    for ident, message in result.errors.items():
        warn(f"region {ident!r} not filled: {message}")
    if result.errors and len(result.errors) == len(result.regions):
        raise SvgtileError(f"none of the {len(result.regions)} regions could be filled (see the warnings); "
                           "nothing written", source=str(output))  # fmt: skip
    if kind == "geojson":
        text = placements_document(result)
    else:
        params = {"map": Path(map_file).name, "styles": Path(styles_file).name, "seed": used_text,
                  "regions": len(result.regions), "failed": len(result.errors)}  # fmt: skip
        text = svg_map(result, params)
    write_file(text, output, protect=inputs)
    if result.errors:
        raise SvgtileError(f"{len(result.errors)} of {len(result.regions)} regions failed (see the warnings); "
                           f"the others were written", source=str(output))  # fmt: skip


def _progress():
    """``progress(done, total, ident, error)``: a self-erasing line on a terminal, else nothing."""
    if not sys.stderr.isatty():
        return None

    def report(done: int, total: int, ident: str, error: str | None) -> None:
        click.echo(f"\rsvgtile: map {done}/{total} regions ({ident[:30]})\033[K", err=True, nl=False)
        Stderr.progress_shown = True

    return report


def svg_map(result: MapFill, params: dict) -> str:
    """The filled map as SVG text (see :func:`svgtile.svg.writer.map_document`)."""
    styles = result.styles
    defs, kinds = [], {}
    for cls in sorted({r.cls for r, a in zip(result.regions, result.results, strict=True) if a is not None}):
        prefix = "svgtile-" + re.sub(r"[^A-Za-z0-9_.-]+", "-", cls).strip("-") + "-"
        ex, _ = load_exemplar(str(styles.classes[cls].exemplar))
        style_defs, kinds[cls] = prefixed_defs(ex, prefix)
        defs.extend(style_defs)
    layers = [
        MapLayer(r.ident, r.cls, r.shape, kinds[r.cls], arr, styles.classes[r.cls].boundary,
                 r.element, r.matrix)
        for r, arr in zip(result.regions, result.results, strict=True)
        if arr is not None
    ]  # fmt: skip
    doc = result.doc
    return map_document(None if doc is None else doc.root, defs, layers, params=params,
                        namespaces=() if doc is None else doc.namespaces)  # fmt: skip


def placements_document(result: MapFill) -> str:
    """Every region's motifs as GeoJSON points, with ``region`` and ``class`` properties."""
    features = []
    for r, arr in zip(result.regions, result.results, strict=True):
        if arr is None:
            continue
        ex, _ = load_exemplar(str(result.styles.classes[r.cls].exemplar))
        names = [k.name for k in ex.kinds]
        radius = np.array([k.prototype.radius for k in ex.kinds])
        for f in geojson.placements(arr, names, radius)["features"]:
            f["properties"] = {"region": r.ident, "class": r.cls, **f["properties"]}
            features.append(f)
    return geojson.placements_text({"type": "FeatureCollection", "features": features})
