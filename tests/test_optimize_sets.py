"""Issue 14's done-when over whole data sets: the optimize engine's likeness, repetition,
conflicts and density on every bundled exemplar and every accepted FGDC / osm-carto / Equinor
tile (imported as ``svgtile import`` does), on small regions so the module stays quick.

Bounds: likeness L ≥ 0.85 (:mod:`optimize_measure`: between the ``tile`` and ``random``
engines' neighbourhood distance on the same region and seed), repetition ≤ 0.2, no overlap, no
violator, density / ρ in [0.9, 1.1].  Where a bound is not met the test is marked
``xfail(strict=True)`` with the figure measured; the bounds are never loosened.  A set's test
stops at its first tile that misses a bound (so a failing set costs one tile, a passing set the
whole set).
"""

from __future__ import annotations

import os
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
#: The first tile of each set that misses a bound, with its figures (2 x 2 tiles, seed 1; re-measured
#: with issue 12's repetition, which leaves out the lattice of an exact tile: allotments passes now;
#: since an exact lattice tile starts as the tile itself, osm-carto passes whole and Equinor 10000
#: passes: its first miss was 11026, whose density / rho the tile engine measured 0.75 as well, until
#: its prototypes kept its pebbles and dashes apart (tight12) — then 30019, whose two rare squares
#: the solver voted away until a start that is the tile itself seeded its first search (seed30019):
#: every Equinor tile now meets every bound;
#: FGDC's first 15 tiles miss L >= 0.85 all, 7 of them density too: benchmarks/README.md; since
#: opt14e's patches as large as the tile allows and no shrinking vote in a short window, 601
#: passes (L 0.77 -> 0.86, density / rho 0.94 -> 0.97) and 602 is the first miss; since opt14g's
#: patches of the whole period, no overlap and the seeded first search, 602-605 pass and 606 is the
#: first miss, by density; since the refilled start's patches are 0.65 of the period, not the
#: whole of it, which copied the tile side by side, 605 is the first miss, by L: benchmarks/README.md).
SET_MISSES: dict[str, str] = {
    "fgdc": "605.svg: L 0.76 measured (0.85 with patches of the whole period, repetition 0.60 on the gate region)",
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


def _set(name):
    marks = [pytest.mark.skipif(not SETS[name].is_dir(), reason=f"{SETS[name]} is not beside the checkout")]
    if name in SET_MISSES:
        marks.append(pytest.mark.xfail(strict=True, reason=SET_MISSES[name]))
    return pytest.param(name, marks=marks)


@pytest.mark.parametrize("name", [_set(n) for n in SETS])
def test_every_accepted_tile_meets_the_bounds(name):
    accepted = 0
    for path in sorted(SETS[name].glob("*.svg")):
        try:
            t = import_tile(path)
        except TileRefused:
            continue
        ex = parse_exemplar(t.text, source=str(path))
        if ex.cellular is not None:  # a pattern of cells has no motifs to place: the cellular engine's
            continue
        x0, y0, w, h = t.box
        m = measure(ex, analyze(ex), Region.rectangle(2 * w, 2 * h, x0, y0))
        assert not misses(m), f"{path.name}: {', '.join(misses(m))}"
        accepted += 1
    assert accepted > 0
