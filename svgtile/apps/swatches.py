"""A legend sheet of a pattern set: per pattern, the tile repeated beside synthesized textures.

This is how a map maker reviews a whole symbol set (``svgtile swatches``): every tile is imported
(:mod:`svgtile.tiles.importer`), synthesized with the default engine (``auto``) — or with each of
several engines, side by side (``--engine patch --engine growth``) — on the same area as the
repeated tile, and drawn at the same scale; a refused tile (or an engine that refuses it) shows
the reason instead.

The sheet is one SVG: the original tile is a ``<pattern>`` of its own elements (ids prefixed so
that the files cannot clash), the texture a nested ``<svg>`` of the synthesized document.
"""

from __future__ import annotations

import copy
import csv
import io
import math
import re
import textwrap
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

from svgtile.analysis.stats import analyze
from svgtile.apps.load import check_motif_count
from svgtile.core.region import Region
from svgtile.engines import AUTO, synthesize
from svgtile.errors import ExemplarError, SvgtileError
from svgtile.files import read_input
from svgtile.metrics.likeness import measure as measure_likeness
from svgtile.metrics.window import in_window, interior
from svgtile.svg.dialect import SVG_NS, XLINK_NS
from svgtile.svg.reader import parse_exemplar
from svgtile.svg.writer import fmt, svg_document
from svgtile.tiles.importer import import_tile

#: Side of each panel on the sheet, sheet units.
PANEL = 150.0
#: A names CSV (FGDC's INDEX.csv is 40 kB) larger than this is refused before it is read.
MAX_NAMES_BYTES = 16 * 2**20
#: Space between panels and around cells, sheet units.
GAP = 12.0
#: Height of a cell's label, sheet units.
LABEL = 16.0
#: Elements of a tile that never draw and are not copied into the sheet.
SKIP = {"metadata", "title", "desc", "namedview", "script", "style"}


@dataclass(frozen=True)
class Swatch:
    """One pattern and engine on the sheet: ``motifs``/``kinds`` of the import, the texture's
    motif count and its likeness L (:mod:`svgtile.metrics.likeness`; None when undefined), or
    ``refused`` with the reason; ``engine`` is the engine asked for, ``chosen`` the one that drew
    (``auto``'s choice)."""

    path: Path
    label: str
    motifs: int = 0
    kinds: int = 0
    texture: int = 0
    refused: str | None = None
    likeness: float | None = None
    engine: str = AUTO
    chosen: str | None = None


@dataclass(frozen=True)
class Sheet:
    """The sheet's SVG text and its swatches: one per pattern and engine, pattern by pattern."""

    text: str
    swatches: tuple[Swatch, ...]
    engines: tuple[str, ...] = (AUTO,)

    @property
    def patterns(self) -> tuple[tuple[Swatch, ...], ...]:
        """The swatches grouped by pattern, each group in the order of :attr:`engines`."""
        k = len(self.engines)
        return tuple(self.swatches[i : i + k] for i in range(0, len(self.swatches), k))

    @property
    def accepted(self) -> int:
        """Patterns that gave at least one texture."""
        return sum(any(s.refused is None for s in group) for group in self.patterns)

    @property
    def refused(self) -> int:
        return len(self.patterns) - self.accepted


def collect(inputs: list[str] | tuple[str, ...]) -> list[Path]:
    """The ``.svg`` files named or inside the directories named, each directory sorted by name."""
    files: list[Path] = []
    for item in inputs:
        path = Path(item)
        if path.is_dir():
            files.extend(sorted(p for p in path.iterdir() if p.suffix.lower() == ".svg" and p.is_file()))
        else:
            files.append(path)
    return files


def read_names(path: str | Path) -> dict[str, str]:
    """Pattern names from a CSV with a ``name`` column and a ``code`` or ``file`` column (matched
    against the tile's file stem), like the FGDC set's ``INDEX.csv``."""
    text = read_input(path, error=ExemplarError, limit=MAX_NAMES_BYTES)
    try:
        utf16 = text[:2] in (b"\xff\xfe", b"\xfe\xff")  # a spreadsheet's "Unicode text" export
        rows = list(csv.DictReader(io.StringIO(text.decode("utf-16" if utf16 else "utf-8-sig"), newline="")))
    except (UnicodeDecodeError, csv.Error) as exc:
        raise ExemplarError(f"cannot read the names ({exc})", source=str(path)) from None
    names = {}
    for row in rows:
        key = row.get("code") or Path(row.get("file") or "").stem
        if key and row.get("name"):
            names[key] = row["name"]
    if not names:
        raise ExemplarError("no 'name' column with a 'code' or 'file' column", source=str(path))
    return names


def swatch_sheet(
    files: list[Path],
    *,
    swatch: tuple[float, float] | None = None,
    tiles: float = 3.0,
    columns: int = 4,
    seed: int = 1,
    names: dict[str, str] | None = None,
    max_motifs: float = math.inf,
    engines: tuple[str, ...] = (AUTO,),
) -> Sheet:
    """The sheet as SVG text.

    Parameters
    ----------
    files : tile SVGs, in sheet order
    swatch : (w, h) of each synthesized area in the tile's user units; default ``tiles`` tile
        widths and heights
    columns : patterns per row
    seed : seed of every synthesis (the same for each pattern)
    names : file stem -> pattern name, shown after the stem
    max_motifs : a pattern whose swatch would hold more motifs (estimated) is refused
    engines : the engines whose textures stand beside the tile, in this order (``auto``: the
        default engine's choice); with more than one, each panel is captioned with its engine
        and L
    """
    names = names or {}
    engines = tuple(engines)
    if not engines:
        raise ValueError("swatch_sheet needs at least one engine")
    captions = len(engines) > 1  # one engine: the label says L, as it always has
    rows = -(-len(files) // columns)
    cell_w = (1 + len(engines)) * PANEL + (2 + len(engines)) * GAP
    cell_h = PANEL + LABEL + 2 * GAP + (LABEL if captions else 0)
    width, height = columns * cell_w + GAP, rows * cell_h + GAP
    root = ET.Element(f"{{{SVG_NS}}}svg", {
        "viewBox": f"0 0 {fmt(width)} {fmt(height)}", "width": fmt(width), "height": fmt(height),
        "font-family": "DejaVu Sans, Arial, Helvetica, sans-serif",
    })  # fmt: skip
    ET.SubElement(root, f"{{{SVG_NS}}}rect", {"width": fmt(width), "height": fmt(height), "fill": "#ffffff"})
    done = []
    for n, path in enumerate(files):
        x = GAP + (n % columns) * cell_w
        y = GAP + (n // columns) * cell_h
        label = path.stem + (f" {names[path.stem]}" if path.stem in names else "")
        cell = ET.SubElement(root, f"{{{SVG_NS}}}g", {"id": f"swatch-{n + 1}"})
        text = ET.SubElement(cell, f"{{{SVG_NS}}}text", {"x": fmt(x), "y": fmt(y + 11), "font-size": "11"})
        text.text = _short(label, 60)
        top = y + LABEL
        found, original, panels = _swatch(path, label, swatch, tiles, seed, max_motifs, engines=engines)
        done.extend(found)
        if not captions and found[0].likeness is not None:  # the label keeps room for it
            text.text = f"{_short(label, 50)}  L {found[0].likeness:.2f}"
        if original is not None:
            cell.append(_nest(original, f"s{n + 1}o", x, top))
        _frame(cell, x, top)
        if captions:
            _caption(cell, "tile", x, top + PANEL)
        for i, (one, texture) in enumerate(zip(found, panels, strict=True)):
            px = x + (1 + i) * (PANEL + GAP)
            if texture is not None:
                # the first engine's ids are those of a one-engine sheet; the others' get their number
                cell.append(_nest(texture, f"s{n + 1}t" + (f"{i + 1}" if i else ""), px, top))
            else:
                _reason(cell, one.refused or "", px, top)
            _frame(cell, px, top)
            if captions:
                shown = f"  L {one.likeness:.2f}" if one.likeness is not None else ""
                name = engines[i] if one.chosen in (None, engines[i]) else f"{engines[i]} ({one.chosen})"
                _caption(cell, f"{name}{shown}", px, top + PANEL)
    ET.indent(root, space=" ")
    return Sheet(ET.tostring(root, encoding="unicode") + "\n", tuple(done), engines)


# ----------------------------------------------------------------------------- one pattern


def _swatch(path: Path, label: str, swatch, tiles: float, seed: int, max_motifs: float = math.inf, *,
            engines: tuple[str, ...] = (AUTO,)):  # fmt: skip
    """(Swatches, original panel, texture panels) of the tile at ``path``: one Swatch and one
    texture panel per engine of ``engines``, in order; panels are (content root, viewBox) or None.
    The tile is read, imported and analysed once, whatever the number of engines."""
    try:
        data = read_input(path, error=ExemplarError)
        original_root = ET.fromstring(data)
        box = _box(original_root)
    except (OSError, ET.ParseError, ValueError) as exc:
        reason = _oneline(exc if not isinstance(exc, ET.ParseError) else f"not a well-formed XML file ({exc})")
        return [Swatch(path, label, refused=reason, engine=e) for e in engines], None, [None] * len(engines)
    try:
        imported = import_tile(path)
    except SvgtileError as exc:
        reason = str(exc).removeprefix(f"{path}: ")
        original = _repeated(original_root, box, swatch, tiles) if box else None
        return [Swatch(path, label, refused=reason, engine=e) for e in engines], original, [None] * len(engines)
    x0, y0, w, h = imported.box
    sw, sh = swatch if swatch is not None else (tiles * w, tiles * h)
    original = _repeated(original_root, imported.box, (sw, sh), tiles)
    region = Region.rectangle(sw, sh, x0, y0)
    try:
        exemplar = parse_exemplar(imported.text, source=str(path))
        stats = analyze(exemplar)
        check_motif_count(exemplar, stats, region, "the swatch", limit=max_motifs, hint="choose a smaller --size")
    except SvgtileError as exc:
        reason = str(exc).removeprefix(f"{path}: ")
        return [Swatch(path, label, refused=reason, engine=e) for e in engines], original, [None] * len(engines)
    found, panels = [], []
    for engine in engines:
        try:
            made = synthesize(exemplar, region, engine, seed=seed, stats=stats)
        except SvgtileError as exc:
            found.append(Swatch(path, label, refused=str(exc).removeprefix(f"{path}: "), engine=engine))
            panels.append(None)
            continue
        arr = made.arrangement
        texture = ET.fromstring(svg_document(exemplar, arr, region, boundary="clip", params={"seed": seed},
                                             cells=made.cells))  # fmt: skip
        # L on the swatch's interior (one tile in from each edge): few motifs, a rough figure
        inside = in_window(arr, interior(exemplar, region))
        likeness = measure_likeness(exemplar, stats, arr, inside).likeness if inside.any() and made.cells is None else None
        found.append(Swatch(path, label, len(imported), imported.kinds, len(arr), likeness=likeness, engine=engine,
                            chosen=made.engine))  # fmt: skip
        panels.append((texture, (x0, y0, sw, sh)))
    return found, original, panels


def _box(root: ET.Element) -> tuple[float, float, float, float] | None:
    box = root.attrib.get("viewBox")
    if box:
        x, y, w, h = (float(v) for v in re.split(r"[\s,]+", box.strip()))
    else:
        try:
            x, y = 0.0, 0.0
            w = float(re.sub(r"px$", "", root.attrib.get("width", "")))
            h = float(re.sub(r"px$", "", root.attrib.get("height", "")))
        except ValueError:
            return None
    if not (0 < w < math.inf and 0 < h < math.inf and math.isfinite(x) and math.isfinite(y)):
        return None  # nothing to draw the tile in
    return x, y, w, h


def _repeated(root: ET.Element, box, swatch, tiles):
    """An SVG root drawing the tile ``root`` repeated over the swatch area, with its viewBox."""
    x0, y0, w, h = box
    sw, sh = swatch if swatch is not None else (tiles * w, tiles * h)
    out = ET.Element(f"{{{SVG_NS}}}svg")
    defs = ET.SubElement(out, f"{{{SVG_NS}}}defs")
    pattern = ET.SubElement(defs, f"{{{SVG_NS}}}pattern", {
        "id": "tile", "patternUnits": "userSpaceOnUse", "x": fmt(x0), "y": fmt(y0), "width": fmt(w),
        "height": fmt(h), "viewBox": f"{fmt(x0)} {fmt(y0)} {fmt(w)} {fmt(h)}",
    })  # fmt: skip
    for key in ("fill", "stroke", "stroke-width", "style"):
        if key in root.attrib:  # the root's inherited style (Equinor puts fill="none" there)
            pattern.set(key, root.attrib[key])
    for child in root:
        if isinstance(child.tag, str) and child.tag.rsplit("}", 1)[-1] not in SKIP:
            pattern.append(copy.deepcopy(child))
    ET.SubElement(out, f"{{{SVG_NS}}}rect", {
        "x": fmt(x0), "y": fmt(y0), "width": fmt(sw), "height": fmt(sh), "fill": "url(#tile)",
    })  # fmt: skip
    return out, (x0, y0, sw, sh)


_URL = re.compile(r"url\(\s*#([^)\s]+)\s*\)")


def _nest(panel, prefix: str, x: float, y: float) -> ET.Element:
    """A panel as a nested ``<svg>`` at (x, y), PANEL wide, every id prefixed with ``prefix``."""
    content, (vx, vy, vw, vh) = panel
    scale = PANEL / max(vw, vh)
    nested = ET.Element(f"{{{SVG_NS}}}svg", {
        "x": fmt(x), "y": fmt(y), "width": fmt(vw * scale), "height": fmt(vh * scale),
        "viewBox": f"{fmt(vx)} {fmt(vy)} {fmt(vw)} {fmt(vh)}", "overflow": "hidden",
    })  # fmt: skip
    for child in content:
        if isinstance(child.tag, str) and child.tag.rsplit("}", 1)[-1] not in SKIP:
            nested.append(copy.deepcopy(child))
    for el in nested.iter():
        for key, value in list(el.attrib.items()):
            if key == "id":
                el.set(key, f"{prefix}-{value}")
            elif key in ("href", f"{{{XLINK_NS}}}href") and value.startswith("#"):
                el.set(key, f"#{prefix}-{value[1:]}")
            elif "url(" in value:
                el.set(key, _URL.sub(lambda m: f"url(#{prefix}-{m.group(1)})", value))
    return nested


def _frame(parent: ET.Element, x: float, y: float) -> None:
    ET.SubElement(parent, f"{{{SVG_NS}}}rect", {
        "x": fmt(x), "y": fmt(y), "width": fmt(PANEL), "height": fmt(PANEL),
        "fill": "none", "stroke": "#888888", "stroke-width": "0.5",
    })  # fmt: skip


def _caption(parent: ET.Element, text: str, x: float, y: float) -> None:
    """A panel's caption (its engine and L) under the panel at (x, y)."""
    caption = ET.SubElement(parent, f"{{{SVG_NS}}}text", {"x": fmt(x), "y": fmt(y + 12), "font-size": "10"})
    caption.text = _short(text, 30)


def _reason(parent: ET.Element, reason: str, x: float, y: float) -> None:
    text = ET.SubElement(parent, f"{{{SVG_NS}}}text", {"x": fmt(x + 6), "y": fmt(y + 20), "font-size": "9", "fill": "#a00000"})
    text.text = "refused:"
    for i, line in enumerate(textwrap.wrap(reason, 34)[:10]):
        span = ET.SubElement(parent, f"{{{SVG_NS}}}text", {"x": fmt(x + 6), "y": fmt(y + 34 + 11 * i), "font-size": "9"})
        span.text = line


def _short(text: str, limit: int) -> str:
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _oneline(text: object) -> str:
    return " ".join(str(text).split())
