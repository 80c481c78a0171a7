"""Growth on an exemplar whose motif centres lie on one line (FGDC 624, 625 and nine map-pattern
symbols drawn as one column of marks): it has no rings to grow from (Ijiri et al. 2008, §4).

``svgtile synth`` on such a file chose growth (the order reads rows) and ended in an internal
error (scipy's QhullError from the hull test, then an empty ring table); now auto gives it to
patch, saying why, and ``--engine growth`` refuses it in one line.
"""

from __future__ import annotations

import pytest
from test_order import exemplar, grid_points

from svgtile import analyze
from svgtile.cli.main import main
from svgtile.core.region import Region
from svgtile.engines import ENGINES, choose, synthesize
from svgtile.engines.growth import grows_from
from svgtile.errors import ExemplarError

COLUMN = [(20.0, 2.0 + 3.0 * i) for i in range(13)]  # 13 dots 3 apart, one above the other
#: A slanted row as a file writes it: its centres rounded to 3 decimals lie on no exact line (their
#: matrix has rank 2), yet every triangle of them is a sliver.
SLANTED = [(round(2 + 2.9 * i, 3), round(3 + 1.0785 * i, 3)) for i in range(13)]
#: A hand-drawn row: each mark up to a third of a step off the line.
DRAWN_ROW = [(2 + 2.9 * i, 3 + 1.0785 * i + 0.9 * ((i * 7) % 5 - 2) / 2) for i in range(13)]


def column_svg(tmp_path):
    ex = exemplar(COLUMN)
    path = tmp_path / "column.svg"
    uses = "".join(f'<use xlink:href="#dot" transform="translate({x:g} {y:g})"/>' for x, y in COLUMN)
    path.write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 40 40">'
        '<defs><symbol id="dot"><circle r="0.5"/></symbol></defs>'
        f'<rect id="region" width="40" height="40" fill="none"/>{uses}</svg>')  # fmt: skip
    return ex, path


@pytest.mark.parametrize(("points", "period", "grows"), [
    (COLUMN, False, False),
    ([(2.0 + 3.0 * i, 7.0) for i in range(13)], False, False),  # a row
    ([(1.0 + i, 1.0 + 2.0 * i) for i in range(13)], False, False),  # a slanted line
    (SLANTED, False, False),
    (DRAWN_ROW, False, False),
    ([*COLUMN[:2], (5.0, 5.0)], False, True),  # three points that span the plane
    (COLUMN[:2], False, False),  # too few
    (COLUMN, True, True),  # a tile: its copies fill the plane
    (grid_points(), False, True),
])  # fmt: skip
def test_grows_from_needs_centres_that_span_the_plane(points, period, grows):
    assert grows_from(exemplar(points, period=period)) is grows


def test_auto_gives_one_line_to_patch_and_growth_refuses_it(tmp_path, capsys):
    ex, path = column_svg(tmp_path)
    st = analyze(ex)
    c = choose(ex, st, available=ENGINES)
    assert (c.engine, c.rule) == ("patch", "one-line") and "no rings for growth" in c.why
    with pytest.raises(ExemplarError, match=r"t\.svg: engine 'growth' .* 13 motif centres lie on one line"):
        synthesize(ex, Region.rectangle(60, 60), "growth", seed=1, stats=st)
    out = tmp_path / "out.svg"
    assert main(["synth", str(path), "-o", str(out), "--size", "60x40", "--seed", "1"]) == 0
    assert "svgtile: auto: engine patch: drawn rows on one line" in capsys.readouterr().err
    assert 'engine="patch"' in out.read_text()
    out.unlink()
    rc = main(["synth", str(path), "-o", str(out), "--size", "60x40", "--seed", "1", "--engine", "growth"])
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if not line.startswith("svgtile: warning:")]
    assert rc != 0 and len(errors) == 1 and "lie on one line" in errors[0] and "Traceback" not in err, err
    assert not out.exists()


def test_a_drawn_lattice_is_still_grown():
    ex = exemplar(grid_points())
    c = choose(ex, analyze(ex), available=ENGINES)
    assert (c.engine, c.rule) == ("growth", "drawn-order")


@pytest.mark.parametrize("points", [SLANTED, DRAWN_ROW], ids=["slanted", "drawn-row"])
def test_a_row_near_one_line_goes_to_patch_and_growth_refuses_it(points):
    """Centres near one line (not on it: rank 2) have only skewed triangles, so no ring; growth
    ended in an internal ValueError (an empty ring table's maximum) and auto had chosen it."""
    ex = exemplar(points)
    st = analyze(ex)
    assert choose(ex, st, available=ENGINES).rule == "one-line"
    with pytest.raises(ExemplarError, match="lie on one line"):
        synthesize(ex, Region.rectangle(60, 60), "growth", seed=1, stats=st)
