"""The tree of pattern generators (legakis2001 §4.1), read from a small TOML or JSON description.

Features enter at the root and are routed down: a node passes a feature to the first of its
children whose test it passes — by type (``feature``: corner, edge, face), by ``label`` (§3.1),
or by geometric analysis (§5.3: an edge's ``direction``, its place on a hole's ``top`` or
``bottom``, a corner's ``convex``-ity) — and a leaf names the ``generator`` that makes the
feature's cells.  A feature no leaf takes gets no cells (its space is left to the face).

A description, in TOML (JSON has the same keys)::

    course = 6.0            # course height, user units (t)
    length = 12.0           # cell length along the course, user units (s)
    offset = 0.5            # shift of each course against the one below, share of a length
    mortar = 0.0            # gap between cells, user units (§5.4)
    angle = 0.0             # the courses' bearing, degrees (when no --strike is given)
    cell_style = "fill:none;stroke:#000;stroke-width:0.3"

    [[tree]]                # the root's children, tried in order
    feature = "edge"
    label = "fault"
    generator = "edge_blocks"
    [[tree]]
    feature = "corner"
    generator = "corner"
    [[tree]]
    feature = "edge"
    generator = "edge_bricks"
    [[tree]]
    feature = "face"
    generator = "bricks"

    [[lines]]               # bedding lines along the courses (optional; one table per kind)
    every = 1               # a line every this many courses …
    start = 0               # … on the courses j with j % every == start
    dash = [3.0, 1.5]       # on, off lengths (omit for solid lines)
    offset = 0.5            # dash shift per course, share of the dash period
    shift = 0.0             # dash shift of every line, share of the dash period
    style = "fill:none;stroke:#000;stroke-width:0.3"
    wave = [0.0, 0.4, 0.0, -0.4]   # a wavy line: its offset across the course at even steps …
    wave_period = 12.0      # … along this length, user units (repeating; omit for straight lines)

    [motifs]                # exemplar motifs set in cells (optional)
    share = 0.25            # share of cells holding one
    over = false            # true: drawn over the cells' lines, not inside a cell (peat's
                            # fragments, FGDC 657); only kept clear of each other

    [bands]                 # interbedded courses of unequal heights (optional; FGDC 672, 677)
    period = 15.0           # the repeat across the courses, user units
    rows = [0.0, 3.3, 6.5]  # where course j starts: (j // 3) · period + rows[j % 3]
    cut = [0]               # the courses j % 3 in this list are cut into cells, the rest stay open

A node may hold ``children`` (a list of nodes) instead of a ``generator``: its tests apply to the
whole subtree.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import tomllib

from svgtile.errors import ParameterError
from svgtile.files import read_input

#: Generators by the feature type they texture (§5.2).
GENERATORS = {
    "corner": ("corner", "blocks", "none"),
    "edge": ("edge_bricks", "edge_blocks", "blocks", "none"),
    "face": ("bricks", "blocks", "ashlar", "rhombs", "none"),
}
_TESTS = ("feature", "label", "direction", "hole", "convex")
_NODE_KEYS = {*_TESTS, "generator", "children", "style"}
_TOP_KEYS = {"course", "length", "offset", "mortar", "cell_style", "tree", "lines", "motifs", "ashlar", "rhomb_angle",
             "angle", "bands"}


@dataclass(frozen=True)
class Node:
    """One node of the tree: its tests, and a generator (a leaf) or children."""

    tests: tuple[tuple[str, Any], ...] = ()
    generator: str | None = None
    style: str | None = None
    children: tuple[Node, ...] = ()

    def route(self, feature: dict[str, Any]) -> Node | None:
        """The leaf that takes ``feature`` (its type, label and geometry), or None."""
        if not all(_passes(name, want, feature) for name, want in self.tests):
            return None
        if self.generator is not None:
            return self
        for child in self.children:
            leaf = child.route(feature)
            if leaf is not None:
                return leaf
        return None


def _passes(name: str, want: Any, feature: dict[str, Any]) -> bool:
    have = feature.get(name)
    if name == "direction":  # an edge's axis within [lo, hi] degrees (mod 180)
        if have is None:
            return False
        lo, hi = want
        return (have - lo) % 180.0 <= (hi - lo) % 180.0
    return have == want


@dataclass(frozen=True)
class Description:
    """A cellular pattern: sizes, the generator tree, bedding lines and motifs in cells.

    Attributes
    ----------
    course, length : user units, course height (t) and cell length (s); 0 = from the exemplar
    offset : share of ``length`` each course is shifted against the one below (0.5 = running bond)
    mortar : user units, the gap between adjacent cells (§5.4)
    cell_style : CSS style of the cells' paths ("" = cells not drawn, only claimed)
    tree : the root
    lines : the bedding lines, one dict per kind of line (``every``, ``start``, ``dash``,
        ``offset``, ``shift``, ``style``), or None
    angle : degrees, the courses' bearing when the run gives none
    motifs : the motifs in cells (``share``), or None
    ashlar : (max length, max height) of a random ashlar stone, in grid cells of a third of a course
    rhomb_angle : degrees, the slant of a rhomb's joints from the course normal
    bands : interbedded courses, or None for courses all ``course`` high (:class:`Bands`)
    """

    course: float = 0.0
    length: float = 0.0
    offset: float = 0.5
    mortar: float = 0.0
    cell_style: str = "fill:none;stroke:#000000;stroke-width:0.3"
    tree: Node = field(default_factory=lambda: default_tree())
    lines: tuple[dict[str, Any], ...] | None = None
    motifs: dict[str, Any] | None = None
    ashlar: tuple[int, int] = (4, 2)
    rhomb_angle: float = 45.0
    angle: float = 0.0
    bands: Bands | None = None


@dataclass(frozen=True)
class Bands:
    """Courses of unequal heights repeating across the bedding (interbedded series).

    Attributes
    ----------
    period : user units, the repeat across the courses
    rows : (k,) increasing offsets in [0, period), user units, of the courses' lower sides: course
        ``j`` runs from ``t(j) = (j // k) · period + rows[j % k]`` to ``t(j + 1)``
    cut : the courses ``j % k`` cut into cells (the others are left open: bedding lines only)
    """

    period: float
    rows: tuple[float, ...]
    cut: tuple[int, ...]

    def scaled(self, factor: float) -> Bands:
        return Bands(self.period * factor, tuple(r * factor for r in self.rows), self.cut)


def default_tree(face: str = "bricks") -> Node:
    """Corner bricks, alternating edge bricks, ``face`` on the face: the paper's "Bricks" tree."""
    return Node(children=(
        Node((("feature", "corner"),), "corner"),
        Node((("feature", "edge"),), "edge_bricks"),
        Node((("feature", "face"),), face),
    ))  # fmt: skip


def parse_description(data: dict[str, Any], source: str = "the description") -> Description:
    """A :class:`Description` from parsed TOML/JSON; a ParameterError naming ``source`` otherwise."""

    def bad(message: str) -> ParameterError:
        return ParameterError(f"{source}: {message}")

    if not isinstance(data, dict):
        raise bad("not a table of keys")
    unknown = sorted(set(data) - _TOP_KEYS)
    if unknown:
        raise bad(f"unknown key {unknown[0]!r} (keys: {', '.join(sorted(_TOP_KEYS))})")
    out: dict[str, Any] = {}
    for key in ("course", "length", "offset", "mortar", "rhomb_angle", "angle"):
        if key in data:
            value = data[key]
            if isinstance(value, bool) or not isinstance(value, (int, float)) or value != value:
                raise bad(f"{key} must be a number")
            if key in ("course", "length", "mortar") and value < 0:
                raise bad(f"{key} must not be negative")
            out[key] = float(value)
    if "cell_style" in data:
        if not isinstance(data["cell_style"], str):
            raise bad("cell_style must be text")
        out["cell_style"] = data["cell_style"]
    if "ashlar" in data:
        a = data["ashlar"]
        if not (isinstance(a, list) and len(a) == 2 and all(isinstance(v, int) and v >= 1 for v in a)):
            raise bad("ashlar must be two whole numbers ≥ 1 (max length, max height)")
        out["ashlar"] = (a[0], a[1])
    if "bands" in data:
        out["bands"] = _bands(data["bands"], bad)
    if "tree" in data:
        out["tree"] = Node(children=tuple(_node(n, bad) for n in _list(data["tree"], "tree", bad)))
    if "motifs" in data:
        if not isinstance(data["motifs"], dict):
            raise bad("motifs must be a table")
        out["motifs"] = dict(data["motifs"])
        if not isinstance(out["motifs"].get("over", False), bool):
            raise bad("motifs.over must be true or false")
    if "lines" in data:
        specs = data["lines"] if isinstance(data["lines"], list) else [data["lines"]]
        if not all(isinstance(spec, dict) for spec in specs):
            raise bad("lines must be a table or a list of tables")
        out["lines"] = tuple(_line_spec(spec, bad) for spec in specs)
    return Description(**out)


def _bands(b: Any, bad) -> Bands:
    if not (isinstance(b, dict) and set(b) == {"period", "rows", "cut"}):
        raise bad("bands must be a table of period, rows and cut")
    period, rows, cut = b["period"], b["rows"], b["cut"]
    number = (int, float)
    if isinstance(period, bool) or not isinstance(period, number) or not 0 < period < math.inf:
        raise bad("bands.period must be a positive number")
    if not (isinstance(rows, list) and rows and all(isinstance(r, number) and not isinstance(r, bool) for r in rows)
            and all(0 <= a < b for a, b in zip(rows, [*rows[1:], period], strict=True))):  # fmt: skip
        raise bad("bands.rows must be increasing numbers in [0, period)")
    if not (isinstance(cut, list) and all(isinstance(k, int) and not isinstance(k, bool) and 0 <= k < len(rows) for k in cut)):
        raise bad("bands.cut must be course numbers in [0, number of rows)")
    return Bands(float(period), tuple(float(r) for r in rows), tuple(sorted(set(cut))))


_LINE_KEYS = {"every": 1, "start": 0, "dash": None, "offset": 0.0, "shift": 0.0, "style": None, "wave": None,
              "wave_period": 0.0}


def _line_spec(spec: dict[str, Any], bad) -> dict[str, Any]:
    unknown = sorted(set(spec) - set(_LINE_KEYS))
    if unknown:
        raise bad(f"unknown lines key {unknown[0]!r} (keys: {', '.join(_LINE_KEYS)})")
    out = {**_LINE_KEYS, **spec}
    dash = out["dash"]
    if dash is not None and not (isinstance(dash, list) and len(dash) == 2
                                 and all(isinstance(v, (int, float)) and v > 0 for v in dash)):  # fmt: skip
        raise bad("lines.dash must be two positive numbers (on, off)")
    if not (isinstance(out["every"], int) and out["every"] >= 1 and isinstance(out["start"], int)):
        raise bad("lines.every must be a whole number ≥ 1, lines.start a whole number")
    for key in ("offset", "shift"):
        if isinstance(out[key], bool) or not isinstance(out[key], (int, float)):
            raise bad(f"lines.{key} must be a number")
    if out["style"] is not None and not isinstance(out["style"], str):
        raise bad("lines.style must be text")
    wave, period = out["wave"], out["wave_period"]
    if wave is not None and not (
        isinstance(wave, list) and len(wave) >= 2 and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                          and math.isfinite(v) for v in wave)
        and isinstance(period, (int, float)) and not isinstance(period, bool) and 0 < period < math.inf):  # fmt: skip
        raise bad("lines.wave must be two or more offsets, with a positive lines.wave_period")
    return out


def _list(value: Any, where: str, bad) -> list:
    if not isinstance(value, list):
        raise bad(f"{where} must be a list of nodes")
    return value


def _node(data: Any, bad) -> Node:
    if not isinstance(data, dict):
        raise bad("a tree node must be a table")
    unknown = sorted(set(data) - _NODE_KEYS)
    if unknown:
        raise bad(f"unknown tree key {unknown[0]!r} (keys: {', '.join(sorted(_NODE_KEYS))})")
    if ("generator" in data) == ("children" in data):
        raise bad("a tree node has a generator or children, not both or neither")
    tests = tuple((k, _test(k, data[k], bad)) for k in _TESTS if k in data)
    if "children" in data:
        return Node(tests, None, data.get("style"), tuple(_node(n, bad) for n in _list(data["children"], "children", bad)))
    gen = data["generator"]
    feature = data.get("feature")
    allowed = GENERATORS.get(feature, tuple(sorted({g for v in GENERATORS.values() for g in v})))
    if gen not in allowed:
        where = f" for a {feature}" if feature else ""
        raise bad(f"unknown generator {gen!r}{where} (choose from {', '.join(allowed)})")
    style = data.get("style")
    if style is not None and not isinstance(style, str):
        raise bad("style must be text")
    return Node(tests, gen, style)


def _test(name: str, value: Any, bad) -> Any:
    if name == "feature" and value not in GENERATORS:
        raise bad(f"feature must be one of {', '.join(GENERATORS)}, not {value!r}")
    if name == "direction":
        if not (isinstance(value, list) and len(value) == 2 and all(isinstance(v, (int, float)) for v in value)):
            raise bad("direction must be two angles [low, high], degrees")
        return (float(value[0]) % 180.0, float(value[1]) % 180.0)
    if name == "hole" and value not in ("top", "bottom", "outer"):
        raise bad(f"hole must be top, bottom or outer, not {value!r}")
    if name == "convex" and not isinstance(value, bool):
        raise bad("convex must be true or false")
    if name == "label" and not isinstance(value, str):
        raise bad("label must be text")
    return value


def read_description(path: str | Path) -> Description:
    """A description from a ``.toml`` or ``.json`` file (by its suffix; TOML otherwise)."""
    path = Path(path)
    data = read_input(path, error=ParameterError)  # bounded: a FIFO or /dev/zero is refused, not read
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ParameterError(f"{path}: cannot read the tree description ({exc})") from None
    try:
        data = json.loads(text) if path.suffix.lower() == ".json" else tomllib.loads(text)
    except (json.JSONDecodeError, tomllib.TOMLDecodeError) as exc:
        raise ParameterError(f"{path}: not valid {'JSON' if path.suffix.lower() == '.json' else 'TOML'} ({exc})") from None
    return parse_description(data, str(path))
