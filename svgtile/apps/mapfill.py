"""Filling a whole map: every classed unit with its class's texture, in parallel (issue 5 item 3).

A *styles file* (TOML) maps classes to exemplars and parameters::

    seed = 7                      # defaults for every class (any key of a class table)
    boundary = "clip"
    avoid = ["labels", "faults"]  # ids in the map, or MAP.svg#ID / FILE.geojson specs
    avoid_margin = 2              # growth of avoid zones, map units
    class_attribute = "data-unit" # SVG maps: the attribute naming a unit's class
    class_property = "unit"       # GeoJSON maps: the property naming a feature's class

    [classes.Qal]
    exemplar = "exemplars/gravel.svg"   # relative to the styles file
    engine = "patch"                    # patch, tile or random
    grid = "hex"
    overlap = 0.05
    max_rotation = 30
    junction = 0.6
    vary_orientation = false
    boundary = "inside"
    unit = 1.0                          # map units per exemplar user unit
    refine = 5                          # optimisation iterations after the engine (any engine)

Each region is synthesized on its own (:func:`fill_region`), or cut into world-anchored tiles
(:mod:`svgtile.runners.tiling`) when a tile size is given and its engine is tile-exact; regions
and tiles run on Dask (:mod:`svgtile.runners.schedule`); a region or tile that fails is reported
and the others are kept.  All regions of a run share one seed, and the engines
anchor randomness in world coordinates, so two touching units of one class continue each other's
texture, and editing one unit leaves the others byte-identical.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

import shapely

from svgtile.apps.load import check_motif_count, load_exemplar
from svgtile.apps.mapcells import fill_cells, implied_engine, is_cellular, map_labels, styles_labels
from svgtile.apps.mapread import (
    AVOID_MARGIN,
    MAX_AVOID_MARGIN,
    MapRegion,
    classed_regions,
    is_gis,
    read_avoid_shape,
    split_spec,
)
from svgtile.core.arrangement import Arrangement
from svgtile.core.cells import Cellwork
from svgtile.core.region import BOUNDARY_MODES, Region
from svgtile.engines import ENGINES, engines_with, make_params, public_params
from svgtile.errors import ParameterError, RegionError, SvgtileError
from svgtile.files import read_input
from svgtile.gis import geojson, layers
from svgtile.runners.schedule import Unit, run
from svgtile.runners.tiling import WHOLE, Bands, Tile, plan, synthesize_tile, tile_region
from svgtile.svg.mapdoc import SvgShapes

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

#: Keys of a class table passed to the engine: every engine's public parameters, and the boundary.
PARAM_KEYS = tuple(public_params())
#: A styles file is a few lines per class; a larger one is refused before it is parsed.
MAX_STYLES_BYTES = 2**20
ENGINE_KEYS = (*PARAM_KEYS, "boundary")
#: Every key a class table (or the defaults) may have.
CLASS_KEYS = (*ENGINE_KEYS, "exemplar", "engine", "seed", "unit", "refine")
#: Keys only the top level may have.
RUN_KEYS = ("avoid", "avoid_margin", "class_attribute", "class_property", "classes")

Progress = Callable[[int, int, str, "str | None"], None]
#: ``sink(index, region, band, motifs)``: one complete band of a region, map units, in any order.
Sink = Callable[[int, MapRegion, int, Arrangement], None]
#: ``cell_sink(index, region, cells)``: a cellular region's cells and lines, the exemplar's user
#: units (its class's ``unit`` makes them map units), before its motifs' band.
CellSink = Callable[[int, MapRegion, Cellwork], None]


@dataclass(frozen=True)
class Style:
    """How one class is filled.

    Attributes
    ----------
    cls : the class name
    exemplar : path of the exemplar SVG
    engine : name in :data:`svgtile.engines.ENGINES`
    params : the engine's parameters the styles give (checked; the engine's own defaults fill
        the rest); a top-level default is kept only for classes whose engine has it
    boundary : how motifs meet the unit's edges and holes
    seed : int or None (the run's seed)
    unit : map units per exemplar user unit
    refine : iterations of optimisation run on the engine's output (``refine = N``, any engine);
        None when the styles do not say (``svgtile map --refine`` then applies, else 0)
    """

    cls: str
    exemplar: Path
    engine: str = "patch"
    params: dict = field(default_factory=dict)
    seed: int | None = None
    unit: float = 1.0
    boundary: str = "clip"
    refine: int | None = None


@dataclass(frozen=True)
class Styles:
    """A parsed styles file: per-class styles and the run's options."""

    classes: dict[str, Style]
    avoid: tuple[str, ...] = ()
    avoid_margin: float = AVOID_MARGIN
    class_attribute: str | None = None
    class_property: str = "class"
    source: str = "<styles>"


def read_styles(path: str | Path, *, boundary: str = "clip") -> Styles:
    """Parse a styles file (see the module docstring); errors name the file and the key.

    ``boundary`` is the boundary mode of the classes that give none (``inside`` for point outputs).
    """
    source = str(path)
    raw = read_input(path, error=ParameterError, limit=MAX_STYLES_BYTES)
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except RecursionError:
        raise ParameterError("tables or arrays are nested too deeply", source=source) from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ParameterError(f"not a valid TOML file ({' '.join(str(exc).split())})", source=source) from None
    return parse_styles(data, source=source, folder=Path(path).parent, boundary=boundary)


def parse_styles(data: dict, *, source: str = "<styles>", folder: Path = Path(), boundary: str = "clip") -> Styles:
    """:func:`read_styles` on already-parsed TOML data."""
    unknown = sorted(set(data) - set(CLASS_KEYS) - set(RUN_KEYS))
    if unknown:
        raise ParameterError(f"unknown key {unknown[0]!r} (expected [classes.NAME] tables and {', '.join(CLASS_KEYS + RUN_KEYS[:-1])})", source=source)
    tables = data.get("classes")
    if not isinstance(tables, dict) or not tables:
        raise ParameterError("no [classes.NAME] table: nothing maps a class to an exemplar", source=source)
    defaults = {k: data[k] for k in CLASS_KEYS if k in data}
    classes, used = {}, set()
    for name, table in tables.items():
        if not isinstance(table, dict):
            raise ParameterError(f"classes.{name} must be a table", source=source)
        bad = sorted(set(table) - set(CLASS_KEYS))
        if bad:
            raise ParameterError(f"classes.{name}: unknown key {bad[0]!r} (expected {', '.join(CLASS_KEYS)})", source=source)
        engine = table.get("engine", defaults.get("engine"))
        if engine is None and isinstance(table.get("exemplar", defaults.get("exemplar")), str):
            # no engine named: a cellular exemplar (svgtile import of a bedded tile) draws cells
            engine = implied_engine(folder / table.get("exemplar", defaults.get("exemplar")))
            table = {**table, "engine": engine}
        own = ENGINES[engine].Params.public_names() if isinstance(engine, str) and engine in ENGINES else set()
        used |= own
        # a top-level engine parameter is a default for the classes whose engine has it
        merged = {"boundary": boundary, **{k: v for k, v in defaults.items() if k not in PARAM_KEYS or k in own}, **table}
        classes[str(name)] = _style(str(name), merged, source, folder)
    unused = sorted(k for k in defaults if k in PARAM_KEYS and k not in used)
    if unused:
        raise ParameterError(f"{unused[0]} at the top level is a parameter of no class's engine "
                             f"(it is one of {', '.join(engines_with(unused[0]))})", source=source)  # fmt: skip
    avoid = data.get("avoid", [])
    if isinstance(avoid, str):
        avoid = [avoid]
    if not isinstance(avoid, list) or not all(isinstance(a, str) for a in avoid):
        raise ParameterError("avoid must be a list of ids or MAP.svg#ID specs", source=source)
    # "#labels" and "labels" are ids in the map; "other.svg#ID" and "x.geojson" are files
    avoid = [a[1:] if a.startswith("#") else str(folder / a) if "#" in a or is_gis(a) else a for a in avoid]
    margin = data.get("avoid_margin", AVOID_MARGIN)
    if not isinstance(margin, (int, float)) or isinstance(margin, bool) or not 0 <= margin <= MAX_AVOID_MARGIN:
        raise ParameterError(f"avoid_margin must be a number from 0 to {MAX_AVOID_MARGIN:g}, not {margin!r}", source=source)
    attr, prop = data.get("class_attribute"), data.get("class_property", "class")
    for key, value in (("class_attribute", attr), ("class_property", prop)):
        if value is not None and not isinstance(value, str):
            raise ParameterError(f"{key} must be a string", source=source)
    return Styles(classes, tuple(avoid), float(margin), attr, prop, source)


def _style(name: str, t: dict, source: str, folder: Path) -> Style:
    where = f"classes.{name}"
    if "exemplar" not in t or not isinstance(t["exemplar"], str):
        raise ParameterError(f"{where}: no exemplar = \"FILE.svg\"", source=source)
    engine = t.get("engine", "patch")
    if not isinstance(engine, str) or engine not in ENGINES:
        raise ParameterError(f"{where}: engine must be one of {', '.join(sorted(ENGINES))}, not {engine!r}", source=source)
    params = {k: t[k] for k in PARAM_KEYS if k in t}
    if isinstance(params.get("label"), str) and engine in ENGINES and is_cellular(engine):
        params["label"] = styles_labels(params["label"], folder, where, source)
    if isinstance(params.get("tree"), str) and params["tree"]:  # a description beside the styles file
        params["tree"] = str(folder / params["tree"])
    boundary = t.get("boundary", "clip")
    if not isinstance(boundary, str):
        raise ParameterError(f"{where}: boundary has the wrong type ({boundary!r}; it takes a text)", source=source)
    if boundary not in BOUNDARY_MODES:
        raise ParameterError(f"{where}: --boundary must be one of {', '.join(BOUNDARY_MODES)}, not {boundary!r}", source=source)
    try:
        make_params(engine, params)
    except ParameterError as exc:
        raise ParameterError(f"{where}: {' '.join(str(exc).split())}", source=source) from None
    seed = t.get("seed")
    if seed is not None and (not isinstance(seed, int) or isinstance(seed, bool) or seed < 0):
        raise ParameterError(f"{where}: seed must be an integer >= 0", source=source)
    unit = t.get("unit", 1.0)
    if not isinstance(unit, (int, float)) or isinstance(unit, bool) or not (unit > 0 and math.isfinite(unit)):
        raise ParameterError(f"{where}: unit must be a positive number", source=source)
    refine = t.get("refine")
    if refine is not None and (not isinstance(refine, int) or isinstance(refine, bool) or refine < 0):
        raise ParameterError(f"{where}: refine must be an integer >= 0", source=source)
    return Style(name, folder / t["exemplar"], engine, params, seed, float(unit), boundary, refine)


# ----------------------------------------------------------------------------- one region


def fill_region(
    shape: shapely.Geometry, avoid: shapely.Geometry | None, style: Style, seed: int, max_motifs: float = math.inf,
    tile: Tile = WHOLE,
) -> Arrangement:  # fmt: skip
    """Synthesize one region (or one tile of it) with its style; motifs in map units.

    Parameters
    ----------
    shape : the region, map units
    avoid : the avoid zones near it, map units, or None
    style : its class's style
    seed : the run's seed (the style's own wins)
    max_motifs : refuse a region (a tile) whose estimated motif count is larger
    tile : the tile to fill, in the exemplar's units (:func:`plan_region`); the whole region by
        default

    A cellular class's cells are left out (:func:`fill_working` gives them).
    """
    arr = fill_working(shape, avoid, style, seed, max_motifs, tile)
    return to_map_units(arr[0] if isinstance(arr, tuple) else arr, style)


def fill_working(
    shape: shapely.Geometry, avoid: shapely.Geometry | None, style: Style, seed: int, max_motifs: float = math.inf,
    tile: Tile = WHOLE,
) -> Arrangement | tuple[Arrangement, Cellwork]:  # fmt: skip
    """:func:`fill_region` in the exemplar's units (the frame tiles are merged in); a cellular
    class's region (always whole: :mod:`svgtile.apps.mapcells`) gives ``(motifs, cells)``."""
    ex, stats = load_exemplar(str(style.exemplar))
    region = working_region(shape, avoid, style)
    part = tile_region(region, tile)
    if part is None:
        return Arrangement.empty()
    where = "the region" if tile.whole else f"tile {tile.i},{tile.j} of the region"
    check_motif_count(ex, stats, part, where, limit=max_motifs,
                      hint=f"raise unit of class {style.cls!r} or fill a smaller region")  # fmt: skip
    seed = style.seed if style.seed is not None else seed
    if is_cellular(style.engine):
        return fill_cells(ex, stats, part, style.engine, seed=seed, boundary=style.boundary, params=style.params,
                          refine=style.refine or 0)  # fmt: skip
    return synthesize_tile(ex, region, style.engine, tile, seed=seed, stats=stats, boundary=style.boundary,
                           params=style.params, refine=style.refine or 0)  # fmt: skip


def working_region(shape: shapely.Geometry, avoid: shapely.Geometry | None, style: Style) -> Region:
    """The region in the exemplar's units (map units divided by the style's ``unit``)."""
    return Region.from_geometry(geojson.to_working(shape, style.unit),
                                avoid=None if avoid is None else geojson.to_working(avoid, style.unit))  # fmt: skip


def to_map_units(arr: Arrangement, style: Style) -> Arrangement:
    """Motifs from the exemplar's units to map units."""
    unit = style.unit
    return arr if unit == 1.0 else Arrangement(arr.kind, arr.xy * unit, arr.angle, arr.scale * unit)


def plan_region(shape: shapely.Geometry, avoid: shapely.Geometry | None, style: Style,
                tile_size: float | None) -> list[Tile]:  # fmt: skip
    """The tiles of one region for a tile size in map units (``[WHOLE]`` for None, or when the
    class's engine is not tile-exact)."""
    if tile_size is None:
        return [WHOLE]
    ex, _ = load_exemplar(str(style.exemplar))
    return plan(working_region(shape, avoid, style), ex, style.engine, tile_size / style.unit, params=style.params,
                refine=style.refine or 0)


# ----------------------------------------------------------------------------- the whole map


@dataclass(frozen=True, eq=False)
class MapFill:
    """The outcome of :func:`fill_map`.

    Attributes
    ----------
    regions : every region found, in document order
    results : (len(regions),) motifs of each region, map units, or None where it failed
    errors : ident -> one-line message, for the regions that failed
    doc : the parsed SVG map (None for GeoJSON input)
    warnings : non-fatal problems (classes of the styles file the map does not use …)
    styles : the styles used
    filled : (len(regions),) bool, the regions written (all their motifs or, where a tile
        failed, the others); with a ``sink`` the motifs went there and ``results`` holds None
    cells : (len(regions),) the cells and lines of each cellular region
        (:class:`~svgtile.core.cells.Cellwork`, the exemplar's user units: times its class's
        ``unit`` in map units), None elsewhere, or where they went to a ``cell_sink``
    """

    regions: list[MapRegion]
    results: list[Arrangement | None]
    errors: dict[str, str]
    doc: SvgShapes | None
    warnings: list[str]
    styles: Styles
    filled: list[bool] = field(default_factory=list)
    cells: list[Cellwork | None] = field(default_factory=list)


def read_map(path: str | Path, styles: Styles) -> tuple[list[MapRegion], SvgShapes | None]:
    """The classed regions of a map SVG or GeoJSON file whose class the styles know."""
    classes = set(styles.classes)
    doc = None
    if is_gis(path):
        feats, _ = layers.read_regions(path, class_property=styles.class_property)
        regions = [MapRegion(f.ident, f.cls, f.shape) for f in feats if f.cls in classes]
        if not regions:
            raise RegionError(f"no feature has a property {styles.class_property!r} naming a class of "
                              f"{styles.source}", source=str(path))  # fmt: skip
    else:
        doc = SvgShapes.read(path, comments=True)
        regions = classed_regions(doc, classes, styles.class_attribute)
        if not regions:
            how = f"attribute {styles.class_attribute!r}, " if styles.class_attribute else ""
            raise RegionError(f"no element whose class ({how}class or inkscape:label) is one of {', '.join(sorted(classes))}", source=str(path))
    seen: dict[str, int] = {}
    for n, r in enumerate(regions):  # ids name results and output groups: make them unique
        seen[r.ident] = seen.get(r.ident, 0) + 1
        if seen[r.ident] > 1:
            regions[n] = MapRegion(f"{r.ident}~{seen[r.ident]}", r.cls, r.shape, r.matrix, r.element)
    return regions, doc


def avoid_zone(path: str | Path, doc: SvgShapes | None, specs: tuple[str, ...], margin: float) -> shapely.Geometry | None:
    """The union of the avoid zones: bare ids are elements of the map itself."""
    parts = []
    for spec in specs:
        if "#" in spec or is_gis(spec):
            split_spec(spec)
            parts.append(read_avoid_shape(spec, margin))
        elif doc is not None:
            zone = doc.keep_clear(doc.element(spec), margin)
            if zone.is_empty:
                raise RegionError(f"element #{spec} gives no zone to avoid", source=str(path))
            parts.append(zone)
        else:
            raise RegionError(f"avoid {spec!r}: a GIS map needs avoid specs like FILE.gpkg#LAYER", source=str(path))
    return shapely.union_all(parts) if parts else None


def default_jobs() -> int:
    """Worker processes: the cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def fill_map(
    path: str | Path, styles: Styles, *, seed: int, avoid: tuple[str, ...] = (), jobs: int | None = None,
    progress: Progress | None = None, max_motifs: float = math.inf, scheduler: str = "local",
    tile_size: float | None = None, sink: Sink | None = None, bar: bool = False, cell_sink: CellSink | None = None,
) -> MapFill:  # fmt: skip
    """Fill every classed region of a map with its class's style.

    Parameters
    ----------
    path : the map, SVG or GeoJSON
    styles : the parsed styles file
    seed : the run's seed
    avoid : more avoid specs (added to the styles file's)
    jobs : worker processes (default: the usable cores; 1 runs in this process)
    progress : called as ``progress(done, total, ident, error_or_None)`` after each region
    max_motifs : a region (a tile) whose estimated motif count is larger fails, and the others
        are filled
    scheduler : ``local``, ``processes`` or a Dask scheduler address
        (:mod:`svgtile.runners.schedule`)
    tile_size : cut each region whose engine is tile-exact into tiles this large, map units
        (None: every region whole); the output is the same
    sink : called as ``sink(index, region, band, motifs)`` (map units) for each band of each region as
        soon as it is complete, instead of keeping the motifs in the result; a region run whole
        is one band
    bar : show Dask's progress bar
    cell_sink : called as ``cell_sink(index, region, cells)`` for each cellular region, before
        its motifs' band reaches ``sink`` (:data:`CellSink`), instead of keeping its cells in the
        result

    Returns
    -------
    MapFill; regions that failed have ``None`` results and an entry in ``errors``; so has each
    failed tile, under ``"ID tile I,J"``, its region written without it.
    """
    regions, doc = read_map(path, styles)
    zone = avoid_zone(path, doc, styles.avoid + tuple(avoid), styles.avoid_margin)
    used = {r.cls for r in regions}
    warnings = [f"{styles.source}: class {c!r} matches no region of {path}" for c in sorted(set(styles.classes) - used)]
    cells: list[Cellwork | None] = [None] * len(regions)
    results, errors, filled = fill_regions(regions, zone, with_map_labels(styles, path), seed=seed, jobs=jobs,
                                           progress=progress, max_motifs=max_motifs, scheduler=scheduler,
                                           tile_size=tile_size, sink=sink, bar=bar,
                                           cell_sink=cell_sink or (lambda n, r, c: cells.__setitem__(n, c)))  # fmt: skip
    return MapFill(regions, results, errors, doc, warnings, styles, filled, cells)


def cellular_classes(styles: Styles) -> list[str]:
    """The classes (sorted) whose engine draws cells (:mod:`svgtile.apps.mapcells`)."""
    return sorted(name for name, style in styles.classes.items() if is_cellular(style.engine))


def with_map_labels(styles: Styles, path: str | Path) -> Styles:
    """``styles`` with its cellular classes' labels naming the map's own lines in full, and
    read in each class's working units (:func:`svgtile.apps.mapcells.map_labels`)."""
    classes = {}
    for name, style in styles.classes.items():
        if style.params.get("label") and is_cellular(style.engine):
            label = map_labels(style.params["label"], path, is_gis(path), f"classes.{name}")
            style = replace(style, params={**style.params, "label": label, "label_unit": style.unit})
        classes[name] = style
    return replace(styles, classes=classes)


def fill_regions(
    regions: list[MapRegion], zone: shapely.Geometry | None, styles: Styles, *, seed: int, jobs: int | None = None,
    progress: Progress | None = None, max_motifs: float = math.inf, scheduler: str = "local",
    tile_size: float | None = None, sink: Sink | None = None, bar: bool = False, cell_sink: CellSink | None = None,
) -> tuple[list[Arrangement | None], dict[str, str], list[bool]]:  # fmt: skip
    """Fill each region with its class's style, on Dask (:func:`fill_map`'s work).

    Parameters
    ----------
    regions : the regions, map units; ``zone`` the avoid zones (map units) or None
    seed, jobs, progress, max_motifs, scheduler, tile_size, sink, bar, cell_sink : as for
        :func:`fill_map` (cells are dropped without a ``cell_sink``)

    Returns
    -------
    The motifs of each region (None where it failed, or where they went to ``sink``),
    ``{ident: message}`` of the failures (regions, and tiles as ``"ID tile I,J"``), and which
    regions were written (:attr:`MapFill.filled`).
    """
    results: list[Arrangement | None] = [None] * len(regions)
    filled = [False] * len(regions)
    errors: dict[str, str] = {}
    units: list[Unit] = []
    owner: list[tuple[int, int]] = []  # unit -> (region, tile of the region)
    collect: list[Bands | None] = [None] * len(regions)
    kept: list[dict[int, Arrangement]] = [{} for _ in regions]  # band -> motifs, when there is no sink
    failed_tiles = [0] * len(regions)
    finished = 0

    def region_done(n: int) -> None:
        nonlocal finished
        finished += 1
        if progress is not None:
            progress(finished, len(regions), regions[n].ident, errors.get(regions[n].ident))

    for n, r in enumerate(regions):
        style = styles.classes[r.cls]
        try:
            tiles = plan_region(r.shape, zone, style, tile_size)
        except SvgtileError as exc:
            errors[r.ident] = " ".join(str(exc).split())
            region_done(n)
            continue

        def on_band(b: int, arr: Arrangement, n=n, style=style) -> None:
            arr = to_map_units(arr, style)
            if sink is None:
                kept[n][b] = arr
            else:
                sink(n, regions[n], b, arr)

        collect[n] = Bands(tiles, on_band)
        for t, tile in enumerate(tiles):
            name = r.ident if tile.whole else f"{r.ident} tile {tile.i},{tile.j}"
            units.append(Unit(f"svgtile-{name}", fill_working, (r.shape, zone, style, seed, max_motifs, tile)))
            owner.append((n, t))

    def done(k: int, arr: Arrangement | tuple[Arrangement, Cellwork] | None, error: str | None) -> None:
        n, t = owner[k]
        tiles = collect[n]
        if isinstance(arr, tuple):  # a cellular region (whole): its cells go before its motifs
            arr, cells = arr
            if cell_sink is not None:
                cell_sink(n, regions[n], cells)
        if error is not None:
            failed_tiles[n] += 1
            tile = units[k].args[-1]
            errors[regions[n].ident if tile.whole else f"{regions[n].ident} tile {tile.i},{tile.j}"] = error
        tiles.add(t, arr)
        if tiles.done:
            if failed_tiles[n] < len(tiles.band_of):
                filled[n] = True
                if sink is None:
                    results[n] = Arrangement.concat([kept[n][b] for b in sorted(kept[n])])
                    kept[n] = {}
            collect[n] = None
            region_done(n)

    run(units, done, scheduler=scheduler, workers=min(jobs or default_jobs(), max(len(units), 1)), progress=bar)
    return results, errors, filled
