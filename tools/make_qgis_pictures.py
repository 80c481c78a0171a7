"""Make the README's QGIS pictures in real QGIS, headless: ``docs/qgis-dialog.png`` and
``docs/qgis-result.png``.

Run from the repository root with svgtile's Python (needs QGIS, xvfb-run)::

    python tools/make_qgis_pictures.py

It converts ``examples/units.geojson`` to a GeoPackage (EPSG:32633, metres), installs the plugin
into a throw-away QGIS profile, fills the units through ``qgis_process.bin run svgtile:fill``
(the algorithm the dialog runs), then starts QGIS desktop under ``xvfb-run`` with
``tools/qgis_grab.py``, which opens the dialog and grabs it and the main window.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import shapely
from pyogrio import raw

from svgtile.apps import qgis as qg

ROOT = Path(__file__).resolve().parents[1]


def main() -> int:
    work = Path(tempfile.mkdtemp(prefix="svgtile-qgis-"))
    home, runtime = work / "home", work / "xdg"
    runtime.mkdir(mode=0o700)
    env = {**os.environ, "HOME": str(home), "XDG_DATA_HOME": str(home / "share"), "XDG_RUNTIME_DIR": str(runtime),
           "SVGTILE_GRAB": str(work)}  # fmt: skip
    env.pop("PYTHONPATH", None)
    qg.install(home / "share" / "QGIS" / "QGIS3" / "profiles" / "default", python=sys.executable)
    feats = json.loads((ROOT / "examples" / "units.geojson").read_text())["features"]
    geoms = np.array([shapely.from_geojson(json.dumps(f["geometry"])) for f in feats])
    raw.write(work / "units.gpkg", shapely.to_wkb(geoms),
              [np.array([f["properties"]["unit"] for f in feats], dtype=object),
               np.array([f["properties"]["name"] for f in feats], dtype=object)],
              ["unit", "name"], layer="units", geometry_type="Polygon", crs="EPSG:32633",
              dataset_options={"VERSION": "1.2"})  # fmt: skip
    shutil.copyfile(ROOT / "exemplars" / "gravel.svg", work / "gravel.svg")
    done = subprocess.run(["qgis_process.bin", "run", "svgtile:fill", "--", f"INPUT={work / 'units.gpkg'}|layername=units",
                           f"EXEMPLAR={work / 'gravel.svg'}", "CLASS_FIELD=unit", "SEED=1", "P_GRID=2",
                           f"OUTPUT={work / 'texture.gpkg'}"], env={**env, "QT_QPA_PLATFORM": "offscreen"},
                          capture_output=True, text=True, timeout=600)  # fmt: skip
    if done.returncode != 0:
        print(done.stdout[-3000:], done.stderr[-3000:], file=sys.stderr)
        return 1
    try:
        subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", "qgis.bin", "--nologo", "--noversioncheck",
                        "--code", str(ROOT / "tools" / "qgis_grab.py")], env=env, timeout=180,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)  # fmt: skip
    except subprocess.TimeoutExpired:
        print("QGIS did not quit in time", file=sys.stderr)
    for name in ("dialog", "result"):
        if not (work / f"{name}.png").is_file():
            print(f"QGIS made no {name}.png (see {work})", file=sys.stderr)
            return 1
        shutil.copyfile(work / f"{name}.png", ROOT / "docs" / f"qgis-{name}.png")
    print(f"wrote docs/qgis-dialog.png and docs/qgis-result.png (work folder {work})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
