"""The ``svgtile`` command line: parse options, call the library, report in one line."""

from __future__ import annotations

import json
import math
import os
import re
import secrets
import sys
import warnings
from pathlib import Path

import click
import numpy as np

from svgtile import __version__
from svgtile.analysis.stats import Stats, analyze, motif_estimate
from svgtile.apps.mapread import synth_region
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import BOUNDARY_MODES
from svgtile.engines import ENGINES
from svgtile.engines.patch.engine import PatchParams
from svgtile.errors import ParameterError, SvgtileError
from svgtile.files import check_output, same_file, write_file
from svgtile.gis.geojson import exemplar_placements
from svgtile.svg.reader import read_exemplar
from svgtile.svg.writer import fmt, svg_document

#: Above this estimated motif count ``synth`` refuses to run without ``--force`` (the estimate is
#: the exemplar's motifs per unit area times the output area).  Two million motifs take about a
#: minute and a few GB of memory, and make an SVG of some 180 MB that few viewers can open.
MAX_MOTIFS = 2_000_000
#: Refused even with ``--force``: no machine holds this many motifs (about 1 kB each) in memory.
HARD_MAX_MOTIFS = 1e9
# click >= 8.2 raises this for a bare ``svgtile``; older versions print the help and exit 0
_NO_ARGS_IS_HELP = getattr(click.exceptions, "NoArgsIsHelpError", ())


def _size(text: str) -> tuple[float, float]:
    """``WIDTHxHEIGHT`` (or one number for a square) in user units, both positive and finite."""
    match = re.fullmatch(r"\s*([0-9.eE+-]+)\s*(?:[xX×]\s*([0-9.eE+-]+))?\s*", text)
    try:
        w = float(match.group(1))
        h = float(match.group(2) or match.group(1))
    except (AttributeError, ValueError):
        raise ParameterError(f"--size must look like 800x600 (user units), not {text!r}") from None
    if not (w > 0 and h > 0):
        raise ParameterError(f"--size must be positive, not {text!r}")
    if not (math.isfinite(w) and math.isfinite(h)):
        raise ParameterError(f"--size {text!r} is too large to represent")
    return w, h


class _Stderr:
    """One-line messages on stderr, aware of the progress line a terminal may be showing."""

    progress_shown = False

    @classmethod
    def line(cls, message: str) -> None:
        cls.clear()
        click.echo(" ".join(message.split("\n")), err=True)

    @classmethod
    def clear(cls) -> None:
        if cls.progress_shown:
            click.echo("\r\033[K", err=True, nl=False)
            cls.progress_shown = False


def _warn(message: str) -> None:
    _Stderr.line(f"svgtile: warning: {message}")


def _showwarning(message, category, filename, lineno, file=None, line=None) -> None:
    """Python warnings (numpy, shapely …) as one svgtile line instead of two lines of source."""
    _warn(f"{message} ({category.__name__})")


def _load(path: str) -> tuple[Exemplar, Stats]:
    exemplar = read_exemplar(path)
    for message in exemplar.warnings:
        _warn(f"{path}: {message}")
    stats = analyze(exemplar)
    if stats.overlaps:
        _warn(f"{path}: {stats.overlaps} pair(s) of motifs overlap in the exemplar; continuing")
    return exemplar, stats


def _check_motif_count(ex: Exemplar, stats: Stats, region, where: str, *, force: bool | None = False) -> None:
    """Refuse a region whose estimated motif count (:func:`svgtile.analysis.stats.motif_estimate`) is
    above :data:`MAX_MOTIFS` (unless ``force``; a command without ``--force`` passes None) or above
    :data:`HARD_MAX_MOTIFS`."""
    estimate = motif_estimate(ex, stats, region)
    if not estimate <= HARD_MAX_MOTIFS:
        about = f"about {estimate:.3g}" if math.isfinite(estimate) else "countless"
        raise ParameterError(f"{where} would hold {about} motifs, more than svgtile can hold in memory")
    if estimate > MAX_MOTIFS and not force:
        hint = "; use --force to run anyway" if force is not None else ""
        raise ParameterError(f"{where} would hold about {estimate:,.0f} motifs (limit {MAX_MOTIFS:,}){hint}")


def _progress():
    """A ``progress(stage, fraction)`` callback drawing one self-erasing line, when stderr is a
    terminal; None otherwise (logs and pipes get nothing)."""
    if not sys.stderr.isatty():
        return None

    def report(stage: str, fraction: float) -> None:
        if stage == "done":
            _Stderr.clear()
            return
        click.echo(f"\rsvgtile: {stage:<10} {fraction:4.0%}", err=True, nl=False)
        _Stderr.progress_shown = True

    return report


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="svgtile")
def cli() -> None:
    """Fill any region with small vector motifs so it looks like a small exemplar you drew."""


@cli.command()
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, help="Output SVG file, or - for standard output; a .geojson file gets one point per motif (kind, angle, scale) for GIS.")
@click.option("--size", default=None,
              help="Output size WIDTHxHEIGHT in the exemplar's user units, e.g. 800x600 (one number: a square).")
@click.option("--region", "region_spec", default=None, metavar="MAP.svg#ID|FILE.geojson",
              help="Fill this shape instead of a --size rectangle: an element (closed shape or group) of another SVG, holes by its fill rule, or the polygons of a GeoJSON file (FILE.geojson#ID: one feature).")
@click.option("--avoid", multiple=True, metavar="MAP.svg#ID",
              help="Keep every motif clear of these labels, lines or shapes (texts by their box, lines by their stroke, grown by --avoid-margin). Repeatable.")
@click.option("--avoid-margin", type=float, default=2.0, show_default=True,
              help="Clear space around --avoid zones, user units.")
@click.option("--engine", type=click.Choice(sorted(ENGINES)), default="patch", show_default=True,
              help="Synthesis algorithm: patch = copies of the exemplar blended without seams (AlMeraj et al. 2013); tile = plain repeated copies and random = scattered motifs, both for comparison.")
@click.option("--grid", type=click.Choice(["square", "hex"]), default="square", show_default=True,
              help="Layout of the exemplar copies; hex suits round exemplars.")
@click.option("--overlap", type=float, default=PatchParams.overlap, show_default=True,
              help="How much neighbouring exemplar copies overlap, 0 to 0.5. More overlap hides seams but removes more motifs.")
@click.option("--max-rotation", type=float, default=PatchParams.max_rotation, show_default=True,
              help="Each exemplar copy is turned by a random angle up to this many degrees (0 to 180); motifs keep their own orientation. 0 keeps copies square to the page.")
@click.option("--junction", type=float, default=PatchParams.junction, show_default=True,
              help="Where copies meet, motifs keep this quantile (0 to <1) of the exemplar's nearest gaps apart; 0 = only its smallest gap (the paper's rule).")
@click.option("--vary-orientation", is_flag=True,
              help="Give every motif a new orientation, drawn from the range its kind shows in the exemplar.")
@click.option("--boundary", type=click.Choice(BOUNDARY_MODES), default="clip", show_default=True,
              help="At the region's edge: inside = only whole motifs; centroid = motifs whose centre is inside; clip = cut motifs at the edge; none = let them stick out.")
@click.option("--seed", type=click.IntRange(min=0), default=None,
              help="Random seed; the same exemplar, options and seed give the same file. Without it a seed is chosen and printed.")
@click.option("--force", is_flag=True, help=f"Run even when the estimated motif count exceeds {MAX_MOTIFS:,}.")
@click.option("--import", "as_tile", is_flag=True,
              help="EXEMPLAR is a seamless pattern tile (FGDC, OSM fill …): import it first, as 'svgtile import' does.")
def synth(exemplar, output, size, region_spec, avoid, avoid_margin, engine, grid, overlap, max_rotation,
          junction, vary_orientation, boundary, seed, force, as_tile):
    """Synthesize a texture like EXEMPLAR and write it as SVG.

    EXEMPLAR is an SVG whose motifs are <use> clones of <symbol>s (or plain shapes); the element
    with id="region" (else the viewBox) is the area the motifs were drawn in.
    """
    region = synth_region(_size(size) if size is not None else None, region_spec, avoid, avoid_margin)
    where = f"--size {size}" if size is not None else f"--region {region_spec}"
    params = dict(grid=grid, overlap=overlap, max_rotation=max_rotation, junction=junction,
                  vary_orientation=vary_orientation, boundary=boundary)  # fmt: skip
    PatchParams(**params)  # their ranges, checked before the work whatever the engine
    if output != "-" and same_file(output, exemplar):
        raise ParameterError(f"{output}: refusing to overwrite the exemplar")
    check_output(output, protect=(exemplar,))  # fail before the work, not after
    if as_tile:
        from svgtile.cli.tiles import load_tile

        ex, stats = load_tile(exemplar)
    else:
        ex, stats = _load(exemplar)
    _check_motif_count(ex, stats, region, where, force=force)
    if seed is None:
        seed = secrets.randbelow(2**31)
        click.echo(f"svgtile: seed {seed}", err=True)
    arr = ENGINES[engine](ex, region, rng=np.random.default_rng(seed), stats=stats, progress=_progress(), **params)
    _Stderr.clear()
    if len(arr) == 0:
        _warn(f"no motif fits in {size or region_spec} with --boundary {boundary}; writing an empty texture")
    x0, y0, x1, y1 = region.bounds
    where_meta = {"region": region_spec} if region_spec else {"size": f"{fmt(x1 - x0)}x{fmt(y1 - y0)}"}
    meta = {"engine": engine, "seed": seed, "exemplar": Path(exemplar).name, **where_meta,
            **params, "motifs": len(arr)}  # fmt: skip
    if str(output).lower().endswith(".geojson"):
        text = exemplar_placements(ex, arr)
    else:
        text = svg_document(ex, arr, region, boundary=boundary, params=meta)
    write_file(text, output, protect=(Path(exemplar),))


@cli.command(name="analyze")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print machine-readable JSON.")
def analyze_cmd(exemplar, as_json):
    """Print what synthesis reproduces from EXEMPLAR: kinds, density, distances, orientations."""
    ex, stats = _load(exemplar)
    report = stats_report(ex, stats)
    if as_json:
        click.echo(json.dumps(_json_safe(report), indent=2, allow_nan=False))
    else:
        click.echo(format_report(report))


def stats_report(ex: Exemplar, stats: Stats) -> dict:
    """The analysis as plain data (what ``analyze --json`` prints)."""
    x0, y0, x1, y1 = ex.region.bounds
    counts = np.bincount(ex.motifs.kind, minlength=len(ex.kinds))
    return {
        "exemplar": ex.source,
        "region": {"bounds": [x0, y0, x1, y1], "area": ex.region.area},
        "motifs": len(ex.motifs),
        "density": stats.density,
        "motifs_per_unit_area": stats.count_density,
        "kinds": [
            {
                "name": k.name,
                "count": int(counts[i]),
                "frequency": float(stats.frequency[i]),
                "area": k.prototype.area,
                "arc": {"start": float(stats.arc_start[i]), "width": float(stats.arc_width[i])},
            }
            for i, k in enumerate(ex.kinds)
        ],
        "distance": stats.distance.tolist(),
        "distance_measured": stats.measured.tolist(),
        "overlapping_pairs": stats.overlaps,
    }


def _json_safe(value):
    """``value`` with NaN and infinities as None: JSON has no spelling for them."""
    if isinstance(value, dict):
        return {k: _json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def format_report(r: dict) -> str:
    """The analysis as the table ``svgtile analyze`` prints."""
    x0, y0, x1, y1 = r["region"]["bounds"]
    lines = [
        f"exemplar      {r['exemplar']}",
        f"input region  {x1 - x0:g} x {y1 - y0:g} at ({x0:g}, {y0:g}), area {r['region']['area']:.4g}",
        f"motifs        {r['motifs']} in {len(r['kinds'])} kind(s)",
        f"density ρ     {r['density']:.4f} of the area covered, {r['motifs_per_unit_area']:.4g} motifs per unit²",
        "",
        f"  {'#':>2}  {'kind':<20} {'count':>5} {'share':>6} {'area':>8}   orientation arc",
    ]
    for i, k in enumerate(r["kinds"]):
        a = k["arc"]
        arc = f"{a['start']:+.1f}° … {a['start'] + a['width']:+.1f}° ({a['width']:.1f}°)"
        lines.append(f"  {i:>2}  {k['name']:<20} {k['count']:>5} {k['frequency']:>6.3f} {k['area']:>8.3f}   {arc}")
    lines += ["", "minimum distances d_ij (* = fallback, the exemplar has no such pair):"]
    names = [k["name"][:10] for k in r["kinds"]]
    lines.append("  " + " " * 12 + "".join(f"{n:>12}" for n in names))
    for i, row in enumerate(r["distance"]):
        cells = "".join(
            f"{v:>11.3f}{' ' if r['distance_measured'][i][j] else '*'}" for j, v in enumerate(row)
        )
        lines.append(f"  {names[i]:<12}{cells}")
    if r["overlapping_pairs"]:
        lines.append(f"\nwarning: {r['overlapping_pairs']} overlapping pair(s) in the exemplar")
    return "\n".join(lines)


# Commands that live in modules of their own (they import the helpers above, so they come last).
from svgtile.cli.compare import compare
from svgtile.cli.inkscape import inkscape
from svgtile.cli.map import map_cmd
from svgtile.cli.score import score
from svgtile.cli.tiles import import_cmd, swatches_cmd

for _command in (compare, import_cmd, inkscape, map_cmd, score, swatches_cmd):
    cli.add_command(_command)


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())


def main(argv: list[str] | None = None) -> int:
    """Entry point: every expected failure is one line on stderr and a non-zero exit.

    Exit codes: 0 success (also for help), 1 bad input or unwritable output, 2 bad command line,
    70 internal error (a bug; ``--debug`` anywhere shows the traceback), 130 interrupted.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    args = [a for a in argv if a != "--debug"]
    _Stderr.progress_shown = False
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _showwarning
            # click's own main would print a blank line on ^C and exit on a broken pipe itself
            with cli.make_context("svgtile", args) as ctx:
                cli.invoke(ctx)
    except SvgtileError as exc:
        _Stderr.line(f"svgtile: error: {_one_line(exc)}")
        return 1
    except click.exceptions.Exit as exc:  # --help, --version
        return exc.exit_code
    except _NO_ARGS_IS_HELP as exc:  # bare ``svgtile``
        click.echo(exc.ctx.get_help() if exc.ctx else exc.format_message())
        return 0
    except click.UsageError as exc:
        hint = f" (see '{exc.ctx.command_path} --help')" if exc.ctx else ""
        _Stderr.line(f"svgtile: error: {_one_line(exc.format_message())}{hint}")
        return exc.exit_code
    except click.ClickException as exc:
        _Stderr.line(f"svgtile: error: {_one_line(exc.format_message())}")
        return exc.exit_code
    except (KeyboardInterrupt, click.exceptions.Abort):
        _Stderr.line("svgtile: interrupted")
        return 130
    except BrokenPipeError:  # ``svgtile synth … -o - | head``: the reader left, nothing to report
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, sys.stdout.fileno())  # so the flush at exit cannot fail again
        except (OSError, AttributeError, ValueError):
            pass
        finally:
            os.close(devnull)
        return 1
    except MemoryError:
        _Stderr.line("svgtile: error: out of memory; try a smaller --size")
        return 1
    except Exception as exc:  # a bug, not bad input: still one line, traceback on request
        if debug:
            raise
        _Stderr.line(f"svgtile: internal error: {type(exc).__name__}: {_one_line(exc)} (run with --debug for details)")
        return 70
    return 0

if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
