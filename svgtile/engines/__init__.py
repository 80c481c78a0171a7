"""Synthesis engines: each is a module with ``synthesize(exemplar, region, *, rng, **params)``.

* ``patch`` — patch-based synthesis (AlMeraj, Kaplan & Asente 2013), the default;
* ``tile`` — the Tiling strategy: translated copies of the exemplar (a baseline);
* ``random`` — the Random strategy: dart throwing to the exemplar's statistics (a baseline).

Every engine obeys the output contract of :mod:`svgtile.engines.common`.
"""

from __future__ import annotations

from collections.abc import Callable

from . import patch, random, tile

ENGINES: dict[str, Callable] = {"patch": patch.synthesize, "tile": tile.synthesize, "random": random.synthesize}
