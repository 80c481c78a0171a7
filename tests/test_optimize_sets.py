"""Issue 14's done-when over whole data sets: the optimize engine's likeness, repetition,
conflicts and density on every bundled exemplar and every accepted FGDC / osm-carto / Equinor
tile (imported as ``svgtile import`` does), on small regions so the module stays quick.

Bounds: likeness L ≥ 0.85 (:mod:`optimize_measure`: between the ``tile`` and ``random``
engines' neighbourhood distance on the same region and seed), repetition ≤ 0.2, no overlap, no
violator, density / ρ in [0.9, 1.1].  Where a bound is not met the test is marked
``xfail(strict=True)`` with the figure measured; the bounds are never loosened.  Every accepted
tile is measured once (2 × 2 tiles, seed 1) and each bound is a test of its own, so that a tile
that met a bound and stops meeting it fails, and one that starts meeting it passes unexpectedly
(its entry in :data:`TILE_MISSES` must then go).  Until 2026-12-08 a set's test stopped at its
first tile that missed a bound: FGDC's ran 601, 602, 603 and stopped at 605, and a change to any
of the 29 tiles after 605 that met every bound went unseen.
"""

from __future__ import annotations

import os
from functools import cache
from pathlib import Path

import pytest
from optimize_measure import measure

from svgtile import analyze, read_exemplar
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import score
from svgtile.svg.reader import parse_exemplar
from svgtile.tiles.importer import TileRefused, import_tile

REPO = Path(__file__).resolve().parents[1]
EXEMPLARS = REPO / "exemplars"
DATA = Path(os.environ.get("SVGTILE_SHARED_DATA", REPO.parent / "shared" / "data"))
SETS = {
    "fgdc": DATA / "fgdc-geologic-patterns" / "lithology",
    "osm-carto": DATA / "osm-carto" / "patterns",
    "equinor": DATA / "equinor-lithology" / "svg",
}
#: Measured misses (seed 1, these regions), by exemplar: the figure that misses its bound.  Gravel
#: and chert-nodules met every bound before omix14 brought the kind mix back (gravel 28 % round
#: pebbles for the exemplar's 40 %, kind-mix TV 0.07–0.15; the neighbourhoods a start drawn from
#: the exemplar's middle has are those L matches best; chert's mix was the exemplar's, and held
#: to it window by window its L is 0.80–0.81 on seeds 1–3 for 0.83–0.86: benchmarks/README.md,
#: omix14).
#: Renewal of the start's worst-matched motifs (renew14, its insertion capped by count: renew14c) lifted scrub over the bounds (L 0.83 →
#: 0.90, density / ρ 1.04, kind-mix TV 0.047) and the others part of the way (breccia-plain 0.78 →
#: 0.83, chert-nodules 0.81 → 0.84, gravel 0.74 → 0.80; gravel's kind-mix TV 0.002 → 0.040, and 0.106
#: and 0.067 on seeds 2 and 3).
MISSES: dict[str, str] = {
    "breccia-plain": "L = 0.83 measured",
    "chert-nodules": "L = 0.84 measured (0.86 before the mix was held window by window)",
    "gravel": "L = 0.80 measured (0.88 with the mix at 28 % round pebbles for 40 %)",
}
#: (tile, bound) -> the figure measured when it was written (2 × 2 tiles, seed 1; 2026-12-08,
#: main at 8a325ba): 32 of FGDC's 61 tiles of motifs meet every bound.  Patterns imported as cells
#: are the cellular engine's and are not measured here (FGDC 41, 29 of them with motifs besides
#: their cells; ``benchmarks/optimize_sets.py --cells`` measures those too: 38 of the 90 then meet
#: every bound).  Every osm-carto pattern and Equinor tile meets every bound: osm-carto's
#: exact lattices start as the tile itself; Equinor 11026 since its prototypes kept its pebbles and
#: dashes apart (tight12), 30019 since a start that is the tile itself seeds the first search
#: (seed30019).  FGDC's history (benchmarks/README.md): its first 15 tiles all missed L ≥ 0.85 at
#: first; opt14e's patches as large as the tile allows passed 601, opt14g's patches of the whole
#: period 602, 603 and 605 (there is no 604), and patches of 0.65 of the period (cell65) traded 605's L (0.85 → 0.76) for its
#: repetition on the whole-set gate region (0.60).
TILE_MISSES: dict[tuple[str, str], str] = {
    ("fgdc/605", "likeness"): "L 0.762",
    ("fgdc/606", "likeness"): "L 0.751",
    ("fgdc/607", "likeness"): "L 0.840",
    ("fgdc/613", "likeness"): "L 0.812",
    ("fgdc/614", "likeness"): "L 0.834",
    ("fgdc/621", "likeness"): "L 0.767",
    ("fgdc/622", "likeness"): "L 0.721",
    ("fgdc/623", "likeness"): "L 0.752",
    ("fgdc/626", "likeness"): "L 0.622",
    ("fgdc/626", "repetition"): "repetition 0.213",
    ("fgdc/653", "repetition"): "repetition 0.218",
    ("fgdc/654", "repetition"): "repetition 0.996",
    ("fgdc/655", "likeness"): "L 0.839",
    ("fgdc/659", "likeness"): "L 0.720",
    ("fgdc/664", "repetition"): "repetition 0.232",
    ("fgdc/665", "repetition"): "repetition 0.319",
    ("fgdc/666", "likeness"): "L 0.713",
    ("fgdc/666", "repetition"): "repetition 0.266",
    ("fgdc/681", "likeness"): "L 0.796",
    ("fgdc/682", "likeness"): "L 0.807",
    ("fgdc/683", "likeness"): "L 0.783",
    ("fgdc/684", "likeness"): "L 0.845",
    ("fgdc/685", "likeness"): "L 0.812",
    ("fgdc/686", "likeness"): "L 0.822",
    ("fgdc/714", "likeness"): "L 0.785",
    ("fgdc/715", "likeness"): "L 0.756",
    ("fgdc/719", "likeness"): "L 0.838",
    ("fgdc/722", "likeness"): "L 0.773",
    ("fgdc/729", "likeness"): "L 0.756",
    ("fgdc/730", "repetition"): "repetition 0.283",
    ("fgdc/732", "likeness"): "L 0.804",
    ("fgdc/732", "repetition"): "repetition 0.202",
}


def misses(bounds) -> list[str]:
    m, out = bounds, []
    if not m.likeness >= 0.85:
        out.append(f"L={m.likeness:.2f}")
    if not (m.repetition is not None and m.repetition <= 0.2):
        out.append(f"repetition={m.repetition}")
    if m.overlaps or m.violators:
        out.append(f"conflicts={m.overlaps}/{m.violators}")
    if not (m.density_ratio is not None and 0.9 <= m.density_ratio <= 1.1):
        out.append(f"density={m.density_ratio}")
    return out


def _bundled(name):
    marks = [pytest.mark.xfail(strict=True, reason=MISSES[name])] if name in MISSES else []
    return pytest.param(name, marks=marks)


@pytest.mark.parametrize("name", [_bundled(p.stem) for p in sorted(EXEMPLARS.glob("*.svg"))])
def test_bundled_exemplar_meets_the_bounds(name):
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    stats = analyze(ex)
    x0, y0, x1, y1 = ex.region.bounds
    side = 4 * max(x1 - x0, y1 - y0)
    m = measure(ex, stats, Region.rectangle(side, side))
    assert not misses(m), f"{name}: {', '.join(misses(m))}"


@pytest.mark.parametrize("name", [p.stem for p in sorted(EXEMPLARS.glob("*.svg"))])
def test_bundled_exemplar_keeps_its_kind_mix_and_density(name):
    """A drawn exemplar's start is off its kind mix (its windows take its middle more often than its
    edges: gravel 28 % round pebbles for 40 %); the solver brings it back and the start's count
    brings the cover with it (omix14).  Seed 1, the bounds of the whole-set gates (issue 12):
    kind-mix TV ≤ 0.05, density / ρ in 0.9–1.1 (before: TV 0.056–0.087 on five of the ten)."""
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    stats = analyze(ex)
    x0, y0, x1, y1 = ex.region.bounds
    side = 4 * max(x1 - x0, y1 - y0)
    region = Region.rectangle(side, side)
    s = score(ex, stats, synthesize(ex, region, "optimize", seed=1, stats=stats).arrangement, region)
    assert s.kind_mix_tv <= 0.05, f"{name}: kind-mix TV {s.kind_mix_tv:.3f}"
    assert 0.9 <= s.density_ratio <= 1.1, f"{name}: density / rho {s.density_ratio:.3f}"
    assert s.overlaps_total == s.violators_total == 0


TILES = [f"{name}/{p.stem}" for name, folder in SETS.items() for p in sorted(folder.glob("*.svg"))]


@cache
def motif_tile(tile: str):
    """(exemplar, 2 × 2 tiles region) of ``tile`` ("set/stem"), imported as ``svgtile import``
    does; None if the importer refuses it or imports it as cells (the cellular engine's)."""
    name, stem = tile.split("/")
    path = SETS[name] / f"{stem}.svg"
    try:
        t = import_tile(path)
    except TileRefused:
        return None
    ex = parse_exemplar(t.text, source=str(path))
    if ex.cellular is not None:
        return None
    x0, y0, w, h = t.box
    return ex, Region.rectangle(2 * w, 2 * h, x0, y0)


@cache
def tile_measure(tile: str):
    """The optimize engine's figures on ``tile`` over 2 × 2 tiles, seed 1; None where
    :func:`motif_tile` is None."""
    found = motif_tile(tile)
    if found is None:
        return None
    ex, region = found
    return measure(ex, analyze(ex), region)


def tile_cases(bound: str) -> list:
    return [pytest.param(t, marks=pytest.mark.xfail(strict=True, reason=TILE_MISSES[t, bound]))
            if (t, bound) in TILE_MISSES else t for t in TILES]  # fmt: skip


def measured(tile: str):
    m = tile_measure(tile)
    if m is None:
        pytest.skip(f"{tile}: refused by the importer, or a pattern of cells")
    return m


@pytest.mark.parametrize("tile", tile_cases("likeness"))
def test_tile_likeness_is_at_least_0_85(tile):
    m = measured(tile)
    assert m.likeness >= 0.85, f"{tile}: L {m.likeness:.3f}"


@pytest.mark.parametrize("tile", tile_cases("repetition"))
def test_tile_repetition_is_at_most_0_2(tile):
    m = measured(tile)
    assert m.repetition is not None and m.repetition <= 0.2, f"{tile}: repetition {m.repetition}"


@pytest.mark.parametrize("tile", tile_cases("density"))
def test_tile_density_is_within_ten_percent(tile):
    m = measured(tile)
    assert m.density_ratio is not None and 0.9 <= m.density_ratio <= 1.1, f"{tile}: density / rho {m.density_ratio}"


@pytest.mark.parametrize("tile", tile_cases("conflicts"))
def test_tile_has_no_overlap_and_no_violator(tile):
    m = measured(tile)
    assert m.overlaps == m.violators == 0, f"{tile}: {m.overlaps} overlaps, {m.violators} violators"


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.skipif(not SETS[n].is_dir(), reason=f"{SETS[n]} is not "
                                                                         "beside the checkout")) for n in SETS])  # fmt: skip
def test_each_set_has_tiles_of_motifs(name):
    assert any(motif_tile(t) is not None for t in TILES if t.startswith(name + "/"))


def test_every_known_miss_names_a_tile_and_a_bound():
    bounds = {"likeness", "repetition", "density", "conflicts"}
    assert all(b in bounds for _, b in TILE_MISSES), sorted({b for _, b in TILE_MISSES} - bounds)
    if all(folder.is_dir() for folder in SETS.values()):
        # a tile the importer refuses, or reads as cells, is skipped, so its entry would never fail
        assert {t for t, _ in TILE_MISSES} <= set(TILES)
        assert all(motif_tile(t) is not None for t, _ in TILE_MISSES)
