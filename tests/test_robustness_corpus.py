"""Issue 16 item 5: a sample of the robustness corpus (tools/robustness), run as the user would.

Each case runs ``python -m svgtile`` in a fresh folder under the runner's time and memory limits,
with its HTTP listener and watched pipe, and must end ``ok`` or as a ``clear refusal``: no internal
error, no input changed, no output left, no fetch.  One case per kind of hazard (about 2 s each);
the full corpus and ../shared/data are run by hand (docs/robustness.md).
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

RUNNER = Path(__file__).resolve().parents[1] / "tools" / "robustness" / "run.py"
spec = importlib.util.spec_from_file_location("svgtile_robustness_run", RUNNER)
run = sys.modules[spec.name] = importlib.util.module_from_spec(spec)  # dataclasses look it up
spec.loader.exec_module(run)

SAMPLE = {
    "use-skew90.analyze": "clear refusal",
    "deep-10000.analyze": "clear refusal",
    "stacked-3000.synth": "clear refusal", "use-fanout-2^30.import": "clear refusal",
    "enc-UTF-16.compare": "ok", "svgz.analyze": "clear refusal",
    "external-entity-file.synth": "clear refusal", "fill-url-http.synth": "ok", "fifo.synth": "clear refusal",
    "stdout-full": "clear refusal", "styles-deep-tables": "clear refusal", "clash-map-avoid": "clear refusal",
    "clash-compare-png": "clear refusal", "swatches-all-refused": "clear refusal",
}  # fmt: skip
CASES = {c.name: c for c in run.generate() if c.name in SAMPLE}


@pytest.fixture(scope="module")
def fetches():
    listener = run._Fetches()
    yield listener
    listener.server.shutdown()


def test_the_sample_names_cases_of_the_corpus():
    assert set(CASES) == set(SAMPLE)
    assert {c.group for c in CASES.values()} == {c.group for c in run.generate()}  # every group sampled


@pytest.mark.parametrize("name", sorted(SAMPLE))
def test_corpus_case_ends_cleanly(name, fetches):
    outcome = run.run_case(CASES[name], fetches, timeout=60, memory_mb=2048)
    assert outcome.outcome == SAMPLE[name], outcome
    assert outcome.flags == [SAMPLE[name]], outcome  # nothing else went wrong on the way


def test_the_runner_sees_a_fetch_and_a_changed_input(fetches, tmp_path):
    """The classifier itself can fail a run: a case that fetches and rewrites its input."""
    evil = run.Case("evil", "self-test", ["import", "in.svg", "-o", "in.svg"], {"in.svg": b"x"})
    # not svgtile: a stand-in command that does what svgtile must never do
    script = ("import sys, urllib.request, pathlib\n"
              "try: urllib.request.urlopen(sys.argv[1], timeout=5)\nexcept Exception: pass\n"
              "pathlib.Path('in.svg').write_text('changed')\n")  # fmt: skip
    outcome = run.run_case(evil, fetches, timeout=30, memory_mb=2048, command=["-c", script, "@HTTP@/x"])
    assert "fetch attempted" in outcome.flags and "input changed" in outcome.flags
    assert outcome.outcome == "fetch attempted"


def test_the_runner_limits_cpu_time_and_waiting(fetches):
    """A run that computes past the CPU limit and one that waits past the wall limit are both
    timeouts; a run that waits briefly is not (the limit is CPU time, not a busy machine's wall)."""
    case = run.Case("spin", "self-test", [], {})
    spin = run.run_case(case, fetches, timeout=1, memory_mb=2048, command=["-c", "while True: pass"])
    assert spin.outcome == "timeout" and spin.cpu >= 1, spin
    wait = run.run_case(case, fetches, timeout=1, wall=2, memory_mb=2048, command=["-c", "import time; time.sleep(30)"])
    assert wait.outcome == "timeout" and wait.cpu < 1, wait
    nap = run.run_case(case, fetches, timeout=1, wall=20, memory_mb=2048, command=["-c", "import time; time.sleep(1.5)"])
    assert nap.outcome == "ok" and nap.seconds >= 1.5, nap
