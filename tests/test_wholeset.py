"""Whole-set gates (issue 12.6): every accepted tile of FGDC lithology, osm-carto patterns and
symbols and Equinor, imported and synthesized with the default engine (``auto``), seed 1, over
the rectangle of :func:`gate_region` (an interior of whole tiles).

Bounds: 0 overlaps, 0 violators, density / ρ in 0.9–1.1, kind-mix TV ≤ 0.05 (over the kinds'
shape classes, issue 12.3: kinds drawn fewer than 13 times count with rare kinds of like shape;
where kinds pool, each kind's TV also no more than 0.05 or what a fair draw of as many motifs from
the exemplar's mix gives on average, :func:`svgtile.metrics.kind_mix_noise`), repetition ≤ 0.2,
likeness L ≥ 0.6 and, since the growth and optimize engines exist, L ≥ 0.8 as issue 12.6 asks (Ma,
Wei & Tong 2011 neighbourhood distance between the ``tile`` and ``random`` baselines,
:func:`svgtile.analysis.neighbourhood.likeness`; the 0.6 floor stays a gate of its own, so a tile
listed under 0.8 still may not fall below it), coverage ≤ 1.3 (issue 12.4: the largest
hole no more than 1.3 times the tile's own, measured across the tile's edges,
:func:`svgtile.metrics.coverage.exemplar_empty_disc`).  A bound a tile does not meet is an
``xfail(strict=True)`` that names the tile and the figure measured when it was written
(:data:`KNOWN`), never a loosened bound: a fix turns it into an unexpected pass, and the entry
must then go.

Repetition is the figure beyond the exemplar's own order (issue 12, :mod:`svgtile.metrics.order`):
the lattice of a tile's exact neighbour steps is left out, so auto reproducing an exact lattice
tile on its period passes (71 entries went, 2026-12-02), and since rep13e (2026-12-04) the
exemplar's share at a displacement is read modulo that lattice, so a tile that is its exact
lattice kinds and all — a second site lattice offset inside it (Equinor 40100, 60100–60700,
65100, 80100, 80200), columns of a second kind (30100–30500), a 2 × 2 stamp of a smaller tile
(11030, 65121) — passes too (15 entries went); auto stamping a tile of jittered or irregular
content, or rows whose offsets the row step does not explain, still repeats at the period and
stays listed with that reason.  Since 2026-12-07 the texture's share at a displacement counts only
the motifs with room for a partner there inside the region (:func:`svgtile.metrics.repeats.repetition`
step 4; before, a motif near the region's far edge counted as one without a partner): three
entries came (607, 714, 727: patches of the start recurring at 1.3–1.5 periods, where a third to a
half of the references have no room).

Density and kind mix are measured on the interior (the region shrunk by one tile on every side),
which :func:`gate_region` makes a whole number of tiles across and down, at least
:data:`INTERIOR_MOTIFS` motifs: a tile auto stamps on its period then reads its own density and
mix (1.000, 0.000).  The region used to be max(3, √(600 / motifs)) tiles across and three quarters
of that down, whose interior was about one tile wide and a quarter of a tile high and cut the
period (0.73–0.90 on 21 stamped tiles; those entries went, 2026-12-02).

Runs only where ``../shared/data`` is beside the checkout (as CI has it); the module takes
several minutes (every tile is synthesized three times: auto, tile and random).
"""

from __future__ import annotations

import math
import os
from functools import cache
from pathlib import Path

import numpy as np
import pytest

from svgtile.analysis.neighbourhood import likeness, neighbourhood_distance
from svgtile.analysis.stats import analyze
from svgtile.core.region import Region
from svgtile.engines import synthesize
from svgtile.metrics import score, spacing
from svgtile.svg.reader import parse_exemplar
from svgtile.tiles.importer import TileRefused, import_tile

#: The data sets: ``../shared/data`` beside the checkout, or ``$SVGTILE_DATA``.
DATA = Path(os.environ.get("SVGTILE_DATA") or Path(__file__).resolve().parents[2] / "shared" / "data")
SETS = {
    "fgdc": DATA / "fgdc-geologic-patterns" / "lithology",
    "osm-patterns": DATA / "osm-carto" / "patterns",
    "osm-symbols": DATA / "osm-carto" / "symbols",
    "equinor": DATA / "equinor-lithology" / "svg",
}
pytestmark = pytest.mark.skipif(not DATA.is_dir(), reason="../shared/data (real symbol sets) is not beside the checkout")

TILES = [f"{name}/{p.stem}" for name, folder in SETS.items() for p in sorted(folder.glob("*.svg"))] if DATA.is_dir() else []

#: (tile, figure) -> what was measured when this list was written (2026-12-02, seed 1; repetition
#: re-measured with issue 12's figure the same day).  (fgdc/670's repetition 1.000 and fgdc/725's
#: 0.212 left the list with rep13f, which reads each kind of a tile at its own step and to the
#: figure's resolution: 0.000 and 0.190; tests/test_repetition_resolved.py.)
KNOWN: dict[tuple[str, str], str] = {
    ("fgdc/610", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/611", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/616", "repetition"): "0.727 (2026-12-04, auto's tile-jitter: rows at phases redrawn per band, 1.000 stamped; the phases that keep the distance rule with the next rows are few, so bands take near the tile's: partners at (w + 0.5, h) for 0.75 of the motifs)",
    ("fgdc/618", "repetition"): "0.725 (2026-12-04, auto's tile-jitter: rows at phases redrawn per band, 1.000 stamped; as 616, partners at (0.5, h) for 0.75 of the motifs)",
    ("fgdc/617", "repetition"): "1.000 (2026-12-04, auto's tile-jitter: rows at redrawn phases run on whole along x, and their mixed kinds repeat at (w, 0), which the tile does not show: 0.49)",
    ("fgdc/621", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("fgdc/622", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/623", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/626", "repetition"): "1.000 (auto stamps the tile; every motif its own kind, so the period is no order of it)",
    ("fgdc/653", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/654", "repetition"): "1.000 (auto stamps the tile: its rows' six kinds come in an order that repeats only at the period, so redrawn phases cannot break (w, 0) — redrawn 1.000 at L 0.94, 2026-12-04)",
    ("fgdc/656", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/659", "repetition"): "1.000 (auto stamps the tile; every motif its own kind, so the period is no order of it)",
    ("fgdc/664", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/665", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/671", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/724", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/726", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/732", "repetition"): "1.000 (auto stamps the tile; every motif its own kind, so the period is no order of it)",
    ("fgdc/605", "repetition"): "0.234 (2026-12-05, auto's tile-scatter: optimize, start patches 0.65 of the period)",
    ("fgdc/606", "repetition"): "0.249 (2026-12-05, auto's tile-scatter: optimize, start patches 0.65 of the period)",
    ("fgdc/682", "repetition"): "0.226 (2026-12-05, auto's tile-scatter: optimize, start patches 0.65 of the period)",
    ("fgdc/686", "kind mix"): "TV 0.083 over shape classes, 0.124 per kind against a fair draw's 0.133 (2026-12-06, auto's tile-scatter: optimize, start patches 0.65 of the period)",
    ("fgdc/723", "repetition"): "0.217 (2026-12-05, auto's tile-scatter: optimize, start patches 0.65 of the period)",
    ("fgdc/607", "repetition"): "0.245 (2026-12-07, auto's tile-scatter: optimize, start patches 0.65 of the period; partners at (65.2, −20.2) for 0.31 of the references with room for one — 0.156 when every reference counted, room or not)",
    ("fgdc/714", "repetition"): "0.223 (2026-12-07, auto's tile-scatter: optimize, start patches 0.65 of the period; partners at (70.8, −21.9) for 0.26 of the references with room for one — 0.155 when every reference counted, room or not)",
    ("fgdc/727", "repetition"): "0.295 (2026-12-07, auto's tile-scatter: optimize, start patches 0.65 of the period; partners at (117.0, 9.5) for 0.33 of the references with room for one — 0.146 when every reference counted, room or not)",
    ("fgdc/605", "coverage"): "1.306 (2026-12-06, auto's tile-scatter: optimize; fill_light fills by density, and the density is in bounds)",
    ("fgdc/606", "coverage"): "1.430 (2026-12-06, auto's tile-scatter: optimize; fill_light fills by density, and the density is in bounds)",
    ("fgdc/684", "coverage"): "2.609 (2026-12-06, auto's tile-scatter: optimize; a tile of dense hatch fragments whose own largest hole is small; fill_light fills by density, and the density is in bounds)",
    ("fgdc/685", "coverage"): "2.634 (2026-12-06, auto's tile-scatter: optimize; a tile of dense hatch fragments whose own largest hole is small; fill_light fills by density, and the density is in bounds)",
    ("fgdc/686", "coverage"): "2.240 (2026-12-06, auto's tile-scatter: optimize; a tile of dense hatch fragments whose own largest hole is small; fill_light fills by density, and the density is in bounds)",
    ("fgdc/715", "coverage"): "1.443 (2026-12-06, auto's tile-scatter: optimize; fill_light fills by density, and the density is in bounds)",
    ("osm-symbols/leaftype_leafless", "kind mix"): "TV 0.066 (2026-12-05, auto's tile-scatter: optimize, start patches 0.65 of the period)",
    ("fgdc/605", "likeness 0.8"): "L 0.760 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/606", "likeness 0.8"): "L 0.703 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/613", "likeness 0.8"): "L 0.798 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/614", "likeness 0.8"): "L 0.784 (2026-12-07, auto's tile-scatter: optimize; 0.801 before its import kept one kind for the lenses its outlines' tolerance had split, tight12; averaged over 8 samples 0.794 → 0.783)",
    ("fgdc/666", "likeness 0.8"): "L 0.723 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/682", "likeness 0.8"): "L 0.781 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/683", "likeness 0.8"): "L 0.758 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/684", "likeness 0.8"): "L 0.777 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/685", "likeness 0.8"): "L 0.759 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/715", "likeness 0.8"): "L 0.686 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/729", "likeness 0.8"): "L 0.736 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("fgdc/730", "likeness 0.8"): "L 0.731 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("osm-symbols/leaftype_broadleaved", "likeness 0.8"): "L 0.725 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("osm-symbols/leaftype_leafless", "likeness 0.8"): "L 0.673 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("osm-symbols/leaftype_mixed", "likeness 0.8"): "L 0.662 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("osm-symbols/leaftype_needleleaved", "likeness 0.8"): "L 0.736 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
    ("osm-symbols/leaftype_unknown", "likeness 0.8"): "L 0.738 (2026-12-07, auto's tile-scatter: optimize; L is one sample of 200 centres, ± 0.04)",
}


#: The interior (where density and kind mix are measured) holds at least this many of the tile's
#: motifs, in whole tiles.
INTERIOR_MOTIFS = 100


def gate_region(box: tuple[float, float, float, float], motifs: int) -> Region:
    """The rectangle a tile is synthesized on: its interior is ``a × a`` whole tiles.

    The interior is the region shrunk by ``m = max(w, h)`` on every side
    (:func:`svgtile.metrics.window.interior`), so a region ``2m + a·w`` by ``2m + a·h`` has an
    interior of exactly ``a`` tile widths by ``a`` tile heights: a pattern repeating at the tile's
    period has the same count of every motif in it wherever the period's phase falls, and a figure
    measured there is the pattern's, not the window's.  ``a`` is the fewest whole tiles that hold
    :data:`INTERIOR_MOTIFS` motifs (1 for a tile of 100 or more, 10 for a tile of one motif).

    Parameters
    ----------
    box : (x0, y0, w, h), user units, the tile's box (its period where it repeats)
    motifs : the tile's motif count, ≥ 1
    """
    x0, y0, w, h = box
    m = max(w, h)
    a = max(1, math.ceil(math.sqrt(INTERIOR_MOTIFS / motifs)))
    return Region.rectangle(2 * m + a * w, 2 * m + a * h, x0, y0)


def scored_window(ex, region: Region):
    """The window a tile's texture is scored on: the region's interior (one tile in from every
    side), or the whole region where that is empty (the benchmarks over the whole sets)."""
    from svgtile.metrics import interior

    win = interior(ex, region)
    return region.shape if win.is_empty or win.area <= 0 else win


def motif_tile(tile: str):
    """(imported tile, exemplar, stats) of ``tile`` ("set/stem"); None if the importer refuses
    it, "cellular" if it is imported as cells (the benchmarks over the whole sets use it too)."""
    folder, stem = tile.split("/")
    try:
        t = import_tile(SETS[folder] / f"{stem}.svg")
    except TileRefused:
        return None
    if t.cellular is not None:
        return "cellular"
    ex = parse_exemplar(t.text, source=stem)
    return t, ex, analyze(ex)


def motif_tiles(only: list[str] | tuple[str, ...] = ()):
    """(tile, imported tile, exemplar, stats) of every gate tile of motifs whose name starts with
    one of ``only`` (every one if empty): the whole-set benchmarks' loop."""
    for tile in TILES:
        if only and not any(tile.startswith(o) for o in only):
            continue
        loaded = motif_tile(tile)
        if isinstance(loaded, tuple):  # not refused, not imported as cells
            yield (tile, *loaded)


@cache
def figures(tile: str, engine: str = "auto", params: tuple[tuple[str, object], ...] = ()):
    """(score, exemplar overlaps, L) of ``engine`` (the default engine unless given, with
    ``params`` as (name, value) pairs) on ``tile``; None if it is refused."""
    loaded = motif_tile(tile)
    if not isinstance(loaded, tuple):
        return loaded
    t, ex, stats = loaded
    region = gate_region(t.box, len(ex.motifs))
    result = synthesize(ex, region, engine, seed=1, stats=stats, params=dict(params) or None)
    s = spacing(stats)
    X0, Y0, X1, Y1 = region.bounds

    def e(arr):
        m = 3 * s
        inside = np.flatnonzero((arr.xy[:, 0] > X0 + m) & (arr.xy[:, 0] < X1 - m)
                                & (arr.xy[:, 1] > Y0 + m) & (arr.xy[:, 1] < Y1 - m))  # fmt: skip
        return neighbourhood_distance(arr.xy, arr.kind, ex.motifs.xy, ex.motifs.kind, spacing=s, period=ex.period,
                                      centres=inside, sample=200, rng=np.random.default_rng(0))  # fmt: skip

    baselines = [synthesize(ex, region, b, seed=1, stats=stats).arrangement for b in ("tile", "random")]
    L = likeness(e(result.arrangement), e(baselines[0]), e(baselines[1]))
    return score(ex, stats, result.arrangement, region), stats.overlaps, L


def cases(figure: str) -> list:
    out = []
    for tile in TILES:
        why = KNOWN.get((tile, figure))
        marks = [pytest.mark.xfail(strict=True, reason=f"{tile}: {figure} {why}")] if why else []
        out.append(pytest.param(tile, marks=marks, id=tile))
    return out


def measured(tile: str):
    got = figures(tile)
    if got is None:
        pytest.skip("refused by the importer (not discrete motifs)")
    if got == "cellular":
        pytest.skip("a bedded or brick tile imported as cells: tests/test_cellular_import.py measures it")
    return got


@pytest.mark.parametrize("tile", cases("overlaps"))
def test_no_overlaps_no_violators_and_an_exemplar_without_overlaps(tile):
    s, exemplar_overlaps, _ = measured(tile)
    assert (s.overlaps_total, s.violators_total, exemplar_overlaps) == (0, 0, 0)


@pytest.mark.parametrize("tile", cases("density"))
def test_density_is_within_ten_percent(tile):
    assert 0.9 <= measured(tile)[0].density_ratio <= 1.1


@pytest.mark.parametrize("tile", cases("kind mix"))
def test_kind_mix_is_close(tile):
    s = measured(tile)[0]
    assert s.kind_mix_tv <= 0.05
    # where rare kinds pool into shape classes, each kind's share is still no further off than a
    # fair draw of as many motifs from the exemplar's mix is on average (a tile whose kinds all
    # pool into one class would otherwise pass on any mix of them); the mean, not an upper
    # quantile, so a fair draw itself would fail about half the time: auto's textures keep the
    # tile's counts better than chance (0.01-0.08 under it, benchmarks/README.md "mix12")
    if s.kind_mix_tv_kinds is not None:
        assert s.kind_mix_tv_kinds <= max(0.05, s.kind_mix_noise)


@pytest.mark.parametrize("tile", cases("repetition"))
def test_repetition_is_low(tile):
    assert measured(tile)[0].repetition <= 0.2


@pytest.mark.parametrize("tile", cases("coverage"))
def test_no_hole_is_much_larger_than_the_tiles_own(tile):
    # issue 12.4: holes where copies meet no larger than the exemplar's own (its largest empty disc,
    # measured across the tile's edges, as a stamp of the tile has it: coverage 1)
    s = measured(tile)[0]
    radii = (s.empty_disc_radius, s.exemplar_empty_disc_radius)
    if s.coverage is None:  # a tile without holes: so must the texture be
        assert s.empty_disc_radius == 0, radii
    else:
        assert s.coverage <= 1.3, radii


@pytest.mark.parametrize("tile", cases("likeness"))
def test_likeness_is_at_least_0_6(tile):
    assert measured(tile)[2] >= 0.6


@pytest.mark.parametrize("tile", cases("likeness 0.8"))
def test_likeness_is_at_least_0_8(tile):
    # issue 12.6: "L ≥ 0.6 (≥ 0.8 once the growth and optimize engines exist)" — they do
    assert measured(tile)[2] >= 0.8
