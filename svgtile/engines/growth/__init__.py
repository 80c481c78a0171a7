"""The local-growth engine of Ijiri, Měch, Igarashi & Miller 2008 (``--engine growth``).

Read in pipeline order: :mod:`.connectivity` (§4, the exemplar's ring shapes),
:mod:`.matching` (§5.2–5.3, the best-matching reference), :mod:`.grow` (§5.1, §5.4, growth from
seeds), :mod:`.relax` (§5.5, relaxation), :mod:`.engine` (world cells, the tools, the protocol).
"""

from __future__ import annotations

from svgtile.engines.growth.engine import GROWTH, GrowthParams

__all__ = ["GROWTH", "GrowthParams"]
