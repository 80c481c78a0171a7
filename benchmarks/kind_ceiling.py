"""How far kinds alone could lift optimize's likeness: greedy kind changes against eq. (1) itself.

Issue 14 asks for L ≥ 0.85 under ``--engine optimize`` on every bundled exemplar; breccia-plain
stays near 0.78, and the diagnosis of 2026-12-02 put most of its neighbourhood distance in kinds
(about 1.1 neighbours of seven of the wrong kind).  This measures the ceiling of any kind step:
the optimize texture (a square of 4 exemplar widths, as benchmarks/optimize_sets.py) keeps its
positions, and its kinds are changed greedily to lower the sum of the Ma, Wei & Tong 2011 eq. (1)
distances (:func:`svgtile.analysis.neighbourhood.neighbourhood_distance`'s own costs, k = 6,
α = 1) of every neighbourhood a motif is in.  Footprints are ignored (a change may overlap): the
figures are optimistic estimates of what a kind step could give — a greedy local search, not a
bound (a better search could find more):

* ``flip``: any kind, three sweeps in a random order (the kind mix may drift);
* ``swap``: two motifs of one world-anchored window of 12 spacings (optimize's kind-mix window)
  exchange kinds when the pair's summed change is negative, non-neighbours only, re-checked
  jointly: the window's mix is kept exactly (stricter than optimize, which allows ± 0.01 of it).

Run by hand (seconds per sweep on the bundled exemplars):
    python benchmarks/kind_ceiling.py breccia-plain [--seed 1] [--sweeps 3]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

#: Neighbours per neighbourhood, as tests/optimize_measure.py's distance (and svgtile score's L).
K = 6


def main() -> None:
    import optimize_measure as om

    from svgtile import analyze, read_exemplar
    from svgtile.analysis.neighbourhood import (
        EXEMPLAR_FACTOR,
        _nearest_costs,
        likeness,
        neighbourhoods,
    )
    from svgtile.core.arrangement import Arrangement
    from svgtile.core.region import Region
    from svgtile.engines import synthesize
    from svgtile.metrics.window import spacing

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("exemplar", help="a bundled exemplar's name (exemplars/NAME.svg)")
    ap.add_argument("--seed", type=int, default=1, help="the optimize texture's and baselines' seed")
    ap.add_argument("--sweeps", type=int, default=3, help="sweeps of each search")
    args = ap.parse_args()
    ex = read_exemplar(HERE.parent / "exemplars" / f"{args.exemplar}.svg")
    st = analyze(ex)
    x0, y0, x1, y1 = ex.region.bounds
    side = 4 * max(x1 - x0, y1 - y0)
    region = Region.rectangle(side, side)
    arr = synthesize(ex, region, "optimize", seed=args.seed, stats=st).arrangement
    base = [om.distance(ex, st, region, synthesize(ex, region, b, seed=args.seed, stats=st).arrangement)
            for b in ("tile", "random")]  # fmt: skip

    def L(kind: np.ndarray) -> float:
        """Likeness of the texture with these kinds, (n,) int (its positions kept)."""
        return likeness(om.distance(ex, st, region, Arrangement(kind, arr.xy, arr.angle, arr.scale)), *base)

    s = spacing(st)
    p_e, k_e = neighbourhoods(ex.motifs.xy, ex.motifs.kind, EXEMPLAR_FACTOR * K, period=ex.period)
    p_e = p_e / s
    xy, n = arr.xy, len(arr)
    nn = cKDTree(xy).query(xy, K + 1)[1][:, 1:]
    member = [[] for _ in range(n)]  # the neighbourhoods each motif is in
    for o in range(n):
        for j in nn[o]:
            member[j].append(o)
    p_t = neighbourhoods(xy, arr.kind, K)[0] / s
    nk = int(ex.motifs.kind.max()) + 1

    def cost(centres: np.ndarray, kind: np.ndarray) -> float:
        """Summed eq. (1) distance of the neighbourhoods of ``centres`` (m,) int under ``kind``
        (n,) int, squared exemplar spacings."""
        return float(_nearest_costs(p_t[centres], kind[nn[centres]], kind[centres], p_e, k_e, ex.motifs.kind, 1.0,
                                    rotate=False).sum())  # fmt: skip

    def mix(kind: np.ndarray) -> str:
        """Each kind's share of the texture's motifs under ``kind`` (n,) int, as text."""
        return " ".join(f"{v:.3f}" for v in np.bincount(kind, minlength=nk) / n)

    own_mix = " ".join(f"{v:.3f}" for v in np.bincount(ex.motifs.kind, minlength=nk) / len(ex.motifs))
    print(f"{args.exemplar} seed {args.seed}: {n} motifs, L {L(arr.kind):.3f}, mix {mix(arr.kind)} (exemplar {own_mix})")
    kind = arr.kind.copy()
    for sweep in range(args.sweeps):
        changed = 0
        for o in np.random.default_rng(sweep).permutation(n):
            hood = np.array([o] + member[o])
            own = kind[o]
            best, won = cost(hood, kind) - 1e-9, own
            for q in range(nk):
                if q != own:
                    kind[o] = q
                    c = cost(hood, kind)
                    if c < best:
                        best, won = c, q
            kind[o] = won
            changed += won != own
        print(f"flip sweep {sweep + 1}: {changed} changed, L {L(kind):.3f}, mix {mix(kind)}")
    kind = arr.kind.copy()
    window = np.unique(np.floor(xy / (12.0 * s)).astype(np.int64), axis=0, return_inverse=True)[1].ravel()
    near = [set([o, *member[o], *nn[o]]) for o in range(n)]
    for sweep in range(args.sweeps):
        delta = np.zeros((n, nk))
        for o in range(n):
            hood = np.array([o] + member[o])
            own, now = kind[o], cost(hood, kind)
            for q in range(nk):
                if q != own:
                    kind[o] = q
                    delta[o, q] = cost(hood, kind) - now
            kind[o] = own
        done, swaps = np.zeros(n, dtype=bool), 0
        for w in np.unique(window):
            idx = np.flatnonzero(window == w)
            for a in range(nk):
                for b in range(a + 1, nk):
                    one = sorted((o for o in idx if kind[o] == a), key=lambda o: delta[o, b])
                    two = sorted((o for o in idx if kind[o] == b), key=lambda o: delta[o, a])
                    for o, p in zip(one, two, strict=False):
                        if delta[o, b] + delta[p, a] >= 0:
                            break
                        if done[o] or done[p] or p in near[o]:
                            continue
                        hood = np.array(sorted({o, *member[o], p, *member[p]}))
                        now = cost(hood, kind)
                        kind[o], kind[p] = b, a
                        if cost(hood, kind) < now - 1e-9:
                            done[o] = done[p] = True
                            swaps += 1
                        else:
                            kind[o], kind[p] = a, b
        print(f"swap sweep {sweep + 1}: {swaps} swaps, L {L(kind):.3f}, mix {mix(kind)}")


if __name__ == "__main__":
    main()
