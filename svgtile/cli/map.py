"""``svgtile map``: fill every classed unit of a map with its class's texture (issue 5 item 3)."""

from __future__ import annotations

import collections
import dataclasses
import secrets
import sys
from pathlib import Path

import click

from svgtile.apps.gisout import (
    check_style,
    filled_exemplars,
    map_parts,
    write_placements,
    write_style,
)
from svgtile.apps.load import MAX_MOTIFS, load_exemplar
from svgtile.apps.mapfill import cellular_classes, default_jobs, fill_map, read_styles
from svgtile.apps.mapwrite import BandWriter, class_prefix, write_geojson, write_map_svg
from svgtile.cli.common import (
    POINT_FORMATS,
    Stderr,
    default_boundary,
    output_format,
    spec_files,
    warn,
)
from svgtile.engines import engines_with, public_params
from svgtile.errors import ParameterError, SvgtileError
from svgtile.files import check_output, same_file
from svgtile.gis.layers import common_crs, is_gis
from svgtile.runners.schedule import check_scheduler
from svgtile.runners.spool import Spool
from svgtile.svg.writer import prefixed_defs


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
              help="The filled map (.svg), or one point per motif for GIS (.gpkg, .shp, .fgb, .geojson; in MAP's CRS).")
@click.option("--with-style", is_flag=True,
              help="With a GIS output: also write OUT.qml (a QGIS style) and OUT-symbols/CLASS/KIND.svg.")
@click.option("--avoid", multiple=True, metavar="ID|MAP.svg#ID",
              help="More labels, lines or shapes every texture keeps clear of (an id in MAP, or a spec). Repeatable.")
@click.option("--seed", type=click.IntRange(min=0), default=None,
              help="Random seed shared by every region (a class's own seed wins, and a top-level seed in the styles file is every class's). Without it one is chosen and printed.")
@click.option("--jobs", type=click.IntRange(min=1), default=None,
              help="Worker processes filling regions (or tiles) at once with --scheduler local or processes [default: the usable cores].")
@click.option("--scheduler", default="local", show_default=True, metavar="local|processes|ADDRESS",
              help="Where the work runs: local = Dask's local scheduler on this machine; processes = a Dask LocalCluster of --jobs worker processes; an address such as tcp://host:8786 = that Dask cluster (its workers must see the exemplars at the same paths).")
@click.option("--tile-size", type=click.FloatRange(min=0, min_open=True), default=None, metavar="SIZE",
              help="Cut each region into world-anchored tiles SIZE map units wide, run as separate units; the output is the same. Regions whose engine is not tile-exact (patch, random) are run whole.")
@click.option("--refine", type=click.IntRange(min=0), default=None, metavar="N",
              help="Improve every class's texture by N iterations of optimisation (Ma, Wei & Tong 2011) after its engine; a class's own refine key wins.")
@_with_params
def map_cmd(map_file, styles_file, output, avoid, seed, jobs, with_style, scheduler, tile_size, refine):
    """Fill every unit of MAP (SVG, or a GIS layer: .gpkg, .shp, .fgb, .geojson) whose class the styles file knows.

    A unit's class is its class attribute (or the attribute the styles file names) or its
    Inkscape label; in a GIS layer, the field the styles file names (default "class"). The output
    keeps the map and adds one texture group per unit, above the unit and below what follows it.
    A unit that fails is reported; the others are written, and the exit code is 1.

    \b
    The styles file (TOML), a table [classes.NAME] per class:
      exemplar = "FILE.svg"   the class's exemplar, relative to the styles file
      engine = "patch"        one of the engines (svgtile synth --help); unnamed, "cellular" for an
                              exemplar svgtile import made cellular (a bedded tile), else "patch"
      seed = 7                this class's seed (else the run's)
      unit = 1.0              map units per exemplar user unit
      boundary = "clip"       inside, centroid, clip or none (default: clip; inside for GIS points)
      refine = 0              optimisation iterations after the engine (any engine)
    and any parameter of its engine, as in svgtile synth with _ for -; a cellular class's
    label = "fault=#faults" names a line of MAP itself (its cells are drawn in the unit's group,
    and written as polygons to .geojson; a point layer such as .gpkg refuses them).
    Keys at the top level are defaults for every class (an engine parameter only for the
    classes whose engine has it; a seed there is every class's), plus:
      avoid = ["labels"]      ids in the map (or MAP.svg#ID specs) every texture keeps clear of
      avoid_margin = 2        clear space around them, map units
      class_attribute = "data-unit"   SVG maps: the attribute naming a unit's class
      class_property = "unit"         GIS maps: the field naming a feature's class

    Engine parameters: %(params)s.
    """
    kind = output_format(output, ("svg", "geojson", "gis"))
    if with_style and (kind not in POINT_FORMATS or output == "-"):
        raise ParameterError("--with-style goes with a GIS output file (.gpkg, .shp, .fgb, .geojson)")
    styles = read_styles(styles_file, boundary=default_boundary(kind, None))
    crs = common_crs(map_file, [a for a in (*styles.avoid, *avoid) if is_gis(a)])
    if refine is not None:
        styles = dataclasses.replace(styles, classes={c: s if s.refine is not None else dataclasses.replace(s, refine=refine)
                                                      for c, s in styles.classes.items()})  # fmt: skip
    inputs = (Path(map_file), Path(styles_file), *(s.exemplar for s in styles.classes.values()),
              *spec_files((*styles.avoid, *avoid)))  # fmt: skip
    if output != "-" and any(same_file(output, p) for p in inputs):
        raise ParameterError(f"{output}: refusing to overwrite an input file")
    check_output(output, protect=inputs)
    if with_style:
        check_style(output, protect=inputs)
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
    check_scheduler(scheduler)
    bar = sys.stderr.isatty() and output != "-"
    if kind in POINT_FORMATS and (kind != "geojson" or crs is not None):  # GDAL writes the layer at the end
        cellular = cellular_classes(styles)
        if cellular:
            where = "a map with a CRS" if kind == "geojson" else "a point layer"
            raise ParameterError(f"{output}: class {cellular[0]!r} is cellular, and its cells are polygons, which "
                                 f"{where} written here cannot hold yet: write the map to .svg, or a map without a "
                                 "CRS to .geojson")  # fmt: skip
        result = fill_map(map_file, styles, seed=seed, avoid=avoid, jobs=jobs or default_jobs(), max_motifs=MAX_MOTIFS,
                          scheduler=scheduler, tile_size=tile_size, bar=bar)  # fmt: skip
        Stderr.clear()
        _warn_about(result, output, [0 if a is None else len(a) for a in result.results])
        exemplars = filled_exemplars(result)
        write_placements(map_parts(result, exemplars), output, crs=crs, protect=inputs)
        if with_style:
            write_style(output, exemplars, protect=inputs)
    else:  # SVG (and GeoJSON with no CRS) is streamed: bands spooled as they are done, assembled in world order
        folder = None if output == "-" else str(Path(output).resolve().parent)
        with Spool(folder) as spool:
            bands = BandWriter(spool, kind)
            placed: collections.Counter[int] = collections.Counter()
            result = fill_map(map_file, styles, seed=seed, avoid=avoid, jobs=jobs or default_jobs(),
                              max_motifs=MAX_MOTIFS, scheduler=scheduler, tile_size=tile_size,
                              sink=_sink(bands, kind, styles, placed), bar=bar,
                              cell_sink=_cell_sink(bands, kind, styles, placed))  # fmt: skip
            Stderr.clear()
            _warn_about(result, output, [placed[n] for n in range(len(result.regions))])
            if kind == "geojson":
                write_geojson(output, [n for n, ok in enumerate(result.filled) if ok], bands, protect=inputs)
                if with_style:
                    write_style(output, filled_exemplars(result), protect=inputs)
            else:
                params = {"map": Path(map_file).name, "styles": Path(styles_file).name, "seed": used_text,
                          "regions": len(result.regions), "failed": len(result.errors)}  # fmt: skip
                write_map_svg(output, result, bands, params, protect=inputs)
    if result.errors:
        tiles = any(ident not in {r.ident for r in result.regions} for ident in result.errors)
        what = f"{len(result.errors)} regions or tiles" if tiles else f"{len(result.errors)} of {len(result.regions)} regions"
        raise SvgtileError(f"{what} failed (see the warnings); the others were written", source=str(output))


def _sink(bands: BandWriter, kind: str, styles, placed: collections.Counter):
    """``sink(region, band, motifs)`` for :func:`fill_map`: each band formatted and spooled, its
    motifs counted in ``placed`` (region number -> motifs)."""
    kinds: dict[str, tuple] = {}

    def sink(n: int, r, b: int, arr) -> None:
        placed[n] += len(arr)
        ex, _ = load_exemplar(str(styles.classes[r.cls].exemplar))
        if kind == "geojson":
            bands.features(n, b, arr, ex, {"region": r.ident, "class": r.cls})
        else:
            if r.cls not in kinds:
                kinds[r.cls] = prefixed_defs(ex, class_prefix(r.cls))[1]
            bands.svg(n, b, arr, kinds[r.cls])

    return sink


def _cell_sink(bands: BandWriter, kind: str, styles, placed: collections.Counter):
    """``cell_sink(region, cells)`` for :func:`fill_map`: a cellular unit's cells and lines
    spooled before its motifs, counted in ``placed``."""

    def cell_sink(n: int, r, cells) -> None:
        placed[n] += len(cells)
        unit = styles.classes[r.cls].unit
        if kind == "geojson":
            bands.cell_features(n, cells, {"region": r.ident, "class": r.cls}, scale=unit)
        else:
            bands.cells_svg(n, cells, unit)

    return cell_sink


def _warn_about(result, output: str, placed: list[int]) -> None:
    """The fill's warnings, failed regions and regions filled with nothing (``placed``: motifs
    per region), a line each; an error, before anything is written, when no region could be
    filled."""
    for message in result.warnings:
        warn(message)
    for ident, message in result.errors.items():
        warn(f"region {ident!r} not filled: {message}")
    for r, ok, count in zip(result.regions, result.filled, placed, strict=True):
        if ok and count == 0 and r.ident not in result.errors:
            warn(f"no motif fits in region {r.ident!r} (class {r.cls!r}); it is left empty")
    if result.errors and not any(result.filled):
        raise SvgtileError(f"none of the {len(result.regions)} regions could be filled (see the warnings); "
                           "nothing written", source=str(output))  # fmt: skip
