"""The kind mix per shape class and per kind on every gate tile whose rare kinds pool (issue 12.3).

For each tile of the whole sets (tests/test_wholeset.py) whose analysis pools kinds drawn fewer
than :data:`svgtile.analysis.classes.RARE_BELOW` times into shape classes, auto's texture over
:func:`test_wholeset.gate_region` (seed 1) is read on the gate's interior: the kind-mix TV over
classes (the gate's figure), the TV per kind, what a fair draw of as many motifs from the
exemplar's exact mix gives per kind (:func:`svgtile.metrics.kind_mix_noise`), and the ``random``
engine's TV per kind on the same region (dart throwing with the exemplar's frequencies).

Run by hand (``$SVGTILE_DATA`` or ``../shared/data`` beside the checkout), one Markdown row per tile:
    python benchmarks/kind_mix_classes.py [fgdc/605 ...]
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import test_wholeset as W

from svgtile.analysis.classes import RARE_BELOW
from svgtile.engines import synthesize
from svgtile.metrics import kind_mix_noise, kind_mix_tv
from svgtile.metrics.window import in_window


def row(tile: str, t, ex, stats) -> str | None:
    """One Markdown row, or None where no kinds pool."""
    cls = stats.classes
    if len(np.unique(cls)) == len(cls):
        return None
    region = W.gate_region(t.box, len(ex.motifs))
    win = W.scored_window(ex, region)
    auto = synthesize(ex, region, "auto", seed=1, stats=stats).arrangement
    rand = synthesize(ex, region, "random", seed=1, stats=stats).arrangement
    inside = in_window(auto, win)
    rare = int((np.bincount(ex.motifs.kind, minlength=len(cls)) < RARE_BELOW).sum())
    figs = (kind_mix_tv(auto, stats, inside=inside), kind_mix_tv(auto, stats, inside=inside, classes=False),
            kind_mix_noise(int(inside.sum()), stats.frequency),
            kind_mix_tv(rand, stats, win, classes=False))  # fmt: skip
    return (f"| {tile} | {len(ex.motifs)} | {len(cls)} | {rare} | {len(np.unique(cls))} | {int(inside.sum())} | "
            + " | ".join(f"{f:.3f}" for f in figs) + " |")  # fmt: skip


def main(only: list[str]) -> None:
    print("| tile | motifs | kinds | rare kinds | classes | interior motifs | TV classes | TV kinds "
          "| fair draw | random, kinds |")  # fmt: skip
    print("|---" * 10 + "|", flush=True)
    for tile, t, ex, stats in W.motif_tiles(only):
        line = row(tile, t, ex, stats)
        if line:
            print(line, flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
