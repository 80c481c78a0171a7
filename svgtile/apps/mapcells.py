"""Cellular classes in a map fill (issue 15; legakis2001 on every unit of a class).

A class of a styles file is *cellular* when its engine draws cells (``engine = "cellular"``),
or when it names no engine and its exemplar carries a cellular description (as ``svgtile
import`` writes one for a bedded or brick tile).  Its units are filled whole — edge and corner
cells follow the whole unit's boundary, which a tile's boundary is not, so a cellular engine
declares an unbounded reach and :func:`svgtile.runners.tiling.plan` never cuts it — and each
gives its cells and lines (:class:`~svgtile.core.cells.Cellwork`, the exemplar's user units)
beside its motifs.

Edges may be labelled by the map's own lines (``label = "fault=#faults"`` names the element
``faults`` of the map being filled; ``fault=OTHER.svg#ID`` a file beside the styles file), so
a tree routes a unit's faulted edges to their own generator (legakis2001 §4.1).
"""

from __future__ import annotations

from pathlib import Path

from svgtile.apps.load import load_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.cells import Cellwork
from svgtile.core.exemplar import Exemplar
from svgtile.core.region import Region
from svgtile.engines import get_engine, synthesize
from svgtile.engines.base import draws_cells
from svgtile.errors import ParameterError, SvgtileError


def is_cellular(engine: str) -> bool:
    """Whether the engine named ``engine`` draws cells (:func:`~svgtile.engines.base.draws_cells`)."""
    return draws_cells(get_engine(engine))


def implied_engine(exemplar: Path) -> str:
    """The engine of a class that names none: ``cellular`` for an exemplar with a cellular
    description, else ``patch`` (also when the exemplar cannot be read: filling its units then
    says why, unit by unit)."""
    try:
        ex, _ = load_exemplar(str(exemplar))
    except SvgtileError:
        return "patch"
    return "cellular" if getattr(ex, "cellular", None) else "patch"


def styles_labels(spec: str, folder: Path, where: str, source: str) -> str:
    """A class's ``label`` value with every ``NAME=FILE#ID`` made relative to the styles file's
    ``folder``; ``NAME=#ID`` (or ``NAME=ID``), the map's own element, is kept for
    :func:`map_labels`.  A malformed item is refused, naming the class."""
    items = []
    for item in filter(None, (s.strip() for s in spec.split(","))):
        name, eq, where_to = item.partition("=")
        file, sep, ident = where_to.partition("#")
        if not (eq and name.strip() and where_to.strip()) or (sep and not ident):
            raise ParameterError(f"{where}: label {item!r}: expected NAME=#ID (an element of the map) or "
                                 "NAME=FILE.svg#ID", source=source)  # fmt: skip
        items.append(f"{name.strip()}={folder / file}#{ident}" if file and sep else item)
    return ",".join(items)


def map_labels(spec: str, map_path: str | Path, gis: bool, where: str) -> str:
    """``spec`` (:func:`styles_labels`) with the map's own elements named in full
    (``NAME=MAP.svg#ID``) for the engine's ``label`` parameter."""
    items = []
    for item in filter(None, spec.split(",")):
        name, _, where_to = item.partition("=")
        file, sep, ident = where_to.partition("#")
        if file and sep:
            items.append(item)
            continue
        if gis:
            raise ParameterError(f"{where}: label {item!r} names a line of the map, and the lines of a GIS map cannot "
                                 "label cells yet: give NAME=LINES.svg#ID", source=str(map_path))  # fmt: skip
        items.append(f"{name}={map_path}#{ident if sep else file}")
    return ",".join(items)


def fill_cells(ex: Exemplar, stats, region: Region, engine: str, *, seed: int, boundary: str, params: dict,
               refine: int) -> tuple[Arrangement, Cellwork]:  # fmt: skip
    """One cellular unit, whole: its motifs and its cells (the exemplar's user units)."""
    result = synthesize(ex, region, engine, seed=seed, stats=stats, boundary=boundary, params=params, refine=refine)
    cells = result.cells if result.cells is not None else Cellwork.empty()
    return result.arrangement, cells

