"""Synthesis engines: each is a module with ``synthesize(exemplar, region, *, rng, **params)``."""

from __future__ import annotations

from collections.abc import Callable

from . import patch

ENGINES: dict[str, Callable] = {"patch": patch.synthesize}
