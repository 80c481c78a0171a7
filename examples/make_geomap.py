"""Write the synthetic geologic map ``examples/geomap.svg`` (and render the filled map to PNG).

The map is made up (CC0): five units — alluvium along a river (Qal), marsh (Qm), till (Qt),
shale (Ksh) with a breccia inlier (Tb) as a hole drawn with ``fill-rule="evenodd"`` — plus a
fault, a river line and labels, the things a texture must keep clear of.  The till is drawn inside
a translated group and its boundary with the shale is stated twice, as map editors do.

    python examples/make_geomap.py            # writes examples/geomap.svg
    python examples/make_geomap.py --render   # also renders examples/geomap-filled.svg to PNG
                                              # (needs the png extra: pip install -e '.[png]')
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import shapely

HERE = Path(__file__).parent
W, H = 480.0, 320.0


def units() -> dict[str, shapely.Geometry]:
    """The units as non-overlapping polygons covering the map."""
    frame = shapely.box(0, 0, W, H)
    t = np.linspace(-20, W + 20, 60)
    river_line = shapely.LineString(np.c_[t, 190 + 35 * np.sin(t / 70.0) + 12 * np.sin(t / 23.0)])
    qal = shapely.buffer(river_line, 22, quad_segs=8).intersection(frame)
    a = np.linspace(0, 2 * np.pi, 48, endpoint=False)
    qm = shapely.Polygon(np.c_[95 + 80 * np.cos(a), 265 + 42 * np.sin(a) * (1 + 0.15 * np.cos(3 * a))])
    qm = qm.intersection(frame).difference(qal)
    x = np.linspace(0, W, 40)
    top = shapely.Polygon(np.r_[np.c_[x, 105 + 18 * np.sin(x / 45.0)], [[W, 0], [0, 0]]])
    qt = top.difference(qal)
    tb = shapely.Polygon(np.c_[365 + 42 * np.cos(a) * (1 + 0.1 * np.sin(4 * a)), 262 + 30 * np.sin(a)])
    ksh = frame.difference(shapely.union_all([qal, qm, qt, tb]))
    return {"Qal": qal, "Qm": qm, "Qt": qt, "Ksh": ksh, "Tb": tb}, river_line


def path_d(geom: shapely.Geometry, dy: float = 0.0) -> str:
    parts = []
    for poly in shapely.get_parts(geom):
        for ring in [poly.exterior, *poly.interiors]:
            xy = np.asarray(ring.coords)[:-1]
            parts.append("M" + " L".join(f"{x:.2f} {y + dy:.2f}" for x, y in xy) + " Z")
    return " ".join(parts)


COLOURS = {"Qal": "#fff3b0", "Qm": "#d8efe4", "Qt": "#f3e2c7", "Ksh": "#d9d4e8", "Tb": "#f4c9b8"}


def geomap() -> str:
    u, river = units()
    shale = u["Ksh"]
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<svg xmlns="http://www.w3.org/2000/svg" '
        'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
        f'width="{W:g}" height="{H:g}" viewBox="0 0 {W:g} {H:g}">',
        "  <!-- a made-up geologic map for svgtile (CC0); see examples/make_geomap.py -->",
        '  <g id="units" inkscape:groupmode="layer" inkscape:label="Units" stroke="#555" stroke-width="0.6">',
        f'    <path id="qal" class="Qal" fill="{COLOURS["Qal"]}" d="{path_d(u["Qal"])}"/>',
        f'    <path id="qm" class="Qm" fill="{COLOURS["Qm"]}" d="{path_d(u["Qm"])}"/>',
        # the till sits in a translated group, as after a move in Inkscape
        '    <g transform="translate(0 -10)">',
        f'      <path id="qt" inkscape:label="Qt" fill="{COLOURS["Qt"]}" d="{path_d(u["Qt"], 10.0)}"/>',
        "    </g>",
        # the shale with the breccia inlier as a second subpath: a hole by the even-odd rule
        f'    <path id="ksh" class="Ksh" fill="{COLOURS["Ksh"]}" fill-rule="evenodd" d="{path_d(shale)}"/>',
        f'    <path id="tb" class="Tb" fill="{COLOURS["Tb"]}" d="{path_d(u["Tb"])}"/>',
        "  </g>",
        f'  <path id="river" d="{path_d_line(river)}" fill="none" stroke="#3a7bd5" stroke-width="2"/>',
        '  <g id="faults" fill="none" stroke="#000" stroke-width="1.4">',
        '    <path d="M 250 -5 L 285 120 L 300 200 L 330 330"/>',
        "  </g>",
        '  <g id="labels" font-family="sans-serif" font-size="13" font-weight="bold" fill="#222" text-anchor="middle">',
        '    <text x="170" y="60">Qt</text>',
        '    <text x="90" y="272">Qm</text>',
        '    <text x="405" y="170">Qal</text>',
        '    <text x="150" y="135">Ksh</text>',
        '    <text x="365" y="267">Tb</text>',
        '    <text x="420" y="308" font-size="9" font-weight="normal">svgtile example</text>',
        "  </g>",
        "</svg>",
    ]
    return "\n".join(lines) + "\n"


def path_d_line(line: shapely.LineString) -> str:
    xy = np.asarray(line.coords)
    return "M" + " L".join(f"{x:.2f} {y:.2f}" for x, y in xy)


def render(svg: Path, png: Path, width: int = 960) -> None:
    """The README's picture, with svgtile's one renderer (labels in DejaVu Sans, a system font)."""
    from svgtile.apps.preview import render_png

    png.write_bytes(render_png(svg.read_text(), width))


if __name__ == "__main__":
    (HERE / "geomap.svg").write_text(geomap())
    if "--render" in sys.argv[1:]:
        render(HERE / "geomap-filled.svg", HERE / "geomap-filled.png")
