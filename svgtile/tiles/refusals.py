"""Why a pattern tile is refused (:mod:`svgtile.tiles.importer`, :mod:`svgtile.tiles.cellular`)."""

from __future__ import annotations

from svgtile.errors import ExemplarError


class TileRefused(ExemplarError):
    """The tile is not an arrangement of discrete motifs (hatching, continuous lines, a fill)."""


class LeftOut(TileRefused):
    """Read as courses and cells, the tile would leave out ``share`` (> ``bound``) of its stroke
    length in ``pieces`` pieces (:data:`svgtile.tiles.cellular.LEFT_OUT`): refused."""

    def __init__(self, pieces: int, share: float, bound: float, *, source: str | None = None) -> None:
        super().__init__(f"read as courses and cells it would leave out {pieces} piece(s), {share:.0%} of its stroke "
                         f"length (more than {bound:.0%}): not a bedded or brick pattern svgtile can draw",
                         source=source)  # fmt: skip
