"""The linework figures (ink, S; svgtile.metrics.linework) of every tile of the shared sets accepted
as cells: one JSON line per tile (tile, ink, S, D, dust, seconds).

    python benchmarks/cellular_linework.py > figures.jsonl      # from the repository root
"""

from __future__ import annotations

import json
import time
from pathlib import Path

from svgtile.apps.linework import measure_tile
from svgtile.errors import SvgtileError
from svgtile.tiles.importer import import_tile

DATA = Path(__file__).resolve().parents[2] / "shared" / "data"
SETS = {"fgdc": DATA / "fgdc-geologic-patterns" / "lithology", "osm": DATA / "osm-carto" / "patterns",
        "osm-symbols": DATA / "osm-carto" / "symbols", "equinor": DATA / "equinor-lithology" / "svg"}  # fmt: skip


def main() -> None:
    for name, folder in SETS.items():
        for path in sorted(folder.glob("*.svg")):
            try:
                if import_tile(path).cellular is None:
                    continue
            except SvgtileError:
                continue
            t0 = time.perf_counter()
            f = measure_tile(path, seed=1)
            row = {"tile": f"{name}/{path.stem}", "ink": f.ink, "S": f.structure, "D": f.distance, "dust": f.dust,
                   "sec": round(time.perf_counter() - t0, 2)}  # fmt: skip
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
