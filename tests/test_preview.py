"""The one PNG renderer: what every caller (compare --png, swatches --png) gets from it."""

from __future__ import annotations

import sys

import pytest

from svgtile.apps.preview import RendererMissing, render_png
from svgtile.errors import OutputError

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
LABEL = ('<svg xmlns="http://www.w3.org/2000/svg" width="60" height="20">'
         '<text x="2" y="15" font-family="sans-serif" font-size="14">Gravel</text></svg>')


def _width(png: bytes) -> int:
    return int.from_bytes(png[16:20], "big")


def test_render_png_is_width_pixels_wide_and_at_least_one():
    pytest.importorskip("resvg_py")
    png = render_png(LABEL, 120)
    assert png.startswith(PNG_MAGIC) and _width(png) == 120
    assert int.from_bytes(png[20:24], "big") == 40  # the document's aspect ratio
    assert _width(render_png(LABEL, 0)) == 1


def test_render_png_passes_the_sans_serif_font_through():
    resvg_py = pytest.importorskip("resvg_py")
    # the swatch sheet renders with resvg's default, the contact sheet with DejaVu Sans
    assert render_png(LABEL, 120, sans_serif=None) == bytes(
        resvg_py.svg_to_bytes(svg_string=LABEL, width=120, background="white"))
    assert render_png(LABEL, 120) == bytes(
        resvg_py.svg_to_bytes(svg_string=LABEL, width=120, background="white", sans_serif_family="DejaVu Sans"))


def test_missing_renderer_is_one_output_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "resvg_py", None)  # import fails as if not installed
    with pytest.raises(RendererMissing) as info:
        render_png(LABEL, 10)
    assert isinstance(info.value, OutputError)
    assert str(info.value) == "--png needs the optional renderer: pip install 'svgtile[png]' (resvg-py)"


def test_swatches_without_renderer_say_the_same(tmp_path, capsys, monkeypatch):
    from svgtile.cli.main import main

    monkeypatch.setitem(sys.modules, "resvg_py", None)
    tile = tmp_path / "t.svg"
    tile.write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10">'
                    '<circle cx="5" cy="5" r="1" fill="none" stroke="#000" stroke-width="0.2"/></svg>')
    assert main(["swatches", str(tile), "-o", str(tmp_path / "s.svg"), "--png"]) == 1
    err = capsys.readouterr().err
    assert err == "svgtile: error: --png needs the optional renderer: pip install 'svgtile[png]' (resvg-py)\n"


def test_text_is_drawn_in_a_real_font():
    """Labels must show (issue 17 item 5): the PNG of a text differs from the PNG without it."""
    pytest.importorskip("resvg_py")
    from svgtile.apps.preview import render_png

    head = '<svg xmlns="http://www.w3.org/2000/svg" width="120" height="40">'
    text = '<text x="10" y="30" font-family="sans-serif" font-size="24">Qal</text>'
    assert render_png(head + text + "</svg>", 120) != render_png(head + "</svg>", 120)
