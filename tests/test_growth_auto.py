"""``--engine auto`` grows drawn rows and lattices (issue 13): the choice on every bundled exemplar,
the reason for it (growth keeps their order better than patch), and issue 13's gates on them.

Figures at 300 × 300, seed 1, centroid boundary, scored by :func:`svgtile.metrics.score` (seeds 1–3
in benchmarks/README.md, "Growth as auto's choice"); gates not met are ``xfail(strict=True)``
with the measured value, never loosened.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import cKDTree

from svgtile import analyze, read_exemplar
from svgtile.analysis.order import read_order
from svgtile.cli.main import main
from svgtile.core.region import Region
from svgtile.engines import ENGINES, choose, synthesize
from svgtile.metrics import repetition, score
from svgtile.metrics.window import spacing

REPO = Path(__file__).resolve().parents[1]
EXEMPLARS = sorted(p.stem for p in (REPO / "exemplars").glob("*.svg"))
#: The bundled exemplars whose order (svgtile analyze) is rows or a lattice.
ORDERED = {"marsh": "rows", "sand": "lattice"}


@cache
def loaded(name: str):
    ex = read_exemplar(REPO / "exemplars" / f"{name}.svg")
    return ex, analyze(ex)


@cache
def arrangement(name: str, engine: str):
    ex, st = loaded(name)
    return synthesize(ex, Region.rectangle(300, 300), engine, seed=1, stats=st, boundary="centroid").arrangement


@cache
def figures(name: str, engine: str):
    ex, st = loaded(name)
    return score(ex, st, arrangement(name, engine), Region.rectangle(300, 300))


@pytest.mark.parametrize("name", EXEMPLARS)
def test_auto_grows_the_drawn_rows_and_lattices_and_leaves_the_rest_to_patch(name):
    ex, st = loaded(name)
    c = choose(ex, st, available=ENGINES)
    assert (c.engine, c.rule) == (("growth", "drawn-order") if name in ORDERED else ("patch", "scatter"))
    if name in ORDERED:
        assert c.why.startswith(f"drawn {'a lattice' if ORDERED[name] == 'lattice' else 'rows'} (steps ")


def test_cli_says_growth_for_marsh_and_a_patch_option_keeps_patch(tmp_path, capsys):
    marsh = str(REPO / "exemplars" / "marsh.svg")
    out = tmp_path / "m.svg"
    assert main(["synth", marsh, "-o", str(out), "--size", "60x40", "--seed", "1"]) == 0
    err = capsys.readouterr().err
    assert "svgtile: auto: engine growth: drawn rows (steps 5.18 units at 180°)" in err
    assert 'engine="growth"' in out.read_text()
    assert main(["synth", marsh, "-o", str(out), "--size", "60x40", "--seed", "1", "--max-rotation", "0"]) == 0
    assert "svgtile: auto: engine patch: " in capsys.readouterr().err
    # options of two engines that none takes both: the engine chosen refuses the stray one in one line
    rc = main(["synth", marsh, "-o", str(out), "--size", "60x40", "--max-rotation", "0", "--priority", "x=1"])
    err = capsys.readouterr().err
    assert rc != 0 and "has no parameter --" in err and "Traceback" not in err


@pytest.mark.parametrize("name", sorted(ORDERED))
def test_growth_keeps_the_order_better_than_patch(name):
    grown, patched = figures(name, "growth"), figures(name, "patch")
    assert grown.likeness > patched.likeness + 0.1, (grown.likeness, patched.likeness)
    assert grown.overlaps_total == grown.violators_total == 0


#: Issue 13's gates not met on the bundled drawn exemplars (seed 1).  Marsh's likeness: the final
#: kind passes had taken it 0.763 → 0.838 by moving the kind mix (kind-mix TV 0.116); since they hold
#: the exemplar's mix (2026-12-07, growth.kinds.mix_bounds) it is 0.765 (tests/test_growth_kinds.py;
#: benchmarks/README.md, "growth's kind mix").  (Sand's repetition 0.224 was one until issue 13's
#: figure, which excuses what the exemplar shows inside itself: 0.000 since.)
NOT_MET: dict[tuple[str, str], float] = {("marsh", "likeness"): 0.765}
GATES = {"likeness": lambda s: s.likeness >= 0.8, "kind mix": lambda s: s.kind_mix_tv <= 0.05,
         "repetition": lambda s: s.repetition <= 0.2,
         "density": lambda s: 0.9 <= s.density_ratio <= 1.1,
         "conflicts": lambda s: s.overlaps_total == s.violators_total == 0}  # fmt: skip


@pytest.mark.parametrize(("name", "gate"), [
    pytest.param(n, g, marks=pytest.mark.xfail(strict=True, reason=f"{g} {NOT_MET[n, g]:.3f}"))
    if (n, g) in NOT_MET else (n, g) for n in sorted(ORDERED) for g in GATES])  # fmt: skip
def test_growth_gates_on_the_drawn_rows_and_lattices(name, gate):
    s = figures(name, "growth")
    assert GATES[gate](s), (s.likeness, s.kind_mix_tv, s.repetition, s.density_ratio, s.overlaps_total,
                            s.violators_total)  # fmt: skip


def test_auto_passes_over_growth_when_its_work_is_over_the_limit(tmp_path, capsys, monkeypatch):
    """A region too large for growth's work (the limit lowered here, so the test stays small) gets
    patch, with a line saying why; --force keeps growth."""
    import svgtile.cli.synth as synth_cli

    marsh = str(REPO / "exemplars" / "marsh.svg")
    out = tmp_path / "m.svg"
    # about 130 motifs: growth ≈ 0.04 s of declared work, patch ≈ 0.003 s
    monkeypatch.setattr(synth_cli, "MAX_WORK_SECONDS", 0.01)
    assert main(["synth", marsh, "-o", str(out), "--size", "60x40", "--seed", "1"]) == 0
    err = capsys.readouterr().err
    assert "engine growth (drawn-order) would be over the work limit for this region" in err
    assert "svgtile: auto: engine patch: " in err
    assert 'engine="patch"' in out.read_text()
    assert main(["synth", marsh, "-o", str(out), "--size", "60x40", "--seed", "1", "--force"]) == 0
    assert "svgtile: auto: engine growth: drawn rows" in capsys.readouterr().err
    assert 'engine="growth"' in out.read_text()


@pytest.mark.parametrize(("option", "engine"), [(["--strike", "30"], "cellular"), (["--passes", "2"], "optimize")])
def test_auto_with_an_option_of_an_engine_no_rule_picks_runs_that_engine(tmp_path, capsys, option, engine):
    """An option only optimize or cellular takes, given with auto, picks that engine (it ended in
    an internal AssertionError: no rule held among the engines that take it)."""
    out = tmp_path / "m.svg"
    rc = main(["synth", str(REPO / "exemplars" / "marsh.svg"), "-o", str(out), "--size", "60x40", "--seed", "1",
               *option])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 0, err
    assert f"svgtile: auto: engine {engine}: the options given are the {engine} engine's" in err
    assert f'engine="{engine}"' in out.read_text()


def test_auto_never_falls_back_to_a_baseline_and_a_narrowed_choice_says_why(tmp_path, capsys, monkeypatch):
    """Over the work limit for every engine a rule picks, auto keeps its choice and the work check
    refuses it in one line (it fell back to the tile baseline, then an AssertionError); narrowed to
    patch on an exemplar with rows, the reason names the rows."""
    import svgtile.cli.synth as synth_cli

    marsh = str(REPO / "exemplars" / "marsh.svg")
    out = tmp_path / "m.svg"
    monkeypatch.setattr(synth_cli, "MAX_WORK_SECONDS", 1e-4)
    rc = main(["synth", marsh, "-o", str(out), "--size", "60x40", "--seed", "1"])
    err = capsys.readouterr().err
    assert rc != 0 and "would hold about" in err and "engine 'growth'" in err and "Traceback" not in err
    assert not out.exists()
    monkeypatch.undo()
    assert main(["synth", marsh, "-o", str(out), "--size", "60x40", "--seed", "1", "--max-rotation", "0"]) == 0
    assert "svgtile: auto: engine patch: rows (steps 5.18 units at 180°), but the options given" in capsys.readouterr().err


def row_steps(xy: np.ndarray, g: np.ndarray, tol: float) -> np.ndarray:
    """(p, 2): each motif's displacement to the motif nearest ``x + g``, where one lies within ``tol``."""
    d, j = cKDTree(xy).query(xy + g, distance_upper_bound=tol)
    ok = np.isfinite(d)
    return xy[j[ok]] - xy[ok]


def test_sands_repetition_is_its_exemplars_own_rows():
    """Why sand's repetition was 0.224 by issue 12's figure (``repetition_order``): growth's rows
    are no more regular than the exemplar's (the spread of one step and of two steps along a row
    at least 95 % of the exemplar's, per axis), and that figure on the exemplar's own 90 motifs is
    higher, at the same vector — two steps along the row, which it counted because the rows are
    not exact.  Issue 13's figure excuses what the exemplar shows there: both pass."""
    ex, st = loaded("sand")
    s = spacing(st)
    g = np.asarray(read_order(ex).steps[0].vector)
    own = repetition(ex.motifs, ex, st, ex.region)
    grown = figures("sand", "growth")
    assert own.repetition_order > grown.repetition_order > 0.2, (own.repetition_order, grown.repetition_order)
    assert own.repetition <= 0.05 and grown.repetition <= 0.2, (own.repetition, grown.repetition)
    for v in (own.repetition_order_vector, grown.repetition_order_vector):
        assert np.hypot(*(np.asarray(v) - 2 * g)) < 0.1 * s, v
    arr = arrangement("sand", "growth")
    for k in (1, 2):
        mine, theirs = row_steps(arr.xy, k * g, 0.4 * s).std(0), row_steps(ex.motifs.xy, k * g, 0.4 * s).std(0)
        assert np.all(mine >= 0.95 * theirs), (k, mine, theirs)
