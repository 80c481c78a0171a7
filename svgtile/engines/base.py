"""The engine protocol: what every synthesis engine declares, and what it is handed.

An engine is an object with

* ``name`` — how users call it (``--engine NAME``, ``engine = "NAME"`` in a styles file);
* ``summary`` — one sentence for ``--help``, in the user's words;
* ``Params`` — a frozen dataclass subclassing :class:`EngineParams`: its fields are the engine's
  parameters, each with a default, and the fields declared with :func:`param` (help text, option
  name, choices) are the public ones, from which the CLI options, the styles-file keys of
  ``svgtile map`` and the Inkscape dialog are made (tests check the ``.inx`` against them);
  ``__post_init__`` checks ranges and raises :class:`~svgtile.errors.ParameterError`;
* ``place(ctx, params) -> Arrangement`` — the synthesis itself, given a :class:`Context`;
* ``controls`` (optional) — the map controls it honours, a frozenset of :class:`Controls` field
  names (``"flow"``, ``"barriers"``, ``"grow_within"``); a control given to an engine that does
  not honour it is an error, never silently ignored;
* ``place_cells(ctx, params) -> (Arrangement, Cellwork)`` (optional) — an engine whose output
  is cells and lines besides motifs (``cellular``) returns both; :func:`synthesize` then puts the
  cells in :attr:`Result.cells`;
* ``reach(exemplar, params) -> float`` — how far, in user units, what happens outside a tile can
  change the motifs inside it; a tiled run (one tile synthesized with a halo this wide, keeping
  only the motifs anchored in the tile) equals the whole run exactly when the reach is finite.
  ``math.inf`` says the engine is not tile-exact and must be run whole;
* ``seconds_per_motif`` (optional) — what one motif costs ``svgtile synth`` end to end with this
  engine (CPU seconds on the reference machine of ``benchmarks/work_per_motif.py``, rounded up):
  the work guard (:func:`svgtile.apps.load.check_work`) refuses a run estimated at over a minute
  unless forced, rather than let it run away.

:func:`svgtile.engines.synthesize` does what every engine shares: it checks the parameters (a
parameter the engine does not have is an error), draws the run's world-anchored key from the
seed, filters the motifs by the boundary mode, puts them in reading order, and returns a
:class:`Result` that carries everything a writer needs.

What an engine's ``place`` must return: an :class:`~svgtile.core.arrangement.Arrangement` with
no overlapping footprints and no distance-rule violations (:mod:`svgtile.core.conflicts`), its
positions, angles and scales rounded to :data:`~svgtile.core.arrangement.DECIMALS` when they are
created (so every check runs on exactly what is written), every random choice derived from
``ctx.key`` with world-anchored hashes (:mod:`svgtile.core.cellrng`).  It may leave motifs the
boundary mode drops, and any order.
"""

from __future__ import annotations

import dataclasses
import typing
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, Protocol, runtime_checkable

import numpy as np
import shapely

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.cells import Cellwork
from svgtile.core.exemplar import Exemplar
from svgtile.core.flow import FlowField
from svgtile.core.region import Region
from svgtile.errors import ParameterError

Progress = Callable[[str, float], None]


def param(default: Any, help: str, *, option: str | None = None, choices: tuple[str, ...] | None = None,
          interval: tuple[float, float] | None = None, metavar: str | None = None) -> Any:  # fmt: skip
    """A public engine parameter: a dataclass field with what the CLI and dialogs show.

    Parameters
    ----------
    default : its value when not given
    help : what it does, in the user's words (CLI ``--help``, tooltips)
    option : the CLI option, default ``--`` + the field name with ``-`` for ``_``
    choices : the allowed values of a text parameter
    interval : ``(low, high)``, the interval of a number parameter (for dialogs; the parameter
        class's ``__post_init__`` checks it, and may exclude an end)
    metavar : how ``--help`` names its value
    """
    return dataclasses.field(default=default, metadata={"help": help, "option": option, "choices": choices,
                                                        "interval": interval, "metavar": metavar})  # fmt: skip


@dataclass(frozen=True)
class PublicParam:
    """One public parameter of an engine, as the CLI, styles files and dialogs see it."""

    name: str
    type: type
    default: Any
    help: str
    option: str
    choices: tuple[str, ...] | None
    interval: tuple[float, float] | None
    metavar: str | None


_TYPE_WORDS = {float: "number", int: "whole number", bool: "true or false", str: "text"}


@dataclass(frozen=True)
class EngineParams:
    """Base of every engine's parameter class (frozen; ranges checked in ``__post_init__``)."""

    @classmethod
    def public(cls) -> tuple[PublicParam, ...]:
        """The parameters declared with :func:`param`, in field order."""
        out = []
        hints = typing.get_type_hints(cls)
        for f in dataclasses.fields(cls):
            if "help" not in f.metadata:
                continue
            m = f.metadata
            kind = hints[f.name]
            if kind not in (float, int, bool, str):
                raise TypeError(f"{cls.__name__}.{f.name}: a public parameter is a float, int, bool or str")
            option = m["option"] or "--" + f.name.replace("_", "-")
            out.append(PublicParam(f.name, kind, f.default, m["help"], option, m["choices"], m["interval"], m["metavar"]))
        return tuple(out)

    @classmethod
    def public_names(cls) -> frozenset[str]:
        """The names of the public parameters."""
        return frozenset(p.name for p in cls.public())

    @classmethod
    def check_types(cls, values: dict[str, Any]) -> None:
        """Refuse a value of the wrong type (a number for a float, which may be written as an int;
        ``true``/``false`` only for a bool), naming the parameter; before any range check."""
        hints = typing.get_type_hints(cls)
        for name, value in values.items():
            want = hints.get(name)
            ok = {float: lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
                  int: lambda v: isinstance(v, int) and not isinstance(v, bool),
                  bool: lambda v: isinstance(v, bool), str: lambda v: isinstance(v, str)}.get(want, lambda v: True)
            if not ok(value):
                raise ParameterError(f"{name} has the wrong type ({value!r}; it takes a {_TYPE_WORDS[want]})")

    def public_values(self) -> dict[str, Any]:
        """``{name: value}`` of the public parameters (what a texture's metadata records)."""
        return {p.name: getattr(self, p.name) for p in self.public()}


@dataclass(frozen=True, eq=False)
class Controls:
    """What a map maker draws to steer a texture besides its region (Ijiri et al. 2008 §6's tools).

    Attributes
    ----------
    flow : the direction motifs, copies, frames or courses follow (``--flow``), or None
    barriers : shapely (Multi)LineString or polygonal geometry, user units, or None — lines no
        motif footprint crosses and growth does not cross (``--barrier``: a fault, a river)
    grow_within : shapely polygonal geometry, user units, or None — the only area motifs are
        placed in (``--grow-within``, the spray tool; a stroke is buffered by half its width)
    """

    flow: FlowField | None = None
    barriers: shapely.Geometry | None = None
    grow_within: shapely.Geometry | None = None

    def given(self) -> frozenset[str]:
        """Names of the controls that are set."""
        return frozenset(f.name for f in dataclasses.fields(self) if getattr(self, f.name) is not None)


#: Option spelling of each control, for messages.
CONTROL_OPTIONS = {"flow": "--flow", "barriers": "--barrier", "grow_within": "--grow-within"}


@dataclass(frozen=True, eq=False)
class Context:
    """What an engine's ``place`` is handed.

    Attributes
    ----------
    exemplar : the parsed exemplar
    stats : its analysis
    region : the output region (with its avoid zones)
    boundary : one of :data:`svgtile.core.region.BOUNDARY_MODES`
    key : the run's 63-bit key (:func:`svgtile.core.cellrng.root_key`): every random choice is a
        hash of it and world-anchored integers
    progress : called as ``progress(stage, fraction)``; never None
    controls : the map controls given (only those the engine honours)
    """

    exemplar: Exemplar
    stats: Stats
    region: Region
    boundary: str
    key: int
    progress: Progress
    controls: Controls = dataclasses.field(default_factory=Controls)


@runtime_checkable
class Engine(Protocol):
    """A synthesis engine (see the module docstring)."""

    name: ClassVar[str]
    summary: ClassVar[str]
    Params: ClassVar[type[EngineParams]]

    def place(self, ctx: Context, params: EngineParams) -> Arrangement: ...

    def reach(self, exemplar: Exemplar, params: EngineParams) -> float: ...


#: What an engine that does not declare ``seconds_per_motif`` is taken to cost per motif.
DEFAULT_SECONDS_PER_MOTIF = 1e-4


def seconds_per_motif(engine: Engine) -> float:
    """CPU seconds per motif of a run with ``engine`` (its declaration, else a cautious default)."""
    return float(getattr(engine, "seconds_per_motif", DEFAULT_SECONDS_PER_MOTIF))


def draws_cells(engine: Engine) -> bool:
    """Whether ``engine`` draws cells and lines besides its motifs (it has ``place_cells``, as
    the cellular engine does: :class:`svgtile.engines.cellular.CellularEngine`)."""
    return hasattr(engine, "place_cells")


def honoured(engine: Engine) -> frozenset[str]:
    """The :class:`Controls` an engine honours (none unless it declares ``controls``)."""
    return frozenset(getattr(engine, "controls", frozenset()))


@dataclass(frozen=True, eq=False)
class Result:
    """A synthesized texture with everything needed to write, score or reproduce it.

    Attributes
    ----------
    arrangement : the motifs, filtered by ``boundary``, in reading order
    exemplar, stats : the exemplar and its analysis
    region : the output region
    boundary : how motifs met the region's edge
    engine : the engine's name
    params : the engine's parameters, all resolved
    seed : the seed the run was made with (None when the caller passed a generator; the metadata
        then records none)
    refine : iterations of optimisation run on the engine's output (``--refine``; recorded when
        not 0)
    cells : the cells and lines of a cellular engine (:class:`~svgtile.core.cells.Cellwork`),
        None for an engine that places motifs only
    """

    arrangement: Arrangement
    exemplar: Exemplar
    stats: Stats
    region: Region
    boundary: str
    engine: str
    params: EngineParams
    seed: int | None
    refine: int = 0
    cells: Cellwork | None = None

    def __len__(self) -> int:
        return len(self.arrangement)

    def metadata(self, **where: object) -> dict[str, object]:
        """What a texture records of its run: engine, seed, ``where`` (exemplar, region …), the
        public parameters, the boundary mode and the motif count."""
        run = {"engine": self.engine, **({} if self.seed is None else {"seed": self.seed})}
        own = {**self.params.public_values(), **({"refine": self.refine} if self.refine else {}),
               "boundary": self.boundary, "motifs": len(self.arrangement)}
        if self.cells is not None:
            own["cells"] = len(self.cells.cells)
        clash = (set(where) & set(own)) | (set(where) & set(run))
        if clash:
            raise ValueError(f"metadata keys {sorted(clash)} are the run's own")
        return {**run, **where, **own}


def reading_order(arr: Arrangement) -> Arrangement:
    """Motifs in reading order (rows, then columns): a stable, diff-friendly output."""
    return arr.take(np.lexsort((arr.xy[:, 0], arr.xy[:, 1])))
