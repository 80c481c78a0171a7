"""Reading back a texture svgtile wrote, in the terms of its exemplar (for ``svgtile score``).

A texture reuses its exemplar's symbols (:func:`svgtile.svg.writer.svg_document`), so it is read with
the exemplar reader (:func:`svgtile.svg.reader.read_exemplar`) and each of its kinds is matched to
the exemplar's kind that draws the same element the same way: same ``href``, same residual
linear part and same ``<use>`` attributes.  Kind indices follow the order of first appearance, so
the texture's and the exemplar's differ in general; :func:`read_texture` renumbers the texture's.

The output region is the clip path the texture's motif group is clipped to (``--boundary
clip``, map regions with holes included), else the texture's viewBox.

A texture in svgtile's own form (:func:`svgtile.svg.writer.svg_document`: one ``<g id="svgtile…">``
of ``<use>`` elements whose ``transform`` is ``translate(x y) [rotate(a)] [scale(s)] [kind
suffix]``) is read in bulk (:func:`read_own_texture`): the exemplar reader sees one ``<use>`` per
distinct ``href``, attributes and suffix, and the transforms of all motifs are composed and split
with numpy exactly as the reader would compose and split each one, so the Arrangement is the
same bit for bit.  Anything else (a hand-edited file: a ``matrix()`` transform, a nested group, a
moved element) is read by the exemplar reader, motif by motif.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from concurrent.futures import Executor
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar, Kind
from svgtile.core.region import Region
from svgtile.errors import ExemplarError, RegionError, TextureKindError
from svgtile.files import MAX_TEXTURE_BYTES, read_input
from svgtile.svg import uselines
from svgtile.svg.dialect import SVG_NS, XLINK_NS, drawable_children
from svgtile.svg.reader import DocumentReader, read_exemplar
from svgtile.svg.uselines import Block, OwnLines, Pose

_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def kind_key(kind: Kind) -> tuple:
    """What identifies a kind across files: element drawn, residual linear part, use attributes."""
    return (kind.href, tuple(np.round(kind.residual, 4).ravel()), tuple(kind.use_attrs))


def read_texture(
    path: str | Path, exemplar: Exemplar, *, pool: Executor | None = None, split_above: int | None = None
) -> tuple[Arrangement, Region]:
    """The motifs and output region of a texture made from ``exemplar``.

    Parameters
    ----------
    path : the texture SVG (svgtile's output, or any SVG using the exemplar's symbols)
    exemplar : the exemplar it was made from
    pool : an executor (``svgtile score``: one forked worker process) whose worker scans the
        last part of the ``<use>`` lines of a large texture in svgtile's own form while this
        thread scans the rest (:func:`start_reading`); None: all here.  The motifs are the same.
    split_above : split the scan only above this many lines (default
        :data:`~svgtile.svg.uselines.SPLIT_ABOVE`)

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
    return start_reading(path, pool=pool, split_above=split_above).finish(exemplar)


def start_reading(path: str | Path, *, pool: Executor | None = None, split_above: int | None = None) -> Reading:
    """Read the file of a texture and, if it is in svgtile's own form with more than
    ``split_above`` ``<use>`` lines (default :data:`~svgtile.svg.uselines.SPLIT_ABOVE`), hand the
    last :data:`~svgtile.svg.uselines.WORKER_SHARE` of them to ``pool``'s worker to scan
    (:func:`~svgtile.svg.uselines.scan`); :meth:`Reading.finish` does the rest.

    In two steps so that a caller can give the worker more work behind the scan before this
    thread scans its part (``svgtile score``: the baselines, which need the exemplar alone).
    Errors are raised by :meth:`Reading.finish`.
    """
    try:
        data = read_input(path, error=ExemplarError, limit=MAX_TEXTURE_BYTES)
    except ExemplarError:
        data = None  # the exemplar reader reports it
    if data is None or _first_match(_CELL_PATH, _CELL_HEAD, data) is not None:
        return Reading(str(path), data, None, cellular=data is not None)
    data = _without_ground(data)
    block = uselines.start_block(data, pool, uselines.SPLIT_ABOVE if split_above is None else split_above)
    return Reading(str(path), data, block, cellular=False)


@dataclass(frozen=True, eq=False)
class Reading:
    """A texture whose file is read and whose ``<use>`` lines may be being scanned
    (:func:`start_reading`)."""

    path: str
    data: bytes | None
    block: Block | None
    cellular: bool

    def finish(self, exemplar: Exemplar) -> tuple[Arrangement, Region]:
        """The motifs and output region of the texture, in the terms of ``exemplar``
        (:func:`read_texture`)."""
        path, data = self.path, self.data
        if self.cellular:
            raise ExemplarError("a cellular texture (cells and lines, svgtile's cellular engine): only textures of "
                                "motifs are measured", source=path)  # fmt: skip
        root = own = None
        cut = uselines.cut_document(data, self.block) if self.block is not None else None
        if cut is not None:  # svgtile's own form: ElementTree parses it without its <use> lines
            skeleton, lines = cut
            try:
                root = ET.fromstring(skeleton)
            except (ET.ParseError, ValueError, LookupError):
                root = None
            own = read_own_texture(root, path, lines=lines) if root is not None else None
            if own is None:
                root = None
        if root is None and data is not None:
            try:
                root = ET.fromstring(data)
            except (ET.ParseError, ValueError, LookupError):
                pass  # the exemplar reader reports it
            own = read_own_texture(root, path) if root is not None else None
        if own is not None:
            kinds, motifs, region = own
        else:
            texture = read_exemplar(path)
            kinds, motifs, region = texture.kinds, texture.motifs, texture.region
        mapping = _kind_mapping(kinds, exemplar, path)
        arr = Arrangement(mapping[motifs.kind], motifs.xy, motifs.angle, motifs.scale)
        clip = _clip_region(root, path) if root is not None else None
        return arr, clip if clip is not None else Region(region)


def _kind_mapping(kinds: tuple[Kind, ...], exemplar: Exemplar, source: str) -> np.ndarray:
    """(t,) int array: the exemplar's index of each of the texture's kinds."""
    index = {kind_key(k): i for i, k in enumerate(exemplar.kinds)}
    mapping = np.empty(len(kinds), dtype=np.int64)
    for t, kind in enumerate(kinds):
        found = index.get(kind_key(kind))
        if found is None:  # a residual written to 4 decimals may round the other way when read back
            found = _nearest_kind(kind, exemplar.kinds)
        if found is None:
            raise TextureKindError(
                f"motif kind {kind.name!r} is not in the exemplar {exemplar.source} "
                "(was the texture made from another exemplar?)",
                source=source,
            )
        mapping[t] = found
    return mapping


#: How far a kind's residual linear part read back from a texture may lie from its exemplar
#: kind's: the writer rounds each entry to 4 decimals (half of 1e-4), which a rotation then
#: spreads over the entries (a skewed kind: 1.27785 written 1.2779, read back 1.27784).
RESIDUAL_TOLERANCE = 5e-4


def _nearest_kind(kind: Kind, kinds: tuple[Kind, ...]) -> int | None:
    """Index of the kind of ``kinds`` that draws the same element with the same attributes and
    the residual nearest ``kind``'s, within :data:`RESIDUAL_TOLERANCE`; None if there is none."""
    best, found = RESIDUAL_TOLERANCE, None
    for i, k in enumerate(kinds):
        if (k.href, tuple(k.use_attrs)) == (kind.href, tuple(kind.use_attrs)):
            gap = float(np.abs(np.asarray(k.residual) - np.asarray(kind.residual)).max())
            if gap <= best:
                best, found = gap, i
    return found


# ----------------------------------------------------------------------------- svgtile's own form

_USE = f"{{{SVG_NS}}}use"
#: A cell or line as :func:`svgtile.svg.writer.cell_elements` writes it.
_CELL_PATH = re.compile(rb'<path class="svgtile-(?:corner|edge|face|line)" ')
_CELL_HEAD = b'<path class="svgtile-'
_HREF = f"{{{XLINK_NS}}}href"
#: The ground svgtile paints first in its motif group (:func:`svgtile.svg.writer._ground`), as written.
_OWN_GROUND = re.compile(rb'(<g id="svgtile[^"<>]*"(?: clip-path="[^"<>]*")?>)\n[ \t]*<path class="svgtile-ground" '
                         rb'style="fill:[^";<>]*;stroke:none" fill-rule="evenodd" d="[^"<>]*" />')
_GROUND_HEAD = b'<g id="svgtile'


def _without_ground(data: bytes) -> bytes:
    """The texture without the ground path svgtile wrote under its motifs (the exemplar's
    ``svgtile:ground``): paint, not a motif, so neither reader must count it.

    ``_OWN_GROUND.sub(rb"\\1", data, count=1)``, the same bytes (``data`` itself if there is
    no ground), found by :func:`_first_match`."""
    found = _first_match(_OWN_GROUND, _GROUND_HEAD, data)
    if found is None:
        return data
    return b"".join((data[: found.start()], found.group(1), data[found.end() :]))


def _first_match(pattern: re.Pattern, head: bytes, data: bytes) -> re.Match | None:
    """``pattern.search(data)`` for a ``pattern`` every match of which starts with the plain
    bytes ``head``, found faster: ``head`` is looked for with ``bytes.find`` (a texture of 177k
    motifs is 19 MB, over which the regular expression engine looked for it at ≈ 1 GB/s, ``find``
    at several) and ``pattern`` matched only there, in order, so the first match is the same."""
    at = data.find(head)
    while at >= 0:
        found = pattern.match(data, at)
        if found is not None:
            return found
        at = data.find(head, at + 1)
    return None


def _own_use_block(
    data: bytes, *, pool: Executor | None = None, split_above: int = uselines.SPLIT_ABOVE
) -> tuple[bytes, OwnLines] | None:
    """Cut the ``<use>`` lines out of a texture in svgtile's own form, without parsing XML.

    svgtile writes its motif group last, one ``<use>`` per line (:func:`svgtile.svg.writer.svg_document`).
    If ``data`` ends with such a group, every line of which matches :data:`~svgtile.svg.uselines._OWN_USE`, this
    returns the document with only the first line of each group of lines kept (for
    ElementTree: its parse of 177k ``<use>`` takes a second) and the lines scanned; ``pool``'s
    worker scans the last :data:`~svgtile.svg.uselines.WORKER_SHARE` of more than ``split_above`` lines.  Any other document gives
    None: then it is parsed whole.
    """
    found = uselines.start_block(data, pool, split_above)
    return uselines.cut_document(data, found) if found is not None else None


def read_own_texture(
    root: ET.Element, source: str, *, lines: OwnLines | None = None
) -> tuple[tuple[Kind, ...], Arrangement, shapely.Geometry] | None:
    """Kinds, motifs and input region of a texture in svgtile's own form, read in bulk.

    What :func:`svgtile.svg.reader.parse_exemplar` gives for the same document — the same kinds,
    and motifs equal bit for bit in the same order — or None if the document is not in the form
    :func:`svgtile.svg.writer.svg_document` writes (then read it with the exemplar reader).

    The exemplar reader composes each ``<use>``'s transform with svgelements (one ``Matrix`` per
    operation) and splits it into position, rotation and scale (``DocumentReader._use_kind``).
    Here every operation is applied to all motifs at once with the same floating-point operations
    in the same order (:func:`~svgtile.svg.uselines._pre_cat`), the determinant and the matrix products are numpy's
    batched versions of the reader's, and ``cos``/``sin``/``atan2`` are the C library's, as
    svgelements and the reader call them (numpy's own may differ in the last bit on some CPUs).
    Kinds are found by the exemplar reader itself, on a copy of the document holding only the
    first ``<use>`` of each distinct ``href``, attributes and suffix.

    Parameters
    ----------
    root : the parsed document; with ``lines``, the document :func:`_own_use_block` cut, whose
        motif group holds only the first ``<use>`` of each of ``lines``' groups
    source : its name, for messages
    lines : the ``<use>`` lines :func:`_own_use_block` scanned, if the document was cut

    Returns
    -------
    kinds : the texture's kinds, in order of first appearance
    motifs : Arrangement of the n motifs whose centroid lies in the input region, ``kind``
        indexing ``kinds``; ``xy`` (n, 2) user units, ``angle`` (n,) degrees, ``scale`` (n,)
    region : the input region (the root viewBox), user units
    """
    if root.tag != f"{{{SVG_NS}}}svg" or not set(root.attrib) <= {"width", "height", "viewBox"}:
        return None
    if "viewBox" not in root.attrib or root.find(".//*[@id='region']") is not None:
        return None
    drawn = drawable_children(root)
    if len(drawn) != 1:
        return None
    group = drawn[0]
    if group.tag != f"{{{SVG_NS}}}g" or not (group.get("id") or "").startswith("svgtile"):
        return None
    if not set(group.attrib) <= {"id", "clip-path"} or len(group) == 0:
        return None
    uses = list(group)
    rows = [(u.tag, len(u), *u.attrib.items()) for u in uses]
    if any(r[0] != _USE or r[1] or len(r) < 4 or r[-1][0] != "transform" or r[2][0] != _HREF for r in rows):
        return None
    transforms = [r[-1][1] for r in rows]
    text = "\n".join(transforms)
    parsed = uselines.OWN_TRANSFORM.findall(text)
    if len(parsed) != len(uses) or text.count("\n") != len(uses) - 1:
        return None
    heads: dict[tuple, int] = {}
    head = np.array([heads.setdefault(r[2:-1], len(heads)) for r in rows], dtype=np.int64)
    if any(k in ("x", "y", "transform") for h in heads for k, _ in h):
        return None
    if lines is not None:
        # the cut group holds one <use> per group of lines: they must be distinct elements too
        distinct = {(h, p[4]) for h, p in zip(head.tolist(), parsed, strict=True)}
        if len(uses) != len(lines.first) or len(distinct) != len(uses):
            return None
        if parsed != list(lines.first_columns):
            return None
        first, motif_kind, pose = lines.first, lines.group, lines.pose
    else:
        columns = tuple(zip(*parsed, strict=True))
        suffix = uselines.numbered(columns[4])
        first, motif_kind = uselines.first_groups(head * (int(suffix.max()) + 1) + suffix)
        uses = [uses[i] for i in first.tolist()]
        pose = uselines.pose(columns, suffix)

    # the kinds, from the exemplar reader on one <use> per group (in order of first appearance),
    # without the viewBox: those first motifs may all lie outside it (clip keeps cut motifs)
    mini = ET.Element(root.tag)
    mini.extend(c for c in root if c is not group)
    mini_group = ET.SubElement(mini, group.tag, group.attrib)
    mini_group.extend(uses)
    try:
        sample = DocumentReader(mini, source).read()
        # the input region as the reader finds it in the root alone (its viewBox)
        region = DocumentReader(ET.Element(root.tag, root.attrib), source)._region(Arrangement.empty(), [])
    except (ExemplarError, RecursionError):
        return None  # the exemplar reader will say what is wrong with the whole file
    if len(sample.kinds) != len(first) or len(sample.motifs) != len(first):
        return None  # two groups are one kind, or one draws nothing: leave it to the reader

    if pose is None:
        return None  # scaled to nothing: the reader drops it with a warning, or refuses a singular transform
    return _place(pose, motif_kind, sample.kinds, region)


def _place(
    pose: Pose, kind: np.ndarray, kinds: tuple[Kind, ...], region: shapely.Geometry
) -> tuple[tuple[Kind, ...], Arrangement, shapely.Geometry] | None:
    """Position, rotation and scale of each motif, as ``DocumentReader._use_kind`` gives them.

    ``pose`` : the n motifs' poses; ``kind`` : (n,) index into ``kinds``; ``region`` : the
    input region, which keeps the motifs whose centroid it holds (boundary included).
    """
    cos, sin, scale = pose.cos, pose.sin, pose.scale
    rot = np.stack([np.stack([cos, -sin], 1), np.stack([sin, cos], 1)], 1)
    offset = np.array([k.offset for k in kinds]).reshape(-1, 2)[kind]
    xy = pose.t + ((scale[:, None, None] * rot) @ (-offset)[:, :, None])[:, :, 0]
    inside = shapely.intersects_xy(region, xy[:, 0], xy[:, 1])
    if not inside.any():
        return None  # the reader's error
    arr = Arrangement(kind, xy, pose.angle, scale)
    return kinds, arr if inside.all() else arr.take(inside), region


def _clip_region(root: ET.Element, source: str) -> Region | None:
    """The region of the clip path on svgtile's motif group, or None if it is not clipped."""
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
