"""The ``<use>`` lines of a texture in svgtile's own form, scanned as text (for :mod:`svgtile.svg.texture`).

svgtile writes its motif group last, one ``<use>`` per line, each transform ``translate(x y)
[rotate(a)] [scale(s)] [kind suffix]`` (:func:`svgtile.svg.writer.svg_document`).  This module
finds that group in the document's bytes (:func:`start_block`), scans its lines with one regular
expression (:func:`scan`) and composes and splits every transform with numpy exactly as the
exemplar reader composes and splits each one with svgelements (:func:`pose`), bit for bit.

Every figure of a line depends on that line alone but for the numbering of the groups (a kind's
lines), so the lines can be scanned in parts — the last part in another process, for
``svgtile score --jobs 2`` — and the parts joined (:func:`joined`) into what one scan gives.
"""

from __future__ import annotations

import itertools
import math
import os
import re
import select
import sys
import time
from concurrent.futures import BrokenExecutor, Executor, Future
from dataclasses import dataclass
from operator import itemgetter

import numpy as np

from svgtile.core.worker import worker_submit

#: A number as :func:`svgtile.svg.writer.fmt_array` writes it (no exponent, no leading ``+``).
_FIXED = r"-?\d+(?:\.\d+)?"
#: One motif's transform per line: x, y, angle, scale, the kind's suffix (with its leading space).
OWN_TRANSFORM = re.compile(
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
#: attributes as written, then its transform as :data:`OWN_TRANSFORM` splits it (the lookahead
#: spares the scan of each transform as one more attribute).
_OWN_USE = re.compile(_possessive(
    rf'^[ \t]*+<use (xlink:href="#[^"<>\n]*+"(?: (?!transform=)[A-Za-z_][-\w.:]*+="[^"<>\n]*+")*+) '
    rf'transform="translate\(({_FIXED_SCAN}) ({_FIXED_SCAN})\)(?: rotate\(({_FIXED_SCAN})\))?+'
    rf'(?: scale\(({_FIXED_SCAN})\))?+{_SUFFIX}"/>$',
), re.M)


#: ``<use>`` lines of svgtile's motif group above which a reader given a pool scans part of them
#: in its worker (:func:`svgtile.svg.texture.start_reading`): below it, handing the lines over
#: and the result back costs more than the part of the scan saves.
SPLIT_ABOVE = 20_000

#: The worker's share of the lines (of their text, cut at a line boundary): less than half, as
#: after its scan it measures the baselines and the footprint figures (≈ 0.58 s CPU on the
#: 177,723-motif gravel texture, with scipy.ndimage's import) while this process, after its
#: scan, reads the rest and measures the other figures (≈ 0.50 s); the scan is ≈ 0.30 s in all
#: (min of 5, one process: benchmarks/README.md, "score11e").
WORKER_SHARE = 0.4


@dataclass(frozen=True, eq=False)
class Pose:
    """Where each of n motifs' ``<use>`` puts its element, as ``DocumentReader._use_kind``
    splits the composed transform (:func:`pose`), before the kind's offset.

    Attributes
    ----------
    t : (n, 2) float array, the translation of the composed transform, user units
    scale : (n,) float array, ``sqrt(|det|)`` of its linear part
    angle : (n,) float array, its rotation, degrees
    cos, sin : (n,) float arrays, of ``angle`` (the C library's, as the reader computes them)
    """

    t: np.ndarray
    scale: np.ndarray
    angle: np.ndarray
    cos: np.ndarray
    sin: np.ndarray


@dataclass(frozen=True, eq=False)
class OwnLines:
    """``<use>`` lines of svgtile's motif group, scanned as text (:func:`scan`).

    A *group* is the lines with the same ``href`` and attributes text and the same kind suffix;
    groups are numbered in order of first appearance.

    Attributes
    ----------
    group : (n,) int array, each motif's group
    first : (g,) int array, the first line of each group (increasing)
    keys : g tuples, each group's ``href`` and attributes text and suffix
    first_lines : g strings, each group's first line
    first_columns : g tuples, ``x``, ``y``, ``angle``, ``scale`` and ``suffix`` of each group's
        first line as :data:`OWN_TRANSFORM` finds them in its transform (``""`` if missing)
    pose : the n motifs' :class:`Pose`, or None if a transform is singular (then the exemplar
        reader is left to say so)
    """

    group: np.ndarray
    first: np.ndarray
    keys: tuple[tuple[str, str], ...]
    first_lines: tuple[str, ...]
    first_columns: tuple[tuple[str, ...], ...]
    pose: Pose | None


@dataclass(frozen=True, eq=False)
class Block:
    """Where the ``<use>`` lines of svgtile's motif group lie in a texture (:func:`start_block`):
    ``data[start:end]`` is ``"\\n" + lines + "\\n" + indent``; ``body`` is the text of the lines
    this process scans — all of them, or the first part when ``far`` (a future of
    :func:`scan_lent`) is scanning the rest in the worker: ``rest`` is then ``(serial, start,
    stop)``, the document's serial (:func:`lend`) and where those lines lie in it."""

    start: int
    end: int
    body: str
    rest: tuple[int, int, int] | None
    far: Future | None


#: The document the worker of ``svgtile score`` finds in its memory, forked after the file was
#: read (:func:`lend`): ``(serial, data, pid of the lender, started)``, or None.  The worker scans
#: its part of the lines there instead of receiving the text through a pipe (≈ 6 MB of the
#: 177k-motif texture: pickled, written and read back, and the worker started scanning only then).
#: ``started`` is the pipe (read end, write end) on which a worker says it has begun
#: (:func:`_await_start`).
_LENT: tuple[int, bytes, int, tuple[int, int]] | None = None
_SERIAL = itertools.count(1)
#: The longest the lender waits for its worker to say it has begun (:func:`_await_start`), s.
START_WAIT = 0.5


def lend(data: bytes) -> int:
    """Put ``data`` where a worker forked from now on finds it (:func:`scan_lent`), with a pipe
    for it to say it has begun (:func:`_await_start`), and return its serial number, which such a
    worker holds too; :func:`take_back` releases it here (a document lent before and not taken
    back is released first: one is lent at a time)."""
    global _LENT
    if _LENT is not None:  # one document lent at a time: the one before is not wanted
        take_back(_LENT[0])
    serial = next(_SERIAL)
    _LENT = (serial, data, os.getpid(), os.pipe())
    return serial


def take_back(serial: int) -> None:
    """Release the document lent as ``serial`` (:func:`lend`), if it is still the one lent."""
    global _LENT
    if _LENT is not None and _LENT[0] == serial:
        _close(_LENT[3])
        _LENT = None


def _close(fds: tuple[int, ...]) -> None:
    """Close the descriptors ``fds``, those already closed left as they are."""
    for fd in fds:
        try:
            os.close(fd)
        except OSError:
            pass


def scan_lent(serial: int, start: int, stop: int) -> OwnLines | bool | None:
    """In a worker forked after :func:`lend`: :func:`scan` of the lines ``data[start:stop]`` of
    the document lent as ``serial`` (None if they are not UTF-8 or not svgtile's ``<use>``
    lines); False if this process does not hold that document (its worker was forked before it
    was lent): then the lender scans them itself.  A forked worker lets go of its copy after."""
    global _LENT
    lent = _LENT
    if lent is None or lent[0] != serial:
        return False
    if lent[2] != os.getpid():  # a forked worker: the lender's copy is its own to keep
        _LENT = None
        try:
            os.write(lent[3][1], b"1")  # begun (_await_start)
        except OSError:
            pass
        _close(lent[3])
    return _scan_bytes(lent[1], start, stop)


def _await_start(serial: int, far: Future) -> None:
    """Wait, the GIL released, until the worker has begun :func:`scan_lent` of the document lent
    as ``serial`` (or ``far`` is done, or :data:`START_WAIT` has passed).  Only a worker forked
    after :func:`lend` signals: one in this process (a thread) never does, and then this waits
    until its part is done.

    The task reaches the worker through the executor's two threads of this process, and each
    needs the GIL; :func:`cut_document` scans this process's part, whose regular expression
    holds the GIL for ≈ 0.08 s on the 177k-motif texture — the worker's scan began up to 0.13 s
    after this process's (benchmarks/README.md "score11f").  Waiting there first lets those
    threads run at once (a few ms), with any task the caller handed the worker after
    :func:`start_block` (``svgtile score``: the baselines).  Only time is at stake: where the
    pipe cannot be polled (no ``select.poll``, Windows), this does not wait."""
    lent = _LENT
    if lent is None or lent[0] != serial:
        return
    try:
        poller = select.poll()
        poller.register(lent[3][0], select.POLLIN)
    except (AttributeError, OSError, ValueError):
        return
    deadline = time.monotonic() + START_WAIT
    while not far.done():
        left = deadline - time.monotonic()
        if left <= 0:
            return
        try:
            if poller.poll(min(left, 0.01) * 1000.0):
                return
        except (OSError, ValueError):
            return


def _scan_bytes(data: bytes, start: int, stop: int) -> OwnLines | None:
    """:func:`scan` of the lines ``data[start:stop]``, None if they are not UTF-8."""
    try:
        text = data[start:stop].decode("utf-8")
    except UnicodeDecodeError:
        return None
    return scan(text)


def start_block(data: bytes, pool: Executor | None, split_above: int) -> Block | None:
    """Find svgtile's motif group of ``<use>`` lines at the end of ``data`` (None if there is
    none) and, with a ``pool`` and more than ``split_above`` lines, hand the last
    :data:`WORKER_SHARE` of them (from a line boundary on) to its worker (:func:`scan_lent`: the
    document is lent first, so a worker forked at this hand-over finds it in its own memory).

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
    if opening is None:
        return None
    # the group's end is the document's last </g> (searched from the end, where it is: not over
    # the 19 MB of lines); a </g> among the lines fails the scan (no line of it is a <use>)
    end = data.rfind(b"</g>")
    if end < opening.end() or re.fullmatch(rb"</g>[ \n]*</svg>[ \n]*", data[end:]) is None:
        return None
    # data[opening.end():end] is "\n" + one line per <use> + "\n" + the indent of </g> (spaces
    # and newlines are single bytes in UTF-8, never part of another character's)
    stop = end
    while stop > opening.end() and data[stop - 1] == 0x20:
        stop -= 1
    if stop - opening.end() < 3 or data[opening.end()] != 0x0A or data[stop - 1] != 0x0A:
        return None
    # the lines are data[first:last]; the worker's part, from a line boundary on, is decoded and
    # scanned there (in the document it holds, lent before it was forked), this one's here
    first, last = opening.end() + 1, stop - 1
    middle = data.find(b"\n", first + int((last - first) * (1.0 - WORKER_SHARE)), last)
    rest = far = None
    if pool is not None and middle >= 0 and data.count(b"\n", first, last) >= split_above:
        serial = lend(data)
        far = worker_submit(pool, scan_lent, serial, middle + 1, last)  # None: the worker died, all here
        if far is None:
            take_back(serial)
        else:
            rest, last = (serial, middle + 1, last), middle
    try:
        body = data[first:last].decode("utf-8")
    except UnicodeDecodeError:
        if rest is not None:  # the worker's part is not wanted
            take_back(rest[0])
        return None
    return Block(opening.end(), end, body, rest, far)


def cut_document(data: bytes, block: Block) -> tuple[bytes, OwnLines] | None:
    """The document cut to the first ``<use>`` of each group, and the lines scanned (both
    parts' joined, :func:`joined`); None if a line is not a ``<use>`` as svgtile writes it (or
    not UTF-8)."""
    if block.far is not None:  # the worker first: this thread's scan holds the GIL for long
        _await_start(block.rest[0], block.far)
    lines = scan(block.body)
    if block.far is None:
        return _cut(data, block, lines) if lines is not None else None
    serial, start, stop = block.rest
    if lines is None:  # the worker's part is not wanted
        take_back(serial)
        return None
    try:
        far = block.far.result()
    except BrokenExecutor:  # the worker died (killed, out of memory): scanned here instead
        far = False
    finally:
        take_back(serial)
    if far is False:  # (or the worker was forked before the document was lent)
        far = _scan_bytes(data, start, stop)
    return _cut(data, block, joined(lines, far)) if far is not None else None


def _cut(data: bytes, block: Block, lines: OwnLines) -> tuple[bytes, OwnLines]:
    """The document with only ``lines``' first line of each group kept, and ``lines``."""
    kept = "\n".join(lines.first_lines).encode("utf-8")
    return data[: block.start] + b"\n" + kept + b"\n" + data[block.end :], lines


def scan(text: str) -> OwnLines | None:
    """The ``<use>`` lines ``text`` (lines joined by ``"\\n"``) scanned: their groups and poses,
    or None if a line is not a ``<use>`` as svgtile writes it (:data:`_OWN_USE`).  Every figure
    of a line is its own, but for the numbering of the groups, so the lines can be scanned in
    parts and the parts joined (:func:`joined`)."""
    found = _OWN_USE.findall(text)
    if len(found) != text.count("\n") + 1:
        return None
    # the columns one by one (zip(*found) would step 177k tuples' iterators together, 4× slower)
    heads, *columns = (list(map(itemgetter(i), found)) for i in range(6))
    suffix = numbered(columns[4])
    first, group = first_groups(numbered(heads) * (int(suffix.max()) + 1) + suffix)
    at = first.tolist()
    # the lines up to the last group's first one (it comes early: splitting all 177k lines took
    # a tenth of the read)
    lines = text.split("\n", at[-1] + 1)
    return OwnLines(
        group, first, tuple((heads[i], columns[4][i]) for i in at), tuple(lines[i] for i in at),
        tuple(tuple(c[i] for c in columns) for i in at), pose(columns, suffix),
    )  # fmt: skip


def joined(a: OwnLines, b: OwnLines) -> OwnLines:
    """The scan of lines ``a`` followed by lines ``b``: ``b``'s groups renumbered after ``a``'s
    in order of first appearance, as one scan of all of them numbers them."""
    index = {k: g for g, k in enumerate(a.keys)}
    new = [g for g, k in enumerate(b.keys) if k not in index]
    for g in new:
        index[b.keys[g]] = len(index)
    renumber = np.array([index[k] for k in b.keys], dtype=np.int64)
    pose = None
    if a.pose is not None and b.pose is not None:
        pose = Pose(*(np.concatenate([getattr(a.pose, f), getattr(b.pose, f)]) for f in ("t", "scale", "angle", "cos", "sin")))
    return OwnLines(
        np.concatenate([a.group, renumber[b.group]]),
        np.concatenate([a.first, b.first[new] + len(a.group)]),
        a.keys + tuple(b.keys[g] for g in new),
        a.first_lines + tuple(b.first_lines[g] for g in new),
        a.first_columns + tuple(b.first_columns[g] for g in new),
        pose,
    )


def numbered(keys: list | tuple) -> np.ndarray:
    """(n,) int array: each of the n hashable ``keys`` numbered in order of first appearance."""
    index = {k: i for i, k in enumerate(dict.fromkeys(keys))}
    return np.fromiter(map(index.__getitem__, keys), np.int64, len(keys))


def first_groups(key: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The first element of each distinct value of ``key`` (n,), increasing, and each element's
    group, groups numbered in order of first appearance.  ``key`` is non-negative; where its
    values are few against n (a texture's kinds: they are, 177k motifs have some ten), one pass
    over it instead of a sort (25 ms of the 177k-motif texture's read)."""
    n = len(key)
    top = int(key.max()) + 1 if n else 0
    if 0 < top <= 4 * n:
        at = np.full(top, n, dtype=np.int64)
        np.minimum.at(at, key, np.arange(n, dtype=np.int64))
        present = np.flatnonzero(at < n)
        first = at[present]
        order = np.argsort(first, kind="stable")
        group_of_key = np.empty(top, dtype=np.int64)
        group_of_key[present[order]] = np.arange(len(present))
        return first[order], group_of_key[key]
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
    for texts, op in ((angles, "rotate"), (scales, "scale")):
        given = np.fromiter(map(bool, texts), bool, n)
        every = bool(given.all())  # then no row needs picking out (each a copy of the 6 × n)
        if not every and not given.any():
            continue
        v = _numbers(texts if every else list(filter(None, texts)))
        if op == "rotate":
            theta = math.tau * v / 360.0  # svgelements Angle.degrees
            ct = np.fromiter(map(math.cos, theta.tolist()), np.float64, len(theta))
            st = np.fromiter(map(math.sin, theta.tolist()), np.float64, len(theta))
            factor = (ct, st, -st, ct, 0.0, 0.0)
        else:
            factor = (v, 0.0, 0.0, v, 0.0, 0.0)
        if every:
            m = _pre_cat(m, factor)
        else:
            at = np.flatnonzero(given)
            m[:, at] = _pre_cat(m[:, at], factor)
    return m


def _numbers(texts: list[str] | tuple[str, ...]) -> np.ndarray:
    """(n,) float array of decimal ``texts``: Python's ``float`` of each, the correctly rounded
    double that ``np.array(texts, dtype=np.float64)`` gives too (≈ 1.4 × as fast as it)."""
    return np.fromiter(map(float, texts), np.float64, len(texts))


def pose(columns: tuple[list[str], ...] | list[list[str]], suffix: np.ndarray) -> Pose | None:
    """The :class:`Pose` of each of n motifs from its transform's columns (``x``, ``y``,
    ``angle``, ``scale`` and ``suffix`` texts, ``""`` where missing; ``suffix`` (n,) the suffix
    texts numbered), or None if a transform is singular.

    Row by row: a motif's pose depends on its own columns alone, bit for bit.
    """
    xs, ys, angles, scales, suffix_text = columns
    m = _compose(_numbers(xs), _numbers(ys), angles, scales)
    suffixes = {suffix_text[i]: s for s, i in enumerate(np.unique(suffix, return_index=True)[1].tolist())}
    for text, s in suffixes.items():
        at = np.flatnonzero(suffix == s)
        for op, values in _SUFFIX_PART.findall(text):
            v = [float(t) for t in values.split()]
            part = m[:, at]
            m[:, at] = _pre_cat(part, (1.0, 0.0, 0.0, 1.0, v[0], v[1]) if op == "translate" else tuple(v))
    n = m.shape[1]
    a, b, c, d, e, f = m
    mat = np.zeros((n, 3, 3))
    mat[:, 0], mat[:, 1], mat[:, 2, 2] = np.stack([a, c, e], 1), np.stack([b, d, f], 1), 1.0
    # the reader's walk: identity (root, group) @ transform @ translation(x = 0, y = 0); a product
    # with the identity is each entry plus zeros, which only turns a −0 into +0: ``+ 0.0`` does
    # the same, bit for bit (two batched 3 × 3 products of 177k matrices cost 20 ms)
    mat += 0.0
    lin = mat[:, :2, :2]
    det = np.linalg.det(lin)
    if (np.abs(det) < 1e-12).any():
        return None
    scale = np.sqrt(np.abs(det))
    # math.degrees and math.radians are one multiplication by a constant (CPython's radToDeg,
    # degToRad): numpy's is the same, bit for bit; atan2, cos and sin stay the C library's
    angle = np.fromiter(map(math.atan2, lin[:, 1, 0].tolist(), lin[:, 0, 0].tolist()), np.float64, n)
    angle *= 180.0 / math.pi
    turn = angle * (math.pi / 180.0)
    cos = np.fromiter(map(math.cos, turn.tolist()), np.float64, n)
    sin = np.fromiter(map(math.sin, turn.tolist()), np.float64, n)
    return Pose(mat[:, :2, 2], scale, angle, cos, sin)
