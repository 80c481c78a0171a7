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
     "svgtile.svg.mapdoc", "svgtile.svg.uselines", "svgtile.svg.texture"),
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


#: What a command that synthesizes nothing must not import: the engines' implementations (the
#: registry holds their light declarations) and the heavy libraries only they use.
NOT_AT_START = ("numba", "scipy.interpolate", "svgtile.engines.growth.engine", "svgtile.engines.growth.kernel",
                "svgtile.engines.cellular.engine", "svgtile.engines.cellular.frame", "svgtile.engines.optimize.solver")


@pytest.mark.parametrize("module", ["svgtile.cli.score", "svgtile.cli.main", "svgtile.cli.analyze", "svgtile.engines"])
def test_start_up_imports_no_engine_implementation(module):
    """``svgtile score`` / ``analyze`` and the CLI's start-up import the engines' declarations only
    (issue 11: numba and scipy.interpolate cost every command ~0.25 s); the registry still knows
    every engine and its parameters."""
    import subprocess
    import sys

    code = (f"import sys, {module}\n"
            "from svgtile.engines import ENGINES, public_params\n"
            "assert {'patch', 'growth', 'cellular', 'optimize', 'tile', 'random'} <= set(ENGINES)\n"
            "assert {'relax_every', 'passes', 'strike'} <= set(public_params())\n"
            f"print(sorted(m for m in sys.modules if m.split('.')[0] == 'numba' or m.startswith({NOT_AT_START!r})))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]", f"import {module} loaded {out.strip()}"
