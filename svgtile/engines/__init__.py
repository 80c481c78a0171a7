"""Synthesis engines behind one protocol (:mod:`svgtile.engines.base`), and :func:`synthesize`.

Built in:

* ``patch`` — patch-based synthesis (AlMeraj, Kaplan & Asente 2013), the default;
* ``tile`` — the Tiling strategy: translated copies of the exemplar (a baseline);
* ``random`` — the Random strategy: dart throwing to the exemplar's statistics (a baseline);
* ``growth`` — local growth from the exemplar's neighbourhoods (Ijiri, Měch, Igarashi & Miller 2008).
* ``optimize`` — discrete element texture optimisation (Ma, Wei & Tong 2011) from a patch start.
* ``cellular`` — feature-based cellular textures (Legakis, Dorsey & Gortler 2001): bricks, blocks,
  ashlar, rhombs and bedding lines turning a unit's corners and following its edges.

Other packages add engines through the ``svgtile.engines`` entry-point group (the ecosystem's
plug-in convention, as vpype's): an entry point ``NAME = module:ENGINE`` naming an object that
follows :class:`~svgtile.engines.base.Engine`.  A plug-in cannot replace a built-in engine.

:func:`synthesize` is the one place an engine is called: the CLI, ``svgtile map``, ``compare``,
``swatches`` and the Inkscape bridge all go through it.

The registry holds declarations only — each engine's parameter class and protocol object, in a
module that imports none of its implementation (``growth`` and ``cellular``: their packages'
``__init__``; ``optimize``: :mod:`.optimize.engine`).  An engine's implementation, with what it
alone needs (numba, scipy's interpolators; the engines' solver modules), is imported when it
runs, so ``svgtile score``, ``analyze`` and every command's start-up do without them (scipy's
sparse linear algebra is loaded anyway, by :mod:`scipy.spatial`)
(``tests/test_layout.py`` checks it).
"""

from __future__ import annotations

from collections.abc import Mapping
from importlib.metadata import entry_points

import numpy as np
import shapely

from svgtile.analysis.stats import Stats, analyze
from svgtile.core import cellrng
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import BOUNDARY_MODES, Region
from svgtile.engines.base import (
    CONTROL_OPTIONS,
    Context,
    Controls,
    Engine,
    EngineParams,
    Progress,
    PublicParam,
    Result,
    draws_cells,
    honoured,
    reading_order,
)
from svgtile.engines.cellular import CELLULAR, CellularParams
from svgtile.engines.choose import AUTO, Choice, choose, steerable, with_choice
from svgtile.engines.growth import GROWTH, GrowthParams
from svgtile.engines.optimize.engine import OPTIMIZE, OptimizeParams
from svgtile.engines.patch.engine import PATCH, PatchParams
from svgtile.engines.random import RANDOM, RandomParams
from svgtile.engines.tile import TILE, TileParams
from svgtile.errors import ExemplarError, ParameterError

#: The entry-point group plug-in engines register under.
ENTRY_POINT_GROUP = "svgtile.engines"


#: Names a plug-in parameter may not take: they are options of every command or styles keys.
RESERVED = frozenset({"seed", "boundary", "size", "region", "engine", "unit", "exemplar", "output", "avoid",
                      "avoid_margin", "force", "jobs", "styles", "refine", "scheduler", "tile_size"})
#: Plug-ins found but not registered, name -> why (``svgtile.engines.get_engine`` names them).
REFUSED: dict[str, str] = {}


def _registry() -> dict[str, Engine]:
    engines: dict[str, Engine] = {e.name: e for e in (PATCH, TILE, RANDOM, GROWTH, OPTIMIZE, CELLULAR)}
    shared = {p.name: p for e in engines.values() for p in e.Params.public()}
    for ep in entry_points(group=ENTRY_POINT_GROUP):
        if ep.name in engines or ep.name == AUTO:
            REFUSED[ep.name] = "a built-in engine has that name" if ep.name in engines else "svgtile reserves that name"
            continue
        try:  # a broken plug-in must not break svgtile: it is refused, with the reason kept
            engine = ep.load()
            if not isinstance(engine, Engine) or engine.name != ep.name:
                raise TypeError("not an engine of that name (svgtile.engines.base.Engine)")
            for p in engine.Params.public():
                if p.name in RESERVED:
                    raise TypeError(f"its parameter {p.name!r} is a name svgtile reserves")
                if p.name in shared and (shared[p.name].type, shared[p.name].option) != (p.type, p.option):
                    raise TypeError(f"its parameter {p.name!r} differs from another engine's")
        except Exception as exc:
            REFUSED[ep.name] = f"{type(exc).__name__}: {' '.join(str(exc).split())}"
            continue
        shared.update({p.name: p for p in engine.Params.public()})
        engines[ep.name] = engine
    return engines


#: name -> engine, built-in first.
ENGINES: dict[str, Engine] = _registry()


def get_engine(name: str) -> Engine:
    """The engine called ``name``; a clear error naming the choices otherwise."""
    try:
        return ENGINES[name]
    except (KeyError, TypeError):
        why = f"; the plug-in of that name was refused: {REFUSED[name]}" if isinstance(name, str) and name in REFUSED else ""
        raise ParameterError(f"unknown engine {name!r} (choose from {', '.join(sorted(ENGINES))}){why}") from None


def public_params() -> dict[str, PublicParam]:
    """Every engine's public parameters, by name (the union the CLI offers as options).

    Two engines that share a parameter name must give it the same type and option.
    """
    out: dict[str, PublicParam] = {}
    for engine in ENGINES.values():
        for p in engine.Params.public():
            seen = out.setdefault(p.name, p)
            if (seen.type, seen.option) != (p.type, p.option):  # pragma: no cover - a programming error
                raise TypeError(f"engines disagree on the parameter {p.name!r}")
    return out


def engines_with(name: str) -> list[str]:
    """Names of the engines that have the public parameter ``name``."""
    return [e.name for e in ENGINES.values() if name in e.Params.public_names()]


def make_params(engine: Engine | str, params: Mapping[str, object] | EngineParams | None = None, *,
                spell=repr) -> EngineParams:  # fmt: skip
    """The engine's parameter object from ``params``, checked.

    Parameters
    ----------
    engine : an engine or its name
    params : values by field name (missing ones take their defaults), or a parameter object
    spell : how a message names a parameter (the CLI passes its option spelling)

    Raises
    ------
    ParameterError
        A parameter the engine does not have, or a value out of its range.
    """
    engine = get_engine(engine) if isinstance(engine, str) else engine
    if isinstance(params, EngineParams):
        if not isinstance(params, engine.Params):
            raise ParameterError(f"engine {engine.name!r} takes {engine.Params.__name__}, not {type(params).__name__}")
        return params
    params = dict(params or {})
    fields = set(engine.Params.__dataclass_fields__)  # public ones, and the library's tuning fields
    unknown = [k for k in params if k not in fields]
    if unknown:
        own = ", ".join(spell(p.name) for p in engine.Params.public()) or "none"
        raise ParameterError(f"engine {engine.name!r} has no parameter {spell(unknown[0])} (its parameters: {own})")
    engine.Params.check_types(params)
    return engine.Params(**params)


def synthesize(
    exemplar: Exemplar,
    region: Region,
    engine: Engine | str = "patch",
    *,
    seed: int | None = None,
    rng: np.random.Generator | None = None,
    stats: Stats | None = None,
    boundary: str = "clip",
    progress: Progress | None = None,
    params: Mapping[str, object] | EngineParams | None = None,
    controls: Controls | None = None,
    refine: int = 0,
) -> Result:
    """Fill ``region`` with a texture like ``exemplar``, with one engine.

    Parameters
    ----------
    exemplar : the parsed exemplar
    region : the output region, user units (with its avoid zones)
    engine : an engine or its name (:data:`ENGINES`), or ``"auto"``: the engine and parameters
        :func:`svgtile.engines.choose.choose` picks from the exemplar's order (``params`` given
        here override its parameters)
    seed, rng : the only source of randomness, exactly one of them: a seed (recorded in the
        result) or a generator; one 63-bit key is drawn from it
        (:func:`svgtile.core.cellrng.root_key`)
    stats : the exemplar's analysis, if already computed
    boundary : one of :data:`svgtile.core.region.BOUNDARY_MODES`
    progress : called as ``progress(stage, fraction)``; ``("done", 1.0)`` last
    params : the engine's parameters (see :func:`make_params`)
    controls : flow field, barriers, growth area (:class:`~svgtile.engines.base.Controls`); each
        must be one the engine honours
    refine : N ≥ 0, iterations of discrete element texture optimisation (Ma, Wei & Tong 2011,
        :func:`svgtile.engines.optimize.solver.refine`) run on the engine's output, after the
        boundary mode; 0 (the default) leaves the engine's output as it is

    Returns
    -------
    Result whose arrangement has no overlaps and no distance-rule violations, is filtered by the
    boundary mode and in reading order.
    """
    if engine == AUTO:
        stats = analyze(exemplar) if stats is None else stats
        given = Controls().given() if controls is None else controls.given()
        named = () if isinstance(params, EngineParams) else tuple(params or ())
        picked = choose(exemplar, stats, available=steerable(ENGINES, given, named))
        engine, params = picked.engine, with_choice(picked, None if isinstance(params, EngineParams) else params)
    engine = get_engine(engine) if isinstance(engine, str) else engine
    check_motifs(exemplar, engine)
    p = make_params(engine, params)
    if boundary not in BOUNDARY_MODES:
        raise ParameterError(f"--boundary must be one of {', '.join(BOUNDARY_MODES)}, not {boundary!r}")
    if (seed is None) == (rng is None):
        raise TypeError("synthesize takes exactly one of seed and rng")
    controls = Controls() if controls is None else controls
    foreign = sorted(controls.given() - honoured(engine))
    if foreign:
        takers = [e.name for e in ENGINES.values() if foreign[0] in honoured(e)]
        which = f" (engines that do: {', '.join(takers)})" if takers else ""
        raise ParameterError(f"engine {engine.name!r} cannot honour {CONTROL_OPTIONS[foreign[0]]}{which}")
    stats = analyze(exemplar) if stats is None else stats
    report = progress or (lambda stage, fraction: None)
    key = cellrng.root_key(np.random.default_rng(seed) if rng is None else rng)
    ctx = Context(exemplar, stats, region, boundary, key, report, controls)
    if not (isinstance(refine, int) and not isinstance(refine, bool) and refine >= 0):
        raise ParameterError(f"--refine must be a whole number of iterations, at least 0, not {refine!r}")
    cells = None
    if draws_cells(engine):  # a cellular engine: cells and lines besides its motifs
        arr, cells = engine.place_cells(ctx, p)
    else:
        arr = engine.place(ctx, p)
    arr = arr.take(region.keep(arr, exemplar.prototypes, boundary))
    if refine and len(arr) >= 2:  # (fewer: nothing to refine)
        # imported here: the solver (numba) costs every command that does not refine its start-up
        from svgtile.engines.optimize.solver import refine as _refine

        arr, _ = _refine(arr, exemplar, stats, _steered(region, controls), boundary, iterations=refine, key=ctx.key,
                         flow=controls.flow, progress=report)  # fmt: skip
    arr = reading_order(arr)
    report("done", 1.0)
    return Result(arr, exemplar, stats, region, boundary, engine.name, p, seed, refine=refine, cells=cells)


def check_motifs(exemplar: Exemplar, engine: Engine) -> None:
    """Refuse an engine that places motifs for an exemplar with none (an imported pattern of
    cells and lines only, which the cellular engine draws), before any work.

    Raises
    ------
    ExemplarError
    """
    if len(exemplar.motifs) == 0 and not draws_cells(engine):
        raise ExemplarError(f"engine {engine.name!r} places motifs, and this pattern of cells has none: "
                            "use the cellular engine (--engine cellular or auto; in a styles file engine = \"cellular\" "
                            "or no engine key)", source=exemplar.source)  # fmt: skip


def _steered(region: Region, controls: Controls) -> Region:
    """``region`` with the map controls' no-go areas as avoid zones, for ``refine``: its moves
    then cross no ``--barrier`` (a line, grown by a hair to have an area) and leave no
    ``--grow-within`` area, as the engine's motifs do not (a move that would is undone)."""
    zones = [] if region.avoid is None else [region.avoid]
    x0, y0, x1, y1 = region.bounds
    hair = 1e-9 * max(x1 - x0, y1 - y0)
    if controls.barriers is not None:
        zones.append(shapely.buffer(controls.barriers, hair))
    if controls.grow_within is not None:
        big = max(x1 - x0, y1 - y0)
        zones.append(shapely.difference(shapely.box(x0 - big, y0 - big, x1 + big, y1 + big), controls.grow_within))
    if len(zones) == (region.avoid is not None):
        return region
    return Region(region.shape, shapely.union_all(zones))


__all__ = ["AUTO", "ENGINES", "CellularParams", "Choice", "Context", "Controls", "Engine", "EngineParams",
           "GrowthParams", "OptimizeParams", "PatchParams", "RandomParams", "Result", "TileParams", "check_motifs",
           "choose", "engines_with", "get_engine", "make_params", "public_params", "synthesize"]  # fmt: skip
