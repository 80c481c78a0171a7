"""GIS outputs and the QGIS algorithm, timed (issue 18).  Run by hand, not in CI::

    python benchmarks/bench_gis.py [--motifs 100000] [--qgis]

*write*: the placements of one gravel texture of about ``--motifs`` motifs written as svgtile's
GeoJSON text, and by GDAL as GeoPackage, Shapefile and FlatGeobuf (synthesis not counted).
``--qgis``: ``svgtile:fill`` through ``qgis_process.bin`` on ``examples/units.gpkg`` (the whole
run: QGIS start, the svgtile process, writing), against QGIS's own ``native:randompointsinpolygons``
with the same number of points, in a throw-away QGIS profile.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from svgtile.apps.gisout import write_placements  # noqa: E402
from svgtile.apps.load import load_exemplar  # noqa: E402
from svgtile.core.region import Region  # noqa: E402
from svgtile.engines import synthesize  # noqa: E402


def bench_write(motifs: int, folder: Path) -> None:
    ex, stats = load_exemplar(str(ROOT / "exemplars" / "gravel.svg"))
    side = (motifs / len(ex.motifs)) ** 0.5 * 60
    arr = synthesize(ex, Region.rectangle(side, side), "patch", seed=1, stats=stats, boundary="inside").arrangement
    parts = [(ex, arr, None, None)]
    print("| format | motifs | write (s) | size (MB) |\n|---|---:|---:|---:|")
    for suffix, crs in ((".geojson", None), (".gpkg", "EPSG:32633"), (".shp", "EPSG:32633"), (".fgb", "EPSG:32633")):
        out = folder / f"t{suffix}"
        t = time.perf_counter()
        write_placements(parts, out, crs=crs)
        wall = time.perf_counter() - t
        size = sum(p.stat().st_size for p in folder.glob("t.*") if p.suffix in (suffix, ".dbf", ".shx", ".prj", ".cpg")
                   or p.suffix == suffix)  # fmt: skip
        print(f"| {suffix} | {len(arr):,} | {wall:.2f} | {size / 1e6:.1f} |")
        for p in folder.glob("t.*"):
            p.unlink()


def bench_qgis(folder: Path) -> None:
    from svgtile.apps import qgis as qg

    home, runtime = folder / "home", folder / "xdg"
    runtime.mkdir(mode=0o700)
    env = {**os.environ, "HOME": str(home), "XDG_DATA_HOME": str(home / "share"), "XDG_RUNTIME_DIR": str(runtime),
           "QT_QPA_PLATFORM": "offscreen"}  # fmt: skip
    env.pop("PYTHONPATH", None)
    qg.install(home / "share" / "QGIS" / "QGIS3" / "profiles" / "default", python=sys.executable)
    units = f"{ROOT / 'examples' / 'units.gpkg'}|layername=units"

    def run(*args):
        t = time.perf_counter()
        done = subprocess.run(["qgis_process.bin", "run", *args], env=env, capture_output=True, text=True, timeout=900)
        wall = time.perf_counter() - t
        if done.returncode != 0:
            raise SystemExit(done.stdout[-2000:] + done.stderr[-2000:])
        return wall, json.loads(done.stdout[done.stdout.index("{"):])["results"]

    wall, res = run("svgtile:fill", "--json", "--", f"INPUT={units}", f"EXEMPLAR={ROOT / 'exemplars' / 'gravel.svg'}",
                    "SEED=1", f"OUTPUT={folder / 'svgtile.gpkg'}")  # fmt: skip
    from pyogrio import read_info

    n = read_info(res["OUTPUT"])["features"]
    print(f"| svgtile:fill (patch, gravel) | {n:,} | {wall:.1f} |")
    wall, _ = run("native:randompointsinpolygons", "--json", "--", f"INPUT={units}", f"POINTS_NUMBER={n // 2}",
                  "MIN_DISTANCE=2", f"OUTPUT={folder / 'native.shp'}")  # fmt: skip
    print(f"| native:randompointsinpolygons (min distance 2) | {n // 2 * 2:,} | {wall:.1f} |")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--motifs", type=int, default=100_000)
    parser.add_argument("--qgis", action="store_true")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        bench_write(args.motifs, Path(tmp))
        if args.qgis:
            print("\n| run | points | wall (s) |\n|---|---:|---:|")
            bench_qgis(Path(tmp))


if __name__ == "__main__":
    main()
