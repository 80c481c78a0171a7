"""The ``svgtile`` command group: one module per command, and :func:`main`, which runs one and
turns every failure into one line and an exit code (:mod:`svgtile.cli.main` is the entry point).

The commands import what they share from :mod:`svgtile.cli.common`, never this module, so the
package has no import cycle.  This module imports the standard library, click and
:mod:`svgtile.cli.output` only: a command's own module is imported when it is looked up, and
what it needs when it runs, so ``svgtile score`` can fork its worker before scipy and shapely are
imported.
"""

from __future__ import annotations

import functools
import importlib
import os
import signal
import sys
import threading
import warnings
from collections.abc import Iterator, MutableMapping

import click

from svgtile import __version__
from svgtile.cli.output import Ending, Stderr, command_paths, one_line, showwarning
from svgtile.errors import SvgtileError
from svgtile.files import check_paths

#: Every command, as ``name: "module:attribute"``; a command's module is imported only when the
#: command is looked up (run, or listed by ``--help``), so ``svgtile score`` does not pay for
#: importing ``map``, ``qgis`` and the rest.
COMMANDS = {
    "synth": "svgtile.cli.synth:synth",
    "analyze": "svgtile.cli.analyze:analyze_cmd",
    "compare": "svgtile.cli.compare:compare",
    "import": "svgtile.cli.tiles:import_cmd",
    "inkscape": "svgtile.cli.inkscape:inkscape",
    "map": "svgtile.cli.map:map_cmd",
    "propagate": "svgtile.cli.propagate:propagate_cmd",
    "qgis": "svgtile.cli.qgis:qgis",
    "score": "svgtile.cli.score:score",
    "swatches": "svgtile.cli.tiles:swatches_cmd",
    "symbols": "svgtile.cli.symbols:symbols_cmd",
}


class LazyCommands(MutableMapping):
    """The group's command table: names are known up front, each command is imported on first
    lookup (click's ``Group`` reads its ``commands`` mapping only by name, iteration and ``get``)."""

    def __init__(self, specs: dict[str, str]) -> None:
        self._specs = dict(specs)
        self._loaded: dict[str, click.Command] = {}

    def __getitem__(self, name: str) -> click.Command:
        if name not in self._loaded:
            module, _, attr = self._specs[name].partition(":")
            self._loaded[name] = _guarded(getattr(importlib.import_module(module), attr))
        return self._loaded[name]

    def __setitem__(self, name: str, command: click.Command) -> None:
        self._specs.setdefault(name, "")
        self._loaded[name] = _guarded(command)

    def __delitem__(self, name: str) -> None:
        del self._specs[name]
        self._loaded.pop(name, None)

    def __iter__(self) -> Iterator[str]:
        return iter(self._specs)

    def __len__(self) -> int:
        return len(self._specs)


# click >= 8.2 raises this for a bare ``svgtile``; older versions print the help and exit 0
_NO_ARGS_IS_HELP = getattr(click.exceptions, "NoArgsIsHelpError", ())


@click.group(commands=LazyCommands(COMMANDS), context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="svgtile")
def cli() -> None:
    """Fill any region with small vector motifs so it looks like a small exemplar you drew."""


def _guarded(command: click.Command) -> click.Command:
    """``command`` (and a group's subcommands) checking, before it reads or writes anything, that
    no output is one of its inputs (:func:`svgtile.cli.common.command_paths`): the one place a
    command added later is covered without a line of its own."""
    if isinstance(command, click.Group):
        for sub in command.commands.values():
            _guarded(sub)
        return command
    callback = command.callback

    @functools.wraps(callback)
    def run(*args, **kwargs):
        check_paths(*command_paths(click.get_current_context()))
        return callback(*args, **kwargs)

    command.callback = run
    return command


class Terminated(BaseException):
    """SIGTERM or SIGHUP arrived: unwind like ^C, so temporary files are removed on the way."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _terminate(signum, frame) -> None:
    raise Terminated(signum)


def main(argv: list[str] | None = None) -> int:
    """Entry point: every expected failure is one line on stderr and a non-zero exit.

    Exit codes: 0 success (also for help), 1 bad input or unwritable output, 2 bad command line,
    70 internal error (a bug; ``--debug`` anywhere shows the traceback), 130 interrupted (^C),
    128 + N ended by signal N (143: SIGTERM).  Only 0 means the output is complete; after any
    other code no output file was written, except by ``map`` with failed units (exit 1, the
    message says the others were written).
    """
    Ending.asked = False
    if threading.current_thread() is not threading.main_thread():  # signals are the main thread's
        return _main(argv)
    old = {s: signal.signal(s, _terminate) for s in (signal.SIGTERM, signal.SIGHUP)}
    Ending.will_end = argv is None
    try:
        code = _main(argv)
    finally:
        Ending.will_end = False
        for signum, handler in old.items():
            signal.signal(signum, handler)
    if argv is None:  # the process's command line: a command may have asked to end it now
        Ending.end(code)
    Ending.asked = False  # main([...]) from Python goes on
    return code


def _main(argv: list[str] | None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    args = [a for a in argv if a != "--debug"]
    Stderr.progress_shown = False
    try:
        with warnings.catch_warnings():
            warnings.showwarning = showwarning
            # click's own main would print a blank line on ^C and exit on a broken pipe itself
            with cli.make_context("svgtile", args) as ctx:
                cli.invoke(ctx)
    except SvgtileError as exc:
        Stderr.line(f"svgtile: error: {one_line(exc)}")
        return 1
    except click.exceptions.Exit as exc:  # --help, --version
        return exc.exit_code
    except _NO_ARGS_IS_HELP as exc:  # bare ``svgtile``
        click.echo(exc.ctx.get_help() if exc.ctx else exc.format_message())
        return 0
    except click.UsageError as exc:
        hint = f" (see '{exc.ctx.command_path} --help')" if exc.ctx else ""
        Stderr.line(f"svgtile: error: {one_line(exc.format_message())}{hint}")
        return exc.exit_code
    except click.ClickException as exc:
        Stderr.line(f"svgtile: error: {one_line(exc.format_message())}")
        return exc.exit_code
    except (KeyboardInterrupt, click.exceptions.Abort):
        Stderr.line("svgtile: interrupted")
        return 130
    except Terminated as exc:
        Stderr.line(f"svgtile: stopped by {exc}")
        return 128 + exc.signum
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
        Stderr.line("svgtile: error: out of memory; try a smaller --size")
        return 1
    except _geos_error() as exc:  # input geometry no reader caught (a map's, a region's)
        Stderr.line(f"svgtile: error: geometry too extreme to compute with ({one_line(exc)}); check the "
                    "coordinates and transforms of the inputs")  # fmt: skip
        return 1
    except OSError as exc:  # the system refused something no reader anticipated (ELOOP, EMFILE …)
        where = f"{exc.filename}: " if exc.filename else ""
        Stderr.line(f"svgtile: error: {where}{one_line(exc.strerror or exc)}")
        return 1
    except Exception as exc:  # a bug, not bad input: still one line, traceback on request
        if debug:
            raise
        Stderr.line(f"svgtile: internal error: {type(exc).__name__}: {one_line(exc)} (run with --debug for details)")
        return 70
    return 0


def _geos_error() -> type[BaseException] | tuple:
    """shapely's GEOS error, if shapely was imported (else none can have been raised)."""
    errors = sys.modules.get("shapely.errors")
    return errors.GEOSException if errors is not None else ()
