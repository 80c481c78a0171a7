"""The ``svgtile`` command line: one group, one module per command, and :func:`main`.

The commands import what they share from :mod:`svgtile.cli.common`, never this module, so the
package has no import cycle; this module only registers them and turns every failure into one
line and an exit code.
"""

from __future__ import annotations

import os
import sys
import warnings

import click

from svgtile import __version__
from svgtile.cli.analyze import analyze_cmd
from svgtile.cli.common import Stderr, one_line, showwarning
from svgtile.cli.compare import compare
from svgtile.cli.inkscape import inkscape
from svgtile.cli.map import map_cmd
from svgtile.cli.propagate import propagate_cmd
from svgtile.cli.qgis import qgis
from svgtile.cli.score import score
from svgtile.cli.symbols import symbols_cmd
from svgtile.cli.synth import synth
from svgtile.cli.tiles import import_cmd, swatches_cmd
from svgtile.errors import SvgtileError

# click >= 8.2 raises this for a bare ``svgtile``; older versions print the help and exit 0
_NO_ARGS_IS_HELP = getattr(click.exceptions, "NoArgsIsHelpError", ())


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="svgtile")
def cli() -> None:
    """Fill any region with small vector motifs so it looks like a small exemplar you drew."""


for _command in (synth, analyze_cmd, compare, import_cmd, inkscape, map_cmd, propagate_cmd, qgis, score, swatches_cmd,
                 symbols_cmd):
    cli.add_command(_command)


def main(argv: list[str] | None = None) -> int:
    """Entry point: every expected failure is one line on stderr and a non-zero exit.

    Exit codes: 0 success (also for help), 1 bad input or unwritable output, 2 bad command line,
    70 internal error (a bug; ``--debug`` anywhere shows the traceback), 130 interrupted.
    """
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
    except Exception as exc:  # a bug, not bad input: still one line, traceback on request
        if debug:
            raise
        Stderr.line(f"svgtile: internal error: {type(exc).__name__}: {one_line(exc)} (run with --debug for details)")
        return 70
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
