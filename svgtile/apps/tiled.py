"""One huge texture, its tiles run by Dask and written as they finish (``synth --scheduler``).

The region is cut into world-anchored tiles (:func:`svgtile.runners.tiling.plan`); each is one
unit of work (:mod:`svgtile.runners.schedule`), a band's motifs are spooled as soon as its
tiles are in (:class:`svgtile.apps.mapwrite.BandWriter`), and the file is then written as
:func:`svgtile.svg.writer.result_document` or
:func:`svgtile.gis.geojson.exemplar_placements` would write the whole run — the same bytes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from svgtile.analysis.stats import Stats
from svgtile.apps.mapwrite import BandWriter, write_geojson, write_texture_svg
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.engines import get_engine, make_params
from svgtile.engines.base import EngineParams, Result
from svgtile.runners.schedule import Unit, run
from svgtile.runners.spool import Spool
from svgtile.runners.tiling import Bands, Tile, plan, synthesize_tile


@dataclass(frozen=True, eq=False)
class TiledRun:
    """What :func:`synthesize_to_file` did.

    Attributes
    ----------
    tiles : the tiles run (one, ``whole``, when the engine is not tile-exact)
    motifs : the motifs written
    errors : ``"tile I,J"`` -> one-line message, for the tiles that failed (the others written)
    """

    tiles: list[Tile]
    motifs: int
    errors: dict[str, str] = field(default_factory=dict)


def synthesize_to_file(
    out: str | Path, kind: str, exemplar: Exemplar, stats: Stats, region: Region, engine: str, *, seed: int,
    boundary: str, params: EngineParams | dict | None, tile_size: float | None, where: dict[str, object], refine: int = 0,
    scheduler: str = "local", workers: int = 1, bar: bool = False, protect: tuple = (),
    on_plan: Callable[[list[Tile]], None] | None = None,
) -> TiledRun:  # fmt: skip
    """Synthesize ``region`` tile by tile on Dask and write it to ``out`` (``svg`` or ``geojson``).

    Parameters
    ----------
    out, kind : the output file and its format
    exemplar, stats, region, engine, seed, boundary, params, refine : as for
        :func:`svgtile.engines.synthesize`
    tile_size : the tiles' side, user units (None: one unit, the whole region)
    where : the run's place for the metadata (``size`` or ``region``, ``exemplar``)
    scheduler, workers, bar : where the tiles run (:func:`svgtile.runners.schedule.run`)
    protect : paths the output must not overwrite
    on_plan : told the tiles before they run (the CLI says when a region is run whole)
    """
    p = make_params(engine, params)
    tiles = plan(region, exemplar, engine, tile_size, params=p, refine=refine)
    if on_plan is not None:
        on_plan(tiles)
    errors: dict[str, str] = {}
    count = 0
    folder = None if str(out) == "-" else str(Path(out).resolve().parent)
    with Spool(folder) as spool:
        writer = BandWriter(spool, kind)

        def on_band(b: int, arr: Arrangement) -> None:
            nonlocal count
            count += len(arr)
            if kind == "geojson":
                writer.features(0, b, arr, exemplar)
            else:
                writer.svg(0, b, arr, exemplar.kinds)

        collect = Bands(tiles, on_band)

        def done(n: int, arr: Arrangement | None, error: str | None) -> None:
            if error is not None:
                errors[f"tile {tiles[n].i},{tiles[n].j}"] = error
            collect.add(n, arr)

        units = [Unit(f"svgtile-tile-{t.i},{t.j}", _tile, (exemplar, stats, region, engine, t, seed, boundary, p, refine))
                 for t in tiles]  # fmt: skip
        run(units, done, scheduler=scheduler, workers=min(workers, len(units)), progress=bar)
        if kind == "geojson":
            write_geojson(out, [0], writer, protect=protect)
        else:
            result = Result(Arrangement.empty(), exemplar, stats, region, boundary, get_engine(engine).name, p, seed,
                            refine=refine)
            meta = result.metadata(**where)
            meta["motifs"] = count
            write_texture_svg(out, exemplar, region, writer, boundary=boundary, params=meta, protect=protect)
    return TiledRun(tiles, count, errors)


def _tile(exemplar: Exemplar, stats: Stats, region: Region, engine: str, tile: Tile, seed: int, boundary: str,
          params: EngineParams, refine: int = 0) -> Arrangement:  # fmt: skip
    """One tile's unit of work (module level, so worker processes can unpickle it)."""
    return synthesize_tile(exemplar, region, engine, tile, seed=seed, stats=stats, boundary=boundary, params=params,
                           refine=refine)  # fmt: skip
