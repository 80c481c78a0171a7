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

import math
import re
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from operator import itemgetter
from pathlib import Path

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar, Kind
from svgtile.core.region import Region
from svgtile.errors import ExemplarError, RegionError
from svgtile.files import MAX_TEXTURE_BYTES, read_input
from svgtile.svg.dialect import SVG_NS, XLINK_NS, drawable_children
from svgtile.svg.reader import DocumentReader, read_exemplar

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
    root = own = None
    try:
        data = read_input(path, error=ExemplarError, limit=MAX_TEXTURE_BYTES)
    except ExemplarError:
        data = None  # the exemplar reader reports it
    if data is not None and _CELL_PATH.search(data):
        raise ExemplarError("a cellular texture (cells and lines, svgtile's cellular engine): only textures of "
                            "motifs are measured", source=str(path))  # fmt: skip
    if data is not None:
        data = _without_ground(data)
    cut = _own_use_block(data) if data is not None else None
    if cut is not None:  # svgtile's own form: ElementTree parses it without its <use> lines
        skeleton, lines = cut
        try:
            root = ET.fromstring(skeleton)
        except (ET.ParseError, ValueError, LookupError):
            root = None
        own = read_own_texture(root, str(path), lines=lines) if root is not None else None
        if own is None:
            root = None
    if root is None and data is not None:
        try:
            root = ET.fromstring(data)
        except (ET.ParseError, ValueError, LookupError):
            pass  # the exemplar reader reports it
        own = read_own_texture(root, str(path)) if root is not None else None
    if own is not None:
        kinds, motifs, region = own
    else:
        texture = read_exemplar(path)
        kinds, motifs, region = texture.kinds, texture.motifs, texture.region
    mapping = _kind_mapping(kinds, exemplar, str(path))
    arr = Arrangement(mapping[motifs.kind], motifs.xy, motifs.angle, motifs.scale)
    clip = _clip_region(root, str(path)) if root is not None else None
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
            raise ExemplarError(
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
_HREF = f"{{{XLINK_NS}}}href"
#: A number as :func:`svgtile.svg.writer.fmt_array` writes it (no exponent, no leading ``+``).
_FIXED = r"-?\d+(?:\.\d+)?"
#: One motif's transform per line: x, y, angle, scale, the kind's suffix (with its leading space).
_OWN_TRANSFORM = re.compile(
    rf"^translate\(({_FIXED}) ({_FIXED})\)(?: rotate\(({_FIXED})\))?(?: scale\(({_FIXED})\))?"
    rf"((?: translate\({_FIXED} {_FIXED}\))?(?: matrix\({_FIXED} {_FIXED} {_FIXED} {_FIXED} 0 0\))?)$",
    re.M,
)
_SUFFIX_PART = re.compile(rf"(translate|matrix)\(((?:{_FIXED} ?)+)\)")

#: :data:`_FIXED` with possessive quantifiers, for the scan of every ``<use>`` line: a number is
#: followed by a space or ``)``, so giving back a digit never helps a match, and not trying
#: spares the scan about a seventh of its time.
_FIXED_SCAN = r"-?\d++(?:\.\d++)?+"


def _possessive(pattern: str) -> str:
    """``pattern`` as written on Python ≥ 3.11; before it (no possessive quantifiers in ``re``)
    the same pattern with greedy ones, which match the same lines, a little slower."""
    return pattern if sys.version_info >= (3, 11) else re.sub(r"([+*?])\+", r"\1", pattern)



_SUFFIX = (rf"((?: translate\({_FIXED_SCAN} {_FIXED_SCAN}\))?+"
           rf"(?: matrix\({_FIXED_SCAN} {_FIXED_SCAN} {_FIXED_SCAN} {_FIXED_SCAN} 0 0\))?+)")  # fmt: skip
#: The opening tag of svgtile's motif group, as :func:`svgtile.svg.writer.svg_document` writes it.
_OWN_GROUP = re.compile(rb'<g id="svgtile[^"<>]*"(?: clip-path="[^"<>]*")?>')
#: One ``<use>`` line as :func:`svgtile.svg.writer.use_elements` writes it: its ``href`` and other
#: attributes as written, then its transform as :data:`_OWN_TRANSFORM` splits it (the lookahead
#: spares the scan of each transform as one more attribute).
_OWN_USE = re.compile(_possessive(
    rf'^[ \t]*+<use (xlink:href="#[^"<>\n]*+"(?: (?!transform=)[A-Za-z_][-\w.:]*+="[^"<>\n]*+")*+) '
    rf'transform="translate\(({_FIXED_SCAN}) ({_FIXED_SCAN})\)(?: rotate\(({_FIXED_SCAN})\))?+'
    rf'(?: scale\(({_FIXED_SCAN})\))?+{_SUFFIX}"/>$',
), re.M)


@dataclass(frozen=True, eq=False)
class OwnLines:
    """The ``<use>`` lines of svgtile's motif group, scanned as text (:func:`_own_use_block`).

    Attributes
    ----------
    columns : five lists of n strings, ``x``, ``y``, ``angle``, ``scale`` and ``suffix`` of
        each motif as :data:`_OWN_TRANSFORM` finds them in its transform (``""`` if missing)
    group : (n,) int array, each motif's group — lines with the same ``href`` and attributes
        text and the same suffix — numbered in order of first appearance
    first : (g,) int array, the first motif of each group (increasing)
    suffix : (n,) int array, each motif's suffix text numbered in order of first appearance
    """

    columns: tuple[list[str], ...]
    group: np.ndarray
    first: np.ndarray
    suffix: np.ndarray


#: The ground svgtile paints first in its motif group (:func:`svgtile.svg.writer._ground`), as written.
_OWN_GROUND = re.compile(rb'(<g id="svgtile[^"<>]*"(?: clip-path="[^"<>]*")?>)\n[ \t]*<path class="svgtile-ground" '
                         rb'style="fill:[^";<>]*;stroke:none" fill-rule="evenodd" d="[^"<>]*" />')


def _without_ground(data: bytes) -> bytes:
    """The texture without the ground path svgtile wrote under its motifs (the exemplar's
    ``svgtile:ground``): paint, not a motif, so neither reader must count it."""
    return _OWN_GROUND.sub(rb"\1", data, count=1)


def _own_use_block(data: bytes) -> tuple[bytes, OwnLines] | None:
    """Cut the ``<use>`` lines out of a texture in svgtile's own form, without parsing XML.

    svgtile writes its motif group last, one ``<use>`` per line (:func:`svgtile.svg.writer.svg_document`).
    If ``data`` ends with such a group, every line of which matches :data:`_OWN_USE`, this
    returns the document with only the first line of each group of lines kept (for
    ElementTree: its parse of 177k ``<use>`` takes a second) and the lines scanned.  Any other
    document gives None: then it is parsed whole.

    A dropped line repeats the ``href`` and attributes text of a kept one and has a transform of
    plain numbers, so the cut document is well-formed and means the same exactly when the whole
    one does.  Before the group there may be no comment, CDATA section, document type or
    processing instruction (which could hide or redefine what the scan sees).
    """
    start = data.rfind(b'<g id="svgtile')
    if start < 0:
        return None
    before = data[:start]
    if any(t in before for t in (b"<!--", b"<![CDATA[", b"<!DOCTYPE", b"<!ENTITY")):
        return None
    if before.count(b"<?") != (1 if before.startswith(b"<?xml ") else 0):
        return None
    opening = _OWN_GROUP.match(data, start)
    end = data.find(b"</g>", opening.end()) if opening else -1
    if end < 0 or re.fullmatch(rb"</g>[ \n]*</svg>[ \n]*", data[end:]) is None:
        return None
    try:
        block = data[opening.end() : end].decode("utf-8")
    except UnicodeDecodeError:
        return None
    inner = block.rstrip(" ")  # "\n" + one line per <use> + "\n" + the indent of </g>
    if len(inner) < 3 or inner[0] != "\n" or inner[-1] != "\n":
        return None
    body = inner[1:-1]
    found = _OWN_USE.findall(body)
    if len(found) != body.count("\n") + 1:
        return None  # a line that is not a <use> as svgtile writes it
    # the columns one by one (zip(*found) would step 177k tuples' iterators together, 4× slower)
    heads, *columns = (list(map(itemgetter(i), found)) for i in range(6))
    suffix = _numbered(columns[4])
    first, group = _first_groups(_numbered(heads) * (int(suffix.max()) + 1) + suffix)
    # the lines up to the last kept one (a group's first line comes early: splitting all 177k
    # lines took a tenth of the read)
    lines = body.split("\n", int(first[-1]) + 1)
    kept = "\n".join(lines[i] for i in first.tolist()).encode("utf-8")
    return data[: opening.end()] + b"\n" + kept + b"\n" + data[end:], OwnLines(tuple(columns), group, first, suffix)


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
    in the same order (:func:`_pre_cat`), the determinant and the matrix products are numpy's
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
    parsed = _OWN_TRANSFORM.findall(text)
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
        if parsed != [tuple(c[i] for c in lines.columns) for i in lines.first.tolist()]:
            return None
        columns, first, motif_kind, suffix = lines.columns, lines.first, lines.group, lines.suffix
    else:
        columns = tuple(zip(*parsed, strict=True))
        suffix = _numbered(columns[4])
        first, motif_kind = _first_groups(head * (int(suffix.max()) + 1) + suffix)
        uses = [uses[i] for i in first.tolist()]
    xs, ys, angles, scales, suffix_text = columns
    suffixes = {suffix_text[i]: s for s, i in enumerate(np.unique(suffix, return_index=True)[1].tolist())}

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

    m = _compose(np.array(xs, dtype=np.float64), np.array(ys, dtype=np.float64), angles, scales)
    for text_, s in suffixes.items():
        at = np.flatnonzero(suffix == s)
        for op, values in _SUFFIX_PART.findall(text_):
            v = [float(t) for t in values.split()]
            part = m[:, at]
            m[:, at] = _pre_cat(part, (1.0, 0.0, 0.0, 1.0, v[0], v[1]) if op == "translate" else tuple(v))
    return _split(m, motif_kind, sample.kinds, region)


def _numbered(keys: list | tuple) -> np.ndarray:
    """(n,) int array: each of the n hashable ``keys`` numbered in order of first appearance."""
    index = {k: i for i, k in enumerate(dict.fromkeys(keys))}
    return np.fromiter(map(index.__getitem__, keys), np.int64, len(keys))


def _first_groups(key: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The first element of each distinct value of ``key`` (n,), increasing, and each element's
    group, groups numbered in order of first appearance."""
    groups, first, member = np.unique(key, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    kind_of_group = np.empty(len(groups), dtype=np.int64)
    kind_of_group[order] = np.arange(len(groups))
    return first[order], kind_of_group[member.ravel()]


def _pre_cat(s: np.ndarray, m: tuple) -> np.ndarray:
    """``Matrix.pre_cat`` of svgelements for many matrices: ``s · m`` as its six sums compute it.

    ``s`` : (6, n) float array, the matrices ``(a, b, c, d, e, f)``; ``m`` : six floats or (n,)
    arrays.  The ``· 0`` and ``· 1`` terms are kept, as they can change the sign of a zero.
    """
    sa, sb, sc, sd, se, sf = s
    ma, mb, mc, md, me, mf = m
    return np.stack([
        sa * ma + sc * mb + se * 0.0,
        sb * ma + sd * mb + sf * 0.0,
        sa * mc + sc * md + se * 0.0,
        sb * mc + sd * md + sf * 0.0,
        sa * me + sc * mf + se,
        sb * me + sd * mf + sf,
    ])  # fmt: skip


def _compose(x: np.ndarray, y: np.ndarray, angles: tuple[str, ...], scales: tuple[str, ...]) -> np.ndarray:
    """(6, n) matrices of ``translate(x y) [rotate(a)] [scale(s)]``, as svgelements parses them."""
    n = len(x)
    one, zero = np.ones(n), np.zeros(n)
    m = _pre_cat(np.stack([one, zero, zero, one, zero, zero]), (1.0, 0.0, 0.0, 1.0, x, y))
    turned = np.flatnonzero(np.fromiter(map(bool, angles), bool, n))
    if len(turned):
        a = np.array(list(filter(None, angles)), dtype=np.float64)
        theta = math.tau * a / 360.0  # svgelements Angle.degrees
        ct = np.fromiter(map(math.cos, theta.tolist()), np.float64, len(theta))
        st = np.fromiter(map(math.sin, theta.tolist()), np.float64, len(theta))
        m[:, turned] = _pre_cat(m[:, turned], (ct, st, -st, ct, 0.0, 0.0))
    scaled = np.flatnonzero(np.fromiter(map(bool, scales), bool, n))
    if len(scaled):
        s = np.array(list(filter(None, scales)), dtype=np.float64)
        m[:, scaled] = _pre_cat(m[:, scaled], (s, 0.0, 0.0, s, 0.0, 0.0))
    return m


def _split(
    m6: np.ndarray, kind: np.ndarray, kinds: tuple[Kind, ...], region: shapely.Geometry
) -> tuple[tuple[Kind, ...], Arrangement, shapely.Geometry] | None:
    """Position, rotation and scale of each motif, as ``DocumentReader._use_kind`` splits them.

    ``m6`` : (6, n) svgelements matrices; ``kind`` : (n,) index into ``kinds``; ``region`` : the
    input region, which keeps the motifs whose centroid it holds (boundary included).
    """
    n = m6.shape[1]
    a, b, c, d, e, f = m6
    mat = np.zeros((n, 3, 3))
    mat[:, 0], mat[:, 1], mat[:, 2, 2] = np.stack([a, c, e], 1), np.stack([b, d, f], 1), 1.0
    # the reader's walk: identity (root, group) @ transform @ translation(x = 0, y = 0)
    mat = np.eye(3) @ mat @ np.eye(3)
    lin = mat[:, :2, :2]
    det = np.linalg.det(lin)
    if (np.abs(det) < 1e-12).any():
        return None  # scaled to nothing: the reader drops it with a warning, or refuses a singular transform
    scale = np.sqrt(np.abs(det))
    # math.degrees and math.radians are one multiplication by a constant (CPython's radToDeg,
    # degToRad): numpy's is the same, bit for bit; atan2, cos and sin stay the C library's
    angle = np.fromiter(map(math.atan2, lin[:, 1, 0].tolist(), lin[:, 0, 0].tolist()), np.float64, len(det))
    angle *= 180.0 / math.pi
    turn = angle * (math.pi / 180.0)
    cos = np.fromiter(map(math.cos, turn.tolist()), np.float64, len(turn))
    sin = np.fromiter(map(math.sin, turn.tolist()), np.float64, len(turn))
    rot = np.stack([np.stack([cos, -sin], 1), np.stack([sin, cos], 1)], 1)
    offset = np.array([k.offset for k in kinds]).reshape(-1, 2)[kind]
    xy = mat[:, :2, 2] + ((scale[:, None, None] * rot) @ (-offset)[:, :, None])[:, :, 0]
    inside = shapely.intersects_xy(region, xy[:, 0], xy[:, 1])
    if not inside.any():
        return None  # the reader's error
    arr = Arrangement(kind, xy, angle, scale)
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
