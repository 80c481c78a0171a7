"""An experiment not adopted (opt14i): the optimize start's patches capped at a share of the tile's period.

On a repeating tile the solver refills, :func:`svgtile.engines.optimize.engine.start_side` takes
the larger of ``start_cell`` (5 exemplar spacings) and ``TILE_CELL`` of the period, so on a tile
of under 5 / 0.65 ≈ 7.7 spacings the patches (Ma, Wei & Tong 2011 §4.1) are 5 spacings — on FGDC
653 and 664 (periods of 3.5 and 3.9 spacings) larger than the period itself: two neighbouring
patches then hold the whole tile each, at one displacement.  This runs
``benchmarks/optimize_sets.py`` with the side capped at ``--cap`` × the tile's shorter period
(the engine itself unchanged), to measure what that cap does over a whole set.

    python benchmarks/optimize_cell_cap.py --cap 1.0 [--sets fgdc] [--limit N]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import optimize_sets

import svgtile.engines.optimize.engine as engine


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cap", type=float, required=True, help="the patch side at most this share of the period")
    args, rest = ap.parse_known_args()
    side = engine.start_side

    def capped(exemplar, start_cell, refill):
        cell = side(exemplar, start_cell, refill)
        return min(cell, args.cap * min(exemplar.period)) if refill and exemplar.period is not None else cell

    engine.start_side = capped
    sys.argv = [sys.argv[0], *rest]
    optimize_sets.main()


if __name__ == "__main__":
    main()
