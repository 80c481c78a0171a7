"""The one exemplar loader (read or import, then analyse, once per process) and the one
motif-count guard every command runs before synthesis."""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from functools import lru_cache

from svgtile.analysis.crowding import check_crowding
from svgtile.analysis.stats import Stats, analyze, motif_estimate
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.errors import ParameterError
from svgtile.svg.reader import parse_exemplar, read_exemplar

#: Above this estimated motif count synthesis is refused unless forced (the estimate is the
#: exemplar's motifs per unit area times the output area).  Two million motifs take about a
#: minute and a few GB of memory, and make an SVG of some 180 MB that few viewers can open.
MAX_MOTIFS = 2_000_000
#: Refused even when forced: no machine holds this many motifs (about 1 kB each) in memory.
HARD_MAX_MOTIFS = 1e9
#: Above this estimated work (CPU seconds on the reference machine) synthesis is refused unless
#: forced: a run the user did not expect to take minutes is stopped before it starts, with the
#: estimate, instead of running away (issue 16).
MAX_WORK_SECONDS = 60.0


@lru_cache(maxsize=32)
def _read(path: str, as_tile: bool, stamp: tuple[int, int] | None) -> tuple[Exemplar, Stats, tuple[str, ...]]:
    if as_tile:
        from svgtile.tiles.importer import import_tile

        imported = import_tile(path)
        exemplar = parse_exemplar(imported.text, source=path)
        notes = tuple(imported.notes)
    else:
        exemplar = read_exemplar(path)
        notes = exemplar.warnings
    check_crowding(exemplar, imported=as_tile)  # before the analysis, which would run away
    stats = analyze(exemplar)
    if stats.overlaps:
        notes = (*notes, f"{stats.overlaps} pair(s) of motifs overlap in the exemplar; continuing")
    return exemplar, stats, notes


def _stamp(path: str) -> tuple[int, int] | None:
    """What keys the cache besides the path: an edited file is read again (None if unreadable:
    the reader then says why)."""
    try:
        st = os.stat(path)
    except OSError:
        return None
    return st.st_mtime_ns, st.st_size


def load_exemplar(path: str, *, as_tile: bool = False,
                  warn: Callable[[str], None] | None = None) -> tuple[Exemplar, Stats]:  # fmt: skip
    """An exemplar and its analysis, read once per process (a map fills many units of a class).

    Parameters
    ----------
    path : the exemplar SVG, or with ``as_tile`` a seamless pattern tile to import first
        (:func:`svgtile.tiles.importer.import_tile`)
    warn : called with each non-fatal problem, ``"PATH: message"`` (the reader's warnings, the
        import's notes, overlapping motifs), on every call
    """
    exemplar, stats, notes = _read(str(path), as_tile, _stamp(path))
    if warn is not None:
        for note in notes:
            warn(f"{path}: {note}")
    return exemplar, stats


def check_motif_count(exemplar: Exemplar, stats: Stats, region: Region, where: str, *,
                      limit: float = MAX_MOTIFS, hint: str = "", forceable: bool = False) -> float:  # fmt: skip
    """Refuse ``region`` if its estimated motif count is above ``limit`` or :data:`HARD_MAX_MOTIFS`.

    Parameters
    ----------
    where : names the region in the message (``--size 800x600``, ``the shape 'path12'`` …)
    limit : the caller's limit (``math.inf`` with ``--force``)
    hint : what the user can do, appended to the message (``choose a smaller --size`` …)
    forceable : the caller has ``--force``: say so when only ``limit`` is exceeded

    Returns
    -------
    The estimate (:func:`svgtile.analysis.stats.motif_estimate`).
    """
    estimate = motif_estimate(exemplar, stats, region)
    if not estimate <= HARD_MAX_MOTIFS:
        about = f"about {estimate:.3g}" if math.isfinite(estimate) else "countless"
        raise ParameterError(f"{where} would hold {about} motifs, more than svgtile can hold in memory"
                             + (f"; {hint}" if hint else ""))  # fmt: skip
    if estimate > limit:
        hints = [h for h in (hint, "use --force to run anyway" if forceable else "") if h]
        raise ParameterError(f"{where} would hold about {estimate:,.0f} motifs (limit {limit:,.0f})"
                             + "".join(f"; {h}" for h in hints))  # fmt: skip
    return estimate


def check_work(estimate: float, engines: str | Sequence[str], where: str, *, refine: int = 0, workers: int = 1,
               limit: float = MAX_WORK_SECONDS, forceable: bool = False, params: object = None) -> float:  # fmt: skip
    """Refuse a run whose estimated work is over ``limit`` seconds.

    The work is ``estimate`` motifs (:func:`check_motif_count`) times the engine's declared
    :func:`~svgtile.engines.base.seconds_per_motif` (summed over ``engines`` when a command runs
    several), plus ``refine`` iterations of the optimize solver's per-motif cost (and one for
    each of the optimize engine's ``passes`` beyond the default its declaration was measured
    at), shared among ``workers`` for a tiled run.  The declarations are CPU seconds on the
    machine of ``benchmarks/work_per_motif.py`` (2 cores, see benchmarks/README.md), rounded up:
    a faster machine finishes sooner; the refusal is about minutes, not seconds.

    Parameters
    ----------
    estimate : motifs the run will place
    engines : the engine's name (resolved, not ``auto``), or the names of each engine run
    where : names the region in the message (``--size 800x600``)
    limit : ``math.inf`` with ``--force``
    forceable : the caller has ``--force``: say so
    params : the engine's parameters (an ``EngineParams``), if known: the optimize engine's
        ``passes``

    Returns
    -------
    The estimated seconds.
    """
    from svgtile.engines import get_engine
    from svgtile.engines.base import seconds_per_motif

    names = (engines,) if isinstance(engines, str) else tuple(engines)
    per_motif = sum(seconds_per_motif(get_engine(n)) for n in names)
    solver = get_engine("optimize")
    passes = getattr(params, "passes", None) if isinstance(params, solver.Params) and "optimize" in names else None
    more = max(0, int(passes) - solver.Params().passes) if passes is not None else 0  # beyond the measured default
    if refine or more:
        per_motif += (refine * len(names) + more) * float(solver.refine_seconds_per_motif)
    seconds = estimate * per_motif / max(1, workers)
    if seconds > limit:
        smaller = f"choose a smaller {where.split()[0]}" if where.startswith("--") else "fill a smaller area"
        hints = ["use --force to run anyway" if forceable else "", smaller]
        about = f"{seconds / 60:.0f} min" if seconds >= 120 else f"{seconds:.0f} s"
        who = f"engine {names[0]!r}" if len(names) == 1 else "engines " + ", ".join(map(repr, names))
        extra = (f" with --passes {passes}" if more else "") + (f" with --refine {refine}" if refine else "")
        raise ParameterError(f"{where} would hold about {estimate:,.0f} motifs: about {about} of work for {who}{extra} "
                             f"(limit {limit:.0f} s)" + "".join(f"; {h}" for h in hints if h))  # fmt: skip
    return seconds
