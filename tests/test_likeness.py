"""The done-when of issue 3, on every bundled exemplar at 1000 × 1000, seed 1.

The patch engine at its defaults must have no overlaps and no distance-rule violators, a density
ratio in [0.9, 1.1], a kind-mix TV of at most 0.05, at most a quarter of the repetition of the
``tile`` engine and at most half the structure distance (nearest-gap W1) of the ``random`` engine,
all measured by :func:`svgtile.metrics.score` on the interior.

The bundled exemplars are drawn with a cartographer's structure (tools/make_exemplars.py: offset
rows, nests, clumps, split fragments, bedding chains), which the ``random`` engine loses.  Patch
keeps it inside its copies and must rebuild it where copies meet and where density repair pastes
discs: the junction rule, rigid copies and the lacking kind's roomiest spot
(:mod:`svgtile.engines.patch.engine`) are what bring it under half of random's distance everywhere.  The
margins are thin on boulders, shale and till (ratios 0.47–0.48 at seed 1; README, "Likeness").
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest

from svgtile import analyze, read_exemplar
from svgtile.apps.compare import compare
from svgtile.core.region import Region
from svgtile.metrics import Score

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
NAMES = sorted(p.stem for p in EXEMPLARS.glob("*.svg"))
SIZE = 1000.0
SEED = 1
#: patch's likeness L is above this on every exemplar (issue 12 asks 0.6 of the engines to come;
#: measured at seed 1: 0.26 sand, 0.34 till to 0.98 boulders; tile 0.93–1.06, random −0.04–0.04)
PATCH_LIKENESS = 0.2


@cache
def scores(name: str) -> dict[str, Score]:
    """Engine name -> score of its texture of ``name`` on SIZE × SIZE with SEED."""
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    results = compare(ex, analyze(ex), Region.rectangle(SIZE, SIZE), seed=SEED)
    return {r.engine: r.score for r in results}


def test_every_exemplar_is_listed():
    assert len(NAMES) >= 10


@pytest.mark.parametrize("name", NAMES)
def test_patch_has_no_overlaps_or_violators(name):
    s = scores(name)["patch"]
    assert s.motifs > 1000
    assert s.overlaps == s.violators == 0
    assert s.overlaps_total == s.violators_total == 0


@pytest.mark.parametrize("name", NAMES)
def test_patch_density_is_within_ten_percent(name):
    assert 0.9 <= scores(name)["patch"].density_ratio <= 1.1


@pytest.mark.parametrize("name", NAMES)
def test_patch_kind_mix_is_close(name):
    assert scores(name)["patch"].kind_mix_tv <= 0.05


@pytest.mark.parametrize("name", NAMES)
def test_patch_repeats_a_quarter_of_tile_at_most(name):
    s = scores(name)
    assert s["tile"].repetition > 0.9  # the baseline repeats, or the comparison says nothing
    assert s["patch"].repetition <= 0.25 * s["tile"].repetition


@pytest.mark.parametrize("name", NAMES)
def test_patch_keeps_twice_the_structure_of_random(name):
    s = scores(name)
    assert s["patch"].gap_distance <= 0.5 * s["random"].gap_distance


@pytest.mark.parametrize("name", NAMES)
def test_patch_pair_correlation_is_closer_than_random(name):
    # the weaker structure check that holds everywhere: patch's pair correlation is nearer the
    # exemplar's than random's (measured ratios 0.39–0.71)
    s = scores(name)
    assert s["patch"].pair_correlation_distance < s["random"].pair_correlation_distance


@pytest.mark.parametrize("name", NAMES)
def test_likeness_baselines_sit_at_their_ends(name):
    # tile and random on this region are not the baselines themselves (those fill a region of
    # their own), so they land near 1 and 0, not on them (measured: within 0.06 of each)
    s = scores(name)
    assert s["tile"].likeness == pytest.approx(1.0, abs=0.15)
    assert s["random"].likeness == pytest.approx(0.0, abs=0.15)
    assert s["patch"].neighbourhood_tile == s["random"].neighbourhood_tile  # one baseline per exemplar


@pytest.mark.parametrize("name", NAMES)
def test_patch_keeps_more_order_than_random(name):
    assert scores(name)["patch"].likeness > PATCH_LIKENESS
