"""The one number format of everything svgtile writes: at most :data:`~svgtile.core.arrangement.DECIMALS`
decimals, no trailing zeros, no ``-0``."""

from __future__ import annotations

import numpy as np

from svgtile.core.arrangement import DECIMALS

# Below this magnitude np.round(v, 4) has a short repr with at most 4 decimals and no exponent.
_FAST_LIMIT = 1e11
#: From this magnitude on a float64 has no fraction: rounding to 4 decimals leaves it as it is.
_ROUND_LIMIT = 2.0**53


def fmt(v: float) -> str:
    """Fixed number format: four decimals at most, no trailing zeros, no ``-0``.

    >>> fmt(1.0), fmt(-0.00001), fmt(2.50004), fmt(-3.14159)
    ('1', '0', '2.5', '-3.1416')
    """
    return fmt_array(np.array([v]))[0]


def fmt_array(values: np.ndarray) -> list[str]:
    """:func:`fmt` for a whole array at once, (n,) floats to n strings.

    Values are rounded with ``np.round(v, 4)``; the shortest repr of such a float is its decimal
    value with at most four decimals, so only the ``.0`` of whole numbers needs removing.  Huge or
    non-finite values (never written in practice) take the slow path; from :data:`_ROUND_LIMIT` on
    a float has no fraction to round (its spacing is 0.125 or more), and ``np.round``'s scaling by
    10⁴ would overflow near the largest floats (1e308 written as ``inf``).
    """
    v = np.asarray(values, dtype=np.float64).reshape(-1)
    rounded = np.round(np.clip(v, -_ROUND_LIMIT, _ROUND_LIMIT), DECIMALS)
    v = np.where(np.abs(v) < _ROUND_LIMIT, rounded, v) + 0.0  # + 0.0: no -0
    out = [s[:-2] if s[-2:] == ".0" else s for s in map(repr, v.tolist())]
    for i in np.flatnonzero(~(np.abs(v) < _FAST_LIMIT)).tolist():
        s = f"{v[i]:.{DECIMALS}f}".rstrip("0").rstrip(".")
        out[i] = "0" if s in ("-0", "") else s
    return out
