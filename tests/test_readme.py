"""Every command of the README runs as written, from a checkout (issue 17 item 1).

The commands of the ``sh`` blocks after the set-up section are run with ``bash`` in the
repository's root, with ``out/`` moved to a temporary folder and the Inkscape installer pointed
at a temporary user folder; each must exit 0.  (The two set-up commands are what ``.ci/run``
runs.)
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data"


def readme_commands() -> list[str]:
    text = (REPO / "README.md").read_text()
    tour = text[text.index("## A short tour"):]
    blocks = re.findall(r"```sh\n(.*?)```", tour, re.S)
    commands = []
    for block in blocks:
        for line in block.splitlines():
            line = re.sub(r"\s+#\s.*$", "", line).strip()
            if line.startswith("svgtile "):
                commands.append(line)
    return commands


def test_the_readme_has_commands_to_run():
    commands = readme_commands()
    assert len(commands) >= 15
    assert any(c.startswith("svgtile map ") for c in commands)
    assert all(" out/" in c or "-o" not in c or "-o -" in c for c in commands), "outputs go to out/"


@pytest.mark.parametrize("command", readme_commands())
def test_readme_command_runs_as_written(command, tmp_path):
    if "../shared/data" in command and not DATA.is_dir():
        pytest.skip("the shared data sets are not beside this checkout")
    svgtile = shutil.which("svgtile")
    if svgtile is None or Path(svgtile).parent != Path(sys.executable).parent:
        pytest.skip("the svgtile command of this environment is not on PATH")
    run = command.replace(" out/", f" {tmp_path}/")
    if run.startswith("svgtile inkscape "):
        run += f" --user-dir {tmp_path / 'inkscape'}"
    if "gravel-texture.svg" in run and "synth" not in run:  # made by the README's first command
        subprocess.run(["svgtile", "synth", "exemplars/gravel.svg", "-o", str(tmp_path / "gravel-texture.svg"),
                        "--size", "300x200", "--seed", "1"], cwd=REPO, check=True)  # fmt: skip
    done = subprocess.run(["bash", "-c", run], cwd=REPO, capture_output=True, text=True,
                          env={**os.environ, "PYTHONWARNINGS": "ignore"}, timeout=600)  # fmt: skip
    assert done.returncode == 0, f"{command}\n{done.stderr}"
