"""Writing an imported tile as exemplar SVG (stage 6 of :mod:`svgtile.tiles.importer`): one
``<symbol>`` per kind, one ``<use>`` per motif, the tile as the region with its period."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from svgtile.svg.dialect import GROUND_ATTR, PERIOD_ATTR, SVG_NS, XLINK_NS
from svgtile.svg.numbers import fmt, fmt_array
from svgtile.svg.tilepieces import TilePieces


def exemplar_text(
    tile: TilePieces,
    idx: np.ndarray,
    kind: np.ndarray,
    xy: np.ndarray,
    angle: np.ndarray,
    motif: np.ndarray,
    piece: np.ndarray,
    offset: np.ndarray,
) -> str:
    """The exemplar SVG: a symbol per kind, a ``<use>`` per motif, the tile as the region.

    ``motif``, ``piece`` and ``offset`` list every member piece of every motif: the motif it is
    in, its index into ``idx`` and the translation (m, 2) that brings it to the motif's place.
    """
    x0, y0, w, h = tile.box
    box = " ".join(fmt_array(np.array([x0, y0, w, h])))
    root = ET.Element(f"{{{SVG_NS}}}svg", {"viewBox": box, "width": fmt(w), "height": fmt(h)})
    desc = ET.SubElement(root, f"{{{SVG_NS}}}desc")
    desc.text = (
        f"Imported by svgtile from {Path(tile.source).name}: {len(kind)} motif(s) of "
        f"{int(kind.max()) + 1} kind(s); the region repeats with period {fmt(w)} x {fmt(h)}."
    )
    defs = ET.SubElement(root, f"{{{SVG_NS}}}defs")
    for k in range(int(kind.max()) + 1):
        rep = int(np.flatnonzero(kind == k)[0])
        symbol = ET.SubElement(defs, f"{{{SVG_NS}}}symbol", {"id": f"kind-{k + 1}", "overflow": "visible"})
        sel = np.flatnonzero(motif == rep)
        # pieces of one element drawn in one place form one path (holes keep their fill rule)
        groups: dict[tuple, list[int]] = {}
        for s in sel:
            p = idx[piece[s]]
            groups.setdefault((int(tile.element[p]), *np.round(offset[s], 9)), []).append(s)
        for members in groups.values():
            p0 = idx[piece[members[0]]]
            d = " ".join(_path_data(tile.points[idx[piece[s]]] + offset[s] - xy[rep], bool(tile.closed[idx[piece[s]]])) for s in members)
            attrs = {name: _paint_value(name, value) for name, value in tile.paint[p0]}
            attrs["d"] = d
            ET.SubElement(symbol, f"{{{SVG_NS}}}path", dict(sorted(attrs.items())))
    region = ET.SubElement(root, f"{{{SVG_NS}}}rect", {
        "id": "region", "x": fmt(x0), "y": fmt(y0), "width": fmt(w), "height": fmt(h),
        "fill": "none", PERIOD_ATTR: f"{fmt(w)} {fmt(h)}",
    })  # fmt: skip
    if tile.ground:  # the tile's painted background, for the textures to paint (FGDC 659)
        region.set(GROUND_ATTR, tile.ground)
    group = ET.SubElement(root, f"{{{SVG_NS}}}g", {"id": "motifs"})
    xs, ys, angles = fmt_array(xy[:, 0]), fmt_array(xy[:, 1]), fmt_array(angle)
    for k, x, y, a in zip(kind.tolist(), xs, ys, angles, strict=True):
        transform = f"translate({x} {y})" + (f" rotate({a})" if a != "0" else "")
        ET.SubElement(group, f"{{{SVG_NS}}}use", {f"{{{XLINK_NS}}}href": f"#kind-{k + 1}", "transform": transform})
    ET.indent(root, space=" ")
    return ET.tostring(root, encoding="unicode", xml_declaration=False) + "\n"


def _path_data(pts: np.ndarray, closed: bool) -> str:
    """Path data of a polyline; a single point is a zero-length line (a dot with round caps)."""
    if len(pts) == 1:
        pts = np.vstack([pts, pts])
    v = fmt_array(pts.ravel())
    coords = [f"{v[2 * i]} {v[2 * i + 1]}" for i in range(len(pts))]
    return "M" + coords[0] + " L" + " ".join(coords[1:]) + (" Z" if closed else "")


def _paint_value(name: str, value: str) -> str:
    """A paint value as plain SVG: QGIS ``param(name) default`` becomes its default."""
    text = value.strip()
    if text.startswith("param("):
        rest = text.split(")", 1)[1].strip()
        return rest or ("none" if name == "fill" else "#000000")
    return text
