"""The exemplar's order: rows, lattices, anisotropy, clustering and banding.

AlMeraj et al. 2013 (§3.1–3.5) reproduce what an exemplar's motifs keep *apart* (``d_ij``), how
much they cover (ρ) and how they turn (arcs); they say nothing of how motifs line up.  Symbol
sets drawn by cartographers are often ordered: tufts in offset rows, dashes in courses, dots on a
lattice, strata in bands.  An engine that does not know it breaks that order (copies turned by θ
make rows climb, copies at an arbitrary step show seams in a lattice).  This module reads the
order from the motif centres so that engines and their defaults can follow it
(:mod:`svgtile.engines.choose`):

* **dominant neighbour vectors** — the displacement vectors from each motif to its ``k`` nearest
  neighbours *of its own kind*, folded to one half-plane (``v`` and ``−v`` are one vector), whose
  modes are the steps by which the pattern repeats (Ma, Wei & Tong 2011 §3.2 compare exactly these neighbourhoods);
  a vector's *support* is the share of motifs that have a neighbour at ``±v``;
* **rows** — one supported vector (the step along a row), **lattice** — two non-parallel ones;
* **period** — a pattern tile's own repeat (``exemplar.period``), where there is one;
* **anisotropy** — of the nearest-neighbour directions (the orientation tensor of unit vectors,
  doubled angles so that ``v`` and ``−v`` agree): 0 isotropic, 1 every neighbour on one line;
* **clustering** — Clark & Evans' ratio R of the mean nearest-neighbour distance to a Poisson
  field's at the same density: < 1 clustered, 1 random, > 1 regular (2.15 a hexagonal lattice);
* **banding** — how unevenly motifs fill strips across the row direction (y when there are no
  rows), beyond what chance gives; and how the kind mix changes from strip to strip.

For a pattern tile the neighbours are found across the tile's edges (the 3 × 3 block of tiles,
as :func:`svgtile.analysis.stats.periodic_distance_matrix` does).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from svgtile.core.exemplar import Exemplar

#: Neighbours per motif whose displacements are pooled to find the dominant vectors.
NEIGHBOURS = 6
#: Two displacements within this share of the mean spacing are the same step.
STEP_TOLERANCE = 0.2
#: A step is a row (or lattice) step when at least this share of the motifs has a neighbour there.
SUPPORT = 0.6
#: A second lattice step differs from the first by at least this many degrees.
NOT_PARALLEL = 20.0
#: A step is *exact* when its same-kind partners lie within this many mean spacings of it — half
#: a bin of the repetition figure (0.1 spacings).  Beyond the nearest neighbours only exact steps
#: are trusted (:func:`symmetry_steps`), so a hand-jittered tile's far displacements and chance
#: matches make no step; the repetition figure leaves out only exact steps
#: (:mod:`svgtile.metrics.order`), and optimize starts from the tile itself only on an exact
#: lattice (:func:`svgtile.engines.optimize.init.seamless`).
EXACT_STEP = 0.05
#: Most cells along a side of the displacement histogram that bounds a candidate step's support
#: (:func:`_support_bound`): cells of the step's tolerance, wider where the tile is large.
_BOUND_CELLS = 1024
#: Strips across the row direction are this many mean spacings wide (banding).
STRIP = 1.0
#: Fewest motifs for an order to be read; below this the figures are empty (NaN, no steps).
MIN_MOTIFS = 3
#: Fewest motifs of a drawn (not repeating) exemplar in which rows or a lattice are called: a
#: handful of points always has a "step" most of them share.  A pattern tile's motifs meet
#: their own repeats, so its order is read from one motif up.
MIN_ORDERED = 12


@dataclass(frozen=True)
class Step:
    """One dominant neighbour vector.

    Attributes
    ----------
    vector : (2,) tuple of float, user units; folded to angles in [0°, 180°)
    support : share of the motifs with a neighbour at ``±vector`` (within :data:`STEP_TOLERANCE`)
    spread : root-mean-square distance of those neighbours from ``±vector``, user units: 0 for a
        pattern drawn on an exact lattice, larger for a hand-jittered one
    """

    vector: tuple[float, float]
    support: float
    spread: float = 0.0

    @property
    def length(self) -> float:
        return math.hypot(*self.vector)

    @property
    def angle(self) -> float:
        """Direction in degrees, [0, 180)."""
        return math.degrees(math.atan2(self.vector[1], self.vector[0])) % 180.0


@dataclass(frozen=True)
class Order:
    """What :func:`read_order` finds in an exemplar.

    Attributes
    ----------
    spacing : mean spacing of the motifs, ``1/√λ``, user units
    steps : up to two dominant neighbour vectors, most supported first
    kind : ``"lattice"`` (two supported steps), ``"rows"`` (one) or ``"scatter"`` (none)
    period : (w, h) user units of a repeating tile, or None
    anisotropy : float in [0, 1]; 0 when the nearest neighbours lie in every direction alike
    anisotropy_angle : degrees in [0, 180), the direction most nearest neighbours lie along
    clustering : Clark–Evans R (dimensionless), NaN below :data:`MIN_MOTIFS` (a pattern tile
        needs one motif: its neighbours are its repeats)
    banding : float ≥ 0, the coefficient of variation of motif counts over strips across the
        row direction, less the one of a Poisson field with the same mean count (0 = no bands)
    kind_banding : float in [0, 1], mean total-variation distance of each strip's kind mix from
        the whole exemplar's, less that of the same strips with kinds shuffled (0 = kinds mixed)
    band_angle : degrees, the direction of the strips (the rows', or 0 for horizontal)
    """

    spacing: float
    steps: tuple[Step, ...]
    kind: str
    period: tuple[float, float] | None
    anisotropy: float
    anisotropy_angle: float
    clustering: float
    banding: float
    kind_banding: float
    band_angle: float

    @property
    def rows_horizontal(self) -> bool:
        """Rows (or a lattice step) run within 5° of the page's x axis."""
        return bool(self.steps) and self.steps[0].angle in _near_zero(5.0)

    def lattice_vectors(self) -> np.ndarray:
        """(2, 2) float array, user units: the lattice's two steps (rows: the row step and its
        normal of length 0, which callers must not use as a step)."""
        out = np.zeros((2, 2))
        for i, s in enumerate(self.steps[:2]):
            out[i] = s.vector
        return out

    def to_dict(self) -> dict:
        return {
            "kind": self.kind,
            "spacing": self.spacing,
            "steps": [{"vector": list(s.vector), "length": s.length, "angle": s.angle, "support": s.support,
                       "spread": s.spread}
                      for s in self.steps],
            "period": None if self.period is None else list(self.period),
            "anisotropy": self.anisotropy,
            "anisotropy_angle": self.anisotropy_angle,
            "clustering": self.clustering,
            "banding": self.banding,
            "kind_banding": self.kind_banding,
            "band_angle": self.band_angle,
        }


class _near_zero:
    """Angles in degrees within ``tol`` of 0 modulo 180 (``a in _near_zero(5)``)."""

    def __init__(self, tol: float) -> None:
        self.tol = tol

    def __contains__(self, a: float) -> bool:
        a = a % 180.0
        return min(a, 180.0 - a) <= self.tol


def read_order(exemplar: Exemplar) -> Order:
    """Read the order of ``exemplar``'s motif centres (see the module docstring).

    Deterministic: no randomness (the kind-banding baseline shuffles with a fixed permutation
    derived from the motif count, not from a generator the caller shares).
    """
    xy = exemplar.motifs.xy
    kind = exemplar.motifs.kind
    n = len(xy)
    period = getattr(exemplar, "period", None)
    area = exemplar.region.area
    spacing = math.sqrt(area / n) if n else math.inf
    if n < (1 if period is not None else MIN_MOTIFS):
        return Order(spacing, (), "scatter", period, 0.0, 0.0, math.nan, 0.0, 0.0, 0.0)

    vectors, nearest = neighbour_vectors(xy, period, NEIGHBOURS)
    tol = STEP_TOLERANCE * spacing
    steps = translation_steps(xy, kind, period, tol) if period is not None or n >= MIN_ORDERED else ()
    if period is not None and len(steps) < 2:
        wider = symmetry_steps(xy, kind, period, EXACT_STEP * spacing)
        steps = wider if len(wider) > len(steps) else steps
    kind_name = "lattice" if len(steps) == 2 else "rows" if len(steps) == 1 else "scatter"
    aniso, aniso_angle = _anisotropy(vectors[:, 0, :])
    clustering = float(nearest.mean() / (0.5 * spacing))
    band_angle = steps[0].angle if steps else 0.0
    banding, kind_banding = _banding(xy, kind, exemplar, band_angle, STRIP * spacing)
    return Order(spacing, steps, kind_name, period, aniso, aniso_angle, clustering, banding, kind_banding, band_angle)


def neighbour_vectors(xy: np.ndarray, period: tuple[float, float] | None, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Displacements from every motif to its ``k`` nearest neighbours (across a tile's edges).

    Parameters
    ----------
    xy : (n, 2) float array, user units
    period : (w, h) of a repeating tile, or None

    Returns
    -------
    vectors : (n, k', 2) float array, user units, nearest first, ``k' = min(k, available)``
    nearest : (n,) float array, the distance to the nearest neighbour
    """
    if period is None:
        others = xy
    else:  # the tile's own motifs first, then its 8 neighbouring copies
        shifts = np.array([(i, j) for j in (-1, 0, 1) for i in (-1, 0, 1) if (i, j) != (0, 0)], dtype=np.float64)
        shifts = np.vstack([[0.0, 0.0], shifts]) * np.asarray(period, dtype=np.float64)
        others = (xy[None, :, :] + shifts[:, None, :]).reshape(-1, 2)
    kk = min(k, len(others) - 1)
    dist, idx = cKDTree(others).query(xy, k=kk + 1)
    vec = others[idx[:, 1:]] - xy[:, None, :]
    return vec, dist[:, 1]


def translation_steps(xy: np.ndarray, kind: np.ndarray, period: tuple[float, float] | None,
                      tol: float) -> tuple[Step, ...]:  # fmt: skip
    """The dominant steps between motifs *of one kind*: translations that map the pattern onto
    itself (dots and dashes alternating along a row repeat at two motif steps, not one).

    Parameters
    ----------
    xy : (n, 2) float array, user units
    kind : (n,) int array
    period : (w, h) of a repeating tile, or None
    tol : user units, :data:`STEP_TOLERANCE` times the spacing
    """
    vs, owners, base = [], [], 0
    for c in np.unique(kind):
        idx = np.flatnonzero(kind == c)
        if len(idx) < 2 and period is None:
            continue
        v, _ = neighbour_vectors(xy[idx], period, NEIGHBOURS)
        vs.append(v.reshape(-1, 2))
        owners.append(np.repeat(idx, v.shape[1]))
        base += len(idx)
    if not vs:
        return ()
    return dominant_steps(np.vstack(vs), np.concatenate(owners), len(xy), tol)


def symmetry_steps(xy: np.ndarray, kind: np.ndarray, period: tuple[float, float], tol: float) -> tuple[Step, ...]:
    """The exact steps of a repeating tile whose kinds interleave: translations that map at least
    :data:`SUPPORT` of the motifs onto a motif of their own kind, found among all same-kind
    displacements shorter than half the tile rather than the :data:`NEIGHBOURS` nearest.
    :func:`read_order` asks for them (with ``tol`` = :data:`EXACT_STEP` spacings) only for a
    tile in which the nearest neighbours give fewer than two steps, and takes them only when they
    are more.

    In a tile of "=" signs between rows of dots (Equinor 30100), each kind's nearest neighbours
    of its own kind are the dots' short diagonals, which no other dot shares; the step by which
    the whole pattern repeats, (16, 0) and (8, 8) there, lies further out than six neighbours.
    Every candidate is tested on every motif (exact support, across the tile's edges), so a step
    is kept only when the pattern truly repeats by it.

    Parameters
    ----------
    xy : (n, 2) float array, user units
    kind : (n,) int array
    period : (w, h) of the repeating tile, user units
    tol : user units, how far a match may lie from ``x ± v``

    Returns
    -------
    Up to two steps, most supported first (ties: the shorter), the second at least
    :data:`NOT_PARALLEL` degrees from the first; their ``spread`` is the rms miss of the matches.
    """
    n = len(xy)
    shifts = np.array([(i, j) for j in (-1, 0, 1) for i in (-1, 0, 1)], dtype=np.float64) * np.asarray(period)
    wrapped = (xy[None, :, :] + shifts[:, None, :]).reshape(-1, 2)
    wkind = np.tile(kind, len(shifts))
    # kinds far apart in a third coordinate: a neighbour query finds motifs of the query's kind only
    gap = 10.0 * (sum(period) + tol)
    tree = cKDTree(np.column_stack([wrapped, wkind * gap]))
    reach = 0.5 * min(period)
    pairs = tree.query_ball_point(np.column_stack([xy, kind * gap]), reach, return_sorted=True)
    cand = np.vstack([wrapped[p] - xy[i] for i, p in enumerate(pairs)])
    del pairs  # _support_bound asks again, a little wider: not both lists at once
    cand = cand[np.hypot(cand[:, 0], cand[:, 1]) > tol]
    flip = (cand[:, 1] < 0) | ((cand[:, 1] == 0) & (cand[:, 0] < 0))
    cand = np.where(flip[:, None], -cand, cand)
    if not len(cand):
        return ()
    # one candidate per cell of STEP_TOLERANCE / EXACT_STEP = 4 tolerances: an exact step's
    # displacements all fall in one cell, and the candidates stay few
    cell = np.round(cand / (4.0 * tol)).astype(np.int64)
    cell -= cell.min(axis=0)
    key = cell[:, 0] * (int(cell[:, 1].max()) + 1) + cell[:, 1]  # a cell's number: the first candidate of each
    cand = cand[np.sort(np.unique(key, return_index=True)[1])]
    cand = cand[_support_bound(tree, xy, kind, gap, wrapped, reach + 2.0 * tol, cand, tol) / n >= SUPPORT]
    if not len(cand):
        return ()
    # exact support: the motif has a motif of its kind at +v or at −v (within tol)
    m = len(cand)
    hits = np.zeros((m, n), dtype=bool)
    miss = np.zeros((m, n))
    for sign in (1.0, -1.0):
        q = xy[None, :, :] + sign * cand[:, None, :]
        d, _ = tree.query(np.column_stack([q.reshape(-1, 2), np.tile(kind, m) * gap]), distance_upper_bound=tol)
        d = d.reshape(m, n)
        better = np.isfinite(d) & (~hits | (d < miss))
        miss = np.where(better, d, miss)
        hits |= np.isfinite(d)
    support = hits.mean(axis=1)
    length = np.hypot(cand[:, 0], cand[:, 1])
    steps: list[Step] = []
    alive = support >= SUPPORT
    for _ in range(2):
        if not alive.any():
            break
        order = np.lexsort((length, -support))
        best = order[alive[order]][0]
        v = cand[best]
        spread = math.sqrt(float((miss[best][hits[best]] ** 2).mean()))
        steps.append(Step((float(v[0]), float(v[1])), float(support[best]), spread))
        ang = np.degrees(np.arctan2(cand[:, 1], cand[:, 0]) - math.atan2(v[1], v[0]))
        alive &= np.abs((ang + 90.0) % 180.0 - 90.0) >= NOT_PARALLEL
    return tuple(steps)


def _support_bound(
    tree: cKDTree, xy: np.ndarray, kind: np.ndarray, gap: float, wrapped: np.ndarray, radius: float,
    cand: np.ndarray, tol: float,
) -> np.ndarray:  # fmt: skip
    """(m,) int: at least the number of motifs :func:`symmetry_steps`' exact test finds a partner
    for at ``+v`` or ``−v``, for each of its candidates ``cand`` (m, 2): the same-kind
    displacements within ``radius`` (at least ``|v| + tol``) counted in the cells that the square
    around a disc of radius ``tol`` about ``v``, and one about ``−v``, reaches (cells of ``tol``,
    fewer on a large tile).  A motif with a partner within ``tol`` of ``x + v`` has a displacement there; one
    with several is counted more than once, so this bounds the motifs matched from above.

    The exact test costs a neighbour query per motif and candidate, twice; a candidate whose
    bound is below :data:`SUPPORT` cannot be kept, and is left out before it (FGDC 603, 990
    motifs: 9,924 candidates, 0 kept, the read 7.2 s → 0.3 s).
    """
    pairs = tree.query_ball_point(np.column_stack([xy, kind * gap]), radius)
    d = np.vstack([wrapped[p] - xy[i] for i, p in enumerate(pairs)])
    lo = d.min(axis=0) - 2.0 * tol
    c = max(tol, float((d.max(axis=0) + 2.0 * tol - lo).max()) / _BOUND_CELLS)
    side = np.floor((d.max(axis=0) + 2.0 * tol - lo) / c).astype(np.int64) + 1
    at = np.ravel_multi_index(tuple(np.floor((d - lo) / c).astype(np.int64).T), tuple(side))
    count = np.bincount(at, minlength=int(side.prod())).reshape(tuple(side))
    area = np.zeros((side[0] + 1, side[1] + 1), dtype=np.int64)  # summed-area table of the counts
    area[1:, 1:] = count.cumsum(axis=0).cumsum(axis=1)
    # a hair wide: the query's distances round otherwise, by up to a few ulps of the coordinates
    reach = tol * (1.0 + 1e-6) + 16.0 * np.finfo(np.float64).eps * float(np.abs(wrapped).max(initial=0.0))
    bound = np.zeros(len(cand), dtype=np.int64)
    for sign in (1.0, -1.0):
        v = sign * cand
        a0 = np.clip(np.floor((v - reach - lo) / c).astype(np.int64), 0, side)
        a1 = np.clip(np.floor((v + reach - lo) / c).astype(np.int64) + 1, 0, side)
        bound += area[a1[:, 0], a1[:, 1]] - area[a0[:, 0], a1[:, 1]] - area[a1[:, 0], a0[:, 1]] + area[a0[:, 0], a0[:, 1]]
    return bound


def dominant_steps(v: np.ndarray, owner: np.ndarray, n: int, tol: float) -> tuple[Step, ...]:
    """The (at most two) most supported, non-parallel neighbour steps.

    Every displacement is folded to the half-plane of angles [0°, 180°); the mode is the folded
    displacement with the most others within ``tol`` (ties: the shorter), refined to their mean.
    A step is kept when at least :data:`SUPPORT` of the ``n`` motifs have a neighbour there.

    Parameters
    ----------
    v : (m, 2) float array, user units, displacements from motifs to neighbours
        (:func:`neighbour_vectors`)
    owner : (m,) int array, the motif each displacement starts from
    n : motif count
    tol : user units
    """
    flip = (v[:, 1] < 0) | ((v[:, 1] == 0) & (v[:, 0] < 0))
    v = np.where(flip[:, None], -v, v)
    # near the fold (angle ≈ 0° or 180°) a step and its negative both occur: keep both copies
    pts = np.vstack([v, -v])
    own = np.concatenate([owner, owner])
    tree = cKDTree(pts)
    count = tree.query_ball_point(v, tol, return_length=True).astype(np.float64)
    length = np.hypot(v[:, 0], v[:, 1])
    steps: list[Step] = []
    alive = np.ones(len(v), dtype=bool)
    for _ in range(2):
        if not alive.any():
            break
        # most support first, then the shortest: a lattice's basis, not its diagonals
        order = np.lexsort((length, -count))
        best = order[alive[order]][0]
        near = tree.query_ball_point(v[best], tol)
        centre = pts[near].mean(axis=0) if near else v[best]
        support = len(np.unique(own[near])) / n
        if support < SUPPORT:
            break
        spread = math.sqrt(float(((pts[near] - centre) ** 2).sum(axis=1).mean())) if near else 0.0
        if centre[1] < 0 or (centre[1] == 0 and centre[0] < 0):
            centre = -centre
        steps.append(Step((float(centre[0]), float(centre[1])), float(support), spread))
        ang = np.degrees(np.arctan2(v[:, 1], v[:, 0])) - math.degrees(math.atan2(centre[1], centre[0]))
        ang = np.abs((ang + 90.0) % 180.0 - 90.0)
        alive &= ang >= NOT_PARALLEL
    return tuple(steps)


def _anisotropy(nearest: np.ndarray) -> tuple[float, float]:
    """(strength in [0, 1], direction in degrees [0, 180)) of the nearest-neighbour directions.

    The mean resultant of the doubled angles: 1 when all lie on one line, 0 when spread evenly.
    """
    ang = 2.0 * np.arctan2(nearest[:, 1], nearest[:, 0])
    c, s = float(np.cos(ang).mean()), float(np.sin(ang).mean())
    return math.hypot(c, s), math.degrees(math.atan2(s, c) / 2.0) % 180.0


def _banding(xy: np.ndarray, kind: np.ndarray, exemplar: Exemplar, angle: float, width: float) -> tuple[float, float]:
    """Count banding and kind banding over strips of ``width`` along ``angle`` (degrees).

    The strips cut the projection of the centres on the normal of ``angle``; for a tile whose
    strips are horizontal or vertical, the projection wraps with the tile's period, so the
    strips cover whole rows of the pattern.
    """
    t = math.radians(angle)
    normal = np.array([-math.sin(t), math.cos(t)])
    p = xy @ normal
    lo, hi = float(p.min()), float(p.max())
    period = getattr(exemplar, "period", None)
    if period is not None and (angle in _near_zero(1.0) or (angle - 90.0) in _near_zero(1.0)):
        span = period[1] if angle in _near_zero(1.0) else period[0]
        lo, hi = lo, lo + span
        p = lo + (p - lo) % span
    bins = max(1, round((hi - lo) / width))
    strip = np.minimum(((p - lo) / max(hi - lo, 1e-12) * bins).astype(np.intp), bins - 1)
    counts = np.bincount(strip, minlength=bins).astype(np.float64)
    mean = counts.mean()
    cv = float(counts.std() / mean) if mean > 0 else 0.0
    banding = max(0.0, cv - 1.0 / math.sqrt(mean)) if mean > 0 else 0.0
    k = int(kind.max()) + 1
    if k == 1 or bins == 1:
        return banding, 0.0
    whole = np.bincount(kind, minlength=k) / len(kind)

    def tv(kinds: np.ndarray) -> float:
        mix = np.zeros((bins, k))
        np.add.at(mix, (strip, kinds), 1.0)
        rows = mix.sum(axis=1)
        full = rows > 0
        return float((0.5 * np.abs(mix[full] / rows[full, None] - whole).sum(axis=1) * rows[full]).sum() / rows.sum())

    shuffled = kind[np.random.default_rng(len(kind)).permutation(len(kind))]
    return banding, max(0.0, tv(kind) - tv(shuffled))


def exact_support(xy: np.ndarray, kind: np.ndarray, period: tuple[float, float] | None, g: np.ndarray,
                   tol: float) -> float:  # fmt: skip
    """Share of the motifs with a same-kind motif within ``tol`` of ``x + g`` or ``x − g``
    (across a tile's edges: its motifs and their 8 neighbouring copies).

    The test of an *exact* step, which the repetition figure (:mod:`svgtile.metrics.order`) and
    the optimize engine's seamless start (:func:`svgtile.engines.optimize.init.seamless`) share.
    ``xy`` (n, 2) and ``g`` (2,) and ``tol`` in user units, ``kind`` (n,) ints, ``period`` (w, h)
    or None.
    """
    has = exact_partners(xy, kind, period, g, tol)
    return float(has.mean()) if len(xy) else 0.0


def exact_partners(xy: np.ndarray, kind: np.ndarray, period: tuple[float, float] | None, g: np.ndarray,
                   tol: float) -> np.ndarray:  # fmt: skip
    """(n,) bool: the motifs :func:`exact_support` counts (a same-kind motif within ``tol`` of
    ``x + g`` or ``x − g``, across a tile's edges)."""
    if period is None:
        shifts = np.zeros((1, 2))
    else:
        shifts = np.array([(i, j) for j in (-1, 0, 1) for i in (-1, 0, 1)], dtype=np.float64) * np.asarray(period)
    has = np.zeros(len(xy), dtype=bool)
    for c in np.unique(kind):
        mine = np.flatnonzero(kind == c)
        tree = cKDTree((xy[mine][None, :, :] + shifts[:, None, :]).reshape(-1, 2))
        for sign in (1.0, -1.0):
            d, _ = tree.query(xy[mine] + sign * g, k=1, distance_upper_bound=tol)
            has[mine] |= np.isfinite(d)
    return has


def is_period(g: np.ndarray, period: tuple[float, float], tol: float) -> bool:
    """Whether ``g`` is within ``tol`` of a non-zero integer combination ``(i w, j h)``."""
    w, h = period
    i, j = round(g[0] / w), round(g[1] / h)
    return (i, j) != (0, 0) and abs(g[0] - i * w) <= tol and abs(g[1] - j * h) <= tol


#: A tile is reproduced by a step when every motif meets a motif of its kind there: all but this
#: share (floating-point slack, not a tolerance for jittered motifs).
WHOLE = 1e-9
#: Shortest divisor step tried for a tile's period, in mean spacings, and the most divisors
#: tried; the repetition figure tries the same (:mod:`svgtile.metrics.shown` takes them from
#: here as ``REPEAT_DIVIDE`` and ``REPEAT_DIVIDE_MAX``).
DIVIDE_MIN, DIVIDE_MAX = 0.5, 64
#: A period shorter than this many mean spacings is the pattern's own lattice (a tile of one or
#: two icons): its copies are its nearest neighbours (the repetition figure's ``REPEAT_MIN``,
#: taken from here).
SHORT_PERIOD = 2.0


def stamp_repeats(exemplar: Exemplar, order: Order | None = None) -> bool:
    """Whether stamping a repeating tile on its period repeats content its own exact order does
    not reproduce — the tile is *not* the stamp of a lattice (issues 12 and 13, auto's rules).

    A stamp repeats every motif exactly at the period ``p`` ∈ {(w, 0), (0, h)}.  That is the
    exemplar's own order when the tile already repeats at a step that generates ``p``, to the
    exactness of :data:`EXACT_STEP` (the repetition figure's half bin) and for **every** motif:

    * ``p`` is shorter than :data:`SHORT_PERIOD` mean spacings (one icon per tile: the period is
      its lattice);
    * or ``p / m`` maps every motif onto one of its kind for a whole ``m ≥ 2`` (a tile that is an
      m-fold stamp of a smaller one, or rows exact along ``p``: FGDC 619 and 620 along x);
    * or ``p`` is an integer combination of the analysis's steps (:attr:`Order.steps`, not the
      period itself) that each map every motif (offset rows, a centred lattice: Equinor 30100's
      (16, 0) and (8, 8)).

    When either period is not so generated — motifs hand-jittered off any exact lattice (FGDC
    610, 611, 617), rows exact along x at hand-drawn phases (619, 620), every motif its own kind
    (626, 659, 732), a lattice most but not all motifs share — the stamp repeats at that period,
    which the exemplar cannot show: True.  Not a repeating tile: False.

    Parameters
    ----------
    exemplar : the exemplar (``period`` (w, h) user units where it repeats)
    order : its order (:func:`read_order`), if already read

    Cost: one same-kind k-d tree query per candidate step and motif (≤ 2 · 64 + 2 steps).
    """
    order = read_order(exemplar) if order is None else order
    period = getattr(exemplar, "period", None)
    if period is None:
        return False
    xy, kind = exemplar.motifs.xy, exemplar.motifs.kind
    if not len(xy):
        return False
    s = order.spacing
    tol = EXACT_STEP * s

    def whole(g: np.ndarray) -> bool:
        return exact_support(xy, kind, period, g, tol) >= 1.0 - WHOLE

    steps = [np.asarray(st.vector, dtype=np.float64) for st in order.steps]
    steps = [g for g in steps if not is_period(g, period, tol) and whole(g)]

    def generated(p: np.ndarray) -> bool:
        if math.hypot(*p) < SHORT_PERIOD * s:
            return True
        most = min(DIVIDE_MAX, int(math.hypot(*p) / (DIVIDE_MIN * s)))
        if any(whole(p / m) for m in range(2, most + 1)):
            return True
        if len(steps) == 2:  # lattice coordinates of p, whole to the tolerance
            c = np.linalg.solve(np.column_stack(steps), p)
            return bool(np.abs(np.column_stack(steps) @ np.round(c) - p).max() <= tol)
        if len(steps) == 1:
            g = steps[0]
            m = round(float(p @ g) / float(g @ g))
            return m != 0 and bool(np.abs(m * g - p).max() <= tol)
        return False

    w, h = period
    return not (generated(np.array([w, 0.0])) and generated(np.array([0.0, h])))


__all__ = ["Order", "Step", "dominant_steps", "exact_partners", "exact_support", "is_period", "neighbour_vectors", "read_order", "stamp_repeats", "symmetry_steps", "translation_steps"]
