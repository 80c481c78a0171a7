"""svgtile — geometric texture synthesis from a small SVG exemplar.

Pipeline: :func:`read_exemplar` → :func:`analyze` → an engine's ``synthesize`` → :func:`write_svg`.
"""

from __future__ import annotations

from .analysis import Stats, analyze
from .arrangement import Arrangement
from .errors import SvgtileError
from .exemplar import Exemplar, read_exemplar
from .region import Region

__all__ = ["Arrangement", "Exemplar", "Region", "Stats", "SvgtileError", "analyze", "read_exemplar"]
__version__ = "0.1.0"
