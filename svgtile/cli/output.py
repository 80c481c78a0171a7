"""What every command shares that must not wait for the heavy imports: one-line messages on
stderr, the early end of the process (:class:`Ending`), and the paths a command reads and writes
(:func:`command_paths`).  Standard library and click only, so that :mod:`svgtile.cli.group` can
run a command (``svgtile score`` forks its worker and reads the texture) before scipy, shapely and
the analysis stage are imported."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import click


class Stderr:
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


class Ending:
    """Whether the process may end as soon as the command's output is out (:meth:`ask`).

    Tearing the interpreter down after a command that held a large texture in memory — freeing
    every object one by one, modules, the worker's pool — took ``svgtile score`` 0.2–0.45 s on a
    177,723-motif texture (benchmarks/README.md, "`svgtile score`: the read split across the two
    processes, and no teardown"), time in which nothing is left to do: its figures are printed
    and it wrote no file.
    A command asks with :meth:`ask` once all its output is written; :func:`svgtile.cli.main.main`,
    run as the process's command line (not ``main([...])`` from Python, which goes on), then
    flushes stdout and stderr and ends the process with the command's exit code (:meth:`end`).
    """

    asked = False
    #: Whether a command that asks will end the process (:func:`svgtile.cli.main.main` run as the
    #: process's command line, set by it): then it may leave what only the end undoes (``svgtile
    #: score`` leaves the cyclic collector paused: resuming ran one ≈ 0.02 s collection, score11e).
    will_end = False

    @classmethod
    def ask(cls) -> None:
        cls.asked = True

    @classmethod
    def end(cls, code: int) -> None:
        """End the process now with ``code`` if a command asked; return if none did, or if the
        output cannot be flushed (a closed pipe: the interpreter's exit reports it, as before)."""
        asked, cls.asked = cls.asked, False
        if not asked:
            return
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        except (OSError, ValueError):
            return
        os._exit(code)


def warn(message: str) -> None:
    Stderr.line(f"svgtile: warning: {message}")


def showwarning(message, category, filename, lineno, file=None, line=None) -> None:
    """Python warnings (numpy, shapely …) as one svgtile line instead of two lines of source."""
    warn(f"{message} ({category.__name__})")


#: Parameters that name what a command writes; every other parameter naming an existing file
#: (``MAP.svg#ID`` specs included) is taken for an input.
OUTPUT_PARAMS = ("output",)


def command_paths(ctx: click.Context) -> tuple[list[tuple[str, str]], list[str]]:
    """(inputs, outputs) of the command ``ctx`` runs, from its parameters.

    An output is a parameter of :data:`OUTPUT_PARAMS`; an input is any other parameter value
    (or item of a repeated option) naming an existing file, after a ``#ID`` suffix is cut, paired
    with how the message names it (``the exemplar``, ``an input file (--region map.svg#qal)``).
    Folders are left to their command, which knows which of their files it reads or writes.
    """
    options = {p.name: p for p in ctx.command.params}
    inputs, outputs = [], []
    for name, value in ctx.params.items():
        values = value if isinstance(value, (tuple, list)) else (value,)
        for v in values:
            if not isinstance(v, str) or not v or v == "-":
                continue
            if name in OUTPUT_PARAMS:
                outputs.append(v)
                continue
            for spec in _named_specs(v):
                path = spec.partition("#")[0] if "#" in spec and not Path(spec).exists() else spec
                try:
                    if not Path(path).is_file():
                        continue
                except (OSError, ValueError):  # a symlink loop, a NUL byte: its reader will say
                    continue
                param = options.get(name)
                if isinstance(param, click.Argument):
                    what = f"the {name.split('_')[0]}" if len(values) == 1 else f"the input {v}"
                else:
                    what = f"an input file ({param.opts[-1] if param else name} {v})"
                inputs.append((path, what))
    return inputs, outputs


def _named_specs(value: str) -> list[str]:
    """The file specs in an option value: the value itself, or those of ``NAME=SPEC[,NAME=SPEC…]``
    (``--label edge=map.svg#river``) when it names no file as a whole."""
    try:
        if "=" not in value or Path(value).exists():
            return [value]
    except (OSError, ValueError):
        return [value]
    return [value, *(item.partition("=")[2].strip() for item in value.split(",") if "=" in item)]


def one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split())
