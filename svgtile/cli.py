"""The ``svgtile`` command line: parse options, call the library, report in one line."""

from __future__ import annotations

import json
import math
import re
import secrets
import sys
from pathlib import Path

import click
import numpy as np

from . import __version__
from .analysis import Stats, analyze
from .engines import ENGINES
from .errors import ParameterError, SvgtileError
from .exemplar import Exemplar, read_exemplar
from .output import svg_document, write_text
from .region import BOUNDARY_MODES, Region

#: Above this estimated motif count ``synth`` refuses to run without ``--force``.
MAX_MOTIFS = 2_000_000


def _size(text: str) -> tuple[float, float]:
    match = re.fullmatch(r"\s*([0-9.eE+-]+)\s*(?:[xX×]\s*([0-9.eE+-]+))?\s*", text)
    try:
        w = float(match.group(1))
        h = float(match.group(2) or match.group(1))
    except (AttributeError, ValueError):
        raise ParameterError(f"--size must look like 800x600 (user units), not {text!r}") from None
    if not (w > 0 and h > 0 and math.isfinite(w) and math.isfinite(h)):
        raise ParameterError(f"--size must be positive, not {text!r}")
    return w, h


def _warn(message: str) -> None:
    click.echo(f"svgtile: warning: {message}", err=True)


def _load(path: str) -> tuple[Exemplar, Stats]:
    exemplar = read_exemplar(path)
    for message in exemplar.warnings:
        _warn(f"{path}: {message}")
    stats = analyze(exemplar)
    if stats.overlaps:
        _warn(f"{path}: {stats.overlaps} pair(s) of motifs overlap in the exemplar; continuing")
    return exemplar, stats


def _progress():
    if not sys.stderr.isatty():
        return None

    def report(stage: str, fraction: float) -> None:
        end = "\n" if stage == "done" else ""
        click.echo(f"\rsvgtile: {stage:<10} {fraction:4.0%}", err=True, nl=False)
        if end:
            click.echo("\r" + " " * 30 + "\r", err=True, nl=False)

    return report


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="svgtile")
def cli() -> None:
    """Fill any region with small vector motifs so it looks like a small exemplar you drew."""


@cli.command()
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("-o", "--output", required=True, help="Output SVG file, or - for standard output.")
@click.option("--size", required=True, help="Output size WIDTHxHEIGHT in the exemplar's user units, e.g. 800x600.")
@click.option("--engine", type=click.Choice(sorted(ENGINES)), default="patch", show_default=True,
              help="Synthesis algorithm (patch: AlMeraj et al. 2013).")
@click.option("--grid", type=click.Choice(["square", "hex"]), default="square", show_default=True,
              help="Layout of the exemplar copies; hex suits round exemplars.")
@click.option("--overlap", type=float, default=0.3, show_default=True,
              help="How much neighbouring exemplar copies overlap, 0 to 0.5. More overlap hides seams but removes more motifs.")
@click.option("--max-rotation", type=float, default=30.0, show_default=True,
              help="Each exemplar copy is turned by a random angle up to this many degrees (0 to 180); motifs keep their own orientation. 0 keeps copies square to the page.")
@click.option("--vary-orientation", is_flag=True,
              help="Give every motif a new orientation, drawn from the range its kind shows in the exemplar.")
@click.option("--boundary", type=click.Choice(BOUNDARY_MODES), default="clip", show_default=True,
              help="At the region's edge: inside = only whole motifs; centroid = motifs whose centre is inside; clip = cut motifs at the edge; none = let them stick out.")
@click.option("--seed", type=int, default=None,
              help="Random seed; the same exemplar, options and seed give the same file. Without it a seed is chosen and printed.")
@click.option("--force", is_flag=True, help=f"Run even when the estimated motif count exceeds {MAX_MOTIFS:,}.")
def synth(exemplar, output, size, engine, grid, overlap, max_rotation, vary_orientation, boundary, seed, force):
    """Synthesize a texture like EXEMPLAR and write it as SVG.

    EXEMPLAR is an SVG whose motifs are <use> clones of <symbol>s (or plain shapes); the element
    with id="region" (else the viewBox) is the area the motifs were drawn in.
    """
    width, height = _size(size)
    if not 0.0 <= overlap <= 0.5:
        raise ParameterError(f"--overlap must be between 0 and 0.5, not {overlap:g}")
    if not 0.0 <= max_rotation <= 180.0:
        raise ParameterError(f"--max-rotation must be between 0 and 180 degrees, not {max_rotation:g}")
    if output != "-" and Path(output).resolve() == Path(exemplar).resolve():
        raise ParameterError(f"{output}: refusing to overwrite the exemplar")
    ex, stats = _load(exemplar)
    region = Region.rectangle(width, height)
    estimate = stats.count_density * region.area
    if estimate > MAX_MOTIFS and not force:
        raise ParameterError(
            f"--size {size} would hold about {estimate:,.0f} motifs (limit {MAX_MOTIFS:,}); use --force to run anyway"
        )
    if seed is None:
        seed = secrets.randbelow(2**31)
        click.echo(f"svgtile: seed {seed}", err=True)
    params = dict(grid=grid, overlap=overlap, max_rotation=max_rotation,
                  vary_orientation=vary_orientation, boundary=boundary)  # fmt: skip
    arr = ENGINES[engine](ex, region, rng=np.random.default_rng(seed), stats=stats, progress=_progress(), **params)
    meta = {"engine": engine, "seed": seed, "exemplar": Path(exemplar).name, "size": f"{width:g}x{height:g}",
            **params, "motifs": len(arr)}  # fmt: skip
    text = svg_document(ex, arr, region, boundary=boundary, params=meta)
    write_text(text, output, protect=(Path(exemplar),))


@cli.command(name="analyze")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print machine-readable JSON.")
def analyze_cmd(exemplar, as_json):
    """Print what synthesis reproduces from EXEMPLAR: kinds, density, distances, orientations."""
    ex, stats = _load(exemplar)
    report = stats_report(ex, stats)
    if as_json:
        click.echo(json.dumps(report, indent=2))
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


def format_report(r: dict) -> str:
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


def main(argv: list[str] | None = None) -> int:
    """Entry point: every expected failure is one line on stderr and a non-zero exit."""
    debug = "--debug" in (argv if argv is not None else sys.argv[1:])
    args = [a for a in (argv if argv is not None else sys.argv[1:]) if a != "--debug"]
    try:
        cli.main(args=args, prog_name="svgtile", standalone_mode=False)
    except SvgtileError as exc:
        click.echo(f"svgtile: error: {exc}", err=True)
        return 1
    except click.exceptions.Abort:
        click.echo("svgtile: interrupted", err=True)
        return 130
    except click.exceptions.NoArgsIsHelpError as exc:
        click.echo(exc.ctx.get_help() if exc.ctx else exc.format_message())
        return 0
    except click.ClickException as exc:
        click.echo(f"svgtile: error: {exc.format_message()}", err=True)
        return exc.exit_code
    except KeyboardInterrupt:
        click.echo("svgtile: interrupted", err=True)
        return 130
    except MemoryError:
        click.echo("svgtile: error: out of memory; try a smaller --size", err=True)
        return 1
    except Exception as exc:  # a bug, not bad input: still one line, traceback on request
        if debug:
            raise
        click.echo(f"svgtile: internal error: {type(exc).__name__}: {exc} (run with --debug for details)", err=True)
        return 70
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
