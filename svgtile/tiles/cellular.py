"""Recognising a bedded or brick tile and writing it as a cellular exemplar (issue 15, item 6).

FGDC limestone, dolomite, shale, bedded chert and the interbedded series are not scatters of
motifs: they are courses between bedding lines, cut into bricks or rhombs by joints, with dashes
on the lines and nodules or fossils set in the cells.  :func:`import_cellular` reads that
structure from the tile's pieces (:class:`~svgtile.svg.tilepieces.TilePieces`):

1. **bedding rows** — straight pieces along one bearing (horizontal first, else the bearing of the
   longest straight pieces) grouped by their offset across it: a row that covers the tile's width
   is a solid line, a row of several similar pieces a dashed line (its dash length, period and
   shift measured); the rows give the course height (the tile's height over their number) and
   each row becomes one line of the description, repeating every that many courses, so
   interbedded rows keep their order and weights;
2. **joints** — straight pieces crossing a course (0.6–1.25 of its height) cut it into cells: their
   spacing gives the cell length, their shift from course to course the bond's offset, their slant
   rhombs (dolomite);
3. **motifs** — the rest is imported as discrete motifs (:func:`svgtile.svg.importer.import_pieces`)
   and set in cells, in the share of cells the tile has them.

The exemplar is the scatter importer's, or an empty tile, with the description as the region's
``svgtile:cellular`` attribute (JSON; :mod:`svgtile.engines.cellular.tree`).  A tile with no
bedding rows (crossed hatching, a grid, wavy foliation) is refused with the reason.
"""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path

import numpy as np

from svgtile.errors import ExemplarError
from svgtile.svg.dialect import CELLULAR_ATTR, GROUND_ATTR, PERIOD_ATTR, SVG_NS
from svgtile.svg.numbers import fmt, fmt_array
from svgtile.svg.tilepieces import TilePieces
from svgtile.tiles.refusals import LeftOut

#: How a solid fill is drawn (the tile reader keeps no paint of a frame it drops).
SOLID_STYLE = "fill:#000000;stroke:none"
#: Straight: no point farther from the chord than this share of its length.
STRAIGHT = 0.05
#: A gently wavy stroke (no point farther from the chord than this share of its length) may be a
#: bedding line too: it is drawn straight along the course.
WAVY = 0.3
#: Along the bearing: within this many degrees.
ALONG = 4.0
#: A wavy row's profile: samples along one tile, and the spread across it (share of the period)
#: under which it is straight.
WAVE_SAMPLES = 48
WAVE_FLAT = 0.01
#: A row covering at least this share of the tile's width is a solid line.
SOLID = 0.9
#: A row of three or more pieces of uneven lengths covering at least this share of the tile's
#: width is a broken line, drawn dashed with its mean dash and gap.
BROKEN = 0.25
#: A joint crosses this share of a course, at least and at most.
JOINT = (0.6, 1.25)
#: Refused, cells or not, if pieces besides bedding and joints, unread as motifs, hold more than
#: this share of the tile's stroke length (as dark as 1 − LEFT_OUT of the tile at most).  Measured
#: over the 48 tiles once accepted as cells: 44 leave out 0, 717 0.14, 705 0.40, 709 0.44, 733 0.66.
LEFT_OUT = 0.25


def import_cellular(tile: TilePieces, refused: ExemplarError, import_pieces) -> tuple[str, dict, object | None, list[str]]:
    """The cellular exemplar of ``tile`` (see the module docstring).

    Parameters
    ----------
    tile : the tile's pieces
    refused : why the scatter importer refused it (raised again if the tile is not bedded)
    import_pieces : the scatter importer, for the motifs in cells

    Returns
    -------
    text : the exemplar SVG
    description : the cellular description (JSON-ready)
    motifs : the scatter importer's result for the motifs in cells, or None
    notes : what was left out
    """
    w, h = tile.box[2], tile.box[3]
    if len(tile.points) == 0:
        if not tile.filled_frame:
            raise refused
        # a solid fill (FGDC 658, coal): one block per tile, filled, the face whole
        desc = {"course": round(h, 4), "length": round(w, 4), "offset": 0.0, "cell_style": SOLID_STYLE,
                "tree": [{"feature": "face", "generator": "blocks", "style": SOLID_STYLE}]}  # fmt: skip
        return _with_description(_empty(tile), desc, tile), desc, None, ["a solid fill, drawn black"]
    feats = _straight(tile)
    first = _bearing(feats)
    if first is None:
        raise refused
    left_out: LeftOut | None = None  # the first reading that left out too much, if none fits
    for bearing in dict.fromkeys((first, 0.0)):  # the likeliest bearing, then the horizontal
        try:
            found = _bedded(tile, feats, bearing, refused, import_pieces)
        except ExemplarError as exc:
            left_out = left_out or (exc if isinstance(exc, LeftOut) else None)
            continue
        dashed = any("dash" in spec for spec in found[1].get("lines", ()))
        if bearing != 0.0 or (found[1]["cell_style"] and not dashed):
            return found
        try:  # no joints, or joints and dashed rows (673: bricks between some rows): interbedded courses?
            inter = _interbedded(tile, feats, refused, import_pieces)
        except ExemplarError:
            return found
        bands = inter[1]["bands"]
        return inter if not found[1]["cell_style"] or len(bands["cut"]) < len(bands["rows"]) else found
    raise left_out or refused


def _bedded(tile: TilePieces, feats: dict[str, np.ndarray], bearing: float, refused: ExemplarError, import_pieces
            ) -> tuple[str, dict, object | None, list[str]]:  # fmt: skip
    """:func:`import_cellular` with courses along ``bearing``; ``refused`` raised if not bedded so."""
    w, h = tile.box[2], tile.box[3]
    rows, row_of = _rows(tile, feats, bearing)
    if not rows:
        raise refused
    period = _normal_period(w, h, bearing)
    course = period / len(rows)
    lines = []
    for k, row in enumerate(rows):
        spec: dict = {"every": len(rows), "start": k, "style": row["style"]}
        if row["dash"] is not None:
            spec["dash"] = [round(row["dash"][0], 4), round(row["dash"][1], 4)]
            spec["shift"] = round(row["shift"], 4)
        if "wave" in row:
            spec.update(wave=row["wave"], wave_period=round(_span(w, h, bearing), 4))
        lines.append(spec)
    used = row_of >= 0
    # joints: straight pieces across a course, not in a row
    rel = (feats["angle"] - bearing) % 180.0
    across = feats["length"] * np.abs(np.sin(np.radians(rel)))  # a slanted joint still spans one course
    joint = ~used & feats["wavy"] & (across >= JOINT[0] * course) & (across <= JOINT[1] * course)
    joint &= np.abs(rel - 90.0) <= 50.0
    if joint.any():  # the common slants of joints (ticks inside bricks are not joints)
        slant = np.round(rel[joint] / 5.0).astype(np.int64)
        counts = np.bincount(slant)
        joint[joint] = counts[slant] >= 0.5 * counts.max()
    notes: list[str] = []
    desc: dict = {"course": round(course, 4), "offset": 0.5, "lines": lines, "angle": round(bearing, 4)}
    cells_drawn = False
    if joint.sum() >= max(2, len(rows) // 2):
        ju = _joints(feats, joint, bearing, course, period, w)
        if ju is not None:
            length, offset, slant = ju
            desc.update(length=round(length, 4), offset=round(offset, 4))
            face = "bricks"
            if abs(slant) > 15.0:
                face = "rhombs"
                desc["rhomb_angle"] = round(slant, 4)
            desc["tree"] = [{"feature": "corner", "generator": "corner"}, {"feature": "edge", "generator": "edge_bricks"},
                            {"feature": "face", "generator": face}]  # fmt: skip
            desc["cell_style"] = _style(tile, int(np.flatnonzero(joint)[0]))
            used |= joint
            used |= _joint_fragments(feats, joint, ~used & feats["straight"], w, h, course)
            cells_drawn = True
            if all(r["dash"] is None for r in rows):  # the cells' outlines draw the solid rows
                desc.pop("lines")
    if not cells_drawn:
        desc["cell_style"] = ""
    rest = np.flatnonzero(~used)
    motifs = None
    if len(rest):
        sub = _subset(tile, rest)
        try:
            motifs = import_pieces(sub)
        except ExemplarError as exc:
            # reading the rest as motifs failed: unless rows and joints (cells) carry the pattern,
            # the linework is more than what a cellular pattern draws
            share = _left_out(tile, rest, exc, notes)
            if not cells_drawn and share > 0.5:
                raise refused from None
            if share > LEFT_OUT:  # cells or not, too much of the pattern would be missing
                raise LeftOut(len(rest), share, LEFT_OUT, source=tile.source) from None
            # the filled fragments among that linework are still motifs (FGDC 733's ore lenses)
            filled = rest[_filled(tile, rest)]
            if 0 < len(filled) < len(rest):
                try:
                    motifs = import_pieces(_subset(tile, filled))
                    rest = filled
                    notes[-1] = f"{notes[-1]}; its {len(filled)} filled fragment(s) kept as motifs"
                except ExemplarError:
                    pass
    if motifs is not None and len(motifs):
        cells = len(rows) * (w / desc["length"] if "length" in desc else 1.0)
        if "length" not in desc:  # invisible cells, one motif each
            desc["length"] = round(max(course, w * len(rows) / len(motifs)), 4)
            desc["tree"] = [{"feature": "corner", "generator": "none"}, {"feature": "edge", "generator": "edge_blocks"},
                            {"feature": "face", "generator": "bricks"}]  # fmt: skip
            cells = len(rows) * w / desc["length"]
        desc["motifs"] = {"share": round(min(1.0, len(motifs) / max(cells, 1.0)), 4)}
        if _over(tile, rest, used, bearing, course):
            desc["motifs"]["over"] = True
    if not cells_drawn and "tree" not in desc:
        desc["length"] = round(w, 4)
        desc["tree"] = [{"feature": "face", "generator": "none"}]
    text = _with_description(motifs.text if motifs is not None and len(motifs) else _empty(tile), desc, tile)
    return text, desc, motifs, notes


def _interbedded(tile: TilePieces, feats: dict[str, np.ndarray], refused: ExemplarError, import_pieces
                 ) -> tuple[str, dict, object | None, list[str]]:  # fmt: skip
    """:func:`import_cellular` for horizontal courses of unequal heights, some cut into cells
    (interbedded series: FGDC 672, 677), or courses whose cells hold rows of motifs (637).

    A joint is a steep piece whose ends lie on two rows; a row the joints cross is not bedding
    (dashes in the bricks of 637, 672): its pieces are motifs set in cells.  The courses between
    the rows left are cut into cells where joints run (``bands.cut``), the rest stay open; solid
    rows along cut courses are drawn by the cells' outlines, every other row as a line.
    ``refused`` is raised if no two joints are found.
    """
    x0, y0, w, h = tile.box
    rows, row_of = _rows(tile, feats, 0.0)
    if len(rows) < 2:
        raise refused
    order = np.argsort([r["offset"] for r in rows], kind="stable")
    rows = [rows[i] for i in order.tolist()]
    row_of = np.where(row_of >= 0, np.argsort(order)[np.maximum(row_of, 0)], -1)
    offs = np.array([r["offset"] for r in rows])
    tol = 0.25 * float(np.diff(np.r_[offs, offs[0] + h]).min())
    rel = (feats["angle"] - 0.0) % 180.0
    cand = (row_of < 0) & feats["wavy"] & (np.abs(rel - 90.0) <= 50.0)
    ca, cb = feats["first"][:, 1] - y0, feats["last"][:, 1] - y0
    lo, hi = np.minimum(ca, cb), np.maximum(ca, cb)

    def nearest(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        d = np.abs((x[:, None] - offs[None, :] + h / 2) % h - h / 2)
        return np.argmin(d, axis=1), np.min(d, axis=1)

    ia, da = nearest(lo)
    ib, db = nearest(hi)
    # a joint cut by the tile's side goes on in the next tile: its pieces end at a row or a side
    at_top, at_edge = lo <= 1e-3 * h, hi >= h - 1e-3 * h
    piece = cand & ((da <= tol) | at_top) & ((db <= tol) | at_edge) & ~(at_top & at_edge) & (hi - lo < 0.5 * h)
    joint = piece & (da <= tol) & (hi - lo > 2 * tol)  # a whole joint, or its piece at the tile's lower side
    if joint.sum() < 2:
        raise refused
    # rows the joints cross lie inside cells: not bedding
    p = (offs[None, :] - lo[piece, None]) % h
    crossed = ((p > tol) & (p < (hi - lo)[piece, None] - tol) & (p < h - tol)).sum(axis=0) >= 2
    kept = ~crossed
    k = int(kept.sum())
    kidx = np.cumsum(kept) - 1
    ok = joint & kept[ia] & (at_edge | (kidx[ib] == (kidx[ia] + 1) % k))
    band = kidx[ia]
    counts = np.bincount(band[ok & ~at_edge], minlength=k)
    # a course astride the tile's side: its joints are cut in two, count each once
    upper = piece & at_top & kept[ib]
    counts += np.maximum(np.bincount(band[ok & at_edge], minlength=k), np.bincount((kidx[ib] - 1)[upper] % k, minlength=k))
    cut = np.flatnonzero(counts >= 2)
    if len(cut) == 0:
        raise refused
    per = float(np.median(counts[cut]))
    length = w / per
    s_mid = (feats["mid"][:, 0] - x0) % w
    # the bond's offset: the shift of the joints from one cut course to the next (courses astride
    # the tile's side, with joints in pieces, left out)
    first = {b: float(np.min(s_mid[ok & (band == b)] % length)) for b in cut.tolist() if (ok & (band == b)).any()}
    nxt = dict(zip(cut.tolist(), np.roll(cut, -1).tolist(), strict=True))
    shifts = [((first[nxt[b]] - first[b]) / length) % 1.0 for b in first if nxt[b] in first and nxt[b] != b]
    offset = float(np.median(shifts)) if shifts else 0.5
    chord = feats["last"][ok & ~at_edge] - feats["first"][ok & ~at_edge]
    chord *= np.where(chord[:, 1] < 0, -1.0, 1.0)[:, None]
    slant = float(np.degrees(np.median(np.arctan2(chord[:, 0], chord[:, 1])))) if len(chord) else 0.0
    kept_rows = [r for r, keep in zip(rows, kept.tolist(), strict=True) if keep]
    base = kept_rows[0]["offset"]
    lines = []
    bounds_cut = set(cut.tolist()) | {(int(c) + 1) % k for c in cut.tolist()}
    for n, row in enumerate(kept_rows):
        if row["dash"] is None and n in bounds_cut:
            continue  # the cells' outlines draw it
        spec: dict = {"every": k, "start": n, "style": row["style"]}
        if row["dash"] is not None:
            spec["dash"] = [round(row["dash"][0], 4), round(row["dash"][1], 4)]
            spec["shift"] = round(row["shift"], 4)
        if "wave" in row:
            spec.update(wave=row["wave"], wave_period=round(w, 4))
        lines.append(spec)
    if not ok.any():  # the cut courses' joints are all pieces at the tile's top edge
        raise refused
    joint_style = _style(tile, int(np.flatnonzero(ok)[0]))
    desc: dict = {"course": round(h / k, 4), "length": round(length, 4), "offset": round(offset, 4), "angle": 0.0,
                  "bands": {"period": round(h, 4), "rows": [round((r["offset"] - base) % h, 4) for r in kept_rows],
                            "cut": cut.tolist()},
                  "cell_style": joint_style,
                  "tree": [{"feature": "corner", "generator": "none"}, {"feature": "edge", "generator": "none"},
                           {"feature": "face", "generator": "bricks"}]}  # fmt: skip
    if abs(slant) > 15.0:  # slanted joints: rhombs (dolomite)
        desc["tree"][2]["generator"] = "rhombs"
        desc["rhomb_angle"] = round(slant, 4)
    if lines:
        desc["lines"] = lines
    used = ((row_of >= 0) & kept[np.maximum(row_of, 0)]) | piece
    rest = np.flatnonzero(~used)
    notes: list[str] = []
    motifs = None
    if len(rest):
        try:
            motifs = import_pieces(_subset(tile, rest))
        except ExemplarError as exc:
            if (share := _left_out(tile, rest, exc, notes)) > LEFT_OUT:
                raise LeftOut(len(rest), share, LEFT_OUT, source=tile.source) from None
    if motifs is not None and len(motifs):
        desc["motifs"] = {"share": round(min(1.0, len(motifs) / max(per * len(cut), 1.0)), 4)}
    text = _with_description(motifs.text if motifs is not None and len(motifs) else _empty(tile), desc, tile)
    return text, desc, motifs, notes


def _left_out(tile: TilePieces, rest: np.ndarray, why: ExemplarError, notes: list[str]) -> float:
    """The share of the tile's stroke length in ``rest`` (pieces neither bedding, joints nor motifs:
    ``why`` they are not motifs), noted in ``notes``."""
    share = _ink(tile, rest) / max(_ink(tile, np.arange(len(tile.points))), 1e-12)
    notes.append(f"{len(rest)} piece(s) besides the bedding and joints left out, {share:.0%} of the tile's stroke "
                 f"length ({why})")  # fmt: skip
    return share


def _straight(tile: TilePieces) -> dict[str, np.ndarray]:
    """Per piece: straight open stroke?, chord length, bearing (degrees in [0, 180)), midpoint."""
    n = len(tile.points)
    first = np.array([p[0] for p in tile.points]).reshape(-1, 2)
    last = np.array([p[-1] for p in tile.points]).reshape(-1, 2)
    chord = last - first
    length = np.hypot(chord[:, 0], chord[:, 1])
    dev = np.zeros(n)
    for i, p in enumerate(tile.points):
        if len(p) > 2 and length[i] > 0:
            d = chord[i] / length[i]
            dev[i] = float(np.abs((p[:, 0] - first[i, 0]) * d[1] - (p[:, 1] - first[i, 1]) * d[0]).max())
    straight = ~tile.closed & (length > 0) & (dev <= STRAIGHT * np.maximum(length, 1e-12))
    wavy = ~tile.closed & (length > 0) & (dev <= WAVY * np.maximum(length, 1e-12))
    angle = np.degrees(np.arctan2(chord[:, 1], chord[:, 0])) % 180.0
    return {"straight": straight, "wavy": wavy, "length": length, "angle": angle, "mid": (first + last) / 2, "first": first,
            "last": last}  # fmt: skip


def _bearing(f: dict[str, np.ndarray]) -> float | None:
    """The bedding's bearing: horizontal if straight horizontal pieces hold a tenth of the straight
    ink and half as much as any other bearing, else the bearing holding the most straight ink."""
    s = f["wavy"]
    if not s.any():
        return None
    ink = f["length"] * s
    horizontal = (np.minimum(f["angle"], 180.0 - f["angle"]) <= ALONG) & s
    bins = np.round(f["angle"][s] / 5.0) * 5.0 % 180.0
    weights = np.bincount((bins / 5).astype(np.int64), weights=ink[s], minlength=36)
    # bedding is horizontal unless another bearing holds far more ink (FGDC 657's hatching)
    if ink[horizontal].sum() >= max(0.1 * ink.sum(), 0.5 * weights.max()):
        return 0.0
    return float(np.argmax(weights) * 5.0)


def _span(w: float, h: float, bearing: float) -> float:
    """The length of a line of ``bearing`` across one tile (:func:`_rows`' period of dashes)."""
    c = abs(math.cos(math.radians(bearing)))
    return w / c if c > 1e-9 else h


def _normal_period(w: float, h: float, bearing: float) -> float:
    """The period across lines of ``bearing`` in a tile repeating by (w, 0) and (0, h)."""
    t = math.radians(bearing)
    if abs(math.sin(t)) < 1e-9:
        return h
    if abs(math.cos(t)) < 1e-9:
        return w
    # lines through the lattice: the normal offsets of w·(1,0) and h·(0,1) generate the period
    a, b = abs(w * math.sin(t)), abs(h * math.cos(t))
    for k in range(1, 9):  # the smallest offset that is a whole fraction of both
        g = a / k
        if abs(b / g - round(b / g)) < 0.02:
            return g
    return min(a, b)


def _rows(tile: TilePieces, f: dict[str, np.ndarray], bearing: float) -> tuple[list[dict], np.ndarray]:
    """Bedding rows along ``bearing``: the straight pieces along it grouped by their offset across it.

    Returns the rows in order across the tile (``dash`` = (on, off) or None, ``shift`` of the dashes
    as a share of their period, ``style``) and (n,) each piece's row (-1 for none)."""
    x0, y0, w, h = tile.box
    t = math.radians(bearing)
    u, nrm = np.array([math.cos(t), math.sin(t)]), np.array([-math.sin(t), math.cos(t)])
    period = _normal_period(w, h, bearing)
    tol_angle = ALONG if bearing == 0.0 else 2 * ALONG  # oblique rows are digitised less evenly
    along = f["wavy"] & ((f["angle"] - bearing + tol_angle) % 180.0 <= 2 * tol_angle)
    row_of = np.full(len(f["length"]), -1)
    idx = np.flatnonzero(along)
    if len(idx) == 0:
        return [], row_of
    off = (f["mid"][idx] @ nrm - np.array([x0, y0]) @ nrm) % period
    tol = max(0.01 * period, 0.15)
    order = np.argsort(off)
    groups: list[list[int]] = []
    last = -np.inf
    for i in order.tolist():
        if off[i] - last > tol:
            groups.append([])
        groups[-1].append(i)
        last = off[i]
    if len(groups) > 1 and off[groups[0][0]] + period - off[groups[-1][-1]] <= tol:  # wraps round
        groups[0] = groups.pop() + groups[0]
    if len(groups) > 2:  # hand-digitised rows wobble: groups much closer than the rows' spacing are one
        centre = np.array([float(np.median(off[g])) for g in groups])
        gap = np.diff(centre)
        close = gap < 0.35 * float(np.median(gap))
        merged = [groups[0]]
        for g, c in zip(groups[1:], close.tolist(), strict=True):
            if c:
                merged[-1] = merged[-1] + g
            else:
                merged.append(g)
        groups = merged
    width = abs(w * u[0]) + abs(h * u[1]) if abs(u[0]) > 1e-9 and abs(u[1]) > 1e-9 else (w if abs(u[0]) > 0.5 else h)
    span_len = w / abs(u[0]) if abs(u[0]) > 1e-9 else h  # length of a line across one tile
    rows = []
    for g in groups:
        members = idx[np.array(g)]
        length = f["length"][members]
        cover = length.sum() / span_len
        if cover >= SOLID:
            dash = None
            shift = 0.0
        elif (len(members) >= 2 and length.std() <= 0.35 * length.mean()) or (len(members) >= 3 and cover >= BROKEN):
            starts = np.sort((np.minimum(f["first"][members] @ u, f["last"][members] @ u)) % span_len)
            gaps = np.diff(np.r_[starts, starts[0] + span_len])
            per = span_len / len(members)
            on = float(np.median(length)) if length.std() <= 0.35 * length.mean() else cover * per
            if on >= per * 0.95:
                dash, shift = None, 0.0
            else:
                dash = (on, per - on)
                shift = float((starts[0] % per) / per)
            del gaps
        else:
            continue
        row = {"offset": float(np.median(off[np.array(g)])), "dash": dash, "shift": shift,
               "style": _style(tile, int(members[0]))}  # fmt: skip
        wave = _wave(tile, members, u, nrm, np.array([x0, y0]), row["offset"], period, span_len)
        if wave is not None:
            row["wave"] = wave
        row_of[members] = len(rows)
        rows.append(row)
    del width  # uneven rows are kept: the courses are their mean spacing (the tile's order stays)
    return rows, row_of


def _wave(tile: TilePieces, members: np.ndarray, u: np.ndarray, nrm: np.ndarray, origin: np.ndarray, offset: float,
          period: float, span: float) -> list[float] | None:  # fmt: skip
    """The row's waviness: its offset across the row at ``WAVE_SAMPLES`` even steps along one
    ``span`` (user units, a periodic profile), or None for a straight row (within ``WAVE_FLAT``)."""
    pts = []
    for i in members.tolist():  # each piece densified, so that long straight segments weigh
        p = tile.points[i]
        seg = np.hypot(*np.diff(p, axis=0).T)
        arc = np.r_[0.0, np.cumsum(seg)]
        if arc[-1] <= 0:
            continue
        at = np.linspace(0.0, arc[-1], max(2, int(arc[-1] / span * 4 * WAVE_SAMPLES)))
        pts.append(np.stack([np.interp(at, arc, p[:, 0]), np.interp(at, arc, p[:, 1])], axis=1))
    if not pts:
        return None
    xy = np.concatenate(pts) - origin
    s = (xy @ u) % span
    dt = (xy @ nrm - offset + period / 2) % period - period / 2
    if np.ptp(dt) <= WAVE_FLAT * period:
        return None
    k = np.minimum((s / span * WAVE_SAMPLES).astype(np.int64), WAVE_SAMPLES - 1)
    count = np.bincount(k, minlength=WAVE_SAMPLES)
    mean = np.bincount(k, weights=dt, minlength=WAVE_SAMPLES) / np.maximum(count, 1)
    have = np.flatnonzero(count)
    grid = np.arange(WAVE_SAMPLES)
    profile = np.interp(grid, have, mean[have], period=WAVE_SAMPLES) if len(have) < WAVE_SAMPLES else mean
    return [round(float(v), 4) for v in profile]


def _filled(tile: TilePieces, idx: np.ndarray) -> np.ndarray:
    """(len(idx),) bool: the pieces that are closed, filled shapes."""
    return np.array([bool(tile.closed[i]) and dict(tile.paint[i]).get("fill", "none") not in ("none", "transparent")
                     for i in idx.tolist()], dtype=bool)  # fmt: skip


def _over(tile: TilePieces, motif: np.ndarray, lines: np.ndarray, bearing: float, course: float) -> bool:
    """Whether the tile draws its motifs (pieces ``motif``) over its linework (pieces ``lines``,
    (n,) bool) rather than inside cells: most of them cross a line or are taller than a course
    (FGDC 657's peat fragments on the hatching, 733's ore lenses)."""
    import shapely
    import shapely.affinity

    if len(motif) == 0:
        return False
    fp = tile.footprint[motif]
    crosses = np.zeros(len(motif), dtype=bool)
    if lines.any():
        hit, _ = shapely.STRtree(tile.footprint[lines]).query(fp, predicate="intersects")
        crosses[np.unique(hit)] = True
    turned = [shapely.affinity.rotate(g, -bearing, origin=(0, 0)) for g in fp]
    bounds = shapely.bounds(np.array(turned, dtype=object))
    tall = (bounds[:, 3] - bounds[:, 1]) > course
    return bool((crosses | tall).mean() > 0.5)


def _joint_fragments(f: dict[str, np.ndarray], joint: np.ndarray, candidate: np.ndarray, w: float, h: float,
                     course: float) -> np.ndarray:  # fmt: skip
    """(n,) bool: the ``candidate`` pieces that are the short ends of joints the tile's edge cuts
    (FGDC 627: a joint crossing the tile's bottom edge is drawn as a stroke of 3 at the top and a
    stub of 0.85 at the bottom).  Such a stub, moved by one period, meets a joint end to end and
    runs along it; it belongs to that joint (the engine draws whole joints), not to the motifs."""
    out = np.zeros(len(candidate), dtype=bool)
    if not (candidate.any() and joint.any()):
        return out
    from scipy.spatial import cKDTree

    tol = 0.02 * course
    ends = np.concatenate([f["first"][joint], f["last"][joint]])
    angle = np.concatenate([f["angle"][joint], f["angle"][joint]])
    tree = cKDTree(ends)
    shifts = np.array([(i * w, j * h) for i in (-1, 0, 1) for j in (-1, 0, 1) if i or j])
    idx = np.flatnonzero(candidate)
    for end in ("first", "last"):
        pts = f[end][idx][:, None, :] + shifts[None, :, :]  # (c, 8, 2) the stub's end in the next tiles
        dist, near = tree.query(pts.reshape(-1, 2), distance_upper_bound=tol)
        hit = (dist <= tol).reshape(len(idx), -1)
        near = np.where(np.isfinite(dist), near, 0).reshape(len(idx), -1)
        turn = np.abs((f["angle"][idx][:, None] - angle[near] + 90.0) % 180.0 - 90.0)
        out[idx] |= (hit & (turn <= 5.0)).any(axis=1)
    return out


def _joints(f: dict[str, np.ndarray], joint: np.ndarray, bearing: float, course: float, period: float, w: float
            ) -> tuple[float, float, float] | None:  # fmt: skip
    """(cell length, course offset as a share of it, slant in degrees from the course normal) of the
    joints, or None if they make no regular bond."""
    t = math.radians(bearing)
    u, nrm = np.array([math.cos(t), math.sin(t)]), np.array([-math.sin(t), math.cos(t)])
    mid = f["mid"][joint]
    s, c = mid @ u, mid @ nrm
    crs = np.floor(c / course).astype(np.int64)
    span = w / abs(u[0]) if abs(u[0]) > 1e-9 else w
    counts = np.bincount(crs - crs.min())
    counts = counts[counts > 0]
    per = float(np.median(counts))
    if per < 1:
        return None
    length = span / per
    # offset: shift of the joints from one course to the next, modulo a length
    firsts = {int(k): float(np.min(s[crs == k] % length)) for k in np.unique(crs)}
    shifts = [((firsts[k + 1] - firsts[k]) / length) % 1.0 for k in firsts if k + 1 in firsts]
    offset = float(np.median(shifts)) if shifts else 0.5
    d = (f["last"][joint] - f["first"][joint])
    d = d * np.where((d @ nrm) < 0, -1.0, 1.0)[:, None]
    slant = float(np.degrees(np.median(np.arctan2(d @ u, d @ nrm))))
    return length, offset, slant


def _style(tile: TilePieces, piece: int) -> str:
    paint = dict(tile.paint[piece])
    keys = ("stroke", "stroke-width", "stroke-linecap", "stroke-dasharray")
    return ";".join(["fill:none", *(f"{k}:{paint[k]}" for k in keys if k in paint)])


def _ink(tile: TilePieces, idx: np.ndarray) -> float:
    return float(sum(float(np.hypot(*np.diff(tile.points[i], axis=0).T).sum()) if len(tile.points[i]) > 1 else 0.0
                     for i in idx.tolist()))  # fmt: skip


def _subset(tile: TilePieces, idx: np.ndarray) -> TilePieces:
    return replace(tile, footprint=tile.footprint[idx], points=[tile.points[i] for i in idx.tolist()],
                   closed=tile.closed[idx], element=tile.element[idx], paint=[tile.paint[i] for i in idx.tolist()],
                   frames=[], warnings=[])  # fmt: skip


def _empty(tile: TilePieces) -> str:
    """An exemplar with no motifs: the tile as the region (the description is added after)."""
    x0, y0, w, h = tile.box
    box = " ".join(fmt_array(np.array([x0, y0, w, h])))
    root = ET.Element(f"{{{SVG_NS}}}svg", {"viewBox": box, "width": fmt(w), "height": fmt(h)})
    region = ET.SubElement(root, f"{{{SVG_NS}}}rect", {"id": "region", "x": fmt(x0), "y": fmt(y0), "width": fmt(w),
                                                        "height": fmt(h), "fill": "none",
                                                        PERIOD_ATTR: f"{fmt(w)} {fmt(h)}"})  # fmt: skip
    if tile.ground:
        region.set(GROUND_ATTR, tile.ground)
    return ET.tostring(root, encoding="unicode")


def _with_description(text: str, desc: dict, tile: TilePieces) -> str:
    """``text`` with ``desc`` on its region element, and a note saying so in its ``<desc>``."""
    root = ET.fromstring(text)
    region = next(el for el in root.iter() if el.get("id") == "region")
    region.set(CELLULAR_ATTR, json.dumps(desc, sort_keys=True, separators=(",", ":")))
    note = root.find(f"{{{SVG_NS}}}desc")
    if note is None:
        note = ET.Element(f"{{{SVG_NS}}}desc")
        root.insert(0, note)
    note.text = (f"Imported by svgtile from {Path(tile.source).name} as a cellular pattern (courses of "
                 f"{fmt(desc['course'])}; svgtile:cellular on the region). " + (note.text or "")).strip()  # fmt: skip
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode") + "\n"
