"""Render every bundled exemplar beside a texture synthesized from it, for exemplars/README.md.

Needs the optional renderer: ``pip install -e '.[png]'`` (resvg).  Writes
``exemplars/previews/NAME.png`` (the exemplar) and ``NAME-texture.png`` (a 240 × 150 texture,
seed 1, default options), both at the same scale so motifs compare at a glance, and puts both images under the ``<!-- preview:NAME -->`` line of the
README.  Run from the repository root: ``python tools/make_previews.py``.
"""

from __future__ import annotations

import re
from pathlib import Path

import resvg_py

from svgtile import Region, analyze, read_exemplar
from svgtile.engines import synthesize
from svgtile.svg.writer import svg_document

ROOT = Path(__file__).resolve().parents[1]
EXEMPLARS = ROOT / "exemplars"
PREVIEWS = EXEMPLARS / "previews"
SIZE = (240.0, 150.0)
#: Pixels per user unit, the same for exemplar and texture.
SCALE = 3.0


def render(svg: str, width: int) -> bytes:
    return bytes(resvg_py.svg_to_bytes(svg_string=svg, width=width, background="white"))


def main() -> None:
    PREVIEWS.mkdir(exist_ok=True)
    readme = (EXEMPLARS / "README.md").read_text()
    for path in sorted(EXEMPLARS.glob("*.svg")):
        name = path.stem
        ex = read_exemplar(path)
        region = Region.rectangle(*SIZE)
        arr = synthesize(ex, region, "patch", seed=1, stats=analyze(ex)).arrangement
        text = svg_document(ex, arr, region, boundary="clip", params={"seed": 1})
        x0, _, x1, _ = ex.region.bounds
        (PREVIEWS / f"{name}.png").write_bytes(render(path.read_text(), round((x1 - x0) * SCALE)))
        (PREVIEWS / f"{name}-texture.png").write_bytes(render(text, round(SIZE[0] * SCALE)))
        images = (
            f"<!-- preview:{name} -->\n"
            f"![{name} exemplar](previews/{name}.png) ![{name}: {len(arr)} motifs synthesized on "
            f"{SIZE[0]:g} × {SIZE[1]:g}, seed 1](previews/{name}-texture.png)"
        )
        readme = re.sub(rf"<!-- preview:{re.escape(name)} -->(\n!\[[^\n]*)?", lambda _m, s=images: s, readme)
        print(f"{name}: {len(arr)} motifs")
    (EXEMPLARS / "README.md").write_text(readme)


if __name__ == "__main__":
    main()
