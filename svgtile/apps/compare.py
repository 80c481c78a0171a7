"""Engines side by side: synthesize with each, score each, one table (issue 3, ``svgtile compare``).

:func:`compare` runs the engines on one region with one seed and scores every texture with
:func:`svgtile.metrics.score`; :func:`format_table` prints engines as columns and figures as
rows; :func:`format_score` prints one texture's figures (``svgtile score``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from svgtile.analysis.stats import Stats
from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.engines import ENGINES, engines_with, synthesize
from svgtile.errors import ParameterError
from svgtile.metrics import Score, score

#: The rows of the tables: (field of :class:`~svgtile.metrics.Score`, label, number format).
FIGURES: tuple[tuple[str, str, str], ...] = (
    ("motifs", "motifs in the interior", "d"),
    ("overlaps", "overlapping pairs", "d"),
    ("violators", "distance-rule violators", "d"),
    ("density_ratio", "density / ρ", ".3f"),
    ("density_cv", "density CV over windows", ".3f"),
    ("density_min_ratio", "window density min / ρ", ".3f"),
    ("density_max_ratio", "window density max / ρ", ".3f"),
    ("kind_mix_tv", "kind mix TV", ".3f"),
    ("kind_mix_tv_kinds", "  per kind", ".3f"),
    ("kind_mix_noise", "  its sampling noise", ".3f"),
    ("orientation_outside", "orientation outside arcs", ".3f"),
    ("gap_distance", "structure: nearest-gap W1", ".3f"),
    ("gap_noise", "  its sampling noise", ".3f"),
    ("pair_correlation_distance", "structure: pair correlation", ".3f"),
    ("repetition", "repetition", ".3f"),
    ("repetition_total", "  incl. exemplar's lattice", ".3f"),
    ("coverage", "coverage (empty disc ratio)", ".2f"),
    ("neighbourhood_distance", "neighbourhood distance", ".3f"),
    ("likeness", "likeness L", ".2f"),
)
#: Rows left out of a table where no texture has the figure (the per-kind mix and its noise are
#: measured only where rare kinds are pooled into shape classes).
OPTIONAL = frozenset({"kind_mix_tv_kinds", "kind_mix_noise"})


def _rows(scores: Sequence[Score]) -> list[tuple[str, str, str]]:
    """The rows of :data:`FIGURES` that at least one of ``scores`` has, or that are never left out."""
    return [row for row in FIGURES if row[0] not in OPTIONAL or any(getattr(s, row[0]) is not None for s in scores)]


@dataclass(frozen=True, eq=False)
class EngineScore:
    """One engine's texture and its figures."""

    engine: str
    arrangement: Arrangement
    score: Score


def compare(
    exemplar: Exemplar, stats: Stats, region: Region, *, engines: Sequence[str] = ("patch", "tile", "random"),
    seed: int = 1, progress: Callable[[str, float], None] | None = None, boundary: str = "clip", **params,
) -> list[EngineScore]:  # fmt: skip
    """Synthesize ``region`` with each engine (one seed for all) and score each texture.

    Parameters
    ----------
    exemplar, stats : the exemplar and its analysis
    region : the output region
    engines : names in :data:`svgtile.engines.ENGINES`, in the order of the table's columns
    seed : every engine runs with this seed
    progress : called as ``progress(engine, fraction of the engines done)``
    boundary : how motifs meet the region's edge, for every engine
    **params : engine parameters (``grid``, ``overlap`` …); each engine takes those it has

    Raises
    ------
    ParameterError
        An unknown or repeated engine name, or none.
    """
    engines = list(engines)
    unknown = [e for e in engines if e not in ENGINES]
    if unknown or not engines or len(set(engines)) != len(engines):
        what = f"unknown engine {unknown[0]!r}" if unknown else "each engine at most once, at least one"
        raise ParameterError(f"--engines: {what} (choose from {', '.join(sorted(ENGINES))})")
    stray = [k for k in params if not engines_with(k)]
    if stray:
        raise ParameterError(f"no engine has a parameter {stray[0]!r}")
    out = []
    for n, name in enumerate(engines):
        if progress:
            progress(name, n / len(engines))
        own = ENGINES[name].Params.public_names()  # each engine takes the parameters it has
        arr = synthesize(exemplar, region, name, seed=seed, stats=stats, boundary=boundary,
                         params={k: v for k, v in params.items() if k in own}).arrangement  # fmt: skip
        out.append(EngineScore(name, arr, score(exemplar, stats, arr, region)))
    return out


def _cell(value, spec: str) -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    return format(value, spec)


def format_table(results: Sequence[EngineScore]) -> str:
    """Engines as columns, figures (:data:`FIGURES`) as rows, as plain text."""
    label = max(len(lab) for _, lab, _ in FIGURES)
    width = max(9, *(len(r.engine) for r in results))
    lines = [f"{'figure':<{label}}  " + "  ".join(f"{r.engine:>{width}}" for r in results)]
    for key, lab, spec in _rows([r.score for r in results]):
        lines.append(f"{lab:<{label}}  " + "  ".join(f"{_cell(getattr(r.score, key), spec):>{width}}" for r in results))
    return "\n".join(lines)


def format_markdown(results: Sequence[EngineScore]) -> str:
    """:func:`format_table` as a Markdown table."""
    lines = ["| figure | " + " | ".join(r.engine for r in results) + " |", "|---" * (len(results) + 1) + "|"]
    for key, lab, spec in _rows([r.score for r in results]):
        lines.append(f"| {lab} | " + " | ".join(_cell(getattr(r.score, key), spec) for r in results) + " |")
    return "\n".join(lines)


def format_score(score: Score) -> str:
    """One texture's figures, then its structure per kind pair, as plain text."""
    label = max(len(lab) for _, lab, _ in FIGURES)
    lines = [f"measured on the {score.window} ({score.window_area:.6g} square units, "
             f"mean spacing s = {_cell(score.spacing, '.4g')})"]  # fmt: skip
    lines += [f"{lab:<{label}}  {_cell(getattr(score, key), spec):>9}" for key, lab, spec in _rows([score])]
    lines.append(f"{'  of tile · random':<{label}}  {_cell(score.neighbourhood_tile, '.3f'):>9}"
                 f"  {_cell(score.neighbourhood_random, '.3f')}")  # fmt: skip
    pairs = [p for p in score.kind_pairs if p.gap_distance is not None or p.pair_correlation_distance is not None]
    if pairs:
        lines += ["", "structure per kind pair (gap W1, its sampling noise, pair correlation):"]
        width = max(label - 2, *(len(" → ".join(p.names)) for p in pairs))  # long names keep the columns
        for p in pairs:
            names = " → ".join(p.names)
            gap, pc = _cell(p.gap_distance, ".3f"), _cell(p.pair_correlation_distance, ".3f")
            lines.append(f"  {names:<{width}}  {gap:>9}  {_cell(p.gap_noise, '.3f'):>9}  {pc:>9}")
    return "\n".join(lines)
