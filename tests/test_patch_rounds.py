"""benchmarks/patch_rounds.py counts what each density-repair round does (issue 12's speed
target) from around the library's own loop: its counters must add up to the texture the engine
makes, or its tables in benchmarks/README.md would describe another run."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "patch_rounds.py"


@pytest.fixture(scope="module")
def rounds():
    spec = importlib.util.spec_from_file_location("patch_rounds", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("name", ["till", "gravel"])
def test_round_counters_add_up_to_the_engine_s_texture(rounds, name):
    res = rounds.run(name, 3000, 2)
    rows = res["rounds"]
    assert res["hash"] == res["plain_hash"]  # the counters changed nothing
    assert rows and [r["round"] for r in rows] == list(range(len(rows)))
    # every motif the texture gains or loses in a round is counted by one of the counters
    for before, after in zip(rows, [*rows[1:], None], strict=True):
        end = after["motifs"] if after else res["holes"]["before"]
        assert before["motifs"] + before["added"] - before["thinned"] - before["displaced"] == end
        assert before["rho_after_all"] - before["rho_all"] == pytest.approx(before["gain"], abs=1e-12)
    assert res["holes"]["after"] == res["motifs"]
    assert sum(r["added"] for r in rows) > 0 and sum(r["thinned"] + r["displaced"] for r in rows) > 0
    for skip in res["skips"]:
        assert 0.0 <= skip["skipped"] <= 1.0
    table = rounds.table(res)
    assert table.count("\n| ") >= len(rows) + 2
