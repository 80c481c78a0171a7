"""Counter-based randomness anchored in world coordinates.

The patch engine must give the same texture at a given place whatever the extent of the output
region (brief of issue 2: edit-stable and tiled runs).  A sequential ``np.random.Generator`` cannot
do that: how many numbers were drawn before a grid cell depends on how many cells precede it.  So
the engine draws a single 64-bit *key* from the caller's ``rng`` and derives every random choice as
a hash of ``(key, stream, integer coordinates…)`` — e.g. the rotation of the exemplar copy in grid
cell ``(a, b)`` — with the SplitMix64 finaliser (Steele, Lea & Flood, 2014), vectorised in numpy.
"""

from __future__ import annotations

import numpy as np

_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)


def _mix(x: np.ndarray) -> np.ndarray:
    """SplitMix64 finaliser on a uint64 array (wrapping arithmetic is intended)."""
    with np.errstate(over="ignore"):
        x = (x ^ (x >> np.uint64(30))) * _M1
        x = (x ^ (x >> np.uint64(27))) * _M2
        return x ^ (x >> np.uint64(31))


def hash64(key: int, stream: int, *coords: np.ndarray | int) -> np.ndarray:
    """Hash integer coordinates to well-mixed uint64 values.

    Parameters
    ----------
    key : int
        Root key, drawn once per run from the caller's generator.
    stream : int
        Separates independent uses (rotation, priority, …) of the same coordinates.
    *coords : int arrays, broadcastable to one shape
        Integer coordinates (may be negative).

    Returns
    -------
    (…) uint64 array of the broadcast shape.
    """
    arrays = np.broadcast_arrays(*[np.asarray(c, dtype=np.int64) for c in coords])
    shape = arrays[0].shape if arrays else ()
    with np.errstate(over="ignore"):
        h = _mix(np.full(shape, np.uint64(key & 0xFFFFFFFFFFFFFFFF)) + _GOLDEN * np.uint64(stream + 1))
        for c in arrays:
            h = _mix(h ^ (c.astype(np.uint64) + _GOLDEN))
    return h


def uniform(key: int, stream: int, *coords: np.ndarray | int) -> np.ndarray:
    """Uniform floats in [0, 1) from :func:`hash64`, one per broadcast coordinate tuple."""
    return (hash64(key, stream, *coords) >> np.uint64(11)).astype(np.float64) * 2.0**-53


def root_key(rng: np.random.Generator) -> int:
    """Draw the run's root key from the caller's generator (the only draw an engine makes)."""
    return int(rng.integers(0, 2**63, dtype=np.int64))
