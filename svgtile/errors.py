"""Errors raised at svgtile's boundaries.

Every error a user can cause by bad input is an :class:`SvgtileError`; its string is one line that
names the file (or option) and the problem, so the CLI and the Inkscape extension print it as is.
"""

from __future__ import annotations


class SvgtileError(Exception):
    """Base class: a problem with the user's input, reported as one line."""

    def __init__(self, message: str, *, source: str | None = None) -> None:
        self.source = source
        super().__init__(f"{source}: {message}" if source else message)


class ExemplarError(SvgtileError):
    """The exemplar SVG cannot be read or does not describe an arrangement of motifs."""


class TextureKindError(ExemplarError):
    """A texture's motif kind is not among the exemplar's (made from another exemplar, or from
    this one imported as a pattern tile)."""


class RegionError(SvgtileError):
    """The input or output region is missing, degenerate or unusable."""


class ParameterError(SvgtileError):
    """A synthesis parameter is out of range."""


class OutputError(SvgtileError):
    """The output cannot be written where asked."""
