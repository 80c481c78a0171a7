"""Shared test set-up: tiny exemplar SVGs written to ``tmp_path`` and the ``--update-golden`` flag.

The exemplars are small on purpose (a few motifs in a 20 × 20 region) so that synthesizing
60 × 40 takes a fraction of a second; the bundled ``exemplars/`` are tested elsewhere.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

SVG_HEAD = (
    '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
    'viewBox="0 0 20 20">'
)

#: Two symbol kinds; ``bar`` is drawn away from its origin, so its ``<use>`` needs an offset.
TINY = SVG_HEAD + """
  <defs>
    <symbol id="dot" overflow="visible"><circle r="1" fill="#222"/></symbol>
    <symbol id="bar" overflow="visible"><rect x="0" y="0" width="4" height="1" fill="#555"/></symbol>
  </defs>
  <rect id="region" x="0" y="0" width="20" height="20" fill="none"/>
  <g id="motifs">
    <use xlink:href="#dot" transform="translate(4 4)"/>
    <use xlink:href="#bar" transform="translate(11 4) rotate(30)"/>
    <use xlink:href="#dot" transform="translate(15 14)"/>
    <use xlink:href="#bar" transform="translate(3 12) rotate(-20)"/>
    <use xlink:href="#dot" x="10" y="17"/>
  </g>
</svg>
"""

#: Plain shapes, no symbols: two triangles congruent up to rotation and two circles.
PLAIN = SVG_HEAD + """
  <polygon points="3,3 7,3 5,6" fill="#333"/>
  <polygon points="14,4 14,8 11,6" fill="#333"/>
  <circle cx="6" cy="14" r="1.5" fill="none" stroke="#000" stroke-width="0.5"/>
  <circle cx="15" cy="15" r="1.5" fill="none" stroke="#000" stroke-width="0.5"/>
</svg>
"""

#: A symbol with a viewBox drawn through ``<use width height>``, and SVG 2 ``href``.
VIEWBOX = SVG_HEAD + """
  <defs><symbol id="ring" viewBox="0 0 10 10"><circle cx="5" cy="5" r="4"/></symbol></defs>
  <use href="#ring" x="2" y="2" width="3" height="3"/>
  <use href="#ring" x="12" y="4" width="3" height="3"/>
  <use href="#ring" x="6" y="12" width="3" height="3" transform="rotate(10 7 13)"/>
  <use href="#ring" x="14" y="14" width="3" height="3"/>
</svg>
"""

#: Two motifs share area: svgtile warns and carries on.
OVERLAPPING = SVG_HEAD + """
  <defs><symbol id="dot" overflow="visible"><circle r="1.5"/></symbol></defs>
  <use xlink:href="#dot" transform="translate(5 5)"/>
  <use xlink:href="#dot" transform="translate(6 5)"/>
  <use xlink:href="#dot" transform="translate(14 14)"/>
  <use xlink:href="#dot" transform="translate(6 15)"/>
</svg>
"""

EXEMPLARS = {"tiny": TINY, "plain": PLAIN, "viewbox": VIEWBOX}


#: Test modules of unit tests on small inputs: ``pytest -m quick`` runs them (README).
QUICK_MODULES = {"test_layout", "test_engines_contract", "test_junction", "test_analysis", "test_geojson",
                 "test_preview", "test_inkscape", "test_output", "test_swatches"}


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for item in items:
        if item.path.stem in QUICK_MODULES:
            item.add_marker(pytest.mark.quick)


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--update-golden",
        action="store_true",
        help="rewrite the golden SVG snapshots under tests/golden/ instead of comparing with them",
    )


@pytest.fixture
def update_golden(request: pytest.FixtureRequest) -> bool:
    return bool(request.config.getoption("--update-golden"))


@pytest.fixture
def write_svg(tmp_path: Path):
    """``write_svg(text, name="exemplar.svg") -> Path``: an SVG file in a fresh folder."""

    def write(text: str | bytes, name: str = "exemplar.svg") -> Path:
        path = tmp_path / name
        path.write_bytes(text.encode() if isinstance(text, str) else text)
        return path

    return write


@pytest.fixture
def tiny(write_svg) -> Path:
    return write_svg(TINY, "tiny.svg")


XLINK = "http://www.w3.org/1999/xlink"


def random_exemplar(rng: np.random.Generator, n: int) -> str:
    """An exemplar of ``n`` motifs of three kinds (an L, a ring, a dash) at random places, angles
    and scales in a 100 × 100 viewBox."""
    symbols = (
        '<symbol id="ell" overflow="visible"><polygon points="0,0 6,0 6,2 2,2 2,8 0,8"/></symbol>'
        '<symbol id="ring" overflow="visible"><circle r="2" fill="none" stroke="black" stroke-width="0.5"/></symbol>'
        '<symbol id="dash" overflow="visible"><line x1="0" y1="0" x2="5" y2="0" stroke="black" '
        'stroke-width="0.8" stroke-linecap="round"/></symbol>'
    )
    uses = []
    for _ in range(n):
        href = rng.choice(["ell", "ring", "dash"])
        x, y = rng.uniform(5, 95, 2)
        uses.append(f'<use xlink:href="#{href}" transform="translate({x:.3f} {y:.3f}) '
                    f'rotate({rng.uniform(-180, 180):.2f}) scale({rng.uniform(0.6, 1.6):.3f})"/>')  # fmt: skip
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK}" viewBox="0 0 100 100">'
        f"<defs>{symbols}</defs>{''.join(uses)}</svg>"
    )


def arrange(engine, exemplar, region, *, rng=None, seed=None, stats=None, boundary="clip", progress=None, **params):
    """The arrangement :func:`svgtile.engines.synthesize` makes (the tests' short spelling)."""
    from svgtile.engines import synthesize

    return synthesize(exemplar, region, engine, rng=rng, seed=seed, stats=stats, boundary=boundary,
                      progress=progress, params=params).arrangement  # fmt: skip


def fake_engine(place, like: str = "patch"):
    """An engine with ``like``'s name and parameters whose ``place(ctx, params)`` is ``place``
    (to monkeypatch into :data:`svgtile.engines.ENGINES`)."""
    from svgtile.engines import ENGINES

    real = ENGINES[like]
    return type("FakeEngine", (), {"name": real.name, "summary": real.summary, "Params": real.Params,
                                   "place": staticmethod(place), "reach": real.reach})()  # fmt: skip


def stamp(ex, nx: int, ny: int | None = None):
    """The exemplar's motifs copied on an ``nx × ny`` (default square) grid of its region's size,
    and that region: (Arrangement, Region) — a tiling, the most repetitive texture there is."""
    from svgtile.core.arrangement import Arrangement
    from svgtile.core.region import Region

    ny = nx if ny is None else ny
    x0, y0, x1, y1 = ex.region.bounds
    w, h = x1 - x0, y1 - y0
    a, b = np.meshgrid(np.arange(nx), np.arange(ny))
    offset = np.stack([a.ravel() * w, b.ravel() * h], axis=1)
    m, t = ex.motifs, len(offset)
    xy = (m.xy[None, :, :] + offset[:, None, :]).reshape(-1, 2)
    arr = Arrangement(np.tile(m.kind, t), xy, np.tile(m.angle, t), np.tile(m.scale, t))
    return arr, Region.rectangle(nx * w, ny * h, x0, y0)
