"""Symbols for GIS: each motif kind as its own SVG, and a QGIS style (``.qml``) that draws them.

A placements layer (:mod:`svgtile.gis.layers`) holds one point per motif at its anchor — the
footprint centroid of its kind, the origin of the kind's local frame
(:class:`svgtile.core.exemplar.Kind`).  QGIS draws such a point with an *SVG marker*: the file
is chosen by the point's ``kind`` (and ``class``), the marker is ``size`` map units wide and
turned ``angle`` degrees clockwise.  For that to reproduce the texture, each kind's SVG must

* have a square page of side ``2 · radius`` (the ``size`` field is ``2 · radius · scale · unit``),
* with the anchor at its centre (QGIS centres the marker on the point),
* be drawable by Qt's SVG renderer, which knows no ``<symbol>``: the exemplar's symbols become
  plain groups in ``<defs>``, referenced by one ``<use>`` as in svgtile's own textures.
"""

from __future__ import annotations

import copy
import re
import xml.etree.ElementTree as ET
from xml.sax.saxutils import quoteattr

import numpy as np

from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar
from svgtile.errors import ExemplarError
from svgtile.svg.dialect import SVG_NS, XLINK_NS
from svgtile.svg.numbers import fmt
from svgtile.svg.writer import use_elements

#: Attributes of ``<symbol>`` that mean nothing on the ``<g>`` replacing it.
_SYMBOL_ONLY = ("viewBox", "preserveAspectRatio", "overflow", "refX", "refY", "x", "y", "width", "height")
#: What may not appear in a symbol's file name (and the QGIS expression's regexp_replace twin).
_UNSAFE = r"[^A-Za-z0-9_.-]+"


def file_stem(name: str) -> str:
    """A kind or class name as a file name: runs of other characters than ``A-Za-z0-9_.-`` become ``-``.

    :func:`qml_style`'s expression applies the same rule in QGIS (``regexp_replace``).
    """
    return re.sub(_UNSAFE, "-", name) or "-"


def symbol_documents(exemplar: Exemplar) -> dict[str, str]:
    """Each kind of ``exemplar`` as an SVG document: ``{file name: text}``, in kind order.

    The page is the square ``[-r, r]²`` user units, ``r`` the kind's bounding radius at scale 1
    (:attr:`svgtile.core.footprint.Prototype.radius`), with the kind drawn once at the origin,
    angle 0, scale 1 — exactly as one ``<use>`` of a texture draws it.
    """
    defs = [copy.deepcopy(el) for el in exemplar.defs]
    for el in defs:
        for node in el.iter():
            if isinstance(node.tag, str) and not node.tag.startswith("{"):
                node.tag = f"{{{SVG_NS}}}{node.tag}"
    out: dict[str, str] = {}
    for k, kind in enumerate(exemplar.kinds):
        r = kind.prototype.radius
        side = fmt(2 * r)
        one = Arrangement(np.array([k]), np.zeros((1, 2)), np.zeros(1), np.ones(1))
        use = use_elements(one, exemplar.kinds, indent="  ")[0]
        defs_text = "".join(ET.tostring(el, encoding="unicode") for el in _as_groups(defs, kind))
        name = file_stem(kind.name) + ".svg"
        if name in out:  # QGIS's expression finds a file by the kind's name: one file per name
            other = next(j.name for j in exemplar.kinds if file_stem(j.name) + ".svg" == name)
            raise ExemplarError(f"kinds {other!r} and {kind.name!r} would share the symbol file {name} "
                                "(names differ only in characters a file name cannot hold); rename one", source=exemplar.source)  # fmt: skip
        out[name] = (
            '<?xml version="1.0" encoding="UTF-8"?>\n'
            f'<svg xmlns="{SVG_NS}" xmlns:xlink="{XLINK_NS}" width="{side}" height="{side}" '
            f'viewBox="{fmt(-r)} {fmt(-r)} {side} {side}">\n'
            f"  <title>{_text(kind.name)}</title>\n"
            f"  <defs>{defs_text}</defs>\n{use}\n</svg>\n"
        )
    return out


def _as_groups(defs: list[ET.Element], kind) -> list[ET.Element]:
    """Copies of ``defs`` with every ``<symbol>`` a ``<g>``; the one ``kind`` uses, if it has a
    viewBox, gets the transform its ``<use width height>`` viewport gave it (preserveAspectRatio
    ``xMidYMid meet``, the default, or ``none``)."""
    attrs = dict(kind.use_attrs)
    out = [copy.deepcopy(el) for el in defs]
    for el in out:
        for node in el.iter(f"{{{SVG_NS}}}symbol"):
            box = node.get("viewBox")
            if node.get("id") == kind.href and box and "width" in attrs and "height" in attrs:
                try:
                    vx, vy, vw, vh = (float(v) for v in box.replace(",", " ").split())
                    w, h = float(attrs["width"]), float(attrs["height"])
                except ValueError:
                    vw = vh = 0.0
                if vw > 0 and vh > 0:
                    if node.get("preserveAspectRatio", "").split()[:1] == ["none"]:
                        sx, sy, tx, ty = w / vw, h / vh, -vx * w / vw, -vy * h / vh
                    else:
                        sx = sy = min(w / vw, h / vh)
                        tx, ty = (w - vw * sx) / 2 - vx * sx, (h - vh * sy) / 2 - vy * sy
                    node.set("transform", f"translate({fmt(tx)} {fmt(ty)}) scale({fmt(sx)} {fmt(sy)})")
            node.tag = f"{{{SVG_NS}}}g"
            for key in _SYMBOL_ONLY:
                node.attrib.pop(key, None)
    return out


def _text(value: str) -> str:
    return value.replace("&", "&amp;").replace("<", "&lt;")


def qml_style(folder: str, *, by_class: bool = False) -> str:
    """A QGIS layer style (``.qml``) for a placements layer, drawing each point with its kind's SVG.

    Parameters
    ----------
    folder : absolute path of the folder holding the symbol files (QGIS resolves the marker's
        file name from it); with ``by_class`` a sub-folder per class (:func:`file_stem` of it)
    by_class : the layer has a ``class`` field (``svgtile map``)

    The marker is an SVG marker, centred, whose file, size (map units) and rotation (degrees
    clockwise) come from the fields ``kind`` (and ``class``), ``size`` and ``angle``.
    """
    base = folder.rstrip("/\\").replace("\\", "/").replace("'", "''") + "/"

    def safe(name: str) -> str:
        return f"regexp_replace(\"{name}\", '{_UNSAFE}', '-')"

    path = f"'{base}' || " + (safe("class") + " || '/' || " if by_class else "") + safe("kind") + " || '.svg'"

    def option(name: str, value: str, kind: str = "QString") -> str:
        return f"<Option type={quoteattr(kind)} name={quoteattr(name)} value={quoteattr(value)}/>"

    def field(name: str, value: str, how: str) -> str:
        key = "field" if how == "field" else "expression"
        return (f'<Option type="Map" name="{name}">{option("active", "true", "bool")}'
                f'{option(key, value)}{option("type", "2" if how == "field" else "3", "int")}</Option>')  # fmt: skip

    props = {
        "angle": "0", "color": "0,0,0,255", "fixedAspectRatio": "0", "horizontal_anchor_point": "1",
        "name": "", "offset": "0,0", "offset_unit": "MapUnit", "outline_color": "0,0,0,255",
        "outline_width": "0", "outline_width_unit": "MapUnit", "scale_method": "diameter", "size": "1",
        "size_unit": "MapUnit", "vertical_anchor_point": "1",
    }  # fmt: skip
    layer_props = "".join(option(k, v) for k, v in props.items())
    dd = field("angle", "angle", "field") + field("name", path, "expression") + field("size", "size", "field")
    return (
        "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
        '<qgis version="3.22.0" styleCategories="Symbology">\n'
        ' <renderer-v2 type="singleSymbol" symbollevels="0" forceraster="0" enableorderby="0">\n'
        "  <symbols>\n"
        '   <symbol type="marker" name="0" alpha="1" clip_to_extent="1" force_rhr="0">\n'
        '    <layer class="SvgMarker" enabled="1" locked="0" pass="0">\n'
        f'     <Option type="Map">{layer_props}</Option>\n'
        f'     <data_defined_properties><Option type="Map">{option("name", "")}'
        f'<Option type="Map" name="properties">{dd}</Option>{option("type", "collection")}</Option>'
        "</data_defined_properties>\n"
        "    </layer>\n"
        "   </symbol>\n"
        "  </symbols>\n"
        " </renderer-v2>\n"
        " <blendMode>0</blendMode>\n"
        " <featureBlendMode>0</featureBlendMode>\n"
        " <layerGeometryType>0</layerGeometryType>\n"
        "</qgis>\n"
    )
