"""svgtile — geometric texture synthesis from a small SVG exemplar.

Pipeline: :func:`read_exemplar` (:mod:`svgtile.svg`) → :func:`analyze` (:mod:`svgtile.analysis`) →
:func:`svgtile.engines.synthesize` (one engine protocol) → a :class:`~svgtile.engines.Result` →
:func:`svgtile.svg.writer.result_document` or :mod:`svgtile.gis`; :mod:`svgtile.metrics` scores it.
"""

from __future__ import annotations

from svgtile.analysis.stats import Stats, analyze
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.errors import SvgtileError
from svgtile.svg.reader import read_exemplar

__all__ = ["Arrangement", "Exemplar", "Region", "Stats", "SvgtileError", "analyze", "read_exemplar"]
__version__ = "0.1.0"
