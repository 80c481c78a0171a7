"""The local-growth engine (Ijiri, Měch, Igarashi & Miller 2008): ``--engine growth``.

The paper grows one arrangement from one seed, element by element (§5).  That is sequential, so
a motif's fate would depend on everything grown before it — on the region's whole extent.  To
keep svgtile's promises (same seed ⇒ same bytes, an edit changes only what is near it, tiled runs)
growth runs per *world cell*:

* the plane is cut into square cells anchored at the world origin (a whole number of periods of a
  repeating tile, at least one exemplar width and 6·l wide);
* the cells are coloured 2 × 2 into four phases; all cells of a phase are grown independently,
  each from its own seed — for a tile, a lattice position of a motif chosen by a hash of
  ``(key, cell)``, so every cell grows on the same lattice and the seams vanish; otherwise a
  hashed point and reference near the cell centre;
* a cell of a later phase grows against the motifs of its earlier-phase neighbours (they are
  its fixed neighbours in matching and in relaxation, eq. 6), so growth fronts join across the
  seams instead of colliding; the cells of one phase, which do not meet, are grown in step
  (:meth:`Growth.grow_cells`), each as if alone;
* each cell is relaxed (§5.5) with its neighbours held, then its motifs are checked exactly
  (footprints: no overlap, the distance rule, no barrier crossed) against each other and the
  earlier motifs, and the conflicting ones leave (:func:`svgtile.core.conflicts.cull`, with
  world-anchored priorities); the holes they leave are regrown (:data:`REFILLS` rounds) from the
  ring slots of the motifs kept that no motif fills — §5.4's seeding, restarted;
* on a repeating tile grown unturned, each grown motif is moved to the nearest site of its kind
  in the tile's pattern (:meth:`Growth.on_sites`) before that check: a hand-drawn tile's rings
  are near duplicates, so the best match is often another motif's ring and each front drifts
  off the lattice as a random walk, and fronts meeting out of step left gaps (FGDC 619 and 670
  grew at density 0.77 and 0.67); growth still decides which sites are filled and the kinds,
  and barriers, growth areas and priorities apply as before; on a tile of rows exact along x at
  hand-drawn phases (FGDC 619, 620) the sites are the tile's rows at world phases that wander by
  the tile's own row-to-row steps (:mod:`.phases`), so the texture does not repeat at the period;
* on a repeating tile a last pass fills the gaps that are left with the motifs the placed ones
  predict (:mod:`.gapfill`), the tile's motifs that no whole ring places among them.
* on a drawn exemplar of rows grown unturned, the rows run along world lines (:mod:`.rows`): each
  cell's first seed is put on a line, relaxation holds every motif on its line, and motifs too
  close on one row slide apart along it before the exact check (marsh's rows climbed and met
  out of step at the seams, and a fifth of its grown motifs were removed in conflicts); and
  after a piece has grown, its motifs' kinds are re-chosen against their complete rings, its
  earlier-phase neighbours held (:mod:`.kinds`: each growth step matched only the neighbours
  placed then, and marsh's likeness fell with the distance from the cell's seed), then against
  the exemplar's k-nearest neighbourhoods (:mod:`.neighbourkinds`, ma2011 §3.2), both holding
  the exemplar's kind mix (:func:`.kinds.mix_bounds`).

A cell's motifs are thus a function of the key and the cell alone — not of the region, which
only chooses the cells (with the earlier-phase neighbours they need) and, in
:func:`svgtile.engines.synthesize`, the motifs kept.  Same seed ⇒ same bytes; a far motif never
changes when the region is edited; and the engine is tile-exact with no halo (``reach`` = 0).

The growth area (``--grow-within``) and barriers (``--barrier``) cut each cell into *pieces*;
each piece is grown from its own seed (§5.1: one seed per component), so both sides of a barrier
are filled and growth never crosses one (a seed is made only inside its piece).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import shapely
from scipy.spatial import cKDTree

from svgtile.analysis.stats import periodic_block
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import Conflicts, cross_conflicts, cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.footprint import motif_radius, world_footprints
from svgtile.engines.base import Context
from svgtile.engines.growth import GrowthParams
from svgtile.engines.growth.connectivity import Rings, reference_rings
from svgtile.engines.growth.gapfill import ROUNDS, candidates, predictions
from svgtile.engines.growth.grow import Grown, grow, rings_of
from svgtile.engines.growth.kinds import mix_bounds, repick
from svgtile.engines.growth.neighbourkinds import neighbourhood_kinds
from svgtile.engines.growth.phases import on_rows, row_phases
from svgtile.engines.growth.relax import relax
from svgtile.engines.growth.rows import row_lines, slide_apart
from svgtile.errors import ParameterError

_START, _RING, _NOISE, _PRIORITY = range(4)
#: Rounds of regrowth into the holes the conflict check leaves (see :meth:`Growth.grow_cells`).
REFILLS = 2
#: At most this many cells of a phase are grown in step: enough to share the exact check's fixed
#: cost, few enough that its footprints stay a small part of memory in a run of a million motifs.
IN_STEP = 64


def kind_priority(exemplar: Exemplar, given: dict[str, int]) -> np.ndarray:
    """(k,) int: each kind's priority (§5.1): ``given`` by name, else by footprint area (level
    ``floor(log4(area / smallest area))``: the largest kinds grow first)."""
    names = [k.name for k in exemplar.kinds]
    unknown = [n for n in given if n not in names]
    if unknown:
        raise ParameterError(f"priority: the exemplar has no kind {unknown[0]!r} (its kinds: {', '.join(names)})")
    area = np.array([k.prototype.geometry().area for k in exemplar.kinds]) * np.array(
        [exemplar.motifs.scale[exemplar.motifs.kind == i].mean() ** 2 if (exemplar.motifs.kind == i).any() else 1.0
         for i in range(len(names))])  # fmt: skip
    area = np.maximum(area, 1e-12)
    level = np.floor(np.log(area / area.min()) / np.log(4.0) + 1e-9).astype(np.int64)
    for name, value in given.items():
        level[names.index(name)] = value
    return level


def centre_gaps(exemplar: Exemplar, k: int) -> np.ndarray:
    """(k, k) float: the smallest centre distance between motifs of two kinds in the exemplar
    (periodic for a tile), a little less; ``0`` for pairs it lacks (footprints decide)."""
    motifs = exemplar.motifs
    arr = periodic_block(motifs, exemplar.period) if exemplar.period is not None else motifs
    gap = np.full((k, k), np.inf)
    if len(arr) > 1:
        d, j = cKDTree(arr.xy).query(arr.xy, k=min(len(arr), 24))
        a = np.broadcast_to(arr.kind[:, None], j.shape)[:, 1:]
        b = arr.kind[j[:, 1:]]
        np.minimum.at(gap, (a.ravel(), b.ravel()), d[:, 1:].ravel())
    gap = np.minimum(gap, gap.T)
    return np.where(np.isfinite(gap), gap * 0.98, 0.0)


class Growth:
    """One run: the cells the region needs, grown phase by phase."""

    def __init__(self, ctx: Context, p: GrowthParams) -> None:
        self.ctx, self.p = ctx, p
        ex = ctx.exemplar
        self.ex, self.stats = ex, ctx.stats
        self.rings: Rings = reference_rings(ex)
        self.k = len(ex.kinds)
        flow = ctx.controls.flow
        rotation = p.rotation if p.rotation != "auto" else ("flow" if flow is not None else "none")
        if rotation == "flow" and flow is None:
            raise ParameterError("--rotation flow needs a flow field (--flow MAP.svg#ID)")
        self.rotation = rotation
        self.priority = kind_priority(ex, p.priorities())
        self.gap = centre_gaps(ex, self.k)
        # grown unturned, every motif of a tile belongs on a site of the tile's pattern
        self.snap = p.snap and ex.period is not None and rotation == "none"
        # a tile of rows exact along x: the sites' rows at wandering phases (see .phases)
        self.phases = row_phases(ex, ctx.key, self.stats.distance) if self.snap and p.row_phases else None
        # a repeating tile: what each motif predicts around it is the tile itself (see .gapfill);
        # on rows at wandering phases, its own row's next motifs too (see .phases.reach)
        self.pred = None
        if p.gap_fill and ex.period is not None:
            self.pred = predictions(ex, self.rings, None if self.phases is None else self.phases.reach(self.rings.radius))
        # grown unturned, a drawn exemplar's rows run along world lines (see .rows)
        self.rows = row_lines(ex) if p.rows and rotation == "none" else None
        x0, y0, x1, y1 = ex.region.bounds
        width = max(x1 - x0, y1 - y0, 6.0 * self.rings.mean_length) * p.cell_widths
        if ex.period is not None:
            self.cell = np.array([math.ceil(width / ex.period[0] - 1e-9) * ex.period[0],
                                  math.ceil(width / ex.period[1] - 1e-9) * ex.period[1]])  # fmt: skip
        else:
            self.cell = np.array([width, width])
        self.radius = float(motif_radius(ex.motifs, ex.prototypes).max())
        self.barriers = ctx.controls.barriers
        self.within = ctx.controls.grow_within
        self.cut = None
        if self.barriers is not None:
            self.cut = shapely.buffer(self.barriers, self.rings.short_length / 4)

    # -- cells -------------------------------------------------------------------------------------
    def cells(self) -> list[tuple[int, int]]:
        """The cells to grow: those meeting the region (grown by the motif radius), with the
        earlier-phase neighbours each needs, in phase order."""
        region = self.ctx.region
        domain = shapely.buffer(region.shape, self.radius + float(self.stats.distance.max()))
        if self.within is not None:
            domain = shapely.intersection(domain, shapely.buffer(self.within, self.radius))
        X0, Y0, X1, Y1 = domain.bounds
        if not np.all(np.isfinite([X0, Y0, X1, Y1])):
            return []
        w, h = self.cell
        ia = np.arange(math.floor(X0 / w), math.floor(X1 / w) + 1)
        ib = np.arange(math.floor(Y0 / h), math.floor(Y1 / h) + 1)
        A, B = (v.ravel() for v in np.meshgrid(ia, ib))
        hit = shapely.intersects(shapely.box(A * w, B * h, (A + 1) * w, (B + 1) * h), domain)
        need = {(int(a), int(b)) for a, b in zip(A[hit], B[hit], strict=True)}
        for phase in (3, 2, 1):
            for a, b in [c for c in need if _phase(c) == phase]:
                need |= {(a + da, b + db) for da in (-1, 0, 1) for db in (-1, 0, 1) if _phase((a + da, b + db)) < phase}
        return sorted(need, key=lambda c: (_phase(c), c[1], c[0]))

    def run(self) -> Arrangement:
        order = self.cells()
        self.subs: dict[tuple[int, int], np.ndarray] = {}  # the sub-id (exemplar motif) of each motif
        done: dict[tuple[int, int], Arrangement] = {}
        for phase in range(4):
            cells = [c for c in order if _phase(c) == phase]
            for at in range(0, len(cells), IN_STEP):
                self.ctx.progress("growth", len(done) / len(order))
                step = cells[at : at + IN_STEP]
                for c, (arr, sub) in zip(step, self.grow_cells(step, done), strict=True):
                    done[c], self.subs[c] = arr, sub
        return Arrangement.concat([done[c] for c in order])

    def pieces(self, a: int, b: int) -> list[shapely.Geometry]:
        """The parts of cell ``(a, b)`` growth may fill, split by barriers, inside the growth area."""
        w, h = self.cell
        box = shapely.box(a * w, b * h, (a + 1) * w, (b + 1) * h)
        if self.within is None and self.cut is None:
            return [box]
        shape = box if self.within is None else shapely.intersection(box, self.within)
        if self.cut is not None:
            shape = shapely.difference(shape, self.cut)
        parts = [g for g in shapely.get_parts(shape) if g.area > 0.25 * self.rings.short_length**2]
        return sorted(parts, key=lambda g: g.bounds)

    def start(self, a: int, b: int, part: int, piece: shapely.Geometry) -> tuple[np.ndarray, int]:
        """The piece's initial seed and the reference ring it becomes (§5.1)."""
        ex, rings = self.ex, self.rings
        u = cellrng.uniform(self.ctx.key, _START, a, b, part, np.arange(3))
        r = min(int(u[0] * len(rings)), len(rings) - 1)
        w, h = self.cell
        centre = np.array([(a + 0.5) * w, (b + 0.5) * h]) + (u[1:] - 0.5) * self.rings.mean_length
        if not shapely.contains_xy(piece, *centre):
            centre = np.array(shapely.get_coordinates(shapely.point_on_surface(piece))[0])
        if ex.period is None:
            if self.rows is not None:  # on its row line, so that every cell grows on the same lines
                on = self.rows.onto(centre, rings.element[r : r + 1])[0]
                centre = on if shapely.contains_xy(piece, *on) else centre
            return centre, r
        # a lattice position of the chosen motif near the centre, inside the piece
        pw, ph = ex.period
        base = ex.motifs.xy[rings.element[r]]
        na, nb = np.round((centre - base) / (pw, ph))
        da, db = (v.ravel() for v in np.meshgrid(np.arange(-2, 3), np.arange(-2, 3)))
        cand = base + np.c_[(na + da) * pw, (nb + db) * ph]
        if self.phases is not None:
            cand = self.phases.place(ex, rings.element[r], (na + da).astype(np.int64), (nb + db).astype(np.int64))
        ok = shapely.contains_xy(piece, cand[:, 0], cand[:, 1])
        if ok.any():
            cand = cand[ok]
            return cand[np.argmin(np.hypot(*(cand - centre).T))], r
        return centre, -1

    def grow_cells(self, cells: list[tuple[int, int]],
                   done: dict[tuple[int, int], Arrangement]) -> list[tuple[Arrangement, np.ndarray]]:  # fmt: skip
        """The motifs of ``cells`` (all of one phase), each grown against its earlier-phase
        neighbours in ``done``, and their sub-ids.

        Cells of one phase do not meet and their neighbourhoods are fixed, so each is grown as if
        alone — the same arithmetic, the same motifs — but in step: every cell's growth round,
        then one exact check (:meth:`settle_all`) for all of them, round after round.  A cell
        costs ~50 small numpy/shapely calls a round, most of them in that check; in step, a
        phase pays for them once a round instead of once a cell (benchmarks/README.md).
        """
        work = [self._cell(c, done) for c in cells]
        for part in range(max(len(w.pieces) for w in work)):  # a cell's pieces grow one after another
            jobs = [self._job(w, part) for w in work if part < len(w.pieces)]
            for rnd in range(1 + REFILLS):
                grown = []
                for j in (j for j in jobs if j.live):
                    r = self.grow_round(j, rnd)
                    if r is None:  # nothing grew: the piece is done
                        j.live = False
                    else:
                        grown.append((j, r))
                if not grown:
                    break
                oks = self.settle_all([r[0] for _, r in grown], [r[3] for _, r in grown])
                for (j, (arr, sub, g, fixed)), ok in zip(grown, oks, strict=True):
                    j.kept.append(arr.take(ok))
                    j.ksub.append(sub[ok])
                    if rnd == REFILLS:  # no round left to regrow the holes in
                        j.live = False
                        continue
                    # the holes conflicts left: seeds at the free ring slots of the motifs kept (§5.4)
                    j.more, j.more_kind = self.free_slots(arr.xy[ok], g.ring[ok], g.theta[ok], j.piece,
                                                          Arrangement.concat([fixed, j.kept[-1]]).xy)  # fmt: skip
                    j.live = len(j.more) > 0
            for j in jobs:
                w = j.cell
                if self.rows is not None and self.p.kind_sweeps and j.kept:
                    self.repick_kinds(j)
                if self.pred is not None:
                    self.fill_gaps(j.piece, [w.before, *w.grown], [w.bsub, *w.gsub], j.kept, j.ksub)
                w.grown.extend(j.kept)
                w.gsub.extend(j.ksub)
        return [(Arrangement.concat(w.grown), np.concatenate(w.gsub) if w.gsub else np.zeros(0, np.int64))
                for w in work]  # fmt: skip

    def _cell(self, c: tuple[int, int], done: dict[tuple[int, int], Arrangement]) -> _Cell:
        """Cell ``c``'s fixed surroundings: its earlier-phase neighbours' motifs within reach."""
        a, b = c
        w, h = self.cell
        nb = [(a + da, b + db) for da in (-1, 0, 1) for db in (-1, 0, 1)
              if _phase((a + da, b + db)) < _phase(c) and (a + da, b + db) in done]  # fmt: skip
        before = Arrangement.concat([done[q] for q in nb])
        bsub = np.concatenate([self.subs[q] for q in nb]) if nb else np.zeros(0, np.int64)
        margin = self.rings.radius * 1.2 + 2 * self.radius + float(self.stats.distance.max())
        near = ((before.xy[:, 0] > a * w - margin) & (before.xy[:, 0] < (a + 1) * w + margin)
                & (before.xy[:, 1] > b * h - margin) & (before.xy[:, 1] < (b + 1) * h + margin))  # fmt: skip
        flow = self.flow_table(a, b) if self.rotation == "flow" else None
        return _Cell(c, before.take(near), bsub[near], flow, self.pieces(a, b))

    def _job(self, w: _Cell, part: int) -> _Job:
        """Piece ``part`` of cell ``w``, ready to grow: its seed (§5.1) and tie-breaking draws."""
        a, b = w.c
        piece = w.pieces[part]
        shapely.prepare(piece)
        start, ring0 = self.start(a, b, part, piece)
        # tie-breaking draws: one generator per piece, seeded by a world-anchored hash
        draws = np.random.default_rng(int(cellrng.hash64(self.ctx.key, _NOISE, a, b, part)))
        # its outline is made once for the up to 1 + REFILLS growths of the piece
        return _Job(w, piece, rings_of(piece), start, ring0, draws)

    def grow_round(self, j: _Job, rnd: int) -> tuple[Arrangement, np.ndarray, Grown, Arrangement] | None:
        """Growth round ``rnd`` of piece ``j`` (§5.1, §5.4; relaxed, §5.5): the new motifs, their
        sub-ids, the growth they came from and the fixed motifs they grew against; None if none
        grew.  The exact check is the caller's (:meth:`settle_all`)."""
        rings, p, w = self.rings, self.p, j.cell
        fixed = Arrangement.concat([w.before, *w.grown, *j.kept])
        fsub = np.concatenate([w.bsub, *w.gsub, *j.ksub])

        def relaxer(xy, ring, theta, first):
            return relax(rings, xy, ring, theta, first, rows=self.rows)

        g = grow(rings, j.piece, j.start, j.ring0 if rnd == 0 else -1, fixed_xy=fixed.xy, fixed_kind=fixed.kind,
                 fixed_sub=fsub, more=j.more, more_kind=j.more_kind, rotation=self.rotation, flow=w.flow,
                 priority=self.priority, weights=p.weights, centre_gap=self.gap, draws=j.draws, outline=j.outline,
                 relax=relaxer if p.relaxation and p.relax_every else None, relax_every=p.relax_every)  # fmt: skip
        if not len(g.xy):
            return None
        xy = g.xy
        if p.relaxation and len(xy) > 1:
            held = None
            if self.barriers is not None:  # §5.5 eq. (6): elements at the boundaries stay put
                held = shapely.dwithin(self.barriers, shapely.points(xy), self.radius + rings.short_length)
            xy = relax(rings, np.concatenate([fixed.xy, xy]), g.ring, g.theta, len(fixed), held, rows=self.rows)
        sub = rings.element[g.ring]
        angle = rings.angle[g.ring] + np.degrees(g.theta)
        if self.snap:
            xy, sub = self.on_sites(xy, rings.kind[g.ring])
            angle = self.ex.motifs.angle[sub]
        arr = Arrangement(rings.kind[g.ring], xy, (angle + 180.0) % 360.0 - 180.0, self.ex.motifs.scale[sub])
        if self.rows is not None:  # drawn rows: new motifs in conflict along a row slide apart on it
            arr = slide_apart(arr, fixed, self.ex.prototypes, self.stats.distance, self.rows)
        return arr.quantized(DECIMALS), sub, g, fixed

    def repick_kinds(self, j: _Job) -> None:
        """Piece ``j``'s motifs (``j.kept``) with their kinds re-chosen against their complete
        rings, the cell's earlier motifs and its earlier-phase neighbours' held (:mod:`.kinds`,
        §5.2); a changed motif that fails the exact check (overlap, distance rule, a barrier
        crossed) keeps its old kind, and so do the changes that would then leave a kind's count
        past the passes' bounds (:func:`.kinds.mix_bounds`: what the check keeps back is more
        often a change to a larger footprint, and the mix would drift)."""
        w, ex = j.cell, self.ex
        own, osub = Arrangement.concat(j.kept), np.concatenate(j.ksub)
        if not len(own):  # every motif of the piece was turned down
            return
        fixed = Arrangement.concat([w.before, *w.grown])
        fsub = np.concatenate([w.bsub, *w.gsub])
        f = len(fixed)
        xy, movable = np.concatenate([fixed.xy, own.xy]), np.arange(f + len(own)) >= f
        start = np.concatenate([fixed.kind, own.kind])
        nk = max(int(start.max()) + 1, len(self.stats.frequency))
        _, lo, hi = mix_bounds(start, movable, self.stats.frequency, nk)
        kind, ring = repick(self.rings, xy, start, np.concatenate([fsub, osub]), movable, weights=self.p.weights,
                            sweeps=self.p.kind_sweeps, frequency=self.stats.frequency,
                            then=self.neighbourhood_pass(movable, xy))  # fmt: skip
        kind, ring = kind[f:], ring[f:]
        changed = (kind != own.kind) & (ring >= 0)
        turned = (self.rings.angle[ring] + 180.0) % 360.0 - 180.0
        protos, d = ex.prototypes, self.stats.distance
        while True:
            sub = np.where(changed, self.rings.element[ring], osub)
            cand = Arrangement(np.where(changed, kind, own.kind), own.xy, np.where(changed, turned, own.angle),
                               ex.motifs.scale[sub]).quantized(DECIMALS)  # fmt: skip
            if not changed.any():
                break
            # the motifs were conflict-free: only pairs with a changed one can conflict now
            new = cand.take(changed)
            bad = cross_conflicts(new, Arrangement.concat([fixed, cand.take(~changed)]), protos, d)
            found = find_conflicts(new, protos, d)
            bad[found.i] = bad[found.j] = True
            if self.barriers is not None:  # another kind's footprint may reach across one (§5.5)
                bad |= shapely.intersects(world_footprints(new, protos), self.barriers)
            if bad.any():
                changed[np.flatnonzero(changed)[bad]] = False  # these keep their old kinds; check again
                continue
            # what the check kept back is not even: a change to a larger footprint fails it more
            # often, and the mix the passes held would drift; changes into a kind over its bound
            # (or out of one under it) go back too — not those that bring it back — and the rest
            # is checked again
            count = np.bincount(np.r_[fixed.kind, cand.kind], minlength=len(hi))
            back = changed & ((count[kind] > hi[kind]) | (count[own.kind] < lo[own.kind]))
            if not back.any():
                break
            changed &= ~back
        j.kept, j.ksub = [cand], [sub]

    def neighbourhood_pass(self, movable: np.ndarray, xy: np.ndarray) -> Callable[[np.ndarray], np.ndarray] | None:
        """The pass over kinds that follows the ring pass (:mod:`.neighbourkinds`, ma2011 §3.2): the
        kinds of ``movable`` motifs ((n,) bool) at ``xy`` ((n, 2), user units) re-chosen against the
        exemplar's k-nearest neighbourhoods; None when ``neighbourhood_sweeps`` is 0."""
        if not self.p.neighbourhood_sweeps:
            return None
        m, s, sweeps = self.ex.motifs, self.stats.spacing, self.p.neighbourhood_sweeps
        f = self.stats.frequency
        return lambda kind: neighbourhood_kinds(xy, kind, movable, m.xy, m.kind, s, sweeps=sweeps, frequency=f)

    def flow_table(self, a: int, b: int) -> tuple[np.ndarray, float, float, float]:
        """The flow field's direction (radians) over cell ``(a, b)``, sampled once on a grid of
        spacing r_short (one interpolation per cell instead of one per seed): ``(table, x0, y0,
        step)``, row i and column j at ``(x0 + j·step, y0 + i·step)``; growth reads the nearest."""
        w, h = self.cell
        step = self.rings.short_length / 2
        pad = self.rings.radius * 1.5
        x0, y0 = a * w - pad, b * h - pad
        nx, ny = int(np.ceil((w + 2 * pad) / step)) + 1, int(np.ceil((h + 2 * pad) / step)) + 1
        gx, gy = np.meshgrid(x0 + np.arange(nx) * step, y0 + np.arange(ny) * step)
        table = np.radians(self.ctx.controls.flow.angle(np.c_[gx.ravel(), gy.ravel()])).reshape(ny, nx)
        return table, float(x0), float(y0), float(step)

    def free_slots(self, xy: np.ndarray, ring: np.ndarray, theta: np.ndarray, piece: shapely.Geometry,
                   placed: np.ndarray) -> tuple[np.ndarray, np.ndarray]:  # fmt: skip
        """Seeds at the ring slots of motifs ``xy`` that no motif of ``placed`` fills (within
        r_short), inside ``piece``: (s, 2) positions and (s,) kinds."""
        rings = self.rings
        if not len(xy):
            return np.zeros((0, 2)), np.zeros(0, np.int64)
        valid = np.arange(rings.rel.shape[1])[None, :] < rings.size[ring][:, None]
        c, s = np.cos(theta)[:, None], np.sin(theta)[:, None]
        v = rings.rel[ring]
        pos = xy[:, None] + np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)
        pos, kind = pos[valid], rings.nkind[ring][valid]
        d, _ = cKDTree(placed).query(pos)
        free = (d >= rings.short_length / 2) & shapely.contains_xy(piece, pos[:, 0], pos[:, 1])
        return pos[free], kind[free]

    def on_sites(self, xy: np.ndarray, kind: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each grown position moved to the nearest site of its kind in the tile's pattern (the
        tile repeated from the world origin, or its rows at their world phases, :mod:`.phases`):
        (n, 2) positions and (n,) the exemplar motifs
        (sub-ids) they now copy.

        Parameters
        ----------
        xy : (n, 2) float array, user units
        kind : (n,) int array
        """
        if self.phases is not None:
            return self.phases.sites(self.ex, xy, kind)
        motifs = self.ex.motifs
        period = np.asarray(self.ex.period, float)
        out, sub = np.array(xy, float), np.zeros(len(xy), np.int64)
        for k in np.unique(kind):  # (n_k, m_k) candidate sites: the kind's tile motifs, whole periods away
            i, s = np.flatnonzero(kind == k), np.flatnonzero(motifs.kind == k)
            site = motifs.xy[s][None] + np.round((xy[i, None] - motifs.xy[s][None]) / period) * period
            best = np.argmin(np.hypot(*(site - xy[i, None]).transpose(2, 0, 1)), axis=1)
            out[i], sub[i] = site[np.arange(len(i)), best], s[best]
        return out, sub

    def fill_gaps(self, piece: shapely.Geometry, fixed: list[Arrangement], fsub: list[np.ndarray],
                  kept: list[Arrangement], ksub: list[np.ndarray]) -> None:  # fmt: skip
        """Add to ``kept``/``ksub`` (this piece's motifs and sub-ids) the motifs that placed ones
        predict inside ``piece`` and that break no rule (:mod:`.gapfill`), round by round."""
        r_short = self.rings.short_length / 2
        for _ in range(ROUNDS):
            placed = Arrangement.concat([*fixed, *kept])
            psub = np.concatenate([*fsub, *ksub]) if len(placed) else np.zeros(0, np.int64)
            if not len(placed):
                return
            cand, csub, support = candidates(self.pred, self.ex, placed, psub)
            if self.phases is not None:  # the tile's predictions, moved onto the world rows' sites
                cand, csub, support = on_rows(self.phases, self.ex, cand, support)
            use = shapely.contains_xy(piece, cand.xy[:, 0], cand.xy[:, 1])
            use[use] = cKDTree(placed.xy).query(cand.xy[use])[0] >= r_short
            if not use.any():
                return
            cand, csub, support = cand.take(use), csub[use], support[use]
            ok = self.settle(cand, placed, support)
            if not ok.any():
                return
            kept.append(cand.take(ok))
            ksub.append(csub[ok])

    def settle(self, new: Arrangement, before: Arrangement, support: np.ndarray | None = None) -> np.ndarray:
        """(n,) bool: the motifs of ``new`` that stay — no overlap, no distance-rule violation, no
        barrier crossed, checked on footprints against each other and ``before`` (which stay).
        Among conflicting new motifs those with more ``support`` ((n,) int, optional) stay first."""
        return self.settle_all([new], [before], None if support is None else [support])[0]

    def settle_all(self, news: list[Arrangement], befores: list[Arrangement],
                   supports: list[np.ndarray] | None = None) -> list[np.ndarray]:  # fmt: skip
        """:meth:`settle` of several independent checks at once (one per piece of cells that do
        not meet): ``news[i]`` against itself and ``befores[i]`` alone, the same outcome as one
        call each — pairs of two checks are never tested, and each check is culled on its own —
        at the cost of one."""
        protos, d = self.ex.prototypes, self.stats.distance
        sizes = [len(x) for x in news]
        new = Arrangement.concat(news)
        group = np.repeat(np.arange(len(news)), sizes)
        ok = np.ones(len(new), bool)
        if len(new):
            if self.barriers is not None:
                ok &= ~shapely.intersects(world_footprints(new, protos), self.barriers)
            if self.within is not None:
                ok &= shapely.contains_xy(self.within, new.xy[:, 0], new.xy[:, 1])
            before = Arrangement.concat(befores)
            if len(before):
                bgroup = np.repeat(np.arange(len(befores)), [len(x) for x in befores])
                ok[ok] = ~cross_conflicts(new.take(ok), before, protos, d, groups=(group[ok], bgroup))
            sel = np.flatnonzero(ok)
            sub = new.take(sel)
            grid = np.round(sub.xy * 16).astype(np.int64)
            prio = cellrng.uniform(self.ctx.key, _PRIORITY, grid[:, 0], grid[:, 1])
            if supports is not None:
                prio = prio - np.concatenate(supports)[sel]
            found = find_conflicts(sub, protos, d)
            check = group[sel]  # (s,) the check each motif belongs to
            same = check[found.i] == check[found.j]  # pairs of two checks are not this run's to find
            found = Conflicts(found.i[same], found.j[same], found.overlap[same], found.violation[same])
            violator = np.zeros(len(sub))
            side = found.violation & ~found.overlap
            violator[found.i[side]] = violator[found.j[side]] = 1.0
            # culled check by check: cull ranks the priorities of all the motifs it is given
            at = np.searchsorted(check, np.arange(len(news) + 1))
            order = np.argsort(check[found.i], kind="stable")
            pair_at = np.searchsorted(check[found.i][order], np.arange(len(news) + 1))
            for q in range(len(news)):
                lo, hi = at[q], at[q + 1]
                mine = order[pair_at[q] : pair_at[q + 1]]
                part = Conflicts(found.i[mine] - lo, found.j[mine] - lo, found.overlap[mine], found.violation[mine])
                ok[sel[lo:hi]] = cull(hi - lo, part, prio[lo:hi], violator[lo:hi])
        return np.split(ok, np.cumsum(sizes)[:-1])


@dataclass(eq=False)
class _Cell:
    """A cell in growth: its earlier-phase neighbours' motifs within reach (and their sub-ids),
    its flow table, its pieces, and the motifs of the pieces grown so far."""

    c: tuple[int, int]
    before: Arrangement
    bsub: np.ndarray
    flow: tuple[np.ndarray, float, float, float] | None
    pieces: list[shapely.Geometry]
    grown: list[Arrangement] = field(default_factory=list)
    gsub: list[np.ndarray] = field(default_factory=list)


@dataclass(eq=False)
class _Job:
    """A piece of a cell in growth: what its rounds carry from one to the next — the motifs kept,
    the seeds of the next round (``more``, ``more_kind``) and whether there is one (``live``)."""

    cell: _Cell
    piece: shapely.Geometry
    outline: tuple[np.ndarray, np.ndarray]
    start: np.ndarray
    ring0: int
    draws: np.random.Generator
    kept: list[Arrangement] = field(default_factory=list)
    ksub: list[np.ndarray] = field(default_factory=list)
    more: np.ndarray | None = None
    more_kind: np.ndarray | None = None
    live: bool = True


def _phase(c: tuple[int, int]) -> int:
    return (c[0] & 1) + 2 * (c[1] & 1)
