"""The ``svgtile`` entry point (``[project.scripts]``, ``python -m svgtile``): :func:`main`.

It imports nothing but the standard library until :func:`main` runs, and imports the command
group (:mod:`svgtile.cli.group`) inside it, so a ^C that arrives while the imports run ends the
command as a later one does — one line, ``svgtile: interrupted``, exit code 130 — instead of a
traceback; so does a ^C Python could not raise there (one that lands in an import lock's
callback, which Python reports as "Exception ignored in …" with a traceback, and drops).
"""

from __future__ import annotations

import importlib
import sys

#: What this module shows of :mod:`svgtile.cli.group` (imported on first use).
_GROUP = ("COMMANDS", "LazyCommands", "Terminated", "cli", "_main", "_terminate")


def main(argv: list[str] | None = None) -> int:
    """Run the ``svgtile`` command line (``argv``, else the process's); return its exit code
    (:func:`svgtile.cli.group.main` says what each means)."""
    # a ^C can land where Python cannot raise it — in an import lock's clean-up callback — and is
    # then reported as "Exception ignored in …" with a traceback and lost; while the imports run,
    # such a ^C ends the command as any other does
    lost: list[KeyboardInterrupt] = []
    reported = sys.unraisablehook

    def hold(unraisable) -> None:
        if issubclass(unraisable.exc_type, KeyboardInterrupt):
            lost.append(KeyboardInterrupt())
        else:
            reported(unraisable)

    try:
        sys.unraisablehook = hold  # inside the try: a ^C just after it still puts the old one back
        from svgtile.cli import group
    except KeyboardInterrupt:
        lost.append(KeyboardInterrupt())
    finally:
        sys.unraisablehook = reported
    if lost:
        sys.stderr.write("svgtile: interrupted\n")
        return 130
    return group.main(argv)


def __getattr__(name: str):
    if name not in _GROUP:
        raise AttributeError(f"module 'svgtile.cli.main' has no attribute {name!r}")
    return getattr(importlib.import_module("svgtile.cli.group"), name)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
