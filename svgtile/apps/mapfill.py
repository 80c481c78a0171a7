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

Each region is synthesized on its own (:func:`fill_region`) in a pool of processes; a region that
fails is reported and the others are kept.  All regions of a run share one seed, and the engines
anchor randomness in world coordinates, so two touching units of one class continue each other's
texture, and editing one unit leaves the others byte-identical.
"""

from __future__ import annotations

import concurrent.futures
import math
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import shapely

from svgtile.apps.load import check_motif_count, load_exemplar
from svgtile.apps.mapread import (
    AVOID_MARGIN,
    MAX_AVOID_MARGIN,
    MapRegion,
    classed_regions,
    is_geojson,
    read_avoid_shape,
    split_spec,
)
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import BOUNDARY_MODES, Region
from svgtile.engines import ENGINES, engines_with, make_params, public_params, synthesize
from svgtile.errors import ParameterError, RegionError, SvgtileError
from svgtile.files import read_input
from svgtile.gis import geojson
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
CLASS_KEYS = (*ENGINE_KEYS, "exemplar", "engine", "seed", "unit")
#: Keys only the top level may have.
RUN_KEYS = ("avoid", "avoid_margin", "class_attribute", "class_property", "classes")

Progress = Callable[[int, int, str, "str | None"], None]


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
    """

    cls: str
    exemplar: Path
    engine: str = "patch"
    params: dict = field(default_factory=dict)
    seed: int | None = None
    unit: float = 1.0
    boundary: str = "clip"


@dataclass(frozen=True)
class Styles:
    """A parsed styles file: per-class styles and the run's options."""

    classes: dict[str, Style]
    avoid: tuple[str, ...] = ()
    avoid_margin: float = AVOID_MARGIN
    class_attribute: str | None = None
    class_property: str = "class"
    source: str = "<styles>"


def read_styles(path: str | Path) -> Styles:
    """Parse a styles file (see the module docstring); errors name the file and the key."""
    source = str(path)
    raw = read_input(path, error=ParameterError, limit=MAX_STYLES_BYTES)
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except RecursionError:
        raise ParameterError("tables or arrays are nested too deeply", source=source) from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ParameterError(f"not a valid TOML file ({' '.join(str(exc).split())})", source=source) from None
    return parse_styles(data, source=source, folder=Path(path).parent)


def parse_styles(data: dict, *, source: str = "<styles>", folder: Path = Path()) -> Styles:
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
        engine = table.get("engine", defaults.get("engine", "patch"))
        own = ENGINES[engine].Params.public_names() if isinstance(engine, str) and engine in ENGINES else set()
        used |= own
        # a top-level engine parameter is a default for the classes whose engine has it
        merged = {**{k: v for k, v in defaults.items() if k not in PARAM_KEYS or k in own}, **table}
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
    avoid = [a[1:] if a.startswith("#") else str(folder / a) if "#" in a or is_geojson(a) else a for a in avoid]
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
    return Style(name, folder / t["exemplar"], engine, params, seed, float(unit), boundary)


# ----------------------------------------------------------------------------- one region


def fill_region(
    shape: shapely.Geometry, avoid: shapely.Geometry | None, style: Style, seed: int, max_motifs: float = math.inf
) -> Arrangement:
    """Synthesize one region with its style; motifs in map units (the region's frame).

    Parameters
    ----------
    shape : the region, map units
    avoid : the avoid zones near it, map units, or None
    style : its class's style
    seed : the run's seed (the style's own wins)
    max_motifs : refuse a region whose estimated motif count is larger
    """
    ex, stats = load_exemplar(str(style.exemplar))
    unit = style.unit
    region = Region.from_geometry(geojson.to_working(shape, unit),
                                  avoid=None if avoid is None else geojson.to_working(avoid, unit))  # fmt: skip
    check_motif_count(ex, stats, region, "the region", limit=max_motifs,
                      hint=f"raise unit of class {style.cls!r} or fill a smaller region")  # fmt: skip
    seed = style.seed if style.seed is not None else seed
    arr = synthesize(ex, region, style.engine, seed=seed, stats=stats, boundary=style.boundary,
                     params=style.params).arrangement  # fmt: skip
    if unit != 1.0:
        arr = Arrangement(arr.kind, arr.xy * unit, arr.angle, arr.scale * unit)
    return arr


def _task(
    ident: str, shape, avoid, style: Style, seed: int, max_motifs: float = math.inf
) -> tuple[str, Arrangement | None, str | None]:
    """A worker's job: never raises, so one region's failure cannot take the pool down."""
    try:
        return ident, fill_region(shape, avoid, style, seed, max_motifs), None
    except SvgtileError as exc:
        return ident, None, " ".join(str(exc).split())
    except MemoryError:
        return ident, None, "out of memory"
    except Exception as exc:  # a bug in one region must not lose the others
        return ident, None, f"internal error: {type(exc).__name__}: {' '.join(str(exc).split())}"


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
    """

    regions: list[MapRegion]
    results: list[Arrangement | None]
    errors: dict[str, str]
    doc: SvgShapes | None
    warnings: list[str]
    styles: Styles


def read_map(path: str | Path, styles: Styles) -> tuple[list[MapRegion], SvgShapes | None]:
    """The classed regions of a map SVG or GeoJSON file whose class the styles know."""
    classes = set(styles.classes)
    doc = None
    if is_geojson(path):
        feats = geojson.read_regions(path, class_property=styles.class_property)
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
        if "#" in spec or is_geojson(spec):
            split_spec(spec)
            parts.append(read_avoid_shape(spec, margin))
        elif doc is not None:
            zone = doc.keep_clear(doc.element(spec), margin)
            if zone.is_empty:
                raise RegionError(f"element #{spec} gives no zone to avoid", source=str(path))
            parts.append(zone)
        else:
            raise RegionError(f"avoid {spec!r}: a GeoJSON map needs avoid specs like FILE.geojson", source=str(path))
    return shapely.union_all(parts) if parts else None


def default_jobs() -> int:
    """Worker processes: the cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def fill_map(
    path: str | Path, styles: Styles, *, seed: int, avoid: tuple[str, ...] = (), jobs: int | None = None,
    progress: Progress | None = None, max_motifs: float = math.inf,
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
    max_motifs : a region whose estimated motif count is larger fails (and the others are filled)

    Returns
    -------
    MapFill; regions that failed have ``None`` results and an entry in ``errors``.
    """
    regions, doc = read_map(path, styles)
    zone = avoid_zone(path, doc, styles.avoid + tuple(avoid), styles.avoid_margin)
    used = {r.cls for r in regions}
    warnings = [f"{styles.source}: class {c!r} matches no region of {path}" for c in sorted(set(styles.classes) - used)]
    results: list[Arrangement | None] = [None] * len(regions)
    errors: dict[str, str] = {}
    index = {r.ident: n for n, r in enumerate(regions)}
    tasks = [(r.ident, r.shape, zone, styles.classes[r.cls], seed, max_motifs) for r in regions]
    jobs = min(jobs or default_jobs(), len(tasks))

    def done(ident: str, arr: Arrangement | None, error: str | None, count: int) -> None:
        if error is not None:
            errors[ident] = error
        else:
            results[index[ident]] = arr
        if progress is not None:
            progress(count, len(tasks), ident, error)

    if jobs <= 1:
        for count, task in enumerate(tasks, 1):
            done(*_task(*task), count)
    else:
        pool = concurrent.futures.ProcessPoolExecutor(max_workers=jobs, initializer=_die_with_parent,
                                                      initargs=(os.getpid(),))  # fmt: skip
        try:
            futures = {pool.submit(_task, *task): task[0] for task in tasks}
            for count, future in enumerate(concurrent.futures.as_completed(futures), 1):
                try:
                    done(*future.result(), count)
                except Exception as exc:  # the worker itself died (killed, out of memory)
                    done(futures[future], None, f"worker failed: {type(exc).__name__}", count)
        except BaseException:  # ^C, SIGTERM: stop the workers now rather than finish their regions
            _stop(pool)
            raise
        pool.shutdown()
    return MapFill(regions, results, errors, doc, warnings, styles)


def _die_with_parent(parent: int) -> None:
    """Worker set-up: end when the parent process ends, even by SIGKILL (Linux; elsewhere the
    pool's own check, when the next task is due, has to do)."""
    try:
        import ctypes
        import signal

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:  # the parent died before the request took effect
        os._exit(1)


def _stop(pool: concurrent.futures.ProcessPoolExecutor) -> None:
    """End ``pool``'s workers at once (their regions are lost anyway) and release the pool."""
    processes = list((getattr(pool, "_processes", None) or {}).values())  # no public handle
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in processes:
        proc.kill()
    for proc in processes:
        proc.join(5)
