"""svgtile inside Inkscape: installing the extension, and the fill it asks svgtile to do.

The extension (``inkscape_ext/svgtile_fill.py``, menu Extensions ▸ Render ▸ svgtile ▸ Fill with
Texture…) runs in Inkscape's own Python, which has inkex but usually not shapely or scipy.  It
therefore does no synthesis itself.  It writes the selection to a temporary folder —

* ``exemplar.svg``: the exemplar group, wrapped in its ancestors' composed transform so its
  coordinates are the document's, plus copies of the elements it references (symbols …);
* ``containers.json``: every container as flattened rings in document coordinates, with its
  ``fill-rule`` (format below);

runs ``PYTHON -m svgtile inkscape fill exemplar.svg containers.json --out-dir DIR [options]``
with the interpreter recorded by ``svgtile inkscape install``, and inserts the textures it finds
in ``DIR/texture-<i>.svg``.  Everything svgtile needs is in this module; the extension talks to
it through that command line only.

``containers.json``::

    {"containers": [{"id": "path12", "fill_rule": "evenodd",
                     "rings": [[[x, y], [x, y], ...], ...]}, ...]}
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import shapely

from svgtile.core.region import FILL_RULES, Region, winding_fill
from svgtile.errors import RegionError, SvgtileError
from svgtile.files import write_file

if TYPE_CHECKING:
    from svgtile.engines.base import EngineParams

#: The files of the extension, as found in the source tree's ``inkscape_ext/``.
EXTENSION_FILES = ("svgtile_fill.inx", "svgtile_fill.py")
#: Written by :func:`install` next to the extension: which Python runs svgtile.
CONFIG_NAME = "svgtile_fill.json"
#: The extension's folder inside Inkscape's ``extensions`` folder.
FOLDER = "svgtile"
#: Name of the texture file for container ``i`` in the output folder.
TEXTURE_NAME = "texture-{}.svg"


class InstallError(SvgtileError):
    """The extension cannot be installed or uninstalled where asked."""


# ----------------------------------------------------------------------------- install


def extension_source() -> Path:
    """The folder holding :data:`EXTENSION_FILES`.

    A source checkout (also an editable install) has it beside the package; a wheel installs the
    files as data under ``<prefix>/share/svgtile/inkscape``.
    """
    candidates = [
        Path(__file__).resolve().parents[2] / "inkscape_ext",  # svgtile/apps/inkscape.py
        Path(sys.prefix) / "share" / "svgtile" / "inkscape",
    ]
    for folder in candidates:
        if all((folder / name).is_file() for name in EXTENSION_FILES):
            return folder
    raise InstallError(
        "the extension files are missing from this svgtile installation "
        f"(looked in {', '.join(str(c) for c in candidates)})"
    )


def user_data_dir() -> Path:
    """Inkscape's user data folder (the one holding ``extensions/``).

    ``$INKSCAPE_PROFILE_DIR`` if set (Inkscape honours it too), else what ``inkscape
    --user-data-directory`` answers, else the platform's default.
    """
    env = os.environ.get("INKSCAPE_PROFILE_DIR")
    if env:
        return Path(env)
    exe = shutil.which("inkscape")
    if exe:
        try:
            done = subprocess.run([exe, "--user-data-directory"], capture_output=True, text=True,
                                  timeout=60, stdin=subprocess.DEVNULL)  # fmt: skip
            answer = done.stdout.strip().splitlines()
            if done.returncode == 0 and answer and Path(answer[-1]).is_absolute():
                return Path(answer[-1])
        except (OSError, subprocess.SubprocessError):
            pass
    if sys.platform == "win32":
        return Path(os.environ.get("APPDATA", Path.home() / "AppData" / "Roaming")) / "inkscape"
    if sys.platform == "darwin":
        return Path.home() / "Library" / "Application Support" / "org.inkscape.Inkscape" / "config" / "inkscape"
    return Path(os.environ.get("XDG_CONFIG_HOME") or Path.home() / ".config") / "inkscape"


def install(user_dir: str | Path | None = None, *, python: str | None = None) -> Path:
    """Copy the extension into ``<user_dir>/extensions/svgtile`` and record ``python``.

    Parameters
    ----------
    user_dir : Inkscape's user data folder; :func:`user_data_dir` if None
    python : the interpreter that runs svgtile for the extension; this one if None

    Returns
    -------
    The extension folder.  Installing again replaces the files (and the recorded Python).
    """
    from svgtile import __version__

    source = extension_source()
    target = Path(user_dir if user_dir is not None else user_data_dir()) / "extensions" / FOLDER
    if target.exists() and not target.is_dir():
        raise InstallError("exists and is not a folder", source=str(target))
    if target.is_dir() and any(target.iterdir()) and not (target / CONFIG_NAME).is_file():
        raise InstallError("exists but was not made by 'svgtile inkscape install'; remove it first", source=str(target))
    try:
        target.mkdir(parents=True, exist_ok=True)
        for name in EXTENSION_FILES:
            shutil.copyfile(source / name, target / name)
        config = {"python": python or sys.executable, "svgtile": __version__}
        write_file(json.dumps(config, indent=2) + "\n", target / CONFIG_NAME)
    except OSError as exc:
        raise InstallError(f"cannot install here ({exc.strerror or exc})", source=str(target)) from None
    return target


def uninstall(user_dir: str | Path | None = None) -> Path:
    """Remove what :func:`install` put into ``<user_dir>/extensions/svgtile``; returns that folder."""
    target = Path(user_dir if user_dir is not None else user_data_dir()) / "extensions" / FOLDER
    if not (target / CONFIG_NAME).is_file():
        raise InstallError("the svgtile extension is not installed here", source=str(target))
    try:
        if target.is_symlink():
            target.unlink()
        else:
            shutil.rmtree(target)
    except OSError as exc:
        raise InstallError(f"cannot remove ({exc.strerror or exc})", source=str(target)) from None
    return target


# ----------------------------------------------------------------------------- containers


def read_containers(path: str | Path) -> list[tuple[str, shapely.Geometry]]:
    """Read ``containers.json`` (see the module docstring): (id, area) per container, in order."""
    source = str(path)
    try:
        doc = json.loads(Path(path).read_text(encoding="utf-8"))
        items = doc["containers"]
        out = []
        for item in items:
            ident, rule = str(item["id"]), item.get("fill_rule", "nonzero")
            if rule not in FILL_RULES:
                raise ValueError(f"unknown fill rule {rule!r}")
            rings = [np.asarray(r, dtype=np.float64).reshape(-1, 2) for r in item["rings"]]
            if not all(np.isfinite(r).all() for r in rings):
                raise ValueError(f"container {ident!r} has coordinates that are not finite")
            out.append((ident, winding_fill(rings, rule)))
    except OSError as exc:
        raise RegionError(f"cannot read file ({exc.strerror or exc})", source=source) from None
    except RecursionError:
        raise RegionError("not a containers file (nested too deeply)", source=source) from None
    except (ValueError, KeyError, TypeError) as exc:
        raise RegionError(f"not a containers file ({' '.join(str(exc).split())})", source=source) from None
    if not out:
        raise RegionError("lists no containers", source=source)
    return out


# ----------------------------------------------------------------------------- fill


def fill(
    exemplar_path: str | Path,
    containers_path: str | Path,
    out_dir: str | Path,
    *,
    engine: str,
    seed: int,
    boundary: str,
    max_motifs: float,
    params: EngineParams | dict[str, object],
    load=None,
) -> list[Path]:
    """Synthesize a texture in every container; write ``out_dir/texture-<i>.svg`` for each.

    Parameters
    ----------
    exemplar_path : the exemplar SVG (read once)
    containers_path : ``containers.json``
    out_dir : an existing folder
    engine : a name in :data:`svgtile.engines.ENGINES`
    seed : every container is filled with a generator seeded by ``seed``, so a container's
        texture does not depend on the other containers selected
    boundary : how motifs meet a container's edge
    max_motifs : refuse a container whose estimated motif count is larger
    params : the engine's parameters (:func:`svgtile.engines.make_params`)
    load : ``load(path) -> (Exemplar, Stats)``; the CLI passes its own, which prints warnings

    Each file is what ``svgtile synth`` writes for that container's area (its bounding box is the
    viewBox, the clip path is the container's area in document coordinates).
    """
    from svgtile.apps.load import check_motif_count, check_work, load_exemplar
    from svgtile.engines import synthesize
    from svgtile.svg.writer import result_document

    containers = read_containers(containers_path)
    ex, stats = (load or load_exemplar)(str(exemplar_path))
    regions, total = [], 0.0
    for ident, shape in containers:
        try:
            region = Region(shape)
        except RegionError:
            raise RegionError(f"the shape {ident!r} encloses no area to fill") from None
        total += check_motif_count(ex, stats, region, f"the shape {ident!r}", limit=max_motifs,
                                   hint="scale the exemplar up or fill a smaller shape")  # fmt: skip
        regions.append((ident, region))
    # Inkscape waits for the extension: a run of minutes is refused before it starts
    check_work(total, engine, "the selection", params=params)
    written = []
    for i, (ident, region) in enumerate(regions):
        result = synthesize(ex, region, engine, seed=seed, stats=stats, boundary=boundary, params=params)
        out = Path(out_dir) / TEXTURE_NAME.format(i)
        write_file(result_document(result, container=ident), out)
        written.append(out)
    return written

