"""Writing the synthesized texture as SVG: the exemplar's symbols and one ``<use>`` per motif.

This is the only module that writes XML.  Numbers have a fixed format (at most four decimals,
no trailing zeros), elements a stable order, and nothing depends on the clock or the machine, so
the same inputs and seed give a byte-identical file.  Files are written atomically.
"""

from __future__ import annotations

import copy
import os
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import shapely

from .arrangement import Arrangement
from .errors import OutputError
from .exemplar import SVG_NS, XLINK_NS, Exemplar, Kind
from .region import Region

META_NS = "urn:svgtile:run:1"
USES_MARK = "svgtile-uses"
# ElementTree's namespace registry is process-wide; these are the prefixes any SVG tool expects.
ET.register_namespace("", SVG_NS)
ET.register_namespace("xlink", XLINK_NS)
ET.register_namespace("svgtile", META_NS)


def fmt(v: float) -> str:
    """Fixed number format: four decimals at most, no trailing zeros, no ``-0``."""
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


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
    """One ``<use>`` line per motif, in the arrangement's order."""
    heads = []
    for kind in kinds:
        attrs = "".join(f' {k}="{_escape(v)}"' for k, v in kind.use_attrs)
        suffix = use_transform_suffix(kind)
        heads.append((f'{indent}<use xlink:href="#{_escape(kind.href)}"{attrs} transform="', suffix))
    lines = []
    for k, (x, y), a, s in zip(arr.kind.tolist(), arr.xy.tolist(), arr.angle.tolist(), arr.scale.tolist()):
        head, suffix = heads[k]
        t = f"translate({fmt(x)} {fmt(y)})"
        if (fa := fmt(a)) != "0":
            t += f" rotate({fa})"
        if (fs := fmt(s)) != "1":
            t += f" scale({fs})"
        if suffix:
            t += " " + suffix
        lines.append(f'{head}{t}"/>')
    return lines


def svg_document(
    exemplar: Exemplar, arr: Arrangement, region: Region, *, boundary: str, params: dict[str, object]
) -> str:
    """The output SVG as text.

    Parameters
    ----------
    exemplar : gives the symbols (copied unchanged, ids kept) and kinds
    arr : the motifs
    region : the output region; its bounding box is the document's viewBox
    boundary : ``clip`` adds a clipPath of the region around the motifs
    params : recorded in ``<metadata>`` (engine, seed, parameters)
    """
    x0, y0, x1, y1 = region.bounds
    root = ET.Element(
        f"{{{SVG_NS}}}svg",
        {"width": fmt(x1 - x0), "height": fmt(y1 - y0), "viewBox": " ".join(fmt(v) for v in (x0, y0, x1 - x0, y1 - y0))},
    )
    meta = ET.SubElement(root, f"{{{SVG_NS}}}metadata")
    ET.SubElement(meta, f"{{{META_NS}}}run", {k: str(v) for k, v in sorted(params.items())})
    defs = ET.SubElement(root, f"{{{SVG_NS}}}defs")
    for el in exemplar.defs:
        defs.append(_in_svg_namespace(copy.deepcopy(el)))
    group = ET.SubElement(root, f"{{{SVG_NS}}}g", {"id": "svgtile"})
    if boundary == "clip":
        clip = ET.SubElement(defs, f"{{{SVG_NS}}}clipPath", {"id": "svgtile-clip"})
        ET.SubElement(clip, f"{{{SVG_NS}}}path", {"d": path_data(region.shape), "clip-rule": "evenodd"})
        group.set("clip-path", "url(#svgtile-clip)")
    group.append(ET.Comment(USES_MARK))
    ET.indent(root, space="  ")
    text = ET.tostring(root, encoding="unicode")
    head_end = text.index(">")
    if "xmlns:xlink=" not in text[:head_end]:  # the <use> lines below need it even if defs do not
        text = text.replace("<svg ", f'<svg xmlns:xlink="{XLINK_NS}" ', 1)
    lines = use_elements(arr, exemplar.kinds)
    body = "\n".join(lines)
    text = text.replace(f"<!--{USES_MARK}-->", body.lstrip() if body else "")
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + text + "\n"


def path_data(geom: shapely.Geometry) -> str:
    """SVG path data of a (Multi)Polygon, holes included (use with the evenodd rule)."""
    parts = []
    for poly in shapely.get_parts(geom):
        for ring in [poly.exterior, *poly.interiors]:
            pts = np.asarray(ring.coords)[:-1]
            parts.append("M" + " L".join(f"{fmt(x)} {fmt(y)}" for x, y in pts) + " Z")
    return " ".join(parts)


def write_text(text: str, out: str | Path, *, protect: tuple[Path, ...] = ()) -> None:
    """Write ``text`` to ``out`` atomically (``-`` is standard output).

    Refuses to overwrite any path in ``protect`` (the inputs).  The text goes to a temporary file
    in the target folder that is renamed into place, so a failure never leaves half a file.
    """
    if str(out) == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    out = Path(out)
    for p in protect:
        if out.resolve() == Path(p).resolve():
            raise OutputError("refusing to overwrite an input file", source=str(out))
    folder = out.parent if str(out.parent) else Path(".")
    if not folder.is_dir():
        raise OutputError(f"folder {str(folder)!r} does not exist", source=str(out))
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{out.name}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise OutputError(f"cannot write here ({exc.strerror})", source=str(out)) from None
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _in_svg_namespace(el: ET.Element) -> ET.Element:
    """Give un-namespaced elements (from an SVG without xmlns) the SVG namespace."""
    for node in el.iter():
        if isinstance(node.tag, str) and not node.tag.startswith("{"):
            node.tag = f"{{{SVG_NS}}}{node.tag}"
    return el


def _escape(value: str) -> str:
    return value.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")
