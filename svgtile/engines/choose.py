"""``--engine auto``: the engine and its parameters for an exemplar, from its order (issue 12).

One default for every exemplar serves none of them well: the patch engine's copy rotation turns
rows into staircases, and its copy step lays seams through a lattice.  :func:`choose` reads the
exemplar's order (:func:`svgtile.analysis.order.read_order`) and walks :data:`RULES`, a table of
``(name, test, engine, parameters, why)``; the first rule whose test holds wins.  Adding an engine
to auto's choice is one row: e.g. a growth engine for rows and lattices, or a cellular engine for
bedded tiles, placed above the patch rows it should take over from.

The choice is a plain value (:class:`Choice`), said on stderr by the CLI in one line
(:meth:`Choice.describe`) and recorded in the texture's metadata as the engine and parameters
actually used.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

from svgtile.analysis.order import Order, read_order
from svgtile.analysis.stats import Stats
from svgtile.core.exemplar import Exemplar

#: The name users give to let svgtile choose (``--engine auto``, ``engine = "auto"``).
AUTO = "auto"


@dataclass(frozen=True)
class Choice:
    """The engine auto picked, its parameters and the reason, in the user's words."""

    engine: str
    params: Mapping[str, object] = field(default_factory=dict)
    why: str = ""
    rule: str = ""

    def describe(self) -> str:
        """``engine patch (--grid lattice --max-rotation 0): rows …`` — one line for stderr."""
        opts = " ".join(f"--{k.replace('_', '-')} {_word(v)}" for k, v in self.params.items())
        return f"engine {self.engine}{f' ({opts})' if opts else ''}: {self.why}"


def _word(v: object) -> str:
    return ("true" if v else "false") if isinstance(v, bool) else f"{v:g}" if isinstance(v, float) else str(v)


@dataclass(frozen=True)
class Rule:
    """One row of :data:`RULES`: when ``test(order, stats, exemplar)`` holds, use ``engine`` with
    ``params``."""

    name: str
    test: Callable[[Order, Stats, Exemplar], bool]
    engine: str
    params: Mapping[str, object]
    why: Callable[[Order], str]


def _steps(o: Order) -> str:
    return ", ".join(f"{s.length:.3g} units at {s.angle:.0f}°" for s in o.steps)


#: Rules in order; the last one always holds.  Engines not registered are skipped, so a row for
#: an engine that has not landed yet is harmless.
#:
#: Drawn exemplars (no period) keep the patch defaults even when they show rows: copies of the
#: bundled marsh on its row step (``--grid lattice --max-rotation 0``, turned by 180° and
#: shifted by a step to break the copy period) measured repetition 0.30 against the defaults'
#: 0.08 at 400 × 300, seed 1 — its hand-placed rows repeat their jitter at the copy step.  A
#: growth engine, which grows rows rather than copying them, is the rule to add for them.
#:
#: Repeating tiles with rows or a lattice stay with patch on the period (``tile-order``), not the
#: growth engine: on the 19 regular FGDC/osm-carto tiles (benchmarks/README.md, "Growth engine
#: after the numba kernel", ``benchmarks/growth_vs_patch.py``) growth's likeness L and density
#: ratio are at best equal to patch's (1.000 / 1.000) and lower on FGDC 619 (L 0.864, density
#: 0.770) and 670 (density 0.665), and it is 10–100 times slower.  Growth becomes auto's choice
#: for tiles when it is at least as good there (issue 13).
RULES: tuple[Rule, ...] = (
    Rule("cellular", lambda o, s, e: e.cellular is not None, "cellular", {},
         lambda o: "a bedded or brick pattern (imported as cells): courses of cells that turn the unit's corners "
                   "and follow its edges"),
    Rule("tile-order", lambda o, s, e: o.period is not None and o.kind != "scatter", "patch",
         {"grid": "lattice", "max_rotation": 0.0},
         lambda o: f"a repeating tile with {'a lattice' if o.kind == 'lattice' else 'rows'} (steps {_steps(o)}): "
                   "copies on its period, not turned, so they meet without seams"),
    Rule("scatter", lambda o, s, e: True, "patch", {},
         lambda o: "no repeating rows or lattice to keep: the patch engine's defaults"),
    # reached only when the map controls given leave patch out (see :func:`steerable`)
    Rule("steered", lambda o, s, e: True, "growth", {},
         lambda o: "a flow field, barrier or growth area was given, which the growth engine honours"),
)


def steerable(engines: Mapping[str, object], given: Collection[str]) -> list[str]:
    """Names of the engines that honour every map control in ``given`` (auto chooses among them).

    Parameters
    ----------
    engines : the registered engines by name (:data:`svgtile.engines.ENGINES`)
    given : :meth:`svgtile.engines.base.Controls.given`
    """
    return [name for name, e in engines.items() if set(given) <= set(getattr(e, "controls", ()))]


def choose(exemplar: Exemplar, stats: Stats, *, order: Order | None = None,
           available: Collection[str] | None = None) -> Choice:  # fmt: skip
    """The engine and parameters for ``exemplar`` (the first rule of :data:`RULES` that holds).

    Parameters
    ----------
    exemplar, stats : the exemplar and its analysis
    order : its order, if already read
    available : names of the registered engines (:data:`svgtile.engines.ENGINES`); rules for
        others are skipped.  None: every rule applies.
    """
    order = read_order(exemplar) if order is None else order
    for rule in RULES:
        if (available is None or rule.engine in available) and rule.test(order, stats, exemplar):
            return Choice(rule.engine, dict(rule.params), rule.why(order), rule.name)
    raise AssertionError("the last rule always holds")  # pragma: no cover


def with_choice(choice: Choice, given: Mapping[str, object] | None) -> dict[str, object]:
    """Auto's parameters with those the user gave on top: a user's value always wins."""
    return {**choice.params, **dict(given or {})}
