"""What each density-repair round of the patch engine does (almeraj2013 §3.4, issue 12's speed
target): motifs thinned and added, covered area, density against ρ over all windows and in the
worst window, candidates pasted, CPU per round.

The library's own loop (:func:`svgtile.engines.patch.density.adjust_density`) runs, with counters
around what it calls (:func:`run`); the script checks that the texture it ends with is that of a
plain run (same hash), so the figures describe the real run.
Hole filling (:func:`svgtile.engines.holes.fill_holes`) after the rounds is shown as one more row.

Run by hand (the exemplars one after the other in this process; CPU per round is comparable
within one run only, and includes the counters' own measures):
    python benchmarks/patch_rounds.py --count 100000 [--exemplars till,marsh] [--seed 1] [--json out.json]

Columns: ``added`` motifs pasted, ``thinned`` removed from dense windows, ``displaced`` removed by
displacing candidates, ``Δcover`` the round's change of the covered area (thinning and filling) as
a share of ρ × the windows' area, ``ρ̄`` covered ÷ (ρ × area) over every window (before and after
the round), ``min``/``p10``/``median`` the same per window, ``sparse``/``dense`` windows out of ``windows``, ``cand`` tries ×
exemplar motifs × sparse windows (the pasted motifs before the in-window test), ``cpu`` seconds of
the round.  Below each table: what a rule "skip a sparse window that gained less than f of its
deficit last round, under the same distance rule" would have skipped and lost (:func:`_skip_rule`).
"""

from __future__ import annotations

import argparse
import hashlib
import itertools
import json
import math
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
EXEMPLARS = HERE.parent / "exemplars"


def _digest(arr) -> str:
    return hashlib.sha1(arr.kind.tobytes() + arr.xy.tobytes() + arr.angle.tobytes()).hexdigest()[:10]


def run(name: str, count: int, seed: int) -> dict:
    """Synthesize ``count`` motifs of exemplar ``name`` with the per-round counters in place.

    The library's own loop runs; the counters sit in what it calls: the progress report opens a
    round, the round's first :func:`~svgtile.engines.windows.window_cover` is measured (the texture
    before it), ``_thin`` and ``_fill`` are counted, and the next round's first measure (or hole
    filling) closes it with the texture after it, on the round's own windows.

    Returns a dict: ``rounds`` (list of per-round dicts), ``skips`` (:func:`_skip_rule`), ``holes``
    (hole filling's row), and the hashes of the instrumented and of a plain run.
    """
    from svgtile import analyze, read_exemplar
    from svgtile.core.region import Region
    from svgtile.engines import synthesize
    from svgtile.engines.patch import density as D
    from svgtile.engines.patch import engine as E
    from svgtile.engines.windows import region_windows

    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    stats = analyze(ex)
    side = math.sqrt(count / stats.count_density)
    region = Region.rectangle(side, side)
    protos, rho, params = ex.prototypes, stats.density, E.PatchParams()

    rows: list[dict] = []
    quarters: list[tuple] = []  # per round, :func:`_quarter_gains`
    state: dict = {"fresh": False, "open": None}
    cover, thin, fill, holes = D.window_cover, D._thin, D._fill, E.fill_holes

    def close(arr) -> None:
        """The texture after the open round, on that round's windows."""
        if state["open"] is None:
            return
        row, origin, size, ids, area, covered, q_before, t0 = state["open"]
        state["open"] = None
        _, after = cover(arr, protos, origin, size, ids)
        row.update(gain=float((after.sum() - covered.sum()) / (area.sum() * rho)),
                   rho_after_all=float(after.sum() / (area.sum() * rho)),
                   rho_after_min=float((after / area).min() / rho), cpu=time.process_time() - t0)  # fmt: skip
        sparse = covered / area < rho * (1 - params.density_tolerance)
        quarters.append(_quarter_gains(ids, origin, size, sparse, q_before, _quarter_cover(arr, protos, size), rho,
                                       _rule_of(row["round"], params)))  # fmt: skip
        rows.append(row)

    def progress(stage, fraction) -> None:
        if stage == "density":
            state["fresh"] = True

    def counted_cover(arr, protos_, origin, size, ids, areas=None):
        win, covered = cover(arr, protos_, origin, size, ids, areas)
        if state["fresh"]:  # the round's first measure: the texture before it
            state["fresh"] = False
            t0 = time.process_time()
            close(arr)
            area = region_windows(region, size, origin)[2]
            ratio = covered / area / rho
            row = {"round": len(rows), "windows": len(ids), "motifs": len(arr),
                   "sparse": int((ratio < 1 - params.density_tolerance).sum()),
                   "dense": int((ratio > 1 + params.density_tolerance).sum()),
                   "rho_all": float(covered.sum() / (area.sum() * rho)), "rho_min": float(ratio.min()),
                   "rho_p10": float(np.quantile(ratio, 0.1)), "rho_median": float(np.median(ratio)),
                   "added": 0, "thinned": 0, "displaced": 0, "cand": 0}  # fmt: skip
            state["open"] = (row, origin, size, ids, area, covered, _quarter_cover(arr, protos, size), t0)
        return win, covered

    def counted_thin(arr, *args, **kw):
        keep = thin(arr, *args, **kw)
        state["open"][0]["thinned"] = int((~keep).sum())
        return keep

    def counted_fill(arr, exemplar, stats_, region_, p, boundary, origin, size, ids, deficit, **kw):
        new, removed = fill(arr, exemplar, stats_, region_, p, boundary, origin, size, ids, deficit, **kw)
        state["open"][0].update(added=len(new), displaced=int(removed.sum()),
                                cand=len(ids) * p.disc_tries * len(exemplar.motifs))  # fmt: skip
        return new, removed

    holes_row: dict = {}

    def counted_holes(arr, *args, **kw):
        close(arr)
        t0 = time.process_time()
        out = holes(arr, *args, **kw)
        holes_row.update(before=len(arr), after=len(out), cpu=time.process_time() - t0)
        return out

    plain = synthesize(ex, region, "patch", seed=seed, stats=stats).arrangement
    D.window_cover, D._thin, D._fill, E.fill_holes = counted_cover, counted_thin, counted_fill, counted_holes
    try:
        t0 = time.process_time()
        arr = synthesize(ex, region, "patch", seed=seed, stats=stats, progress=progress).arrangement
        total = time.process_time() - t0
    finally:
        D.window_cover, D._thin, D._fill, E.fill_holes = cover, thin, fill, holes
    return {"exemplar": name, "count": count, "seed": seed, "motifs": len(arr), "rounds": rows,
            "skips": _skip_rule(quarters), "holes": holes_row, "cpu": total, "hash": _digest(arr),
            "plain_hash": _digest(plain)}  # fmt: skip


def _rule_of(rnd: int, params) -> int:
    """Which of the junction rule's steps round ``rnd`` pastes with (as adjust_density picks it)."""
    from svgtile.engines.patch.engine import JUNCTION_STEPS

    return min(JUNCTION_STEPS - 1, JUNCTION_STEPS * rnd // params.density_rounds)


def _quarter_cover(arr, protos, size) -> dict:
    """Covered footprint area per half-window cell (square user units), keyed by cell (i, j):
    the windows of every offset are 2 × 2 of these cells, so one round's gains can be read by
    the next round's windows."""
    from svgtile.analysis.stats import footprint_areas

    cell = np.floor(arr.xy / (size / 2)).astype(np.int64)
    keys, inv = np.unique(cell, axis=0, return_inverse=True)
    area = np.bincount(inv.ravel(), weights=footprint_areas(arr, protos), minlength=len(keys))
    return dict(zip(map(tuple, keys.tolist()), area.tolist(), strict=True))


def _quarter_gains(ids, offset, size, sparse, before: dict, after: dict, rho: float, rule: int):
    """One round, per window: its quarter cells, whether it was sparse, and per quarter cell the
    gain (after − before) and deficit (ρ × cell area − before, ≥ 0) of the round."""
    shift = np.round(offset / size * 2).astype(np.int64)
    base = 2 * ids + shift  # (w, 2) quarter cell of each window's lower-left quarter
    keys = base[:, None, :] + np.array([[0, 0], [1, 0], [0, 1], [1, 1]])[None, :, :]
    quarter = float(np.prod(size / 2))
    gain = {k: after.get(k, 0.0) - before.get(k, 0.0) for k in set(before) | set(after)}
    deficit = {k: max(rho * quarter - v, 0.0) for k, v in before.items()}
    return keys, sparse, gain, deficit, rule


def _skip_rule(quarters: list[tuple], fractions=(0.0, 0.02, 0.05, 0.1, 0.2)) -> list[dict]:
    """What a rule "skip a sparse window when, under the same distance rule last round, its
    quarters gained less than f of their deficit" would have skipped (share of the sparse windows
    searched, the cost) and lost (share of the repair's total area gain), for each f.  Measured on
    the run without the rule: what the skipped windows actually gained is what would be lost (the
    first order of the effect; later rounds would differ)."""
    out = []
    total_gain = sum(sum(q[2].values()) for q in quarters)
    total_sparse = sum(int(q[1].sum()) for q in quarters)
    for f in fractions:
        skipped = lost = 0.0
        for prev, cur in itertools.pairwise(quarters):
            if prev[4] != cur[4] or prev[4] < 0:
                continue
            gain, deficit = prev[2], prev[3]
            keys, sparse = cur[0], cur[1]
            g_now = np.array([sum(cur[2].get(tuple(k), 0.0) for k in w) for w in keys.tolist()])
            g_prev = np.array([sum(gain.get(tuple(k), 0.0) for k in w) for w in keys.tolist()])
            d_prev = np.array([sum(deficit.get(tuple(k), 0.0) for k in w) for w in keys.tolist()])
            skip = sparse & (g_prev <= f * d_prev)
            skipped += skip.sum()
            lost += float(g_now[skip].sum())
        out.append({"f": f, "skipped": skipped / max(total_sparse, 1), "lost": lost / max(total_gain, 1e-300)})
    return out


def table(res: dict) -> str:
    """One Markdown table of a run's rounds."""
    out = [f"**{res['exemplar']}** — {res['motifs']:,} motifs, hash {res['hash']} "
           f"({'the library' + chr(39) + 's' if res['hash'] == res['plain_hash'] else 'NOT the library' + chr(39) + 's'}), "
           f"CPU {res['cpu']:.2f} s", "",
           "| round | windows | sparse | dense | motifs | added | thinned | displaced | cand | Δcover | ρ̄ before | ρ̄ after"
           " | min before | min after | p10 | median | cpu (s) |",
           "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]  # fmt: skip
    for r in res["rounds"]:
        out.append(f"| {r['round']} | {r['windows']} | {r['sparse']} | {r['dense']} | {r['motifs']:,} | {r['added']:,} "
                   f"| {r['thinned']:,} | {r['displaced']:,} | {r['cand']:,} | {r.get('gain', 0):+.4f} "
                   f"| {r['rho_all']:.4f} | {r.get('rho_after_all', r['rho_all']):.4f} | {r['rho_min']:.3f} "
                   f"| {r.get('rho_after_min', r['rho_min']):.3f} | {r['rho_p10']:.3f} | {r['rho_median']:.3f} "
                   f"| {r['cpu']:.2f} |")  # fmt: skip
    h = res["holes"]
    if h:
        out.append(f"| holes | | | | {h['before']:,} | {h['after'] - h['before']:+,} | | | | | | | | | | "
                   f"| {h['cpu']:.2f} |")  # fmt: skip
    out += ["", "| skip when last round's gain ≤ f × deficit | " + " | ".join(f"{s['f']:g}" for s in res["skips"]) + " |",
            "|---|" + "---:|" * len(res["skips"]),
            "| sparse windows skipped | " + " | ".join(f"{s['skipped']:.1%}" for s in res["skips"]) + " |",
            "| area gain lost | " + " | ".join(f"{s['lost']:.1%}" for s in res["skips"]) + " |"]
    return "\n".join(out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=100000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--exemplars", default=",".join(sorted(p.stem for p in EXEMPLARS.glob("*.svg"))))
    parser.add_argument("--json", help="also write every run's figures to this file")
    args = parser.parse_args()
    results = []
    for name in args.exemplars.split(","):
        res = run(name, args.count, args.seed)
        results.append(res)
        print(table(res), flush=True)
        print(flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
