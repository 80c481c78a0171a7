"""Whole-set gates (issue 12.6): every accepted tile of FGDC lithology, osm-carto patterns and
symbols and Equinor, imported and synthesized with the default engine (``auto``), seed 1, over
a rectangle of max(3, √(600 / motifs)) tiles across and three quarters of that down.

Bounds: 0 overlaps, 0 violators, density / ρ in 0.9–1.1, kind-mix TV ≤ 0.05, repetition ≤ 0.2,
likeness L ≥ 0.6 (Ma, Wei & Tong 2011 neighbourhood distance between the ``tile`` and ``random``
baselines, :func:`svgtile.analysis.neighbourhood.likeness`).  A bound a tile does not meet is an
``xfail(strict=True)`` that names the tile and the figure measured when it was written
(:data:`KNOWN`), never a loosened bound: a fix turns it into an unexpected pass, and the entry
must then go.

Repetition is the figure beyond the exemplar's own order (issue 12, :mod:`svgtile.metrics.order`):
the lattice of a tile's exact neighbour steps is left out, so auto reproducing an exact lattice
tile on its period passes (71 entries went, 2026-12-02), while auto stamping a tile of jittered
or irregular content, or rows whose offsets the row step does not explain, still repeats at the
period and stays listed with that reason.

Density and kind mix are measured on the interior (the region shrunk by one tile on every side):
with k = 3 tiles across that is one tile wide and a quarter of a tile high, often under 50 motifs.
A tile auto stamps on its period then reads 0.73–0.90 because the window cuts the period, and reads
0.98–1.00 (kind mix ≤ 0.05) on a region 7 tiles across (2026-12-02, issue 12's density engineer;
the entries say so); those entries stay until the gate measures whole periods.

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
#: re-measured with issue 12's figure the same day).
KNOWN: dict[tuple[str, str], str] = {
    ("fgdc/614", "kind mix"): "TV 0.0501",
    ("equinor/11026", "overlaps"): "0 overlaps, 0 violators, exemplar 4 overlapping pairs (pebbles and dashes 0.2 apart along "
                                   "each row; joined they would meet their own repeat, the importer's notes say so)",
    ("equinor/11026", "density"): "density/ρ 0.722",
    ("equinor/11026", "kind mix"): "TV 0.232",
    ("equinor/11030", "density"): "density/ρ 1.158 (2026-12-02, after import joined 5 dots to their pebbles: 58 motifs, "
                                  "were 63; auto stamps the tile and the interior window holds half a tile, 30 motifs; was 1.098)",
    ("equinor/11030", "kind mix"): "TV 0.114",
    ("equinor/11030", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("equinor/30017", "density"): "density/ρ 0.819 (stamped on its period: 0.986 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/30019", "density"): "density/ρ 0.727 (stamped on its period: 0.979 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/30021", "density"): "density/ρ 0.809 (stamped on its period: 0.985 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/30031", "density"): "density/ρ 0.802 (stamped on its period: 0.985 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/30066", "density"): "density/ρ 0.863 (stamped on its period: 0.989 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/30100", "density"): "density/ρ 0.426",
    ("equinor/30100", "kind mix"): "TV 0.124",
    ("equinor/30100", "repetition"): "0.502",
    ("equinor/30100", "likeness"): "L 0.23",
    ("equinor/30300", "density"): "density/ρ 0.668",
    ("equinor/30300", "repetition"): "0.477",
    ("equinor/30300", "likeness"): "L 0.43",
    ("equinor/30400", "density"): "density/ρ 0.790",
    ("equinor/30400", "kind mix"): "TV 0.055",
    ("equinor/30400", "repetition"): "0.527",
    ("equinor/30400", "likeness"): "L 0.35",
    ("equinor/30500", "density"): "density/ρ 1.192",
    ("equinor/30500", "kind mix"): "TV 0.053",
    ("equinor/30500", "repetition"): "0.489",
    ("equinor/30500", "likeness"): "L 0.48",
    ("equinor/32021", "density"): "density/ρ 0.897 (stamped on its period: 0.992 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/33021", "density"): "density/ρ 0.841 (stamped on its period: 0.988 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/33022", "density"): "density/ρ 0.881 (stamped on its period: 0.991 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/40100", "density"): "density/ρ 0.712",
    ("equinor/40100", "kind mix"): "TV 0.074",
    ("equinor/40100", "likeness"): "L 0.21",
    ("equinor/50000", "density"): "density/ρ 0.794 (stamped on its period: 1.000 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/50090", "density"): "density/ρ 0.826 (stamped on its period: 1.000 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/50090", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("equinor/60038", "density"): "density/ρ 0.894 (stamped on its period: 1.000 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/60100", "density"): "density/ρ 0.573",
    ("equinor/60100", "kind mix"): "TV 0.081",
    ("equinor/60100", "likeness"): "L 0.06",
    ("equinor/60200", "density"): "density/ρ 0.597",
    ("equinor/60200", "kind mix"): "TV 0.064",
    ("equinor/60200", "likeness"): "L 0.10",
    ("equinor/60500", "density"): "density/ρ 0.624",
    ("equinor/60500", "likeness"): "L 0.02",
    ("equinor/60600", "density"): "density/ρ 0.711",
    ("equinor/60600", "kind mix"): "TV 0.071",
    ("equinor/60600", "likeness"): "L -0.07",
    ("equinor/60700", "density"): "density/ρ 0.628",
    ("equinor/60700", "likeness"): "L 0.13",
    ("equinor/60738", "density"): "density/ρ 0.893 (stamped on its period: 0.992 on a 7-tile-wide region; the interior cuts the period)",
    ("equinor/60738", "kind mix"): "TV 0.118 (stamped on its period: 0.009 on a 7-tile-wide region)",
    ("equinor/65100", "density"): "density/ρ 0.690",
    ("equinor/65100", "kind mix"): "TV 0.101",
    ("equinor/65100", "likeness"): "L 0.08",
    ("equinor/65121", "density"): "density/ρ 0.739",
    ("equinor/65121", "kind mix"): "TV 0.141",
    ("equinor/65121", "likeness"): "L 0.11",
    ("equinor/80100", "density"): "density/ρ 0.655",
    ("equinor/80100", "kind mix"): "TV 0.068",
    ("equinor/80100", "likeness"): "L 0.15",
    ("equinor/80200", "density"): "density/ρ 0.686",
    ("equinor/80200", "kind mix"): "TV 0.056",
    ("equinor/80200", "likeness"): "L 0.15",
    ("fgdc/601", "likeness"): "L 0.22",
    ("fgdc/602", "kind mix"): "TV 0.055",
    ("fgdc/602", "likeness"): "L 0.33",
    ("fgdc/603", "likeness"): "L 0.46",
    ("fgdc/605", "kind mix"): "TV 0.172",
    ("fgdc/605", "repetition"): "0.283",
    ("fgdc/605", "likeness"): "L -0.05",
    ("fgdc/606", "density"): "density/ρ 0.690",
    ("fgdc/606", "kind mix"): "TV 0.199",
    ("fgdc/606", "likeness"): "L 0.11",
    ("fgdc/607", "repetition"): "0.346",
    ("fgdc/607", "likeness"): "L 0.41",
    ("fgdc/608", "repetition"): "0.310",
    ("fgdc/608", "likeness"): "L 0.44",
    ("fgdc/609", "likeness"): "L 0.35",
    ("fgdc/610", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/611", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/612", "density"): "density/ρ 0.819",
    ("fgdc/612", "likeness"): "L 0.10",
    ("fgdc/613", "likeness"): "L 0.26",
    ("fgdc/614", "density"): "density/ρ 0.856",
    ("fgdc/614", "likeness"): "L 0.05",
    ("fgdc/616", "density"): "density/ρ 0.889 (stamped on its period: 0.991 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/616", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("fgdc/617", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/618", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("fgdc/619", "density"): "density/ρ 0.889 (stamped on its period: 0.991 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/619", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/620", "density"): "density/ρ 0.889 (stamped on its period: 0.991 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/620", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/621", "density"): "density/ρ 0.889 (stamped on its period: 0.991 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/621", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("fgdc/622", "density"): "density/ρ 0.889 (stamped on its period: 0.991 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/622", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/623", "density"): "density/ρ 0.889 (stamped on its period: 0.991 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/623", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/626", "kind mix"): "TV 0.081 (stamped on its period: 0.050 on a 7-tile-wide region)",
    ("fgdc/626", "repetition"): "1.000 (auto stamps the tile; every motif its own kind, so the period is no order of it)",
    ("fgdc/653", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/654", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("fgdc/655", "likeness"): "L 0.41",
    ("fgdc/656", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/659", "repetition"): "1.000 (auto stamps the tile; every motif its own kind, so the period is no order of it)",
    ("fgdc/664", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/665", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/666", "density"): "density/ρ 0.840",
    ("fgdc/666", "kind mix"): "TV 0.114",
    ("fgdc/666", "likeness"): "L 0.06",
    ("fgdc/669", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("fgdc/670", "repetition"): "1.000 (auto stamps the tile; only its row step is exact, the rows' offsets repeat at the period)",
    ("fgdc/671", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/681", "density"): "density/ρ 0.673",
    ("fgdc/681", "kind mix"): "TV 0.221",
    ("fgdc/681", "likeness"): "L 0.10",
    ("fgdc/682", "density"): "density/ρ 0.629",
    ("fgdc/682", "kind mix"): "TV 0.142",
    ("fgdc/682", "repetition"): "0.218",
    ("fgdc/682", "likeness"): "L 0.17",
    ("fgdc/683", "density"): "density/ρ 0.753",
    ("fgdc/683", "kind mix"): "TV 0.150",
    ("fgdc/683", "likeness"): "L 0.06",
    ("fgdc/684", "density"): "density/ρ 0.573",
    ("fgdc/684", "kind mix"): "TV 0.325",
    ("fgdc/684", "likeness"): "L 0.12",
    ("fgdc/685", "density"): "density/ρ 0.498",
    ("fgdc/685", "kind mix"): "TV 0.424",
    ("fgdc/685", "likeness"): "L 0.16",
    ("fgdc/686", "density"): "density/ρ 0.377",
    ("fgdc/686", "kind mix"): "TV 0.440",
    ("fgdc/686", "likeness"): "L 0.15",
    ("fgdc/701", "kind mix"): "TV 0.051",
    ("fgdc/701", "repetition"): "0.496",
    ("fgdc/701", "likeness"): "L 0.44",
    ("fgdc/702", "kind mix"): "TV 0.052",
    ("fgdc/702", "repetition"): "0.227",
    ("fgdc/714", "density"): "density/ρ 0.636",
    ("fgdc/714", "kind mix"): "TV 0.244",
    ("fgdc/714", "likeness"): "L -0.11",
    ("fgdc/715", "density"): "density/ρ 0.439",
    ("fgdc/715", "kind mix"): "TV 0.349",
    ("fgdc/715", "likeness"): "L -0.05",
    ("fgdc/719", "density"): "density/ρ 0.897",
    ("fgdc/719", "kind mix"): "TV 0.080",
    ("fgdc/719", "repetition"): "0.254",
    ("fgdc/719", "likeness"): "L 0.41",
    ("osm-symbols/leaftype_broadleaved", "repetition"): "0.499",
    ("osm-symbols/leaftype_broadleaved", "likeness"): "L 0.34",
    ("osm-symbols/leaftype_leafless", "repetition"): "0.500",
    ("osm-symbols/leaftype_leafless", "likeness"): "L 0.25",
    ("osm-symbols/leaftype_mixed", "kind mix"): "TV 0.057",
    ("osm-symbols/leaftype_mixed", "repetition"): "0.856",
    ("osm-symbols/leaftype_mixed", "likeness"): "L 0.29",
    ("osm-symbols/leaftype_needleleaved", "repetition"): "0.529",
    ("osm-symbols/leaftype_needleleaved", "likeness"): "L 0.33",
    ("osm-symbols/leaftype_unknown", "kind mix"): "TV 0.057",
    ("osm-symbols/leaftype_unknown", "repetition"): "0.471",
    ("osm-symbols/leaftype_unknown", "likeness"): "L 0.31",
    ("osm-symbols/unpaved", "repetition"): "0.565",
    ("osm-symbols/unpaved", "likeness"): "L 0.58",
    ("fgdc/722", "repetition"): "0.333",
    ("fgdc/722", "likeness"): "L 0.39",
    ("fgdc/723", "likeness"): "L 0.43",
    ("fgdc/724", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/725", "likeness"): "L 0.29",
    ("fgdc/726", "density"): "density/ρ 0.816 (stamped on its period: 0.986 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/726", "repetition"): "1.000 (auto stamps the tile, whose motifs are jittered off any exact lattice)",
    ("fgdc/727", "kind mix"): "TV 0.066",
    ("fgdc/727", "likeness"): "L 0.54",
    ("fgdc/728", "density"): "density/ρ 0.895 (stamped on its period: 1.000 on a 7-tile-wide region; the interior cuts the period)",
    ("fgdc/729", "density"): "density/ρ 0.849",
    ("fgdc/729", "likeness"): "L 0.14",
    ("fgdc/730", "likeness"): "L 0.21",
    ("fgdc/732", "kind mix"): "TV 0.468 (stamped on its period: 0.048 on a 7-tile-wide region)",
    ("fgdc/732", "repetition"): "1.000 (auto stamps the tile; every motif its own kind, so the period is no order of it)",
}


@cache
def figures(tile: str):
    """(score, exemplar overlaps, L) of the default engine on ``tile``; None if it is refused."""
    folder, stem = tile.split("/")
    try:
        t = import_tile(SETS[folder] / f"{stem}.svg")
    except TileRefused:
        return None
    if t.cellular is not None:
        return "cellular"
    ex = parse_exemplar(t.text, source=stem)
    stats = analyze(ex)
    x0, y0, w, h = t.box
    k = max(3.0, math.sqrt(600 / len(ex.motifs)))
    region = Region.rectangle(k * w, k * h * 0.75, x0, y0)
    result = synthesize(ex, region, "auto", seed=1, stats=stats)
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
    assert measured(tile)[0].kind_mix_tv <= 0.05


@pytest.mark.parametrize("tile", cases("repetition"))
def test_repetition_is_low(tile):
    assert measured(tile)[0].repetition <= 0.2


@pytest.mark.parametrize("tile", cases("likeness"))
def test_likeness_is_at_least_0_6(tile):
    assert measured(tile)[2] >= 0.6
