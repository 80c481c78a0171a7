#!/usr/bin/env python3
"""Print the README's all-exemplar likeness table (section "Likeness") as Markdown rows.

Runs :func:`svgtile.apps.compare.compare` (patch, tile, random; one seed) on every bundled exemplar,
or the ones named, on a square region, and prints one row per exemplar with the columns of the
README: overlaps / violators, density / ρ and kind-mix TV of patch, repetition and nearest-gap
W1 of the three engines, patch's gap sampling noise, the patch / random gap ratio (✗ where it
is above the issue's 0.5), pair correlation and coverage of the three engines, the neighbourhood
distance E of the three and their likeness L (the tile and random columns sit near 1 and 0,
not exactly: the baselines are measured on a region of their own).

Usage:  python tools/likeness_table.py [NAME ...] [--size 1000] [--seed 1] [--dir exemplars]
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

from svgtile import analyze, read_exemplar
from svgtile.apps.compare import compare
from svgtile.core.region import Region
from svgtile.metrics import Score

ROOT = Path(__file__).resolve().parents[1]
HEAD = (
    "| exemplar | overlaps / violators | density / ρ | kind mix TV | repetition patch · tile · random "
    "| gap W1 patch · tile · random | gap noise (patch) | patch / random gap "
    "| pair corr. patch · tile · random | coverage patch · tile · random "
    "| neighbourhood E patch · tile · random | L patch · tile · random |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|"
)


def row(name: str, size: float, seed: int, folder: Path = ROOT / "exemplars") -> str:
    """One Markdown row for exemplar ``folder/name.svg`` (patch, tile, random on size × size)."""
    ex = read_exemplar(folder / f"{name}.svg")
    s = {
        r.engine: r.score for r in compare(ex, analyze(ex), Region.rectangle(size, size), seed=seed)
    }
    p, t, r = s["patch"], s["tile"], s["random"]

    def three(figure: Callable[[Score], float], spec: str) -> str:
        return " · ".join(format(figure(e), spec) for e in (p, t, r))

    ratio = p.gap_distance / r.gap_distance
    mark = "" if ratio <= 0.5 else " ✗"
    return (
        f"| {name} | {p.overlaps} / {p.violators} | {p.density_ratio:.3f} | {p.kind_mix_tv:.3f} "
        f"| {three(lambda e: e.repetition, '.2f')} | {three(lambda e: e.gap_distance, '.3f')} | {p.gap_noise:.3f} "
        f"| {ratio:.2f}{mark} | {three(lambda e: e.pair_correlation_distance, '.3f')} "
        f"| {three(lambda e: e.coverage, '.2f')} | {three(lambda e: e.neighbourhood_distance, '.3f')} "
        f"| {three(lambda e: e.likeness, '.2f')} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="exemplar names (default: all in exemplars/)")
    parser.add_argument("--size", type=float, default=1000.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--dir", type=Path, default=ROOT / "exemplars", help="exemplar folder")
    args = parser.parse_args()
    names = args.names or sorted(p.stem for p in args.dir.glob("*.svg"))
    print(HEAD, flush=True)
    for name in names:
        print(row(name, args.size, args.seed, args.dir), flush=True)


if __name__ == "__main__":
    main()
