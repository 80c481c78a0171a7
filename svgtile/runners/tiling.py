"""Tiled synthesis of one region: world-anchored tiles with a halo of the engine's reach.

A region too large for one process is cut along a grid anchored at the world origin: tile
``(i, j)`` owns the half-open cell ``[i·T, (i+1)·T) × [j·T, (j+1)·T)``, ``T`` the tile size in
user units.  Each tile is synthesized on its own, over the region cut to the cell grown by a
*halo*, and keeps only the motifs *anchored* (centred) in its own cell.  Every motif is anchored
in exactly one cell, so the tiles together hold each motif once.

Why the union is the whole run: an engine declares its ``reach`` (:mod:`svgtile.engines.base`),
how far what happens outside a tile can change the motifs inside it; its randomness is
world-anchored (:mod:`svgtile.core.cellrng`), so a motif depends on the seed and on the region
within ``reach`` of it, never on the region's extent.  The halo is that reach plus the size of
a motif, for the boundary mode (:meth:`svgtile.core.region.Region.keep`) looks at the region
under each footprint: within a halo of a cell the cut region *is* the region, and the motifs
anchored in the cell come out exactly as in the whole run.  An engine whose reach is
``math.inf`` (patch, random: their conflict resolution can carry a change arbitrarily far) is
not tile-exact and is run whole, as one tile.

Tiles are grouped in *bands* (rows of tiles, ``j`` fixed): the whole run's reading order
(:func:`svgtile.engines.base.reading_order`: rows, then columns) is the bands in ascending ``j``,
each in reading order, so a writer can put out band after band.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius
from svgtile.core.region import Region
from svgtile.engines import check_motifs, get_engine, make_params, synthesize
from svgtile.engines.base import Engine, EngineParams, reading_order
from svgtile.errors import ParameterError


@dataclass(frozen=True)
class Tile:
    """One world-anchored tile of a region.

    Attributes
    ----------
    i, j : the cell's column and row on the world grid (``j`` is its band)
    cell : ``(x0, y0, x1, y1)``, the half-open cell the tile owns, user units; a whole run's
        single tile owns the whole plane (``±inf``)
    halo : how far around the cell the region is synthesized, user units
    """

    i: int
    j: int
    cell: tuple[float, float, float, float]
    halo: float

    @property
    def whole(self) -> bool:
        """Is this the single tile of a run that is not cut?"""
        return not math.isfinite(self.cell[0])


WHOLE = Tile(0, 0, (-math.inf, -math.inf, math.inf, math.inf), 0.0)

#: Added to every halo, user units: far above the output precision (1e-4), so rounding can never
#: put a motif the boundary mode looks at on the wrong side of a cut.
HALO_SLACK = 1.0


def motif_size(exemplar: Exemplar) -> float:
    """The diameter of the largest motif's bounding disc, user units: how far a boundary mode
    looks around a motif's anchor (:meth:`svgtile.core.region.Region.keep`)."""
    return 2.0 * float(motif_radius(exemplar.motifs, exemplar.prototypes).max())


def halo(engine: Engine | str, exemplar: Exemplar, params: EngineParams | dict | None = None) -> float:
    """The halo a tile of ``engine`` needs, user units: its reach plus a motif's size
    (``math.inf``: the engine is not tile-exact)."""
    engine = get_engine(engine) if isinstance(engine, str) else engine
    reach = float(engine.reach(exemplar, make_params(engine, params)))
    return reach + motif_size(exemplar) + HALO_SLACK if math.isfinite(reach) else math.inf


def is_tiled(exemplar: Exemplar, engine: Engine | str, tile_size: float | None, *,
             params: EngineParams | dict | None = None, refine: int = 0) -> bool:  # fmt: skip
    """Whether :func:`plan` cuts a run into tiles: a ``tile_size`` is given, the run is not
    refined, the exemplar has motifs and the engine is tile-exact (finite :func:`halo`).
    Otherwise the run goes whole, in one worker (or :func:`plan` refuses it)."""
    return (tile_size is not None and not refine and len(exemplar.motifs) > 0
            and math.isfinite(halo(engine, exemplar, params)))  # fmt: skip


def plan(region: Region, exemplar: Exemplar, engine: Engine | str, tile_size: float | None, *,
         params: EngineParams | dict | None = None, refine: int = 0) -> list[Tile]:  # fmt: skip
    """The tiles of ``region`` in world order (bands by ``j``, then ``i``).

    Parameters
    ----------
    region : the region to fill, user units
    exemplar : its exemplar (the motif size)
    engine : the engine, whose ``reach`` gives the halo
    tile_size : the side of a tile, user units; None runs the region whole
    params : the engine's parameters (the reach may depend on them)
    refine : optimisation iterations after the engine (``synthesize(refine=)``); they are not
        tile-exact, so a run with ``refine > 0`` is run whole

    Returns
    -------
    The cells that can hold a motif the whole run keeps (those meeting the region grown by a
    motif's size), or ``[WHOLE]`` when ``tile_size`` is None, the engine's reach is infinite or
    the run is refined.
    """
    if tile_size is not None and not refine:
        if not (tile_size > 0 and math.isfinite(tile_size)):
            raise ParameterError(f"--tile-size must be a positive number, not {tile_size!r}")
        check_motifs(exemplar, get_engine(engine) if isinstance(engine, str) else engine)  # no motif: no halo
    if not is_tiled(exemplar, engine, tile_size, params=params, refine=refine):
        return [WHOLE]
    h = halo(engine, exemplar, params)
    grown = shapely.buffer(region.shape, motif_size(exemplar))
    x0, y0, x1, y1 = grown.bounds
    i = np.arange(math.floor(x0 / tile_size), math.floor(x1 / tile_size) + 1)
    j = np.arange(math.floor(y0 / tile_size), math.floor(y1 / tile_size) + 1)
    ci, cj = (v.ravel() for v in np.meshgrid(i, j))  # row-major: bands, then columns
    boxes = shapely.box(ci * tile_size, cj * tile_size, (ci + 1) * tile_size, (cj + 1) * tile_size)
    meets = shapely.intersects(grown, boxes)
    return [Tile(int(a), int(b), (a * tile_size, b * tile_size, (a + 1) * tile_size, (b + 1) * tile_size), h)
            for a, b in zip(ci[meets].tolist(), cj[meets].tolist(), strict=True)]  # fmt: skip


def tile_region(region: Region, tile: Tile) -> Region | None:
    """``region`` cut to the tile's cell grown by its halo (None: nothing of it there)."""
    if tile.whole:
        return region
    window = shapely.buffer(shapely.box(*tile.cell), tile.halo, join_style="mitre")
    if not shapely.intersects(window, region.shape):
        return None
    shape = shapely.intersection(region.shape, window)
    avoid = None if region.avoid is None else shapely.intersection(region.avoid, window)
    if shapely.area(shape) <= 0:
        return None
    return Region(shape, avoid=avoid)


def anchored(arr: Arrangement, tile: Tile) -> np.ndarray:
    """(n,) bool: the motifs centred in the tile's own (half-open) cell."""
    x0, y0, x1, y1 = tile.cell
    x, y = arr.xy[:, 0], arr.xy[:, 1]
    return (x >= x0) & (x < x1) & (y >= y0) & (y < y1)


def synthesize_tile(
    exemplar: Exemplar, region: Region, engine: Engine | str, tile: Tile, *, seed: int,
    stats: Stats | None = None, boundary: str = "clip", params: EngineParams | dict | None = None, refine: int = 0,
) -> Arrangement:  # fmt: skip
    """The motifs of the whole run of ``region`` that are anchored in ``tile``, in reading order.

    Parameters
    ----------
    exemplar, region, engine, seed, stats, boundary, params, refine : as for
        :func:`svgtile.engines.synthesize`, for the whole region
    tile : one of :func:`plan`'s tiles (:data:`WHOLE` when ``refine > 0``)
    """
    part = tile_region(region, tile)
    if part is None:
        return Arrangement.empty()
    arr = synthesize(exemplar, part, engine, seed=seed, stats=stats, boundary=boundary, params=params,
                     refine=refine).arrangement  # fmt: skip
    return arr if tile.whole else arr.take(np.flatnonzero(anchored(arr, tile)))


def bands(tiles: list[Tile]) -> list[list[int]]:
    """Indices of ``tiles`` grouped by band, bands in world order."""
    out: dict[int, list[int]] = {}
    for n, t in enumerate(tiles):
        out.setdefault(t.j, []).append(n)
    return [out[j] for j in sorted(out)]


def merge_band(parts: list[Arrangement]) -> Arrangement:
    """One band's tiles as one arrangement in reading order (the whole run's, for that band)."""
    return reading_order(Arrangement.concat(parts)) if parts else Arrangement.empty()


def synthesize_tiled(
    exemplar: Exemplar, region: Region, engine: Engine | str, tile_size: float | None, *, seed: int,
    stats: Stats | None = None, boundary: str = "clip", params: EngineParams | dict | None = None,
) -> Arrangement:  # fmt: skip
    """:func:`synthesize_tile` over every tile, in this process: the whole run's arrangement.

    The reference for the distributed runner and its tests; the map and ``synth`` commands send
    the tiles to :mod:`svgtile.runners.schedule` instead.
    """
    tiles = plan(region, exemplar, engine, tile_size, params=params)
    parts = [synthesize_tile(exemplar, region, engine, t, seed=seed, stats=stats, boundary=boundary, params=params)
             for t in tiles]  # fmt: skip
    return Arrangement.concat([merge_band([parts[n] for n in band]) for band in bands(tiles)])


class Bands:
    """Tiles' results gathered into bands: a band is handed on, merged in reading order
    (:func:`merge_band`), the moment its last tile is in, and its tiles are then let go.

    Parameters
    ----------
    tiles : the tiles of one region (:func:`plan`)
    on_band : called as ``on_band(band, arrangement)``, ``band`` counting bands in world order,
        for every band at least one of whose tiles succeeded
    """

    def __init__(self, tiles: list[Tile], on_band) -> None:
        self.groups = bands(tiles)
        self.band_of = {n: b for b, group in enumerate(self.groups) for n in group}
        self.left = [len(g) for g in self.groups]
        self.parts: dict[int, Arrangement] = {}
        self.on_band = on_band

    def add(self, n: int, arr: Arrangement | None) -> None:
        """Tile ``n``'s motifs (None: it failed, and its band goes on without it)."""
        b = self.band_of[n]
        if arr is not None:
            self.parts[n] = arr
        self.left[b] -= 1
        if self.left[b] == 0:
            ok = [self.parts.pop(m) for m in self.groups[b] if m in self.parts]
            if ok:  # a band all of whose tiles failed is not handed on
                self.on_band(b, merge_band(ok))

    @property
    def done(self) -> bool:
        return not any(self.left)
