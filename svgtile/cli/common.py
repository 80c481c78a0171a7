"""What the commands share: option parsing, one-line messages, the progress line, and the engine
options made from the engines' parameter classes (:mod:`svgtile.engines.base`)."""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Callable
from pathlib import Path

import click
from click.core import ParameterSource

from svgtile.analysis.stats import Stats
from svgtile.apps.load import load_exemplar
from svgtile.cli.output import (  # noqa: F401 (the commands import them from here)
    OUTPUT_PARAMS,
    Ending,
    Stderr,
    command_paths,
    one_line,
    showwarning,
    warn,
)
from svgtile.core.exemplar import Exemplar
from svgtile.engines import ENGINES, engines_with, get_engine, make_params, public_params
from svgtile.engines.base import EngineParams, honoured
from svgtile.engines.choose import AUTO, RULE_ENGINES, choose, steerable, with_choice
from svgtile.errors import ParameterError
from svgtile.gis.layers import is_gis


def parse_size(text: str) -> tuple[float, float]:
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


def load(path: str, *, as_tile: bool = False) -> tuple[Exemplar, Stats]:
    """The exemplar and its analysis (:func:`svgtile.apps.load.load_exemplar`), warnings on stderr."""
    return load_exemplar(path, as_tile=as_tile, warn=warn)


def progress_line() -> Callable[[str, float], None] | None:
    """A ``progress(stage, fraction)`` callback drawing one self-erasing line, when stderr is a
    terminal; None otherwise (logs and pipes get nothing)."""
    if not sys.stderr.isatty():
        return None

    def report(stage: str, fraction: float) -> None:
        if stage == "done":
            Stderr.clear()
            return
        click.echo(f"\rsvgtile: {stage:<10} {fraction:4.0%}", err=True, nl=False)
        Stderr.progress_shown = True

    return report


def json_safe(value):
    """``value`` with NaN and infinities as None: JSON has no spelling for them."""
    if isinstance(value, dict):
        return {k: json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


#: Output formats by file suffix (``-``, standard output, and a name without suffix are SVG).
FORMATS = {".svg": "svg", ".geojson": "geojson", ".png": "png", ".gpkg": "gis", ".shp": "gis", ".fgb": "gis"}
#: Output kinds that are one point per motif (the boundary mode defaults to ``inside`` for them).
POINT_FORMATS = ("geojson", "gis")
#: Pixels per user unit of a ``.png`` output, and the limits of its width in pixels.
PNG_SCALE, PNG_MIN, PNG_MAX = 2.0, 64, 8192


def output_format(output: str, allowed: tuple[str, ...] = ("svg", "geojson", "png", "gis")) -> str:
    """What ``-o OUTPUT`` asks for, by its suffix; another suffix is refused (never SVG text in a
    file named ``.png`` or ``.pdf``)."""
    suffix = Path(output).suffix.lower() if output != "-" else ""
    fmt = FORMATS.get(suffix, "svg" if suffix == "" else None)
    if fmt not in allowed:
        names = ", ".join(s for s, f in FORMATS.items() if f in allowed)
        raise ParameterError(f"{output}: svgtile writes {names} (by the file's suffix), not {suffix}")
    if fmt == "png":
        from svgtile.apps.preview import require_renderer

        require_renderer()
    return fmt


def spec_files(specs) -> tuple[Path, ...]:
    """The files that region, map or avoid specs read (``FILE#…`` -> ``FILE``), to protect as inputs.

    A bare id (an element of ``svgtile map``'s own SVG map) names no file.
    """
    return tuple(Path(s.partition("#")[0]) for s in specs if s and ("#" in s or is_gis(s)))


def default_boundary(kind: str, boundary: str | None) -> str:
    """``--boundary`` as given, else ``inside`` for point outputs and ``clip`` for pictures.

    A point layer draws every motif whole (a marker cannot be cut at a unit's edge), so ``clip``
    would leave markers across the edge and over holes; ``inside`` keeps every marker wholly in
    its unit, clear of holes.  ``centroid`` would still let them stick out.
    """
    return boundary if boundary is not None else "inside" if kind in POINT_FORMATS else "clip"


def png_width(width: float) -> int:
    """Pixels of a ``.png`` output for a document ``width`` user units wide."""
    return int(min(PNG_MAX, max(PNG_MIN, round(width * PNG_SCALE))))


#: Below this many motifs in the interior, likeness figures are mostly sampling noise.
FEW_MOTIFS = 200


def warn_if_few(motifs: int, where: str) -> None:
    """Say on stderr that the figures of ``where`` rest on too few motifs to mean much."""
    if motifs < FEW_MOTIFS:
        warn(f"{where}: the figures are measured on only {motifs} motif(s) in the interior (fewer than "
             f"{FEW_MOTIFS}), so they are mostly noise; measure a larger area")


# ----------------------------------------------------------------------------- engine options


def engine_help() -> str:
    """``--engine``'s help: every engine's summary."""
    return "Synthesis algorithm: " + "; ".join(f"{e.name} = {e.summary}" for e in ENGINES.values()) + "."


def engine_options(f=None, *, auto: bool = False):
    """Decorate a command with ``--engine`` and one option per public engine parameter.

    The options have no default of their own (each engine has its defaults, shown in the help);
    :func:`engine_params` passes only those the user gave, so one the chosen engine does not
    have is an error instead of being ignored.  With ``auto``, ``--engine auto`` is offered and is
    the default (:mod:`svgtile.engines.choose`; the command resolves it with :func:`auto_params`).
    """
    if f is None:
        return lambda g: engine_options(g, auto=auto)
    for p in reversed(list(public_params().values())):
        owners = engines_with(p.name)
        default = "off" if p.type is bool else f"{p.default:g}" if isinstance(p.default, float) else p.default
        text = f"{p.help} [{', '.join(owners)}; default: {default}]"
        if p.type is bool:
            f = click.option(p.option, p.name, is_flag=True, default=None, help=text)(f)
        else:
            kind = click.Choice(p.choices) if p.choices else p.type
            f = click.option(p.option, p.name, type=kind, default=None, metavar=p.metavar, help=text)(f)
    if auto:
        return click.option("--engine", type=click.Choice([AUTO, *ENGINES]), default=AUTO, show_default=True,
                            help=engine_help() + f" {AUTO} = chosen from the exemplar's order (rows, lattice, "
                            "period; see svgtile analyze), said on stderr.")(f)  # fmt: skip
    return click.option("--engine", type=click.Choice(list(ENGINES)), default="patch", show_default=True,
                        help=engine_help())(f)  # fmt: skip


def engine_params(ctx: click.Context, engine: str, values: dict) -> EngineParams | dict:
    """The chosen engine's parameters from the options the user gave (see :func:`engine_options`).

    For ``--engine auto`` the options the user gave, by name, for :func:`auto_params` once the
    exemplar is read; each is checked against every engine that has it (types and ranges).
    """
    options = public_params()
    given = {name: values[name] for name in options
             if ctx.get_parameter_source(name) not in (ParameterSource.DEFAULT, None)}  # fmt: skip
    if engine == AUTO:
        for name, value in given.items():
            for owner in engines_with(name):
                make_params(get_engine(owner), {name: value}, spell=_spell)
        return given
    return make_params(get_engine(engine), given, spell=_spell)


def _spell(name: str) -> str:
    return {p.name: p.option for p in public_params().values()}.get(name, "--" + name.replace("_", "-"))


def honoured_by(control: str) -> str:
    """The engines that honour a map control (:class:`svgtile.engines.Controls` field), for help texts."""
    return ", ".join(e.name for e in ENGINES.values() if control in honoured(e)) or "none"


def auto_params(ex, stats, given: dict, controls: frozenset[str] = frozenset(), *,
                affordable: Callable[[str], bool] | None = None) -> tuple[str, EngineParams]:  # fmt: skip
    """Resolve ``--engine auto`` for an exemplar: the engine and parameters :func:`choose` picks
    among those that honour the map ``controls`` given, the user's options on top; says the
    choice on stderr.

    ``affordable(name)`` tells whether an engine's work for this region is within the run's
    limit: auto does not pick an engine the work check would then refuse (growth's rows on a
    region of a million motifs) while another that honours the same controls and options fits;
    it says which it passed over.
    """
    names = steerable(ENGINES, controls, given)
    picked = choose(ex, stats, available=names)
    if affordable is not None and not affordable(picked.engine):
        cheaper = [n for n in names if n in RULE_ENGINES and affordable(n)]  # not a baseline
        if cheaper:
            passed = picked
            picked = choose(ex, stats, available=cheaper)
            click.echo(f"svgtile: auto: engine {passed.engine} ({passed.rule}) would be over the work limit for this "
                       f"region (--force runs it)", err=True)  # fmt: skip
    click.echo(f"svgtile: auto: {picked.describe()}", err=True)
    return picked.engine, make_params(get_engine(picked.engine), with_choice(picked, given), spell=_spell)
