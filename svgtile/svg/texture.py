"""Reading back a texture svgtile wrote, in the terms of its exemplar (for ``svgtile score``).

A texture reuses its exemplar's symbols (:func:`svgtile.svg.writer.svg_document`), so it is read with
the exemplar reader (:func:`svgtile.exemplar.read_exemplar`) and each of its kinds is matched to
the exemplar's kind that draws the same element the same way: same ``href``, same residual
linear part and same ``<use>`` attributes.  Kind indices follow the order of first appearance, so
the texture's and the exemplar's differ in general; :func:`read_texture` renumbers the texture's.

The output region is the clip path the texture's motif group is clipped to (``--boundary
clip``, map regions with holes included), else the texture's viewBox.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar, Kind
from svgtile.core.region import Region
from svgtile.errors import ExemplarError, RegionError
from svgtile.svg.dialect import SVG_NS
from svgtile.svg.reader import read_exemplar

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def kind_key(kind: Kind) -> tuple:
    """What identifies a kind across files: element drawn, residual linear part, use attributes."""
    return (kind.href, tuple(np.round(kind.residual, 4).ravel()), tuple(kind.use_attrs))


def read_texture(path: str | Path, exemplar: Exemplar) -> tuple[Arrangement, Region]:
    """The motifs and output region of a texture made from ``exemplar``.

    Parameters
    ----------
    path : the texture SVG (svgtile's output, or any SVG using the exemplar's symbols)
    exemplar : the exemplar it was made from

    Returns
    -------
    arrangement : Arrangement whose ``kind`` indexes ``exemplar.kinds``; the motifs whose
        centroid lies in the texture's viewBox (those outside cannot be seen)
    region : the output region (clip path, else viewBox), user units

    Raises
    ------
    ExemplarError
        The file cannot be read, or uses a kind the exemplar does not have.
    RegionError
        The clip path has no area.
    """
    texture = read_exemplar(path)
    index = {kind_key(k): i for i, k in enumerate(exemplar.kinds)}
    mapping = np.empty(len(texture.kinds), dtype=np.int64)
    for t, kind in enumerate(texture.kinds):
        found = index.get(kind_key(kind))
        if found is None:
            raise ExemplarError(
                f"motif kind {kind.name!r} is not in the exemplar {exemplar.source} "
                "(was the texture made from another exemplar?)",
                source=str(path),
            )
        mapping[t] = found
    m = texture.motifs
    arr = Arrangement(mapping[m.kind], m.xy, m.angle, m.scale)
    clip = _clip_region(Path(path), texture.source)
    return arr, clip if clip is not None else Region(texture.region)


def _clip_region(path: Path, source: str) -> Region | None:
    """The region of the clip path on svgtile's motif group, or None if it is not clipped."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError):  # read_exemplar has already read it: not reached in practice
        return None
    ids = {el.get("id"): el for el in root.iter() if el.get("id")}
    # the motif group is the root's last <g>, "svgtile" or, should the exemplar's defs use that
    # id, "svgtile-2" …
    groups = [el for el in root if el.tag == f"{{{SVG_NS}}}g" and (el.get("id") or "").startswith("svgtile")]
    group = groups[-1] if groups else None
    ref = re.fullmatch(r"\s*url\(\s*#([^)\s]+)\s*\)\s*", group.get("clip-path", "")) if group is not None else None
    clip = ids.get(ref.group(1)) if ref else None
    if clip is None:
        return None
    rings = []
    for el in clip.iter(f"{{{SVG_NS}}}path"):
        for part in re.split(r"[Mm]", el.get("d", "")):
            values = [float(v) for v in re.findall(_NUMBER, part)]
            if len(values) >= 6:
                rings.append(shapely.Polygon(np.reshape(values[: len(values) // 2 * 2], (-1, 2))))
    if not rings:
        raise RegionError("its clip path has no outline svgtile can read", source=source)
    shape = rings[0]
    for ring in rings[1:]:  # clip-rule evenodd, as svgtile writes it
        shape = shapely.symmetric_difference(shape, shapely.make_valid(ring))
    return Region.from_geometry(shape, source=source)
