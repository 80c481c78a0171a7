"""The arrangement: where each motif is, as a struct of arrays.

A motif instance maps its kind's local frame (origin at the footprint centroid, see
:class:`svgtile.core.exemplar.Kind`) to the world by ``p_world = xy + scale · R(angle) · p_local``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Decimals of positions, angles, scales and every number written: engines round to it when they
#: create motifs, so every check runs on exactly what is written.
DECIMALS = 4


@dataclass(frozen=True, eq=False)
class Arrangement:
    """Motif instances as parallel arrays (no object per motif).

    Attributes
    ----------
    kind : (n,) int array
        Index into the exemplar's ``kinds``.
    xy : (n, 2) float array, user units
        World position of each motif's centroid.
    angle : (n,) float array, degrees
        Rotation of each motif about its centroid, counter-clockwise in a y-up frame (i.e. the
        SVG ``rotate()`` sense in SVG's y-down frame).
    scale : (n,) float array
        Uniform scale of each motif.
    """

    kind: np.ndarray
    xy: np.ndarray
    angle: np.ndarray
    scale: np.ndarray

    def __post_init__(self) -> None:
        n = len(self.kind)
        object.__setattr__(self, "kind", np.asarray(self.kind, dtype=np.int64).reshape(n))
        object.__setattr__(self, "xy", np.asarray(self.xy, dtype=np.float64).reshape(n, 2))
        object.__setattr__(self, "angle", np.asarray(self.angle, dtype=np.float64).reshape(n))
        object.__setattr__(self, "scale", np.asarray(self.scale, dtype=np.float64).reshape(n))

    def __len__(self) -> int:
        return len(self.kind)

    @classmethod
    def empty(cls) -> Arrangement:
        return cls(np.zeros(0, np.int64), np.zeros((0, 2)), np.zeros(0), np.zeros(0))

    def take(self, index: np.ndarray) -> Arrangement:
        """A new arrangement of the selected motifs (boolean mask or integer index)."""
        return Arrangement(self.kind[index], self.xy[index], self.angle[index], self.scale[index])

    def with_angle(self, angle: np.ndarray) -> Arrangement:
        return Arrangement(self.kind, self.xy, angle, self.scale)

    def quantized(self, decimals: int = DECIMALS) -> Arrangement:
        """Rounded to the output's precision, so what is checked is exactly what is written."""
        return Arrangement(
            self.kind, np.round(self.xy, decimals), np.round(self.angle, decimals), np.round(self.scale, decimals)
        )

    @staticmethod
    def concat(parts: list[Arrangement]) -> Arrangement:
        parts = [p for p in parts if len(p)]
        if not parts:
            return Arrangement.empty()
        return Arrangement(
            np.concatenate([p.kind for p in parts]),
            np.concatenate([p.xy for p in parts]),
            np.concatenate([p.angle for p in parts]),
            np.concatenate([p.scale for p in parts]),
        )


def periodic_block(arr: Arrangement, period: tuple[float, float], rings: tuple[int, int] = (1, 1)) -> Arrangement:
    """The tile's motifs on the block of tiles around it, the tile's own first: ``rings`` (a, b)
    tiles on either side along x and y, (2a + 1)(2b + 1)·n motifs (the default: the 3 × 3 block)."""
    a, b = rings
    shifts = np.array([(i, j) for j in range(-b, b + 1) for i in range(-a, a + 1) if (i, j) != (0, 0)],
                      dtype=np.float64).reshape(-1, 2)  # fmt: skip
    shifts = np.vstack([[0.0, 0.0], shifts]) * np.asarray(period, dtype=np.float64)
    t = len(shifts)
    return Arrangement(
        np.tile(arr.kind, t), (arr.xy[None, :, :] + shifts[:, None, :]).reshape(-1, 2),
        np.tile(arr.angle, t), np.tile(arr.scale, t),
    )  # fmt: skip
