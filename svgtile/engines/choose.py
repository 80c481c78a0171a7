"""``--engine auto``: the engine and its parameters for an exemplar, from its order (issue 12).

One default for every exemplar serves none of them well: the patch engine's copy rotation turns
rows into staircases, and its copy step lays seams through a lattice.  :func:`choose` reads the
exemplar's order (:func:`svgtile.analysis.order.read_order`) and walks :data:`RULES`, a table of
``(name, test, engine, parameters, why)``; the first rule whose test holds wins.  Adding an engine
to auto's choice is one row placed above the rows it should take over from: the cellular engine
for bedded tiles, the growth engine for drawn rows and lattices.

The choice is a plain value (:class:`Choice`), said on stderr by the CLI in one line
(:meth:`Choice.describe`) and recorded in the texture's metadata as the engine and parameters
actually used.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, field

from svgtile.analysis.order import Order, read_order, stamp_repeats
from svgtile.analysis.stats import Stats
from svgtile.core.exemplar import Exemplar
from svgtile.engines.growth import grows_from, rows_wander
from svgtile.engines.jitter import rows_fit, rows_repeat_within

#: A tile's rows go to :func:`svgtile.engines.jitter.redraw` (rule ``tile-jitter``) when at least
#: this share of its (row, phase) pairs keep the distance rule (:func:`~svgtile.engines.jitter.rows_fit`):
#: FGDC 616, 617, 654, 669 1.000, 618 0.849; 621 0.753 (redrawn: L 0.40) and 670 0.472 (its
#: columns locked to their neighbours: every redraw falls back to the tile) stay stamped.
#: Redrawn (benchmarks/README.md, jit12): 669 passes every gate (repetition 0.033, L 0.97);
#: 616 and 618 repeat less (0.73) at L 0.96–0.97; 617 and 654 still repeat at (w, 0) (1.000, L
#: 0.92–0.94), their rows' kinds running on whole along x.  The same share of the rows must have
#: kinds that repeat within the period (:func:`~svgtile.engines.jitter.rows_repeat_within`): 654's
#: six kinds come in an order that repeats only at the period (0.0), so it stays stamped; 617
#: (1.0) is still redrawn.
ROWS_FIT = 0.8

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
#: Drawn exemplars (no period) with rows or a lattice get the growth engine (``drawn-order``),
#: which grows rows and lattices motif by motif instead of copying them: on the bundled marsh
#: (rows) and sand (lattice), 300 × 300, seeds 1–3 (benchmarks/README.md, "Growth as auto's
#: choice", ``benchmarks/growth_auto.py``), growth keeps the order better in every run — likeness
#: L 0.67–0.72 against patch's 0.55–0.65 on marsh, 0.87–0.89 against 0.23–0.46 on sand — with no
#: overlaps or violators, at a cost: marsh's density ratio 0.90–0.91 against 0.93–0.96, sand's
#: repetition 0.22 against 0.10, and 3–10 times patch's time.  (Copies of marsh on its row step,
#: ``--grid lattice --max-rotation 0``, repeated its hand-placed jitter at the copy step:
#: repetition 0.30 against 0.08.)
#:
#: Drawn rows on one line (``one-line``: FGDC 624, 625 and nine map-pattern symbols, a column of
#: marks) go to patch: growth grows from rings of neighbours, which centres on one line have not
#: (:func:`svgtile.engines.growth.grows_from`; it ended in an internal error there).
#:
#: Repeating tiles with rows or a lattice stay with patch on the period (``tile-order``): there
#: the tile's exact period makes patch's copies the tile itself (L 1.000, density 1.000 on the 20
#: regular FGDC/osm-carto tiles), and growth, which on a tile keeps to the tile's own sites, gives
#: the same figures (L 1.000, density 1.000–1.001, repetition equal) 20–100 times slower.
#:
#: Repeating tiles of scattered marks (``tile-scatter``: a period, no rows or lattice; FGDC
#: breccias, conglomerates, tills, 601–730, and the osm-carto leaf-type and unpaved symbols, 35
#: of the 146 gate tiles) go to optimize: with patch's defaults likeness was L −0.04–0.68 (34
#: below 0.6), with optimize 0.67–0.85 (none below 0.6, 11 at 0.8 or more), mean 0.27 → 0.77
#: (tests/test_wholeset.py's gates, seed 1, gate_region; benchmarks/wholeset_figures.py).  Its
#: density stays in 0.9–1.1 on 33 of 35 (32 with patch; 605 0.94 → 0.85, 714 0.99 → 0.87), kind-mix
#: TV > 0.05 on 7 (9; 605 0.050 → 0.078, 606 0.049 → 0.061 new), repetition > 0.2 on 12 (10; new on
#: 606, 612–614, 681–685, 715, 723 at 0.203–0.417, gone on 605, 608, 702, 722, 730 and four leaf
#: types), no overlaps or violators either way; whole-set KNOWN entries 79 → 44.  Its cost (synth
#: over the gate region, a loaded 2-core machine): 16 s → 104 s over the 35, 0.6–3× patch's on 20
#: of them, up to 150× on large tiles (FGDC 603, 990 motifs: 0.1 s → 15 s; 609, 655: 13 s).
#: Since optimize's refilled start takes patches of 0.65 of the period, with no overlap (and the
#: seeded first search on 11 of the 35, the tiles of 18.5 spacings or more; 2026-12-05,
#: optimize/engine.py TILE_CELL): L 0.66–0.90, mean 0.80 (19 at
#: 0.8 or more), density in bounds on 34 (606 0.88), TV > 0.05 on 11, repetition > 0.2 on 5
#: (605, 606, 682, 723, 725 at 0.21–0.25), every bound met on 21 of the 35 (20 before, 14 with
#: patches of the whole period); KNOWN entries for them 21 → 17; 215 s over the 35.  Since
#: optimize fills a refilled texture light as a whole (2026-12-06, optimize/engine.py
#: ``fill_light``), density is in bounds on all 35 (606 0.883 → 0.941, L 0.706 → 0.703); the
#: other 34 are as before (their figures identical: the step returns the solver's texture).
#: Drawn scatters (no period: the bundled exemplars) keep patch's defaults, their textures
#: byte-identical (240 × 160, seed 1).
RULES: tuple[Rule, ...] = (
    Rule("cellular", lambda o, s, e: e.cellular is not None, "cellular", {},
         lambda o: "a bedded or brick pattern (imported as cells): courses of cells that turn the unit's corners "
                   "and follow its edges"),
    Rule("tile-rows", lambda o, s, e: o.period is not None and o.kind != "scatter" and stamp_repeats(e, o)
         and rows_wander(e, s.distance), "growth", {},
         lambda o: f"a repeating tile of rows exact along x at hand-drawn phases (steps {_steps(o)}): copies on "
                   "its period would repeat its rows' phases, which its own exact steps do not reproduce, so "
                   "grown with each row at a phase the tile's row-to-row steps give"),
    Rule("tile-jitter", lambda o, s, e: o.period is not None and o.kind != "scatter" and stamp_repeats(e, o)
         and rows_repeat_within(e, o) >= ROWS_FIT and rows_fit(e, o, s.distance) >= ROWS_FIT, "tile", {"redraw_jitter": True},
         lambda o: f"a repeating tile of rows exact along their step at hand-drawn phases (steps {_steps(o)}): "
                   "copies of the tile with each row at a phase drawn from the tile's rows' phases and the other "
                   "motifs' jitter drawn anew, so the rows stay exact and the tile's period does not repeat"),
    Rule("tile-order", lambda o, s, e: o.period is not None and o.kind != "scatter", "patch",
         {"grid": "lattice", "max_rotation": 0.0},
         lambda o: f"a repeating tile with {'a lattice' if o.kind == 'lattice' else 'rows'} (steps {_steps(o)}): "
                   "copies on its period, not turned, so they meet without seams (the tile itself; growth "
                   "gives the same, slower)"),
    Rule("one-line", lambda o, s, e: o.period is None and o.kind != "scatter" and not grows_from(e), "patch", {},
         lambda o: f"drawn rows on one line (steps {_steps(o)}): no rings for growth to grow from, so the patch "
                   "engine's defaults"),
    Rule("drawn-order", lambda o, s, e: o.period is None and o.kind != "scatter", "growth", {},
         lambda o: f"drawn {'a lattice' if o.kind == 'lattice' else 'rows'} (steps {_steps(o)}): grown motif by "
                   "motif from the exemplar's neighbourhoods, so rows and lattices continue"),
    Rule("tile-scatter", lambda o, s, e: o.period is not None and o.kind == "scatter", "optimize", {},
         lambda o: "a repeating tile of scattered marks, no rows or lattice to keep: copies of the tile, then "
                   "every mark's neighbours pulled towards the tile's own, so the marks keep their spacing and "
                   "mix without the seams and turned copies of the patch engine"),
    Rule("scatter", lambda o, s, e: True, "patch", {},
         lambda o: "no repeating rows or lattice to keep: the patch engine's defaults" if o.kind == "scatter" else
                   f"{'a lattice' if o.kind == 'lattice' else 'rows'} (steps {_steps(o)}), but the options given or "
                   "the region's size leave the engines that keep them: the patch engine's defaults"),
    # reached only when the map controls or options given leave patch out (see :func:`steerable`)
    Rule("steered", lambda o, s, e: True, "growth", {},
         lambda o: "the map controls or options given (a flow field, barrier, growth area, a growth parameter) "
                   "are the growth engine's"),
)


def steerable(engines: Mapping[str, object], given: Collection[str], params: Collection[str] = ()) -> list[str]:
    """Names of the engines that honour every map control in ``given`` and take every parameter
    in ``params`` (auto chooses among them): an option the user gave with auto, such as patch's
    ``--max-rotation 0`` for upright reeds, keeps auto to the engines it belongs to.

    Parameters
    ----------
    engines : the registered engines by name (:data:`svgtile.engines.ENGINES`)
    given : :meth:`svgtile.engines.base.Controls.given`
    params : names of the parameters given with auto (``EngineParams`` field names)
    """
    honour = [name for name, e in engines.items() if set(given) <= set(getattr(e, "controls", ()))]
    takes = [name for name in honour
             if set(params) <= set(getattr(getattr(engines[name], "Params", None), "__dataclass_fields__", ()))]  # fmt: skip
    return takes or honour  # none takes them all: the engine chosen refuses the stray option in one line


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
    # the options given belong to an engine no rule picks (optimize's --passes, cellular's --strike)
    name = next(iter(available or ()), None)
    if name is None:
        raise ValueError("choose: no engine available")
    return Choice(name, {}, f"the options given are the {name} engine's", "options")


#: The engines a rule of :data:`RULES` picks (auto passes over the others unless options name them).
RULE_ENGINES = frozenset(rule.engine for rule in RULES)


def with_choice(choice: Choice, given: Mapping[str, object] | None) -> dict[str, object]:
    """Auto's parameters with those the user gave on top: a user's value always wins."""
    return {**choice.params, **dict(given or {})}
