"""``svgtile score`` on a large texture: statistical figures on sample windows, counts exact.

The threshold is lowered here (``sample_above``/``sample_motifs``, or the module constants for
the CLI) so that a texture of a few thousand motifs takes the sampled path in a fraction of a
second; benchmarks/README.md measures the real one.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import shapely

from svgtile.analysis.stats import analyze
from svgtile.cli.main import main
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import score, window
from svgtile.metrics.pattern import _set_covariance
from svgtile.metrics.scoring import SAMPLE_BOUND, SAMPLED
from svgtile.metrics.window import interior, sample_windows
from svgtile.svg.reader import read_exemplar
from svgtile.svg.writer import svg_document

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
#: The lowered threshold: sample above this many motifs …
ABOVE = 1_500
#: … on windows holding about this many.
MOTIFS = 3_000


@pytest.fixture(scope="module")
def gravel_texture():
    """A patch texture of the bundled gravel, about 6,000 motifs in its interior."""
    ex = read_exemplar(EXEMPLARS / "gravel.svg")
    stats = analyze(ex)
    region = Region.rectangle(670, 670)
    arr = synthesize(ex, region, "patch", seed=3, stats=stats).arrangement
    return ex, stats, arr, region


@pytest.fixture(scope="module")
def scores(gravel_texture):
    """The texture's score sampled (the lowered threshold) and exact."""
    ex, stats, arr, region = gravel_texture
    return (score(ex, stats, arr, region, sample_above=ABOVE, sample_motifs=MOTIFS),
            score(ex, stats, arr, region, exact=True, sample_above=ABOVE, sample_motifs=MOTIFS))  # fmt: skip


def test_windows_follow_a_fixed_rule_over_a_rectangle():
    box = shapely.box(0, 0, 900, 600)
    rng = np.random.default_rng(0)
    xy = rng.random((30_000, 2)) * [900, 600]
    inside = np.ones(len(xy), dtype=bool)
    assert sample_windows(box, xy, inside, above=30_000) is None  # not above the threshold
    boxes, sample = sample_windows(box, xy, inside, above=10_000, motifs=6_000)
    again, _ = sample_windows(box, xy[::-1].copy(), inside, above=10_000, motifs=6_000)
    assert shapely.equals_exact(boxes, again, tolerance=0)  # from the bounds, not the motifs' order
    parts = shapely.get_parts(boxes)
    assert sample.windows == len(parts) == 4 * 2  # cells about square: 4 × 2 of 225 × 300
    assert shapely.contains(box, boxes)
    assert sample.of == 30_000 and abs(sample.motifs - 6_000) < 600  # uniform points: the area's share
    b = shapely.bounds(parts)
    w, h = b[:, 2] - b[:, 0], b[:, 3] - b[:, 1]
    assert np.allclose(w, sample.window_size[0]) and np.allclose(h, sample.window_size[1])
    # spread over the whole box: one window centred in each cell
    cx, cy = (b[:, 0] + b[:, 2]) / 2, (b[:, 1] + b[:, 3]) / 2
    assert sorted(set(cx.tolist())) == [112.5, 337.5, 562.5, 787.5] and sorted(set(cy.tolist())) == [150, 450]


def test_windows_of_an_irregular_region_lie_inside_it():
    ring = shapely.Point(500, 500).buffer(480).difference(shapely.box(0, 0, 500, 500))  # a disc less a quarter
    rng = np.random.default_rng(1)
    xy = rng.random((60_000, 2)) * 1000
    inside = shapely.contains_xy(ring, xy[:, 0], xy[:, 1])
    boxes, sample = sample_windows(ring, xy, inside, above=10_000, motifs=8_000)
    assert shapely.contains(ring, boxes) and sample.motifs >= 4_000
    tiny = shapely.box(0, 0, 10, 1000)  # too thin for any window: measured whole
    assert sample_windows(tiny, xy, np.ones(len(xy), dtype=bool), above=10, motifs=60_000) is None


def test_set_covariance_of_windows_apart_is_their_sum():
    boxes = shapely.multipolygons([shapely.box(0, 0, 40, 30), shapely.box(70, 0, 110, 30), shapely.box(0, 60, 40, 90)])
    d = np.array([[0.0, 0.0], [3.0, -4.0], [-20.0, 12.5], [29.0, 0.0]])
    got = _set_covariance(boxes, d, reach=30.0)
    want = [shapely.intersection(boxes, shapely.affinity.translate(boxes, *v)).area for v in d]
    assert np.allclose(got, want, rtol=1e-12)
    assert got[0] == pytest.approx(3 * 40 * 30)


def test_a_large_texture_is_sampled_and_says_so(gravel_texture, scores):
    ex, stats, arr, region = gravel_texture
    s, exact = scores
    assert s.motifs > ABOVE and s.sample is not None
    assert s.sample.of == s.motifs and 0.5 * MOTIFS <= s.sample.motifs < s.motifs
    plain = s.to_dict()
    keys = list(plain)
    assert keys[keys.index("motifs") + 1] == "sampled"
    assert plain["sampled"]["figures"] == list(SAMPLED) and plain["sampled"]["windows"] == s.sample.windows
    assert json.loads(json.dumps(plain, allow_nan=False)) == plain
    assert exact.sample is None and "sampled" not in exact.to_dict()
    assert exact == score(ex, stats, arr, region)  # below the real threshold: measured whole


def test_sampled_figures_stay_within_the_bound(scores):
    s, e = scores
    assert s.gap_distance != e.gap_distance  # measured on other motifs, not copied
    # the bound is measured for samples of SAMPLE_MOTIFS; a sample's deviation shrinks like 1/√m
    scale = math.sqrt(window.SAMPLE_MOTIFS / s.sample.motifs)
    for figure, bound in SAMPLE_BOUND.items():
        bound *= scale if figure != "empty_disc_radius" else 1.0  # the disc is not sampled
        a, b = getattr(s, figure), getattr(e, figure)
        deviation = abs(a - b) / (b if figure == "empty_disc_radius" else 1.0)
        assert deviation <= bound, f"{figure}: sampled {a} against exact {b}"
    # the figures that are not sampled are exact, bit for bit
    for figure in ("motifs", "density_ratio", "density_cv", "kind_mix_tv", "orientation_outside", "overlaps",
                   "violators", "overlaps_total", "violators_total", "repetition", "repetition_vector",
                   "neighbourhood_distance", "likeness"):  # fmt: skip
        assert getattr(s, figure) == getattr(e, figure), figure


def test_counts_are_exact_with_a_planted_overlap_far_from_every_window(gravel_texture, scores):
    ex, stats, arr, region = gravel_texture
    inner = interior(ex, region)
    boxes, _ = sample_windows(inner, arr.xy, shapely.contains_xy(inner, arr.xy[:, 0], arr.xy[:, 1]),
                              above=ABOVE, motifs=MOTIFS)  # fmt: skip
    # the interior motif farthest from every sample window gets a twin on top of it
    far = shapely.distance(boxes, shapely.points(arr.xy))
    far[~shapely.contains_xy(inner, arr.xy[:, 0], arr.xy[:, 1])] = -1
    i = int(np.argmax(far))
    assert far[i] > 3 * math.sqrt(1 / stats.count_density)
    twin = arr.take(np.array([i]))
    planted = Arrangement.concat([arr, Arrangement(twin.kind, twin.xy + 0.3, twin.angle, twin.scale)])
    s = score(ex, stats, planted, region, sample_above=ABOVE, sample_motifs=MOTIFS)
    e = score(ex, stats, planted, region, exact=True)
    clean = scores[1]
    assert s.sample is not None and e.sample is None
    assert s.overlaps == e.overlaps == clean.overlaps + 1
    assert s.violators == e.violators > clean.violators
    assert (s.overlaps_total, s.violators_total) == (e.overlaps_total, e.violators_total)


def test_cli_says_sampled_and_exact_is_not(tmp_path, capsys, monkeypatch, gravel_texture):
    ex, _, arr, region = gravel_texture
    path = tmp_path / "t.svg"
    path.write_text(svg_document(ex, arr, region, boundary="clip", params={"engine": "patch"}))
    monkeypatch.setattr(window, "SAMPLE_ABOVE", ABOVE)
    monkeypatch.setattr(window, "SAMPLE_MOTIFS", MOTIFS)
    assert main(["score", str(EXEMPLARS / "gravel.svg"), str(path)]) == 0
    out = capsys.readouterr().out
    line = next(t for t in out.splitlines() if t.startswith("sampled: "))
    assert re.match(r"sampled: \d+ windows of [\d.]+ × [\d.]+, [\d,]+ of [\d,]+ motifs", line), line
    assert main(["score", str(EXEMPLARS / "gravel.svg"), str(path), "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert plain["sampled"]["motifs"] < plain["motifs"]
    assert main(["score", str(EXEMPLARS / "gravel.svg"), str(path), "--exact", "--json"]) == 0
    exact = json.loads(capsys.readouterr().out)
    assert "sampled" not in exact and exact["motifs"] == plain["motifs"]


def test_the_help_names_the_threshold():
    from svgtile.cli.score import score as command

    help_text = " ".join(command.help.split())
    assert f"more than {window.SAMPLE_ABOVE:,} motifs" in help_text and "--exact" in help_text


def test_lazy_footprints_are_the_footprints(gravel_texture):
    from svgtile.core.footprint import world_footprints
    from svgtile.metrics.coverage import Footprints

    ex, _, arr, _ = gravel_texture
    lazy = Footprints(arr, ex.prototypes)
    some = np.array([7, 3, 7, len(arr) - 1])
    got = lazy[some]
    assert lazy._built.sum() == 3 and len(lazy) == len(arr)  # only those asked for, each once
    want = world_footprints(arr, ex.prototypes)[some]
    assert all(shapely.equals_exact(a, b, tolerance=0) for a, b in zip(got, want, strict=True))
