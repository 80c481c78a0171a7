"""Every command of the README runs as written, from a checkout (issue 17 item 1).

The ``svgtile`` lines of the ``sh`` blocks after the set-up section, and the ``python`` blocks,
are run in the repository's root with this interpreter (``svgtile`` is ``python -m svgtile``),
``out/`` moved to a temporary folder and the Inkscape installer pointed at a temporary user
folder; each must exit 0.  (The two set-up commands are what ``.ci/run`` runs.)
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data"
TOUR = (REPO / "README.md").read_text().split("## A short tour", 1)[1]


def readme_commands() -> list[str]:
    commands = []
    for block in re.findall(r"```sh\n(.*?)```", TOUR, re.S):
        for line in block.replace("\\\n", " ").splitlines():
            line = re.sub(r"\s+#\s.*$", "", line).strip()
            if line.startswith("svgtile "):
                commands.append(line)
    return commands


def _writes(command: str) -> set[str]:
    return set(re.findall(r"-o (out/\S+)", command))


def _reads(command: str) -> set[str]:
    return set(re.findall(r" (out/\S+)", command)) - _writes(command)


def made_from_data(commands: list[str]) -> set[str]:
    """The ``out/`` files the commands make from the shared data sets, directly or from a file
    made so by an earlier command (``svgtile import ../shared/data/…/607.svg -o out/607.svg``,
    then ``svgtile synth out/607.svg …``)."""
    made: set[str] = set()
    for command in commands:
        if "../shared/data" in command or _reads(command) & made:
            made |= _writes(command)
    return made


def needs_data(command: str) -> bool:
    """Whether ``command`` reads the shared data sets, directly or through an ``out/`` file."""
    return "../shared/data" in command or bool(_reads(command) & made_from_data(readme_commands()))


def python_blocks() -> list[str]:
    return re.findall(r"```python\n(.*?)```", TOUR, re.S)


def test_the_readme_has_commands_to_run():
    commands = readme_commands()
    assert len(commands) >= 15 and python_blocks()
    assert any(c.startswith("svgtile map ") for c in commands)
    assert all(" out/" in c or " -o " not in c or "-o -" in c for c in commands), "outputs go to out/"


def test_a_command_on_a_file_made_from_the_data_sets_needs_them():
    """Without the data sets beside the checkout, the commands on what was imported from them
    are skipped with the import (a clean clone alone failed on ``svgtile synth out/607.svg``)."""
    assert needs_data("svgtile synth out/607.svg -o out/607-texture.svg --size 400x300 --seed 1")
    assert not needs_data("svgtile synth exemplars/gravel.svg -o out/g.svg --size 300x200 --seed 1")
    assert "out/607.svg" in made_from_data(readme_commands())


def _run(command: str) -> subprocess.CompletedProcess:
    return subprocess.run(["bash", "-c", command], cwd=REPO, capture_output=True, text=True, timeout=600,
                          env={**os.environ, "PYTHONWARNINGS": "ignore"})  # fmt: skip


@pytest.fixture(scope="module")
def out(tmp_path_factory) -> Path:
    """The README's ``out/``, shared by its commands in order (a later one reads what an earlier
    one wrote)."""
    return tmp_path_factory.mktemp("out")


@pytest.mark.parametrize("command", readme_commands())
def test_readme_command_runs_as_written(command, out):
    tmp_path = out
    if needs_data(command) and not DATA.is_dir():
        pytest.skip("the shared data sets are not beside this checkout")
    run = command.replace(" out/", f" {tmp_path}/")
    if run.startswith("svgtile inkscape "):
        run += f" --user-dir {tmp_path / 'inkscape'}"
    if run.startswith("svgtile qgis "):
        run += f" --profile {tmp_path / 'qgis'}"
    if "gravel-texture.svg" in run and " synth " not in f" {run}":  # made by the README's first command
        done = _run(f"svgtile synth exemplars/gravel.svg -o {tmp_path}/gravel-texture.svg --size 300x200 --seed 1"
                    .replace("svgtile", f"{shlex.quote(sys.executable)} -m svgtile", 1))  # fmt: skip
        assert done.returncode == 0, done.stderr
    run = re.sub(r"^svgtile\b", f"{shlex.quote(sys.executable)} -m svgtile", run)
    done = _run(run)
    assert done.returncode == 0, f"{command}\n{done.stderr}"


@pytest.mark.parametrize("n", range(len(python_blocks())))
def test_readme_python_runs_as_written(n, out):
    tmp_path = out
    code = python_blocks()[n].replace('"out/', f'"{tmp_path}/')
    done = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
