"""The initialisation of Ma, Wei & Tong 2011 §4.1: exemplar patches of the neighbourhood's size.

The plane is cut into world-anchored square cells of side ``c`` (a few exemplar spacings, the
neighbourhood's extent).  Cell ``(a, b)`` receives the exemplar's motifs from a window of side
``c(1 + σ)`` centred at a point of the exemplar drawn by a hash of the run's key and ``(a, b)``,
translated onto the cell's centre.  Where neighbouring patches meet, overlapping or rule-breaking pairs are culled
(:func:`svgtile.core.conflicts.cull`), the motif farther from its own cell's centre leaving
first.  Every choice depends on the cell and its neighbours only, so the start at a place does
not depend on how far the region extends — and neither, after a few local iterations, does the
optimised texture (the engine contract's edit stability).

A repeating tile of an exact lattice is the exception (:func:`seamless`, :func:`period_start`;
as patch's copies on the period, :mod:`svgtile.engines.choose`'s ``tile-order``): its copies on
its own period meet without seams — the tile's pairs across its edges are its own — so the start is the tile
repeated, nothing is culled and the solver, which keeps the element count (§4), keeps the
tile's density.  Patches drawn from random places of the tile met at seams that lost about a
fifth of the motifs to culling (Equinor: density / ρ 0.74–0.84 on every tile).  Any other
tile keeps the patches: repeated whole it would repeat at its period, and the solver inserts
what the seams lost (:mod:`.insert`).

A repeating tile of an inexact lattice — rows of dashes whose positions along the row wander
(FGDC 616–621; 14 FGDC tiles and Equinor 50090 in all) — keeps its patches, but their phases are
drawn on its lattice (:func:`lattice_steps`): each patch is still cut from a place of the tile
drawn by the hash, but moved by at most half a step along each lattice direction so that it
stands a whole number of steps from every other patch — steps solved so that the tile's period
is a whole number of them where the motifs stand on those as well (:data:`FIT_PERIOD`; the
analysis's averaged steps do not fit it: on FGDC 619 the step across the rows reads 2.99–3.00
units for a true 2.977, on 620 the step along the rows 8.77 for 8.93).  Rows then
run on across every seam; drawn at free phases, the rows of two neighbouring patches met at a
seam at different heights, their dashes' ends broke the distance rule and one row in two lost
its dash there — a gap shorter than a dash, which insertion cannot refill.
"""

from __future__ import annotations

import math

import numpy as np

from svgtile.analysis.order import EXACT_STEP, SUPPORT, exact_support, is_period, read_order
from svgtile.analysis.stats import Stats, footprint_areas
from svgtile.core import cellrng
from svgtile.core.arrangement import DECIMALS, Arrangement
from svgtile.core.conflicts import cull, find_conflicts
from svgtile.core.exemplar import Exemplar
from svgtile.core.flow import FlowField
from svgtile.core.footprint import motif_radius, rotation
from svgtile.core.region import Region
from svgtile.engines.windows import square_area, square_windows

#: Weight of a motif's footprint area (over the largest) against its distance from its cell's
#: centre (over the cell side, ≤ ~0.6) in which of two conflicting start motifs leaves, when
#: the smaller go first (``patch_start(refill=True)``).
SIZE = 1.0

#: Whether the start's patches on a refilled repeating tile of lattice order stand a whole
#: number of lattice steps apart (:func:`lattice_steps`; the module notes).  FGDC's 90 tiles
#: (benchmarks/optimize_sets.py, 2 × 2 tiles, seed 1): density / ρ 617 0.896 → 0.94, 619 0.88 →
#: 0.96, 620 0.84 → 0.88, 621 0.89 → 0.93; density in bounds 83 → 86, every bound met 39 → 41
#: (benchmarks/README.md, opt14h).  Measured where the rows lose motifs: the band of a tenth of
#: the cell along the seams held 0.66–0.83 of ρ on 617, 619, 620, 621 (the cell's middle
#: 0.9–1.1); most bins insertion was asked to fill broke the distance rule only (620: 64–69 of
#: about 80 a pass), and tried again up to 0.75 spacings away they gave 620 0.01 of ρ.
LATTICE_PHASES = True
#: Whether :func:`lattice_steps` gives the steps that fit the tile's period — the period
#: ``(W, 0)``, ``(0, H)`` as the nearest whole combination ``N`` of the steps read by
#: :func:`~svgtile.analysis.order.read_order`, the steps then ``N⁻¹ · diag(W, H)`` — rather than
#: the steps as read, averaged over motifs that wander about their sites (FGDC 620: along the rows
#: 8.77 units for the 53.584 / 6 = 8.93 of its six dashes a row, alternate rows 4.18 / 4.59 apart
#: for 4.47 / 4.47; a patch a few steps from the next met it up to a dash's gap off, and the seams
#: across the rows lost a dash in two rows).  Taken where the tile's motifs stand on the fitted
#: steps at least as often as on the read ones (:func:`~svgtile.analysis.order.exact_support`,
#: summed over both): elsewhere the read lattice is not one the period fits, its nearest whole
#: combination another lattice (FGDC 663, fitted regardless: repetition 0.14 → 0.21); a tie (none
#: of the motifs on either, on tiles whose motifs wander) takes the fitted steps.  The fitted steps
#: pass the read ones' tests too (neither the period, a cell of :data:`MIN_CELL_MOTIFS`): a
#: period's own support is always whole, so a lattice solved onto the period would win.  FGDC's 90
#: tiles (2 × 2 tiles, seed 1; benchmarks/README.md, opt14i), 9 of them fitted: every bound met
#: 42 → 44 (620 density / ρ 0.88 → 0.92, L 0.89 → 0.97; 664 repetition 0.204 → 0.19), L ≥ 0.85
#: 46 → 46, no bound lost on any tile.
FIT_PERIOD = True
#: A lattice whose cell holds fewer motifs than this is not the lattice the motifs stand on (a
#: short step between the marks of a pair or a cluster): :func:`lattice_steps` gives none.
#: FGDC 672 (0.36 motifs a cell, a step of 0.22 spacings) snapped to it: repetition 0.14 →
#: 0.23, density / ρ 0.94 → 0.89; 680 (0.47): density 1.01 → 1.04.
MIN_CELL_MOTIFS = 0.5

_SOURCE = 72  # hash streams: where each cell's patch comes from, and culling ties
_TIE = 73
_THIN = 74


def patch_start(exemplar: Exemplar, stats: Stats, region: Region, boundary: str, *, key: int,
                cell: float, overlap: float, flow: FlowField | None = None, refill: bool = False,
                by_count: bool = False, sources: bool = False) -> Arrangement | tuple[Arrangement, np.ndarray]:  # fmt: skip
    """Exemplar patches on world-anchored cells over ``region``, conflicts culled (§4.1).

    Parameters
    ----------
    exemplar, stats : the exemplar and its analysis
    region, boundary : the output region and how its edge is treated
    key : the run's key
    cell : c, the cell side, user units
    overlap : σ ≥ 0, how far each patch's window reaches past its cell, as a fraction of ``c``
    flow : a flow field, or None; each patch is then turned by the field's angle at its cell's
        centre (§5, eq. (7)), motifs with it
    refill : whether insertion refills this start's holes (:mod:`.insert`).  Then, of two
        conflicting motifs at a seam, the smaller leaves first (by :data:`SIZE`): small motifs
        fit the holes, large ones rarely do, and culling by position alone lost the large kinds
        (FGDC 605: 91 of 128 clasts, every dot; 613: 35 of 52 bars) and with them a fifth of
        the density.  (The thinning that follows is left as it is: thinned by size too, a tile
        of discs and dots kept 34 % discs for the exemplar's 25 %; counting only the motifs
        whose centroid lies in the region, FGDC 612's L fell 0.77 → 0.64 for no density.)
        And on a tile of lattice order, not turned by a flow field, the patches' phases are
        drawn on its lattice (:func:`lattice_steps`, the module notes).
    by_count : whether the start is thinned to the exemplar's motifs per unit area, not its
        covered fraction ρ (:func:`thin`): for a start whose kind mix the solver brings back to
        the exemplar's (``Settings.rebalance``), which then brings its cover to ρ as well
    sources : whether to return, with the start, where each of its motifs was copied from

    Returns
    -------
    Arrangement with no conflicts, kept by the boundary mode; with ``sources``, also (n,) int,
    the index of the exemplar motif each of its motifs is a copy of (the first search's seeds,
    :func:`.solver.refine`'s ``first``).
    """
    motifs, protos = exemplar.motifs, exemplar.prototypes
    period = getattr(exemplar, "period", None)
    if seamless(exemplar, flow):
        return period_start(exemplar, stats, region, boundary, sources=sources)
    x0, y0, x1, y1 = exemplar.region.bounds
    win = cell * (1.0 + overlap)
    pts, src = motifs.xy, np.arange(len(motifs))
    if period is not None:
        reps = max(1, math.ceil(win / min(period)))
        sh = np.array([(i, j) for i in range(-reps, reps + 1) for j in range(-reps, reps + 1)], float) * period
        pts = (motifs.xy[None] + sh[:, None]).reshape(-1, 2)
        src = np.tile(src, len(sh))
        lo, hi = np.array([x0, y0]), np.array([x0, y0]) + period
    else:
        half = np.minimum(win / 2, np.array([x1 - x0, y1 - y0]) / 2)
        lo, hi = np.array([x0, y0]) + half, np.array([x1, y1]) - half
    r = float(motif_radius(motifs, protos).max())
    X0, Y0, X1, Y1 = region.bounds
    a = np.arange(math.floor((X0 - r) / cell), math.floor((X1 + r) / cell) + 1)
    b = np.arange(math.floor((Y0 - r) / cell), math.floor((Y1 + r) / cell) + 1)
    A, B = (v.ravel() for v in np.meshgrid(a, b))
    centre = (np.stack([A, B], -1) + 0.5) * cell
    u = np.stack([cellrng.uniform(key, _SOURCE, A, B, 0), cellrng.uniform(key, _SOURCE, A, B, 1)], -1)
    source = lo + u * (hi - lo)  # (c, 2) window centres in the exemplar
    steps = lattice_steps(exemplar) if refill and period is not None and flow is None else None
    if steps is not None:
        # each patch moved by less than a lattice cell, to a whole number of steps from every other
        off = centre - source
        source = centre - np.rint(off @ np.linalg.inv(steps)) @ steps
    # every motif of every window: (cells × motifs) masks, a cell's row at a time is small
    inside = (np.abs(pts[None, :, :] - source[:, None, :]) < win / 2).all(axis=-1)
    ci, mi = np.nonzero(inside)
    e = src[mi]
    if flow is None:
        xy, angle = pts[mi] - source[ci] + centre[ci], motifs.angle[e]
    else:
        theta = flow.angle(centre)
        xy = np.einsum("nij,nj->ni", rotation(theta[ci]), pts[mi] - source[ci]) + centre[ci]
        angle = (motifs.angle[e] + theta[ci] + 180.0) % 360.0 - 180.0
    arr = Arrangement(motifs.kind[e], xy, angle, motifs.scale[e]).quantized(DECIMALS)
    near = region.keep(arr, protos, boundary)
    arr, ci, e = arr.take(near), ci[near], e[near]
    # the motif farther from its own cell's centre leaves first; ties by a hash of its cell and
    # source; with refill, the smaller motif leaves first unless they are of like size
    off = np.abs(arr.xy - centre[ci]).max(axis=1) / cell
    tie = cellrng.uniform(key, _TIE, A[ci], B[ci], e)
    priority = off + 1e-3 * tie
    if refill:
        area = footprint_areas(arr, protos)
        priority -= SIZE * area / max(float(area.max(initial=0.0)), 1e-12)
    keep = cull(len(arr), find_conflicts(arr, protos, stats.distance), priority)
    arr, e = arr.take(keep), e[keep]
    kept = thin(arr, exemplar, stats, region, key=key, window=2 * cell, by_count=by_count)
    return (arr.take(kept), e[kept]) if sources else arr.take(kept)


def lattice_steps(exemplar: Exemplar) -> np.ndarray | None:
    """The lattice on which :func:`patch_start` draws its patches' phases on a repeating tile
    (§4.1's patches, cut where the hash says but whole lattice steps apart).

    Returns
    -------
    (2, 2) float, user units, rows the two steps of the tile's lattice order
    (:func:`~svgtile.analysis.order.read_order`), neither of them its period and its cell
    holding at least :data:`MIN_CELL_MOTIFS` motifs, solved to fit the period (:data:`FIT_PERIOD`:
    whole steps apart is then whole steps apart at every seam, not a fraction of a dash off);
    None where there is no such lattice (or :data:`LATTICE_PHASES` is off).
    """
    if not LATTICE_PHASES:
        return None
    period = getattr(exemplar, "period", None)
    if period is None:
        return None
    order = read_order(exemplar)
    if order.kind != "lattice" or len(order.steps) < 2:
        return None
    tol = EXACT_STEP * math.sqrt(exemplar.region.area / len(exemplar.motifs))
    steps = np.array([st.vector for st in order.steps[:2]], dtype=np.float64)

    def usable(lat: np.ndarray) -> bool:
        # neither step the period, and a cell of at least MIN_CELL_MOTIFS motifs (a lattice whose
        # cell holds fewer is not the one they stand on)
        area = abs(float(np.linalg.det(lat)))
        if any(is_period(g, period, tol) for g in lat) or area < 1e-9:
            return False
        return len(exemplar.motifs) * area / (period[0] * period[1]) >= MIN_CELL_MOTIFS

    if not usable(steps):
        return None
    if not FIT_PERIOD:
        return steps
    # the tile repeats at its period, so the period is a whole number of steps of the lattice its
    # motifs stand on: the steps solved from the nearest whole combination — where the motifs
    # stand on them at least as often as on the steps as read (else the read lattice is not one
    # the period fits, and the nearest whole combination is another lattice)
    per = np.diag(np.asarray(period, dtype=np.float64))
    whole = np.rint(per @ np.linalg.inv(steps))
    if abs(float(np.linalg.det(whole))) < 0.5:
        return steps
    fitted = np.linalg.solve(whole, per)
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    support = [sum(exact_support(xy, kind, period, g, tol) for g in lat) for lat in (steps, fitted)]
    # the fitted lattice passes the read one's tests too (a period's own support is always whole)
    return fitted if support[1] >= support[0] and usable(fitted) else steps


def seamless(exemplar: Exemplar, flow: FlowField | None = None) -> bool:
    """Whether the start is the tile itself (:func:`period_start`): a repeating tile whose motifs
    stand on an exact lattice (two steps, neither the tile's period, each met by a same-kind
    motif within :data:`~svgtile.analysis.order.EXACT_STEP` spacings for
    :data:`~svgtile.analysis.order.SUPPORT` of them), not turned by a flow field.

    Only there is the tile's period a step of the pattern's own order; the tile of irregular
    content, or of rows at a free phase, repeated whole repeats at its period (FGDC 610, 611,
    616, 617, Equinor 11030: repetition 0.5–0.6), so it starts from patches.  The rule is
    :func:`svgtile.metrics.order.order_steps`'s, which the repetition figure leaves out.
    """
    period = getattr(exemplar, "period", None)
    if period is None or flow is not None:
        return False
    order = read_order(exemplar)
    if order.kind != "lattice" or len(order.steps) < 2:
        return False
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    tol = EXACT_STEP * math.sqrt(exemplar.region.area / len(xy))
    for step in order.steps[:2]:
        g = np.asarray(step.vector, dtype=np.float64)
        if is_period(g, period, tol):
            return False  # the period itself: every tile "repeats" at it
        if exact_support(xy, kind, period, g, tol) < SUPPORT:
            return False
    return True


def period_start(exemplar: Exemplar, stats: Stats, region: Region, boundary: str, *,
                 sources: bool = False) -> Arrangement | tuple[Arrangement, np.ndarray]:  # fmt: skip
    """The repeating tile on its own period over ``region`` (§4.1's patches, seamless).

    Copy ``(a, b)`` of the exemplar's motifs is translated by ``(a·W, b·H)``, ``(W, H)`` the
    tile's period, user units, so the texture at a place is the tile's at that place modulo the
    period, whatever the region (world-anchored, as the cells of :func:`patch_start` are).  The
    tile's own pairs across its edges are the only pairs across the copies' seams; a pair there
    that breaks a rule (a tile drawn with a motif too close to its own copy) is culled, the
    motif of the later copy leaving.

    Returns
    -------
    Arrangement with no conflicts, kept by the boundary mode; with ``sources``, also (n,) int,
    the exemplar motif each motif is a copy of (as :func:`patch_start`).
    """
    motifs, protos = exemplar.motifs, exemplar.prototypes
    w, h = exemplar.period
    r = float(motif_radius(motifs, protos).max())
    X0, Y0, X1, Y1 = region.bounds
    ex, ey = motifs.xy[:, 0], motifs.xy[:, 1]
    i = np.arange(math.floor((X0 - r - ex.max()) / w), math.ceil((X1 + r - ex.min()) / w) + 1)
    j = np.arange(math.floor((Y0 - r - ey.max()) / h), math.ceil((Y1 + r - ey.min()) / h) + 1)
    A, B = (v.ravel() for v in np.meshgrid(i, j))
    m = len(motifs)
    xy = (motifs.xy[None] + (np.stack([A * w, B * h], -1))[:, None]).reshape(-1, 2)
    arr = Arrangement(np.tile(motifs.kind, len(A)), xy, np.tile(motifs.angle, len(A)),
                      np.tile(motifs.scale, len(A))).quantized(DECIMALS)  # fmt: skip
    near = region.keep(arr, protos, boundary)
    arr = arr.take(near)
    # the later copy's motif leaves: (row of copies, copy in the row, motif), all world-anchored
    order = (np.repeat(B * (i.max() - i.min() + 1) + A, m) * m + np.tile(np.arange(m), len(A)))[near]
    keep = cull(len(arr), find_conflicts(arr, protos, stats.distance), order.astype(np.float64))
    return (arr.take(keep), np.tile(np.arange(m), len(A))[near][keep]) if sources else arr.take(keep)


def thin(arr: Arrangement, exemplar: Exemplar, stats: Stats, region: Region, *, key: int,
         window: float, by_count: bool = False) -> np.ndarray:  # fmt: skip
    """(n,) bool: motifs kept so that no world-anchored window covers more than ρ of its area
    (``by_count``: holds more than the exemplar's motifs per unit area, times its area).

    Patches overlap by σ so that their seams, once culled, are not sparser than the exemplar;
    where they are denser, motifs leave in the order of a hash of the run's key and their
    position until the window's footprint area is ρ times its area in the region (§3.4 of
    almeraj2013's density, by removal only).

    Parameters
    ----------
    window : side of the windows, user units
    by_count : count the motifs, not their footprint areas.  The windows of a drawn exemplar
        take its middle more often than its edges (:func:`patch_start`), so a start whose
        exemplar holds its kinds unevenly is off its kind mix (gravel: 28 % round pebbles for
        40 %); thinned by area to ρ and its mix then brought back, its cover is the wrong one
        (scrub: density / ρ 0.89–0.94), thinned by count it is ρ once the mix is (0.98–1.02).
    """
    n = len(arr)
    if n == 0:
        return np.zeros(0, dtype=bool)
    ids, which = square_windows(arr.xy, window)
    inside = square_area(ids, window, region)
    if by_count:
        target, area = inside * len(exemplar.motifs) / exemplar.region.area, np.ones(n)
    else:
        target, area = stats.density * inside, footprint_areas(arr, exemplar.prototypes)
    q = np.round(arr.xy * 1e3).astype(np.int64)
    priority = cellrng.uniform(key, _THIN, q[:, 0], q[:, 1])
    order = np.lexsort((-priority, which))  # by window, highest priority first
    w, a = which[order], area[order]
    start = np.r_[0, np.flatnonzero(np.diff(w)) + 1]
    before = np.cumsum(a) - a  # area removed before this one, if all before it leave
    before -= np.repeat(before[start], np.diff(np.r_[start, n]))
    total = np.bincount(which, weights=area, minlength=len(ids))
    leave = total[w] - before > target[w]
    keep = np.ones(n, dtype=bool)
    keep[order[leave]] = False
    return keep
