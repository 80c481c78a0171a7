"""End to end in real Inkscape: the installed extension fills a container with a hole inside a
transformed layer, Undo restores the document, and Inkscape's own Python and inkex run it.

Inkscape (1.2) registers effect actions only with a GUI, so it runs under ``xvfb-run`` with
``--batch-process``, always inside ``timeout`` (anything on stderr would open a modal dialog and
hang the batch).  Extension parameters come from the test profile's ``preferences.xml``.
Skipped when Inkscape or xvfb-run is absent; ``.ci/run`` installs both.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely
import svgelements as se
from shapely import affinity

from svgtile.apps import inkscape as ink
from svgtile.core.region import winding_fill

INKSCAPE, XVFB = shutil.which("inkscape"), shutil.which("xvfb-run")
pytestmark = pytest.mark.skipif(not (INKSCAPE and XVFB), reason="needs Inkscape and xvfb-run (apt-get install inkscape xvfb)")

DOC = Path(__file__).resolve().parent / "inkscape_data" / "svg" / "fill.svg"
SVG = "{http://www.w3.org/2000/svg}"
HREF = "{http://www.w3.org/1999/xlink}href"
ACTION = "org.svgtile.fill-with-texture.noprefs"
PREF = "org.svgtile.fill_with_texture"
PROTOS = {"dot": shapely.Point(0, 0).buffer(1.5, 64), "bar": shapely.box(-2, -0.5, 2, 0.5)}
TIMEOUT = 180


def _fill_area() -> shapely.Geometry:
    """fill.svg's container in document coordinates: an 80 x 60 rectangle with a 30 x 20 hole in
    a layer translate(60 30) rotate(10) scale(1.5)."""
    local = shapely.box(0, 0, 80, 60).difference(shapely.box(25, 20, 55, 40))
    return affinity.translate(affinity.rotate(affinity.scale(local, 1.5, 1.5, origin=(0, 0)), 10, origin=(0, 0)), 60, 30)


@pytest.fixture(scope="module")
def profile(tmp_path_factory):
    """An Inkscape profile folder of its own with the extension installed for this Python."""
    folder = tmp_path_factory.mktemp("inkscape-profile")
    ink.install(folder, python=sys.executable)
    return folder


def _inkscape(profile: Path, tmp: Path, actions: str, prefs: dict[str, str] | None = None) -> Path:
    """Open a copy of fill.svg, run ``actions``, save as plain SVG; returns the saved file."""
    attrs = " ".join(f'{PREF}.{k}="{v}"' for k, v in (prefs or {}).items())
    (profile / "preferences.xml").write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n<inkscape version="1" '
        'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape">\n'
        f'  <group id="extensions" {attrs}/>\n</inkscape>\n'
    )
    doc = tmp / "in.svg"
    shutil.copyfile(DOC, doc)
    out = tmp / f"out-{len(list(tmp.glob('out-*')))}.svg"
    env = {**os.environ, "INKSCAPE_PROFILE_DIR": str(profile), "HOME": str(tmp)}
    cmd = ["timeout", str(TIMEOUT), XVFB, "-a", INKSCAPE, "--with-gui", "--batch-process",
           f"--actions={actions};export-filename:{out};export-plain-svg;export-do", str(doc)]  # fmt: skip
    done = subprocess.run(cmd, env=env, capture_output=True, text=True, stdin=subprocess.DEVNULL, timeout=TIMEOUT + 30)
    assert done.returncode == 0, done.stderr[-2000:]
    assert out.is_file(), done.stderr[-2000:]
    assert DOC.read_bytes() == doc.read_bytes()  # the input file is never written
    return out


def _matrix(el: ET.Element) -> se.Matrix:
    return se.Matrix(el.get("transform") or "")


def _composed(path: list[ET.Element]) -> se.Matrix:
    m = se.Matrix()
    for el in reversed(path):  # innermost first: svgelements composes left to right
        m = m * _matrix(el)
    return m


def _textures(root: ET.Element) -> list[tuple[list[ET.Element], ET.Element]]:
    """(ancestors root-first, group) of every texture group."""
    found = []

    def walk(el, chain):
        for child in el:
            if child.tag == f"{SVG}g" and (child.get("id") or "").startswith("svgtile-texture"):
                found.append(([*chain, child], child))
            else:
                walk(child, [*chain, child])

    walk(root, [])
    return found


def _footprints(chain: list[ET.Element], group: ET.Element) -> list[tuple[str, shapely.Geometry]]:
    base = _composed(chain)
    out = []
    for use in group:
        m = base if not use.get("transform") else _matrix(use) * base
        out.append((use.get(HREF)[1:], affinity.affine_transform(PROTOS[use.get(HREF)[1:]], [m.a, m.c, m.b, m.d, m.e, m.f])))
    return out


@pytest.mark.parametrize("boundary", ["clip", "inside", "centroid", "none"])
def test_fill_in_real_inkscape(profile, tmp_path, boundary):
    out = _inkscape(profile, tmp_path, f"select-by-id:exemplar,container;{ACTION}", {"boundary": boundary, "seed": "4"})
    root = ET.parse(out).getroot()
    (chain, group), = _textures(root)
    parent = chain[-2]
    siblings = list(parent)
    assert parent.get("id") == "layer-map"
    assert siblings[siblings.index(group) - 1].get("id") == "container"  # right above it
    symbols = {s.get("id") for s in root.iter(f"{SVG}symbol")}
    assert symbols == {"dot", "bar"}  # nothing added: the document's own symbols
    for use in root.iter(f"{SVG}use"):
        assert use.get(HREF)[1:] in symbols
    found = _footprints(chain, group)
    assert len(found) > 100 and {h for h, _ in found} == {"dot", "bar"}
    area = _fill_area()
    geoms = np.array([g for _, g in found])
    centres = shapely.centroid(geoms)
    if boundary == "inside":
        assert shapely.contains(area.buffer(1e-3), geoms).all()
    elif boundary == "centroid":
        assert shapely.contains(area.buffer(1e-3), centres).all()
        assert not shapely.contains(area, geoms).all()
    else:
        assert shapely.intersects(area, geoms).all()
        assert not shapely.contains(area, geoms).all()
    clip = group.get("clip-path")
    if boundary != "clip":
        assert clip is None
        return
    clip_el = next(c for c in root.iter(f"{SVG}clipPath") if f"url(#{c.get('id')})" == clip)
    (path,) = list(clip_el)
    rings = [np.array([(seg.end.x, seg.end.y) for seg in sub]) for sub in se.Path(path.get("d")).as_subpaths()]
    m = _composed(chain)
    clip_area = winding_fill([np.c_[r, np.ones(len(r))] @ np.array([[m.a, m.b], [m.c, m.d], [m.e, m.f]]) for r in rings], "evenodd")
    assert clip_area.symmetric_difference(area).area < 1e-3 * area.area


def _canonical(path: Path) -> str:
    return ET.canonicalize(from_file=str(path), strip_text=True)


def test_undo_restores_the_document(profile, tmp_path):
    select = "select-by-id:exemplar,container"
    untouched = _inkscape(profile, tmp_path, select)
    filled = _inkscape(profile, tmp_path, f"{select};{ACTION}")
    undone = _inkscape(profile, tmp_path, f"{select};{ACTION};undo")
    redone = _inkscape(profile, tmp_path, f"{select};{ACTION};undo;redo")
    assert _textures(ET.parse(filled).getroot())
    assert _canonical(undone) == _canonical(untouched)  # one Undo takes the whole effect back
    assert _canonical(redone) == _canonical(filled)


SYSTEM_PYTHON = "/usr/bin/python3"


def _inkscape_extensions() -> Path:
    done = subprocess.run([INKSCAPE, "--system-data-directory"], capture_output=True, text=True, timeout=60)
    return Path(done.stdout.strip()) / "extensions"


@pytest.mark.skipif(not Path(SYSTEM_PYTHON).is_file(), reason="Inkscape's Python is not /usr/bin/python3 here")
def test_inkscape_python_and_bundled_inkex(profile, tmp_path):
    """The effect as Inkscape runs it (its Python, its bundled inkex, cwd = the extension folder):
    success prints nothing; an error prints one line and writes no document."""
    script = profile / "extensions" / "svgtile" / "svgtile_fill.py"
    env = {**os.environ, "PYTHONPATH": str(_inkscape_extensions())}
    env.pop("SVGTILE_PYTHON", None)
    doc = tmp_path / "in.svg"
    shutil.copyfile(DOC, doc)

    def run(*ids):
        return subprocess.run([SYSTEM_PYTHON, str(script), *(f"--id={i}" for i in ids), str(doc)], env=env,
                              cwd=script.parent, capture_output=True, timeout=TIMEOUT)  # fmt: skip

    ok = run("exemplar", "container")
    assert ok.returncode == 0 and ok.stderr == b""
    assert b"svgtile-texture" in ok.stdout and b'xlink:href="#dot"' in ok.stdout
    bad = run("container")
    assert bad.returncode != 0 and bad.stdout == b""
    assert bad.stderr.decode().strip().startswith("svgtile: no exemplar selected")
    assert doc.read_bytes() == DOC.read_bytes()
