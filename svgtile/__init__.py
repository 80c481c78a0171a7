"""svgtile — geometric texture synthesis from a small SVG exemplar.

Pipeline: :func:`read_exemplar` (:mod:`svgtile.svg`) → :func:`analyze` (:mod:`svgtile.analysis`) →
:func:`svgtile.engines.synthesize` (one engine protocol) → a :class:`~svgtile.engines.Result` →
:func:`svgtile.svg.writer.result_document` or :mod:`svgtile.gis`; :mod:`svgtile.metrics` scores it.

The names below are imported on first use (PEP 562): ``import svgtile`` alone costs nothing, so
the command line can start work (``svgtile score`` forks its worker and reads the texture) before
scipy and shapely are imported; ``from svgtile import analyze`` works as it always did.
"""

from __future__ import annotations

import importlib
import importlib.util

TYPE_CHECKING = False  # typing's own constant, without importing typing (≈ 2 ms at start-up)
if TYPE_CHECKING:
    from svgtile.analysis.stats import Stats, analyze
    from svgtile.core.arrangement import Arrangement
    from svgtile.core.exemplar import Exemplar
    from svgtile.core.region import Region
    from svgtile.errors import SvgtileError
    from svgtile.svg.reader import read_exemplar

#: Each public name and the module it lives in.
_LAZY = {
    "Arrangement": "svgtile.core.arrangement",
    "Exemplar": "svgtile.core.exemplar",
    "Region": "svgtile.core.region",
    "Stats": "svgtile.analysis.stats",
    "SvgtileError": "svgtile.errors",
    "analyze": "svgtile.analysis.stats",
    "read_exemplar": "svgtile.svg.reader",
}

__all__ = ["Arrangement", "Exemplar", "Region", "Stats", "SvgtileError", "analyze", "read_exemplar"]
__version__ = "0.1.0"


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        # a subpackage or module not imported yet (``svgtile.errors.SvgtileError`` after a plain
        # ``import svgtile``: the eager package imported them all as a side effect, and code used it)
        if not name.startswith("_") and importlib.util.find_spec(f"{__name__}.{name}") is not None:
            return importlib.import_module(f"{__name__}.{name}")
        raise AttributeError(f"module 'svgtile' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY})
