"""Feature-based cellular textures (Legakis, Dorsey & Gortler 2001), ``--engine cellular``.

Read in pipeline order: :mod:`.mesh` (the base mesh, §3.1), :mod:`.frame` (parameterisation,
§3.2), :mod:`.tree` (the tree of pattern generators, §4.1), :mod:`.generators` (the generators
and their tools, §5.1–5.4), :mod:`.engine` (ordering and occupancy, §3.3 and §4.2).
"""

from __future__ import annotations

from .engine import CELLULAR, CellularEngine, CellularParams

__all__ = ["CELLULAR", "CellularEngine", "CellularParams"]
