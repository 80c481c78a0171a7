"""Writing the synthesized texture as SVG: the exemplar's symbols and one ``<use>`` per motif.

This is the only module that writes XML.  Numbers have a fixed format (at most four decimals,
no trailing zeros), elements a stable order, and nothing depends on the clock or the machine, so
the same inputs and seed give a byte-identical file.  :func:`svgtile.files.write_file` puts it
on disk (atomically).
"""

from __future__ import annotations

import copy
import dataclasses
import re
import xml.etree.ElementTree as ET

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.cells import FEATURES, Cellwork
from svgtile.core.exemplar import Exemplar, Kind
from svgtile.core.region import Region
from svgtile.engines.base import Result
from svgtile.svg.dialect import META_NS, SVG_NS, XLINK_NS
from svgtile.svg.numbers import fmt, fmt_array

USES_MARK = "svgtile-uses"
# Characters XML 1.0 forbids (and lone surrogates from undecodable file names).
_NOT_XML = re.compile("[^\x09\x0A\x0D\x20-\uD7FF\uE000-\uFFFD\U00010000-\U0010FFFF]")


def use_transform_suffix(kind: Kind) -> str:
    """The part of a motif's transform that is the same for every instance of ``kind``."""
    parts = []
    if np.any(kind.offset != 0):
        parts.append(f"translate({fmt(kind.offset[0])} {fmt(kind.offset[1])})")
    if not np.allclose(kind.residual, np.eye(2)):
        n = kind.residual
        parts.append(f"matrix({fmt(n[0, 0])} {fmt(n[1, 0])} {fmt(n[0, 1])} {fmt(n[1, 1])} 0 0)")
    return " ".join(parts)


def use_elements(arr: Arrangement, kinds: tuple[Kind, ...], indent: str = "    ") -> list[str]:
    """One ``<use>`` line per motif, in the arrangement's order.

    ``transform="translate(x y) rotate(angle) scale(s) <kind suffix>"``; ``rotate`` is left out
    for angle 0 and ``scale`` for scale 1 (after formatting).  Columns are formatted in bulk.
    """
    heads, tails = [], []
    for kind in kinds:
        attrs = "".join(f' {k}="{_escape(v)}"' for k, v in kind.use_attrs)
        heads.append(f'{indent}<use xlink:href="#{_escape(kind.href)}"{attrs} transform="translate(')
        suffix = use_transform_suffix(kind)
        tails.append(f' {suffix}"/>' if suffix else '"/>')
    if len(arr) == 0:
        return []
    xs, ys = fmt_array(arr.xy[:, 0]), fmt_array(arr.xy[:, 1])
    rot = [f") rotate({a}" if a != "0" else "" for a in fmt_array(arr.angle)]
    scl = [f") scale({s}" if s != "1" else "" for s in fmt_array(arr.scale)]
    return [
        f"{heads[k]}{x} {y}{r}{s}){tails[k]}"
        for k, x, y, r, s in zip(arr.kind.tolist(), xs, ys, rot, scl, strict=True)
    ]


def result_document(result: Result, **where: object) -> str:
    """A synthesis :class:`~svgtile.engines.base.Result` as SVG text (:func:`svg_document`),
    its run recorded in the metadata (:meth:`Result.metadata`: engine, seed, ``where``,
    parameters, boundary, motif count)."""
    return svg_document(result.exemplar, result.arrangement, result.region, boundary=result.boundary,
                        params=result.metadata(**where), cells=result.cells)  # fmt: skip


def svg_document(
    exemplar: Exemplar, arr: Arrangement, region: Region, *, boundary: str, params: dict[str, object],
    cells: Cellwork | None = None,
) -> str:
    """The output SVG as text.

    Parameters
    ----------
    exemplar : gives the symbols (copied unchanged, ids kept) and kinds
    arr : the motifs
    region : the output region; its bounding box is the document's viewBox
    boundary : ``clip`` adds a clipPath of the region around the motifs
    params : recorded in ``<metadata>`` (engine, seed, parameters), sorted by name
    cells : the cells and lines of a cellular texture, drawn before the motifs
        (:func:`cell_elements`)

    The motifs go in ``<g id="svgtile">`` and the clip path is ``svgtile-clip``; should the
    exemplar's copied defs already use such an id, a numbered suffix keeps ids unique.
    """
    head, tail = svg_document_parts(exemplar, region, boundary=boundary, params=params)
    body = "\n".join([*cell_elements(cells), *use_elements(arr, exemplar.kinds)])
    return head + body + tail if body else head.rstrip(" ").removesuffix("\n") + tail


def svg_document_parts(
    exemplar: Exemplar, region: Region, *, boundary: str, params: dict[str, object]
) -> tuple[str, str]:
    """:func:`svg_document` without its motifs: the text before the first ``<use>`` line and
    after the last, for a writer that streams the lines between (``head + "\\n".join(lines) +
    tail``; with no line at all, ``head.rstrip(" ").removesuffix("\\n") + tail``)."""
    x0, y0, x1, y1 = region.bounds
    width, height, *box = fmt_array(np.array([x1 - x0, y1 - y0, x0, y0]))
    root = ET.Element(
        f"{{{SVG_NS}}}svg",
        {"width": width, "height": height, "viewBox": " ".join((*box, width, height))},
    )
    meta = ET.SubElement(root, f"{{{SVG_NS}}}metadata")
    ET.SubElement(meta, f"{{{META_NS}}}run", {k: _xml_chars(str(v)) for k, v in sorted(params.items())})
    defs = ET.SubElement(root, f"{{{SVG_NS}}}defs")
    for el in exemplar.defs:
        defs.append(_in_svg_namespace(copy.deepcopy(el)))
    taken = {node.get("id") for node in defs.iter()}
    group = ET.SubElement(root, f"{{{SVG_NS}}}g", {"id": _unique_id("svgtile", taken)})
    if boundary == "clip":
        clip_id = _unique_id("svgtile-clip", taken)
        clip = ET.SubElement(defs, f"{{{SVG_NS}}}clipPath", {"id": clip_id})
        ET.SubElement(clip, f"{{{SVG_NS}}}path", {"d": path_data(region.shape), "clip-rule": "evenodd"})
        group.set("clip-path", f"url(#{clip_id})")
    _ground(group, exemplar.ground, region.shape)
    group.append(ET.Comment(USES_MARK))
    ET.indent(root, space="  ")
    text = ET.tostring(root, encoding="unicode")
    head_end = text.index(">")
    if "xmlns:xlink=" not in text[:head_end]:  # the <use> lines below need it even if defs do not
        text = text.replace("<svg ", f'<svg xmlns:xlink="{XLINK_NS}" ', 1)
    # the group is the last element, so its marker is the last one in the text; the first
    # line's indent is the marker's
    before, _, after = text.rpartition(f"<!--{USES_MARK}-->")
    indent = len(before) - len(before.rstrip(" "))
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + before[: len(before) - indent], after + "\n"


def _ground(group: ET.Element, colour: str | None, shape: shapely.Geometry) -> None:
    """The region painted with the exemplar's ground (:attr:`Exemplar.ground`), first in its
    texture group, under the cells and motifs."""
    if colour:
        ET.SubElement(group, f"{{{SVG_NS}}}path", {"class": "svgtile-ground", "style": f"fill:{colour};stroke:none",
                                                   "fill-rule": "evenodd", "d": path_data(shape)})  # fmt: skip


def cell_elements(cells: Cellwork | None, indent: str = "    ") -> list[str]:
    """One ``<path>`` per cell or line, in the cellwork's order, with its style and its feature as
    class (``svgtile-corner``, ``-edge``, ``-face``, ``-line``); cells with holes use evenodd."""
    if cells is None or len(cells) == 0:
        return []
    styles = [_escape(s) for s in cells.styles]
    out = []
    for geom, feature, style in zip(cells.shapes, cells.feature.tolist(), cells.style.tolist(), strict=True):
        polygonal = shapely.get_type_id(geom) in (3, 6)
        d = path_data(geom) if polygonal else line_data(geom)
        rule = ' fill-rule="evenodd"' if polygonal else ""
        if d:
            out.append(f'{indent}<path class="svgtile-{FEATURES[feature]}" style="{styles[style]}"{rule} d="{d}"/>')
    return out


def line_data(geom: shapely.Geometry) -> str:
    """SVG path data of a (Multi)LineString."""
    parts = []
    for line in shapely.get_parts(geom):
        xy = fmt_array(np.asarray(line.coords).ravel())
        if len(xy) >= 4:
            parts.append("M" + " L".join(f"{x} {y}" for x, y in zip(xy[::2], xy[1::2], strict=True)))
    return " ".join(parts)


def path_data(geom: shapely.Geometry) -> str:
    """SVG path data of a (Multi)Polygon, holes included (use with the evenodd rule)."""
    parts = []
    for poly in shapely.get_parts(geom):
        for ring in [poly.exterior, *poly.interiors]:
            xy = fmt_array(np.asarray(ring.coords)[:-1].ravel())
            parts.append("M" + " L".join(f"{x} {y}" for x, y in zip(xy[::2], xy[1::2], strict=True)) + " Z")
    return " ".join(parts)


def _unique_id(base: str, taken: set[str | None]) -> str:
    ident, n = base, 1
    while ident in taken:
        n += 1
        ident = f"{base}-{n}"
    taken.add(ident)
    return ident


def _xml_chars(value: str) -> str:
    """``value`` with characters XML cannot hold replaced by U+FFFD."""
    return _NOT_XML.sub("\ufffd", value)


def _in_svg_namespace(el: ET.Element) -> ET.Element:
    """Give un-namespaced elements (from an SVG without xmlns) the SVG namespace."""
    for node in el.iter():
        if isinstance(node.tag, str) and not node.tag.startswith("{"):
            node.tag = f"{{{SVG_NS}}}{node.tag}"
    return el


def _escape(value: str) -> str:
    return value.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")


# ----------------------------------------------------------------------------- map documents


@dataclasses.dataclass(frozen=True, eq=False)
class MapLayer:
    """One region's texture in a map document.

    Attributes
    ----------
    ident : the region's id; the texture group is ``svgtile-<ident>``
    cls : the region's class (written as ``data-svgtile-class``)
    shape : the region (Multi)Polygon in the root's user units; its clip path
    kinds : the kinds, their ``href`` pointing at the prefixed symbols (:func:`prefixed_defs`)
    arr : the motifs, root user units
    boundary : ``clip`` adds the region's clip path
    anchor : the map element the texture is drawn just above, or None (then at the end)
    matrix : (3, 3) from the anchor's parent's user space to the root's, or None
    ground : the colour the class's texture is drawn on (:attr:`Exemplar.ground`), or None
    """

    ident: str
    cls: str
    shape: shapely.Geometry
    kinds: tuple[Kind, ...]
    arr: Arrangement
    boundary: str
    anchor: ET.Element | None = None
    matrix: np.ndarray | None = None
    ground: str | None = None


def prefixed_defs(exemplar: Exemplar, prefix: str) -> tuple[list[ET.Element], tuple[Kind, ...]]:
    """Copies of the exemplar's defs with every id prefixed, and its kinds pointing at them.

    Two exemplars of one map may both define ``#dot``; with a prefix per style they cannot clash
    with each other nor with the map's ids.  References inside the copies (``href``,
    ``url(#…)``) follow their targets.
    """
    defs = [_in_svg_namespace(copy.deepcopy(el)) for el in exemplar.defs]
    ids = {node.get("id") for el in defs for node in el.iter() if node.get("id")}
    ids |= {k.href for k in exemplar.kinds}

    def rename(match: re.Match) -> str:
        ident = match.group(1)
        return f"url(#{prefix}{ident})" if ident in ids else match.group(0)

    for el in defs:
        for node in el.iter():
            for key, value in list(node.attrib.items()):
                if key == "id" and value in ids:
                    node.set(key, prefix + value)
                elif key in ("href", f"{{{XLINK_NS}}}href") and value.startswith("#") and value[1:] in ids:
                    node.set(key, "#" + prefix + value[1:])
                elif "url(" in value:
                    node.set(key, re.sub(r"url\(\s*#([^)\s]+)\s*\)", rename, value))
    kinds = tuple(dataclasses.replace(k, href=prefix + k.href) for k in exemplar.kinds)
    return defs, kinds


def map_document(
    root: ET.Element | None, defs: list[ET.Element], layers: list[MapLayer], *, params: dict[str, object],
    namespaces: tuple[tuple[str, str], ...] | list = (),
) -> str:
    """The filled map as SVG text: the original map with one texture group per region.

    Parameters
    ----------
    root : the map's root element, changed in place (None: a new document holding the
        regions' outlines, for GeoJSON input)
    defs : the prefixed symbols of every style (:func:`prefixed_defs`), in one new ``<defs>``
    layers : the textures, each drawn right after its anchor element (its unit's own drawing,
        so labels and linework drawn later stay on top)
    params : recorded in ``<metadata>``
    namespaces : (prefix, uri) pairs the map declares, so its prefixes (``sodipodi:``,
        ``inkscape:`` …) come back as they were rather than as ``ns0:``

    Each texture group carries the inverse of its anchor's parent's transform, so its motifs
    and clip path are in the root's user units wherever the anchor sits.
    """
    parts = map_document_parts(root, defs, layers, params=params, namespaces=namespaces)
    out = [parts[0]]
    for layer, part in zip(layers, parts[1:], strict=True):
        body = "\n".join(use_elements(layer.arr, layer.kinds))
        out.append(("\n" + body + "\n" if body else "") + part)
    return "".join(out)


def map_document_parts(
    root: ET.Element | None, defs: list[ET.Element], layers: list[MapLayer], *, params: dict[str, object],
    namespaces: tuple[tuple[str, str], ...] | list = (),
) -> list[str]:
    """:func:`map_document` without its motifs: ``len(layers) + 1`` pieces of text, layer
    ``n``'s ``<use>`` lines going between pieces ``n`` and ``n + 1`` (as ``"\\n" + lines +
    "\\n"``, or nothing for no line), for a writer that streams them.  The layers' ``arr`` is
    not read."""
    outlines: list[ET.Element | None] = [None] * len(layers)
    if root is None:
        root = _outline_document([layer.shape for layer in layers])
        outlines = list(root)
    for prefix, uri in namespaces:
        if prefix and not re.fullmatch(r"ns\d+", prefix) and uri not in (SVG_NS, XLINK_NS):
            ET.register_namespace(prefix, uri)
    taken = {node.get("id") for node in root.iter()} | {node.get("id") for el in defs for node in el.iter()}
    meta = ET.Element(f"{{{SVG_NS}}}metadata", {"id": _unique_id("svgtile-run", taken)})
    ET.SubElement(meta, f"{{{META_NS}}}run", {k: _xml_chars(str(v)) for k, v in sorted(params.items())})
    new_defs = ET.Element(f"{{{SVG_NS}}}defs", {"id": _unique_id("svgtile-defs", taken)})
    new_defs.extend(defs)
    root.insert(0, new_defs)
    root.insert(0, meta)
    parents = {c: p for p in root.iter() for c in p}
    for n, layer in enumerate(layers):
        safe = re.sub(r"[^A-Za-z0-9_.-]+", "-", layer.ident).strip("-") or str(n + 1)
        group = ET.Element(f"{{{SVG_NS}}}g", {"id": _unique_id(f"svgtile-{safe}", taken),
                                              "data-svgtile-class": _xml_chars(layer.cls)})  # fmt: skip
        if layer.matrix is not None and not np.allclose(layer.matrix, np.eye(3)):
            inv = np.linalg.inv(layer.matrix)
            group.set("transform", "matrix({})".format(" ".join(fmt_array(inv[:2].T.ravel()))))
        if layer.boundary == "clip":
            clip_id = _unique_id(f"svgtile-clip-{safe}", taken)
            clip = ET.SubElement(new_defs, f"{{{SVG_NS}}}clipPath", {"id": clip_id})
            ET.SubElement(clip, f"{{{SVG_NS}}}path", {"d": path_data(layer.shape), "clip-rule": "evenodd"})
            group.set("clip-path", f"url(#{clip_id})")
        _ground(group, layer.ground, layer.shape)
        group.append(ET.Comment(f"{USES_MARK}-{n}"))
        anchor = layer.anchor if layer.anchor is not None else outlines[n]
        parent = parents.get(anchor) if anchor is not None else None
        if parent is None:
            root.append(group)
        else:
            parent.insert(list(parent).index(anchor) + 1, group)
    ET.indent(new_defs, space="  ", level=1)
    text = ET.tostring(root, encoding="unicode")
    head_end = text.index(">")
    if "xmlns:xlink=" not in text[:head_end]:
        text = text.replace("<svg ", f'<svg xmlns:xlink="{XLINK_NS}" ', 1)
    text = '<?xml version="1.0" encoding="UTF-8"?>\n' + text + ("" if text.endswith("\n") else "\n")
    parts = []
    for n in range(len(layers)):
        before, _, text = text.partition(f"<!--{USES_MARK}-{n}-->")
        parts.append(before)
    return [*parts, text]


def _outline_document(shapes: list[shapely.Geometry]) -> ET.Element:
    """A new SVG showing each region's outline (the map, when the regions came from GeoJSON)."""
    x0, y0, x1, y1 = shapely.union_all(shapes).bounds
    width, height, *box = fmt_array(np.array([x1 - x0, y1 - y0, x0, y0]))
    root = ET.Element(f"{{{SVG_NS}}}svg", {"width": width, "height": height,
                                           "viewBox": " ".join((*box, width, height))})  # fmt: skip
    for shape in shapes:
        ET.SubElement(root, f"{{{SVG_NS}}}path", {
            "d": path_data(shape), "fill": "none", "stroke": "#000", "stroke-width": fmt(max(x1 - x0, y1 - y0) / 1000),
            "fill-rule": "evenodd"})  # fmt: skip
    return root
