"""Where the patch engine's density and kind mix go, stage by stage, on whole-set gate tiles.

For each tile (``set/stem``, as tests/test_wholeset.py names them) the tile is imported and
synthesized with auto over :func:`test_wholeset.gate_region` (seed 1), as the gates do; when auto
picks the patch engine, the texture is measured on the gate's interior after overlap resolution
(almeraj2013 §3.3), after density repair (§3.4) and after hole filling: motifs, density / ρ,
kind-mix TV and the count of the exemplar's most frequent kinds against their expected count.
The stages are observed by wrapping the engine module's ``resolve``, ``adjust_density`` and
``fill_holes``; nothing is changed.

Run by hand (``$SVGTILE_DATA`` or ``../shared/data`` beside the checkout):
    python benchmarks/patch_stages.py fgdc/686 fgdc/684 equinor/11026
    PYTHONPATH=/tmp/base python benchmarks/patch_stages.py --tests /tmp/base/tests fgdc/686
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent

#: The exemplar's most frequent kinds shown per stage.
TOP = 5


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("tiles", nargs="+", help="set/stem (fgdc/686)")
    parser.add_argument(
        "--tests",
        type=Path,
        default=HERE.parent / "tests",
        help="the tests folder to take the gates from",
    )
    args = parser.parse_args()
    sys.path.insert(0, str(args.tests))
    import test_wholeset as W

    import svgtile.engines.patch.engine as E
    from svgtile.analysis.stats import footprint_areas
    from svgtile.engines import synthesize
    from svgtile.metrics.window import in_window, interior

    now: dict = {}

    def show(stage: str, arr) -> None:
        ex, stats, window = now["ex"], now["stats"], now["window"]
        k = len(ex.prototypes)
        inside = in_window(arr, window)
        n = int(inside.sum())
        count = np.bincount(arr.kind[inside], minlength=k)
        rho = footprint_areas(arr, ex.prototypes)[inside].sum() / window.area / stats.density
        tv = 0.5 * np.abs(count / max(n, 1) - stats.frequency).sum()
        expected = np.bincount(ex.motifs.kind, minlength=k) * window.area / ex.region.area
        top = np.argsort(-expected, kind="stable")[:TOP]
        kinds = " ".join(f"{j}:{count[j]}/{expected[j]:.0f}" for j in top)
        print(f"| {now['tile']} | {stage} | {n} | {rho:.3f} | {tv:.3f} | {kinds} |", flush=True)

    resolve, adjust, fill = E.resolve, E.adjust_density, E.fill_holes

    def resolved(arr, *a, **kw):
        keep = resolve(arr, *a, **kw)
        show("resolve §3.3", arr.take(keep))
        return keep

    def adjusted(arr, *a, **kw):
        out = adjust(arr, *a, **kw)
        show("density repair §3.4", out)
        return out

    def filled(arr, *a, **kw):
        out = fill(arr, *a, **kw)
        show("hole filling", out)
        return out

    E.resolve, E.adjust_density, E.fill_holes = resolved, adjusted, filled
    print(f"| tile | after | motifs | density/ρ | kind-mix TV | top {TOP} kinds: got/expected |")
    print("|---|---|---:|---:|---:|---|")
    for tile in args.tiles:
        loaded = W.motif_tile(tile)
        if not isinstance(loaded, tuple):
            print(f"| {tile} | {loaded or 'refused'} | | | | |")
            continue
        t, ex, stats = loaded
        region = W.gate_region(t.box, len(ex.motifs))
        now.update(tile=tile, ex=ex, stats=stats, window=interior(ex, region))
        result = synthesize(ex, region, "auto", seed=1, stats=stats)
        show(f"{result.engine} (final)", result.arrangement)


if __name__ == "__main__":
    main()
