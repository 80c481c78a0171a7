"""Synthesis engines: each is a module with ``synthesize(exemplar, region, *, rng, **params)``.

* ``patch`` — patch-based synthesis (AlMeraj, Kaplan & Asente 2013), the default;
* ``tile`` — the Tiling strategy: translated copies of the exemplar (a baseline);
* ``random`` — the Random strategy: dart throwing to the exemplar's statistics (a baseline).

Every engine obeys the output contract of :mod:`svgtile.engines.base`.
"""

from __future__ import annotations

from collections.abc import Callable

from svgtile.engines import random, tile
from svgtile.engines.patch import engine as patch

ENGINES: dict[str, Callable] = {"patch": patch.synthesize, "tile": tile.synthesize, "random": random.synthesize}
