"""The package reads as the pipeline: no import cycle, no module importing a later stage, no
module so long that it holds two stages (issue 11).  Run by hand as
``python -m pytest tests/test_layout.py -q``; the failures name the modules."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "svgtile"

#: Pipeline stages, earliest first: a module may import its own stage and earlier ones.
STAGES = [
    ("svgtile.errors", "svgtile.files", "svgtile.core"),
    ("svgtile.svg.dialect", "svgtile.svg.numbers", "svgtile.svg.reader", "svgtile.svg.kinds", "svgtile.svg.tilepieces",
     "svgtile.svg.mapdoc", "svgtile.svg.texture"),
    ("svgtile.analysis", "svgtile.tiles"),
    ("svgtile.engines",),
    ("svgtile.svg.writer", "svgtile.gis", "svgtile.metrics", "svgtile.runners"),
    ("svgtile.apps",),
    ("svgtile.cli", "svgtile.__main__"),
]
MAX_LINES = 600


def modules() -> dict[str, Path]:
    out = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


def stage(module: str) -> int:
    if module == "svgtile":
        return len(STAGES)  # the package's own __init__ re-exports the public API
    for rank, prefixes in enumerate(STAGES):
        if any(module == p or module.startswith(p + ".") for p in prefixes):
            return rank
    raise AssertionError(f"{module} belongs to no stage of tests/test_layout.py")


def imports(module: str, path: Path, *, top_level_only: bool) -> set[str]:
    """svgtile modules that ``module`` imports (``from svgtile.x import name`` may name a module)."""
    known = modules()
    tree = ast.parse(path.read_text())
    nodes = tree.body if top_level_only else list(ast.walk(tree))
    found = set()
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    for node in nodes:
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1] + ([base] if base else []))
            for alias in node.names:
                name = f"{base}.{alias.name}"
                found.add(name if name in known else base)
        elif isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
    return {m for m in found if m in known and m != module}


def test_no_module_is_longer_than_a_stage():
    long = {m: n for m, p in modules().items() if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert not long, f"modules over {MAX_LINES} lines: {long}"


def test_no_module_imports_a_later_stage():
    late = [(m, i) for m, p in modules().items() for i in imports(m, p, top_level_only=False)
            if i != "svgtile" and stage(i) > stage(m)]  # fmt: skip
    assert not late, f"imports of a later stage: {late}"


def test_no_import_cycle():
    graph = {m: imports(m, p, top_level_only=True) for m, p in modules().items()}
    state: dict[str, int] = {}

    def visit(m: str, trail: list[str]) -> None:
        state[m] = 1
        for n in sorted(graph[m]):
            if state.get(n) == 1:
                pytest.fail("import cycle: " + " -> ".join([*trail[trail.index(n):], n]))
            if n not in state:
                visit(n, [*trail, n])
        state[m] = 2

    for m in graph:
        if m not in state:
            visit(m, [m])
