"""The linework figures (:mod:`svgtile.metrics.linework`): on made images, and on every tile of the
real sets accepted as cells — as dark as the stamped tile (ink 0.9–1.1) and its lines running the
same ways at the same spacings (S ≥ 0.75), or a strict xfail naming the measured figure."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest

from svgtile.metrics.linework import INK_BOUNDS, STRUCTURE_MIN, dust, measure, spectrum

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"
SETS = {
    "fgdc": DATA / "fgdc-geologic-patterns" / "lithology",
    "osm": DATA / "osm-carto" / "patterns",
    "equinor": DATA / "equinor-lithology" / "svg",
}
needs_data = pytest.mark.skipif(not DATA.is_dir(), reason="../shared/data (real symbol sets) is not beside the checkout")


def lines(n: int = 256, period: float = 16.0, angle: float = 0.0, width: float = 2.0) -> np.ndarray:
    """(n, n) grey image of parallel lines ``period`` pixels apart, running at ``angle`` degrees."""
    y, x = np.mgrid[0:n, 0:n].astype(float)
    t = np.radians(angle)
    across = np.round(-x * np.sin(t) + y * np.cos(t), 9)
    return (np.abs((across + period / 2) % period - period / 2) < width / 2).astype(float)


def test_the_tile_itself_is_as_dark_and_alike():
    img = lines()
    f = measure(img, img)
    assert f.ink == pytest.approx(1.0) and f.structure == pytest.approx(1.0) and f.distance == pytest.approx(0.0)
    assert f.passes


def test_dust_scores_zero_and_a_shifted_copy_one():
    img = lines()
    assert measure(img, dust(img)).structure == pytest.approx(0.0)
    assert measure(img, np.roll(img, 5, axis=0)).structure > 0.95  # the spectrum ignores phase


def test_lines_turned_or_spaced_otherwise_score_low():
    img = lines(angle=0.0)
    turned = measure(img, lines(angle=90.0))
    assert turned.ink == pytest.approx(1.0, abs=0.02) and turned.structure < 0.3 and not turned.passes
    closer = measure(img, lines(period=8.0))  # twice as many lines: twice the ink, other spacings
    assert closer.ink == pytest.approx(2.0, abs=0.05) and closer.structure < 0.6
    slightly = measure(img, lines(period=17.0))  # a hair wider: soft bins keep it close
    assert slightly.structure > 0.8
    assert measure(img, lines(period=24.0)).structure < STRUCTURE_MIN  # half as far again


def test_the_spectrum_is_normalised_by_orientation_and_spacing():
    s = spectrum(lines(angle=0.0))
    assert s.sum() == pytest.approx(1.0)
    assert s[[0, 1, -1]].sum() > 0.9  # horizontal lines: the bins about 0°
    assert spectrum(np.zeros((64, 64))).sum() == 0.0


def test_a_flat_tile_is_alike_only_to_a_flat_texture():
    solid = np.full((64, 64), 0.9)
    assert measure(solid, np.full((64, 64), 1.0)).structure == 1.0
    assert measure(solid, lines(64)).structure == 0.0


def test_images_of_other_shapes_are_an_error():
    with pytest.raises(ValueError, match="shape"):
        measure(np.zeros((4, 4)), np.zeros((4, 5)))


# ----------------------------------------------------------------------------- the real sets

#: Every tile of the shared sets accepted as cells before issue 12's refusal (2026-12-04, a7ae804).
CELLS = [f"fgdc/{c}" for c in (
    "624 625 627 628 629 631 635 636 637 638 639 640 641 642 644 645 646 647 648 652 657 658 660 661 662 663 667 "
    "668 672 673 674 675 676 677 678 679 680 703 704 705 708 709 717 733").split()] + [
    "osm/grey_vertical_hatch", "osm/intermittent_water", "equinor/21000", "equinor/25000"]  # fmt: skip

#: Refused since issue 12: their bedding and joints leave out 40–66 % of their strokes.
REFUSED = {"fgdc/705", "fgdc/709", "fgdc/733"}

#: (tile, figure) -> what was measured (2026-12-04, seed 1, auto, 4 × 4 tiles, inner 2 × 2 at 512 px).
KNOWN: dict[tuple[str, str], str] = {
    ("fgdc/675", "structure"): "S 0.749 (ink 0.95; interbedded since issue 12, S 0.50 and ink 1.48 before: its tick marks sit in the brick courses, not on the dashed rows)",
    ("fgdc/628", "ink"): "ink 0.79 (S 0.38)",
    ("fgdc/629", "ink"): "ink 0.56 (S 0.04)",
    ("fgdc/631", "ink"): "ink 0.67 (S 0.35)",
    ("fgdc/635", "ink"): "ink 0.88 (S 0.61)",
    ("fgdc/636", "ink"): "ink 0.84 (S 0.54)",
    ("fgdc/637", "ink"): "ink 0.87 (S 0.65)",
    ("fgdc/639", "ink"): "ink 0.73 (S 0.38)",
    ("fgdc/644", "ink"): "ink 0.88 (S 0.63)",
    ("fgdc/645", "ink"): "ink 0.83 (S 0.56)",
    ("fgdc/646", "ink"): "ink 0.87 (S 0.72)",
    ("fgdc/652", "ink"): "ink 0.45 (S 0.46)",
    ("fgdc/657", "ink"): "ink 0.75 (S 0.49)",
    ("fgdc/660", "ink"): "ink 1.56 (S 0.31)",
    ("fgdc/661", "ink"): "ink 0.78 (S 0.53)",
    ("fgdc/703", "ink"): "ink 0.83 (S 0.45)",
    ("fgdc/708", "ink"): "ink 1.51 (S -0.08)",
    ("fgdc/717", "ink"): "ink 0.24 (S 0.06)",
    ("osm/grey_vertical_hatch", "ink"): "ink 3.05 (S 1.00)",
    ("equinor/21000", "ink"): "ink 1.13 (S 1.00)",
    ("fgdc/625", "structure"): "S 0.64 (ink 0.91)",
    ("fgdc/628", "structure"): "S 0.38 (ink 0.79)",
    ("fgdc/629", "structure"): "S 0.04 (ink 0.56)",
    ("fgdc/631", "structure"): "S 0.35 (ink 0.67)",
    ("fgdc/635", "structure"): "S 0.61 (ink 0.88)",
    ("fgdc/636", "structure"): "S 0.54 (ink 0.84)",
    ("fgdc/637", "structure"): "S 0.65 (ink 0.87)",
    ("fgdc/639", "structure"): "S 0.38 (ink 0.73)",
    ("fgdc/641", "structure"): "S 0.73 (ink 0.97)",
    ("fgdc/644", "structure"): "S 0.63 (ink 0.88)",
    ("fgdc/645", "structure"): "S 0.56 (ink 0.83)",
    ("fgdc/646", "structure"): "S 0.72 (ink 0.87)",
    ("fgdc/652", "structure"): "S 0.46 (ink 0.45)",
    ("fgdc/657", "structure"): "S 0.49 (ink 0.75)",
    ("fgdc/660", "structure"): "S 0.31 (ink 1.56)",
    ("fgdc/661", "structure"): "S 0.53 (ink 0.78)",
    ("fgdc/662", "structure"): "S 0.50 (ink 1.07)",
    ("fgdc/663", "structure"): "S 0.44 (ink 1.01)",
    ("fgdc/703", "structure"): "S 0.45 (ink 0.83)",
    ("fgdc/708", "structure"): "S -0.08 (ink 1.51)",
    ("fgdc/717", "structure"): "S 0.06 (ink 0.24)",
}


@cache
def figures(tile: str):
    pytest.importorskip("resvg_py")
    pytest.importorskip("PIL")
    from svgtile.apps.linework import measure_tile

    folder, stem = tile.split("/")
    return measure_tile(SETS[folder] / f"{stem}.svg", seed=1)


def cases(figure: str) -> list:
    out = []
    for tile in CELLS:
        if tile in REFUSED:
            continue
        why = KNOWN.get((tile, figure))
        marks = [pytest.mark.xfail(strict=True, reason=f"{tile}: {figure} {why}")] if why else []
        out.append(pytest.param(tile, marks=[needs_data, *marks], id=tile))
    return out


@needs_data
@pytest.mark.parametrize("tile", sorted(REFUSED))
def test_tiles_leaving_out_their_pattern_are_refused(tile):
    from svgtile.tiles.importer import LeftOut, import_tile

    folder, stem = tile.split("/")
    with pytest.raises(LeftOut, match="leave out"):
        import_tile(SETS[folder] / f"{stem}.svg")


@pytest.mark.parametrize("tile", cases("ink"))
def test_cells_are_as_dark_as_the_tile(tile):
    f = figures(tile)
    assert INK_BOUNDS[0] <= f.ink <= INK_BOUNDS[1], f"ink {f.ink:.2f}"


@pytest.mark.parametrize("tile", cases("structure"))
def test_cells_run_like_the_tile(tile):
    f = figures(tile)
    assert f.structure >= STRUCTURE_MIN, f"S {f.structure:.2f}"
