"""PNG rendering (previews, contact sheet, swatch sheet) and the contact sheet of ``compare --png``.

resvg (the ``resvg-py`` binding, optional extra ``png``) is a well-kept, dependency-free SVG
renderer: it draws ``<symbol>``/``<use>``, clip paths and strokes as browsers do, which is all a
texture needs.  The contact sheet is one SVG — the exemplar and each texture side by side at the
same scale, labelled — rendered once, so what a reader sees is also an SVG they can open.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections.abc import Sequence

from svgtile.errors import OutputError
from svgtile.svg.dialect import SVG_NS, XLINK_NS
from svgtile.svg.writer import fmt

#: Gap between panels and height of the label band, in pixels of the sheet.
PAD, LABEL = 12, 22
#: Width of a label character, pixels (15 px sans-serif, generous).
CHAR = 9
_HREF = (f"{{{XLINK_NS}}}href", "href")


class RendererMissing(OutputError):
    """The optional PNG renderer is not installed (so no PNG can be written)."""


def require_renderer() -> None:
    """Fail at once, before any work, when the renderer is missing (:class:`RendererMissing`)."""
    render_png('<svg xmlns="http://www.w3.org/2000/svg" width="1" height="1"/>', 1)


def render_png(svg: str, width: int, *, sans_serif: str | None = "DejaVu Sans") -> bytes:
    """PNG bytes of the SVG text ``svg``, ``width`` pixels wide, on white: every PNG svgtile writes.

    Parameters
    ----------
    svg : an SVG document as text
    width : int, pixels (at least 1); the height follows the document's aspect ratio
    sans_serif : the font resvg draws for the generic ``sans-serif`` family; None leaves resvg's
        own default (the swatch sheet renders so)

    Raises
    ------
    RendererMissing
        resvg-py is not installed.
    """
    try:
        import resvg_py
    except ImportError:
        raise RendererMissing("--png needs the optional renderer: pip install 'svgtile[png]' (resvg-py)") from None
    return bytes(resvg_py.svg_to_bytes(svg_string=svg, width=max(1, int(width)), background="white",
                                       sans_serif_family=sans_serif))


def contact_sheet(panels: Sequence[tuple[str, str]], scale: float) -> tuple[str, int]:
    """One SVG holding each ``(label, svg text)`` panel side by side, top-aligned, labelled below.

    Every panel keeps its own viewBox and is drawn at ``scale`` pixels per user unit, so motifs
    compare at a glance.  Ids are prefixed per panel (``p0-``, ``p1-`` …) with every reference to
    them, since the exemplar and its textures define the same symbols.

    Returns
    -------
    svg : str, the sheet
    width : int, its width in pixels
    """
    sheet = ET.Element(f"{{{SVG_NS}}}svg")
    x, height = PAD, 0.0
    for n, (label, text) in enumerate(panels):
        root = _prefixed(ET.fromstring(text.encode("utf-8")), f"p{n}-")
        vx, vy, vw, vh = _view_box(root)
        w, h = vw * scale, vh * scale
        slot = max(w, CHAR * len(label))  # a narrow panel still gets room for its label
        x += (slot - w) / 2
        inner = ET.SubElement(sheet, f"{{{SVG_NS}}}svg", {
            "x": fmt(x), "y": fmt(PAD), "width": fmt(w), "height": fmt(h),
            "viewBox": " ".join(fmt(v) for v in (vx, vy, vw, vh)), "overflow": "hidden",
        })  # fmt: skip
        inner.extend(child for child in root if _local(child.tag) not in ("title", "metadata"))
        ET.SubElement(sheet, f"{{{SVG_NS}}}rect", {
            "x": fmt(x), "y": fmt(PAD), "width": fmt(w), "height": fmt(h),
            "fill": "none", "stroke": "#999", "stroke-width": "1",
        })  # fmt: skip
        caption = ET.SubElement(sheet, f"{{{SVG_NS}}}text", {
            "x": fmt(x + w / 2), "y": fmt(PAD + h + LABEL - 6), "text-anchor": "middle",
            "font-family": "DejaVu Sans, Helvetica, Arial, sans-serif", "font-size": "15", "fill": "#000",
        })  # fmt: skip
        caption.text = label
        x += w + (slot - w) / 2 + PAD
        height = max(height, h)
    width, full = round(x), round(PAD + height + LABEL + PAD)
    sheet.set("width", str(width))
    sheet.set("height", str(full))
    sheet.set("viewBox", f"0 0 {width} {full}")
    ET.indent(sheet, space=" ")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(sheet, encoding="unicode") + "\n", width


def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _view_box(root: ET.Element) -> tuple[float, float, float, float]:
    box = root.get("viewBox")
    if box:
        x, y, w, h = (float(v) for v in re.split(r"[\s,]+", box.strip()))
        return x, y, w, h
    return 0.0, 0.0, float(re.match(r"[\d.]+", root.get("width", "100")).group()), float(
        re.match(r"[\d.]+", root.get("height", "100")).group()
    )


def _prefixed(root: ET.Element, prefix: str) -> ET.Element:
    """``root`` with every id and every ``#id`` reference (href, ``url(#…)``) prefixed."""
    ids = {el.get("id") for el in root.iter() if el.get("id")}

    def fix(value: str) -> str:
        return re.sub(r"url\(\s*#([^)\s]+)\s*\)", lambda m: f"url(#{prefix}{m.group(1)})" if m.group(1) in ids else m.group(0), value)

    for el in root.iter():
        if el.get("id"):
            el.set("id", prefix + el.get("id"))
        for key in _HREF:
            ref = el.get(key)
            if ref and ref.startswith("#") and ref[1:] in ids:
                el.set(key, "#" + prefix + ref[1:])
        for key, value in el.attrib.items():
            if "url(" in value:
                el.set(key, fix(value))
    return root
