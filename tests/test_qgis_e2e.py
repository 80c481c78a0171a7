"""End to end in real QGIS, headless: the installed Processing plugin fills a GeoPackage whose unit
has a hole, through ``qgis_process.bin`` (issue 18 item 4), and QGIS draws the result with the
exported symbols.

``qgis_process`` (the wrapper) adds an option QGIS 3.22 rejects, so the binary is called
directly.  QGIS runs with a private HOME / XDG_DATA_HOME (so its default profile is the test's),
``QT_QPA_PLATFORM=offscreen`` and a private ``XDG_RUNTIME_DIR``.  Skipped only when QGIS is absent
(no ``qgis_process.bin``, or no PyQGIS in ``/usr/bin/python3``); ``.ci/run`` installs it.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import shapely
from pyogrio import raw

from svgtile.apps import qgis as qg
from svgtile.apps.load import load_exemplar
from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import world_footprints
from svgtile.core.region import BOUNDARY_MODES
from svgtile.gis import geojson

QGIS_PROCESS = shutil.which("qgis_process.bin")
SYSTEM_PYTHON = "/usr/bin/python3"


def _pyqgis() -> bool:
    try:
        return subprocess.run([SYSTEM_PYTHON, "-c", "import qgis.core"], capture_output=True, timeout=60).returncode == 0
    except (OSError, subprocess.SubprocessError):
        return False


pytestmark = pytest.mark.skipif(
    not (QGIS_PROCESS and _pyqgis()),
    reason="needs QGIS: qgis_process.bin and PyQGIS (apt-get install qgis qgis-providers python3-qgis)",
)

RENDER = Path(__file__).resolve().parents[1] / "tools" / "qgis_render.py"
CRS = "EPSG:32633"
OUTER = shapely.box(0, 0, 80, 60)
HOLE = shapely.box(30, 20, 50, 40)
HOLED = OUTER.difference(HOLE)
NEIGHBOUR = shapely.box(80, 0, 140, 60)
TIMEOUT = 240


@pytest.fixture
def qgis_env(tmp_path):
    """Environment of a QGIS whose default profile is in tmp_path, with the plugin installed."""
    home = tmp_path / "home"
    runtime = tmp_path / "xdg"
    runtime.mkdir(mode=0o700)
    env = {**os.environ, "HOME": str(home), "XDG_DATA_HOME": str(home / "share"), "QT_QPA_PLATFORM": "offscreen",
           "XDG_RUNTIME_DIR": str(runtime)}  # fmt: skip
    # QGIS embeds Debian's libpython, which finds its standard library from the first ``python3`` on
    # PATH: with a virtual environment (or pyenv) first, it loads that interpreter's and loses
    # PyQGIS ("Couldn't load SIP module").  Its Python must be the system's; svgtile's is named
    # to the plugin by absolute path.
    for name in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV"):
        env.pop(name, None)
    env["PATH"] = os.pathsep.join(["/usr/bin", "/bin", *env.get("PATH", "").split(os.pathsep)])
    qg.install(home / "share" / "QGIS" / "QGIS3" / "profiles" / "default", python=sys.executable)
    return env


def qgis_process(env, *args):
    return subprocess.run([QGIS_PROCESS, *args], env=env, capture_output=True, text=True, timeout=TIMEOUT,
                          stdin=subprocess.DEVNULL)  # fmt: skip


def test_fill_polygons_with_texture_in_qgis(tmp_path, tiny, qgis_env):
    units = tmp_path / "units.gpkg"
    raw.write(units, shapely.to_wkb(np.array([HOLED, NEIGHBOUR])), [np.array(["Ksh", "Qal"], dtype=object)],
              ["unit"], layer="units", geometry_type="Polygon", crs=CRS)  # fmt: skip
    road = shapely.LineString([(90, 5), (130, 55)])  # across the plain unit: an avoid layer
    roads = tmp_path / "roads.gpkg"
    raw.write(roads, shapely.to_wkb(np.array([road])), [np.array(["A1"], dtype=object)], ["name"], layer="roads",
              geometry_type="LineString", crs=CRS)  # fmt: skip
    listed = qgis_process(qgis_env, "plugins")
    assert "* svgtile_qgis" in listed.stdout, listed.stdout + listed.stderr
    out = tmp_path / "texture.gpkg"
    done = qgis_process(qgis_env, "run", "svgtile:fill", "--json", "--", f"INPUT={units}", f"EXEMPLAR={tiny}",
                        "CLASS_FIELD=unit", f"BOUNDARY={BOUNDARY_MODES.index('inside')}", "SEED=3",
                        "P_GRID=2", f"AVOID={roads}|layername=roads", f"OUTPUT={out}")  # fmt: skip
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    answer = json.loads(done.stdout[done.stdout.index("{"):])
    assert answer["results"]["OUTPUT"] == str(out)
    # the layer: expected fields, the input's CRS, every motif inside its unit and clear of the hole
    meta, _, wkb, fields = raw.read(out, return_fids=True)
    assert meta["crs"] == CRS
    assert list(meta["fields"]) == ["kind", "angle", "scale", "size", "region", "class"]
    points, fields = shapely.from_wkb(wkb), dict(zip(meta["fields"], fields, strict=True))
    ksh = fields["class"] == "Ksh"
    assert ksh.sum() > 30 and (~ksh).sum() > 30
    assert shapely.within(points[ksh], HOLED).all() and not shapely.intersects(points, HOLE).any()
    assert shapely.within(points[~ksh], NEIGHBOUR).all()
    ex, _ = load_exemplar(str(tiny))
    index = {k.name: i for i, k in enumerate(ex.kinds)}
    xy = shapely.get_coordinates(points[ksh]) * [1.0, -1.0]
    motifs = Arrangement(np.array([index[k] for k in fields["kind"][ksh]]), xy, fields["angle"][ksh].astype(float),
                         fields["scale"][ksh].astype(float))  # fmt: skip
    feet = world_footprints(motifs, [k.prototype for k in ex.kinds])
    assert shapely.within(feet, geojson.flip(HOLED).buffer(1e-3)).all()  # --boundary inside: whole motifs
    qal = Arrangement(np.array([index[k] for k in fields["kind"][~ksh]]),
                      shapely.get_coordinates(points[~ksh]) * [1.0, -1.0], fields["angle"][~ksh].astype(float),
                      fields["scale"][~ksh].astype(float))  # fmt: skip
    clear = shapely.distance(world_footprints(qal, [k.prototype for k in ex.kinds]), geojson.flip(road))
    assert clear.min() >= 2.0 - 1e-3  # the avoid layer, grown by the default margin (2 map units)
    assert (tmp_path / "texture.qml").is_file() and (tmp_path / "texture-symbols" / "dot.svg").is_file()
    # QGIS draws it with the exported symbols (the .qml beside the layer is its default style)
    png = tmp_path / "texture.png"
    gray = tmp_path / "texture.gray"
    width, height = 560, 240
    drawn = subprocess.run([SYSTEM_PYTHON, str(RENDER), "--gray", str(gray), str(png), str(width), str(height),
                            str(out), str(units)], env=qgis_env, capture_output=True, text=True, timeout=TIMEOUT)  # fmt: skip
    assert drawn.returncode == 0, drawn.stderr[-2000:]
    assert "singleSymbol/SvgMarker" in drawn.stdout.splitlines()[0]
    head = png.read_bytes()[:24]
    assert head.startswith(b"\x89PNG") and int.from_bytes(head[16:20], "big") == width
    pixels = np.frombuffer(gray.read_bytes(), np.uint8).reshape(height, width)
    ink = pixels < 128
    assert ink.mean() > 0.01  # not blank
    # map (x, y) -> pixel: the extent is the units' bounds grown by 5 % about their centre
    x0, y0, x1, y1 = 0 - 7, 0 - 3, 140 + 7, 60 + 3
    scale = min(width / (x1 - x0), height / (y1 - y0))
    cx, cy = width / 2, height / 2

    def pixel(x, y):
        return int(cx + (x - 70) * scale), int(cy - (y - 30) * scale)

    (hx0, hy0), (hx1, hy1) = pixel(31, 39), pixel(49, 21)
    assert not ink[hy0:hy1, hx0:hx1].any()  # the hole stays empty
    (ux0, uy0), (ux1, uy1) = pixel(85, 55), pixel(135, 5)
    assert ink[uy0:uy1, ux0:ux1].mean() > 0.02  # the plain unit is filled with drawn motifs
    # drawn with the exported symbols, not QGIS's stand-in for an SVG it cannot find (which would
    # also leave ink): without the symbols folder the picture changes
    (tmp_path / "texture-symbols").rename(tmp_path / "moved-symbols")
    again = subprocess.run([SYSTEM_PYTHON, str(RENDER), "--gray", str(gray), str(png), str(width), str(height),
                            str(out), str(units)], env=qgis_env, capture_output=True, text=True, timeout=TIMEOUT)  # fmt: skip
    assert again.returncode == 0, again.stderr[-2000:]
    stand_in = np.frombuffer(gray.read_bytes(), np.uint8).reshape(height, width)
    assert (stand_in != pixels)[uy0:uy1, ux0:ux1].mean() > 0.01


def test_a_failure_is_reported_and_writes_nothing(tmp_path, qgis_env):
    units = tmp_path / "units.gpkg"
    raw.write(units, shapely.to_wkb(np.array([HOLED])), [np.array(["Ksh"], dtype=object)], ["unit"],
              layer="units", geometry_type="Polygon", crs=CRS)  # fmt: skip
    bad = tmp_path / "bad.svg"
    bad.write_text("<svg")
    out = tmp_path / "texture.gpkg"
    done = qgis_process(qgis_env, "run", "svgtile:fill", "--", f"INPUT={units}", f"EXEMPLAR={bad}", "SEED=1",
                        f"OUTPUT={out}")  # fmt: skip
    assert done.returncode != 0
    assert f"svgtile: error: {bad}" in done.stdout + done.stderr
    assert not out.exists()


PLUGIN_RUN = """
import sys
sys.path.insert(0, sys.argv[1])
from qgis.core import QgsProcessingException, QgsProcessingFeedback
from svgtile_qgis import algorithm
warn = "import sys; sys.stderr.write('svgtile: warning: polygon 1 not filled: no motif fits\\\\n' * 5000)"
algorithm.FillAlgorithm()._run([sys.executable, "-c", warn], QgsProcessingFeedback())
try:
    algorithm.FillAlgorithm()._run([sys.executable, "-c", warn + "; sys.exit('svgtile: error: x.gpkg: bad')"],
                                   QgsProcessingFeedback())
except QgsProcessingException as exc:
    print("raised:", exc)
"""


def test_the_plugin_reads_any_amount_of_messages(tmp_path, qgis_env):
    """svgtile's stderr is read while it runs: 300 kB of warnings (a layer of many unfilled
    polygons) once filled the pipe and stalled the algorithm for ever."""
    done = subprocess.run([SYSTEM_PYTHON, "-c", PLUGIN_RUN, str(RENDER.parents[1] / "qgis_ext")], env=qgis_env,
                          capture_output=True, text=True, timeout=60)  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    assert "raised: svgtile: error: x.gpkg: bad" in done.stdout
