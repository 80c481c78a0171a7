"""``svgtile score`` run as a command ends as soon as its figures are printed.

The interpreter's teardown after a large texture (freeing every object, the modules) took
0.2–0.45 s of the command's wall time for nothing (benchmarks/README.md, "`svgtile score`: the
read split across the two processes, and no teardown"): the command asks :class:`svgtile.cli.common.Ending` to end the process once
all is printed.  These tests hold it to what a user sees: the same output, the same exit code,
the teardown skipped only on success and only for the process's own command line — ``main([...])``
called from Python (these tests, ``benchmarks/score_identity.sh``) goes on.
"""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from conftest import arrange

from svgtile.analysis.stats import analyze
from svgtile.cli.common import Ending
from svgtile.cli.main import main
from svgtile.core.region import Region
from svgtile.svg.reader import read_exemplar
from svgtile.svg.writer import svg_document

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"

#: The command line as the ``svgtile`` script runs it, with an exit handler that tells on stderr
#: whether the interpreter's teardown ran.
_COMMAND = """
import atexit, sys
atexit.register(lambda: print("teardown ran", file=sys.stderr))
from svgtile.cli.main import main
sys.argv = ["svgtile", *sys.argv[1:]]
sys.exit(main())
"""


@pytest.fixture(scope="module")
def texture(tmp_path_factory):
    ex = read_exemplar(EXEMPLARS / "gravel.svg")
    region = Region.rectangle(300, 300)
    arr = arrange("patch", ex, region, rng=np.random.default_rng(3), stats=analyze(ex))
    path = tmp_path_factory.mktemp("ending") / "t.svg"
    path.write_text(svg_document(ex, arr, region, boundary="clip", params={"engine": "patch"}))
    return path


def _command(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", _COMMAND, *args], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_the_command_ends_once_printed_with_the_same_output(texture, capsys, jobs):
    args = ["score", str(EXEMPLARS / "gravel.svg"), str(texture), "--json", "--jobs", jobs]
    assert main(args) == 0  # in-process: goes on, and prints what the command prints
    here = capsys.readouterr().out
    assert Ending.asked is False
    done = _command(*args)
    assert done.returncode == 0, done.stderr
    assert done.stdout == here and json.loads(done.stdout)["likeness"] is not None
    assert "teardown ran" not in done.stderr  # ended before the interpreter's exit handlers
    assert done.stderr == ""


def test_a_failed_command_exits_as_before(tmp_path, texture):
    (tmp_path / "broken.svg").write_text("<svg><g></svg")
    done = _command("score", str(EXEMPLARS / "gravel.svg"), str(tmp_path / "broken.svg"), "--jobs", "2")
    assert done.returncode == 1 and done.stdout == ""
    lines = done.stderr.splitlines()
    assert lines[0].startswith("svgtile: error: ") and "broken.svg" in lines[0]
    assert lines[1:] == ["teardown ran"]  # nothing asked to end early: the usual exit


def test_other_commands_exit_as_before(texture):
    done = _command("analyze", str(EXEMPLARS / "gravel.svg"))
    assert done.returncode == 0 and done.stdout
    assert done.stderr.splitlines()[-1] == "teardown ran"


def test_an_output_that_cannot_be_flushed_is_left_to_the_interpreter(monkeypatch):
    class Closed(io.StringIO):
        def flush(self):
            raise BrokenPipeError(32, "Broken pipe")

    monkeypatch.setattr(sys, "stdout", Closed())
    Ending.ask()
    Ending.end(0)  # returns: the process is still here, and the request is used up
    assert Ending.asked is False
    Ending.end(0)  # not asked: returns at once


def test_the_collector_stays_paused_only_when_the_process_ends(texture, capsys, monkeypatch):
    """score11e: ``svgtile score`` leaves the cyclic collector paused when its process ends right
    after the output (resuming ran one collection of all it made, ≈ 0.02 s); run from Python —
    ``main([...])``, click's runner, or after an error — it resumes it."""
    import gc

    from click.testing import CliRunner

    from svgtile.cli.group import cli

    args = ["score", str(EXEMPLARS / "gravel.svg"), str(texture), "--jobs", "1"]
    assert gc.isenabled()
    assert main(args) == 0 and gc.isenabled() and Ending.will_end is False
    assert CliRunner().invoke(cli, args).exit_code == 0 and gc.isenabled()
    assert main([*args[:2], str(texture.parent / "missing.svg")]) == 1 and gc.isenabled()
    monkeypatch.setattr(Ending, "will_end", True)  # as main() run as the command line sets it
    try:
        assert CliRunner().invoke(cli, args).exit_code == 0
        assert not gc.isenabled(), "the process ends next: the collector is left paused"
    finally:
        gc.enable()
        Ending.asked = False
    capsys.readouterr()
