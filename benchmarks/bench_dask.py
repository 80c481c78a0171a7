"""Benchmark ``svgtile map --scheduler ADDRESS``: a many-unit map plus one huge unit on a Dask
``LocalCluster`` (issue 19 item 5), against single-process ``svgtile synth``.

The map is made up here, as GeoJSON: a grid of ``--units`` square units of the ``patch`` class
(gravel, run whole: patch is not tile-exact) and one square basin of the ``tile`` class (gravel,
cut into ``--tile-size`` tiles), sized so that the units hold about ``--motifs`` motifs in all,
``--big`` of them in the basin.  The command runs in a process of its own (the *writer*, whose
peak memory is measured), against a LocalCluster of ``--workers`` single-threaded worker
processes started here (their peak memory and CPU time are read from them after the run).

The baseline is ``svgtile synth`` in one process: the patch engine over a square of about
``--baseline`` motifs and the tile engine over a square of about ``--big`` / 4.  Motifs per
CPU-second are compared (the machine may be shared: wall time alone would measure the others).

Run by hand:  python benchmarks/bench_dask.py [--motifs 10e6] [--big 2e6] [--units 400] [--workers 2]
It prints JSON and a Markdown table for benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
EXEMPLAR = HERE.parent / "exemplars" / "gravel.svg"
SVGTILE = [sys.executable, "-m", "svgtile"]


def density() -> float:
    """Motifs per unit² the engines give gravel (the exemplar's own density)."""
    from svgtile import read_exemplar

    ex = read_exemplar(EXEMPLAR)
    return len(ex.motifs) / ex.region.area


def make_map(folder: Path, motifs: float, big: float, units: int) -> None:
    rho = density()
    basin = math.sqrt(big / rho)
    side = math.sqrt((motifs - big) / units / rho)
    n = math.ceil(math.sqrt(units))
    feats = [{"type": "Feature", "id": "basin", "properties": {"class": "basin"},
              "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [basin, 0], [basin, basin], [0, basin], [0, 0]]]}}]  # fmt: skip
    for k in range(units):
        x, y = basin + (k % n) * side, (k // n) * side
        ring = [[x, y], [x + side, y], [x + side, y + side], [x, y + side], [x, y]]
        feats.append({"type": "Feature", "id": f"u{k}", "properties": {"class": "unit"},
                      "geometry": {"type": "Polygon", "coordinates": [ring]}})  # fmt: skip
    (folder / "map.geojson").write_text(json.dumps({"type": "FeatureCollection", "features": feats}))
    (folder / "styles.toml").write_text(f"""seed = 1
[classes.basin]
exemplar = "{EXEMPLAR}"
engine = "tile"
[classes.unit]
exemplar = "{EXEMPLAR}"
engine = "patch"
""")


def timed(cmd: list[str]) -> dict:
    """Run ``cmd``; its wall time, CPU time and peak memory (it is the only child then)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed:\n{proc.stderr[-2000:]}")
    return {"wall_s": round(wall, 1), "cpu_s": round(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, 1),
            "peak_mib": round(after.ru_maxrss / 1024)}  # fmt: skip


def count_uses(path: Path) -> int:
    n = 0
    with open(path, "rb") as fh:
        while chunk := fh.read(1 << 24):
            n += chunk.count(b"<use ")
    return n


def worker_usage() -> tuple[int, float]:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, os.times().user + os.times().system


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--motifs", type=float, default=10e6)
    ap.add_argument("--big", type=float, default=2e6)
    ap.add_argument("--units", type=int, default=400)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--tile-size", type=float, default=1500.0)
    ap.add_argument("--baseline", type=float, default=2e5)
    ap.add_argument("--folder", default=None)
    args = ap.parse_args()
    from distributed import Client, LocalCluster

    folder = Path(args.folder or tempfile.mkdtemp(prefix="svgtile-bench-dask-"))
    make_map(folder, args.motifs, args.big, args.units)
    rho = density()
    out: dict = {"machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
                 "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "load_before": os.getloadavg(),
                 "args": vars(args)}  # fmt: skip
    with LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None) as lc, \
            Client(lc) as client:  # fmt: skip
        start = client.run(worker_usage)
        run = timed([*SVGTILE, "map", str(folder / "map.geojson"), "--styles", str(folder / "styles.toml"),
                     "-o", str(folder / "map.svg"), "--scheduler", lc.scheduler_address,
                     "--tile-size", str(args.tile_size)])  # fmt: skip
        end = client.run(worker_usage)
    out["map"] = {"wall_s": run["wall_s"], "writer_peak_mib": run["peak_mib"], "writer_cpu_s": run["cpu_s"],
                  "workers_peak_mib": [round(end[w][0] / 1024) for w in sorted(end)],
                  "workers_cpu_s": [round(end[w][1] - start[w][1], 1) for w in sorted(end)],
                  "motifs": count_uses(folder / "map.svg"), "file_mib": round((folder / "map.svg").stat().st_size / 2**20)}  # fmt: skip
    out["load_after_map"] = os.getloadavg()
    base = {}
    for engine, count in (("patch", args.baseline), ("tile", args.big / 4)):
        side = math.sqrt(count / rho)
        target = folder / f"synth-{engine}.svg"
        r = timed([*SVGTILE, "synth", str(EXEMPLAR), "--engine", engine, "--size", f"{side:.0f}", "--seed", "1",
                   "-o", str(target), "--force"])  # fmt: skip
        r["motifs"] = count_uses(target)
        target.unlink()
        base[engine] = r
    out["synth"] = base
    m = out["map"]
    cpu = sum(m["workers_cpu_s"]) + m["writer_cpu_s"]
    out["map"]["motifs_per_cpu_s"] = round(m["motifs"] / cpu)
    out["map"]["motifs_per_core_wall_s"] = round(m["motifs"] / (m["wall_s"] * args.workers))
    for r in base.values():
        r["motifs_per_cpu_s"] = round(r["motifs"] / r["cpu_s"])
    (folder / "map.svg").unlink()
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
