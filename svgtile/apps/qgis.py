"""svgtile inside QGIS: installing the Processing plugin, and the fill it asks svgtile to do.

The plugin (``qgis_ext/svgtile_qgis``: Processing toolbox ▸ svgtile ▸ Fill polygons with
texture) runs in QGIS's own Python, which has no shapely or scipy and must not get them.  Like
the Inkscape extension (:mod:`svgtile.apps.inkscape`) it only translates: it runs ::

    PYTHON -m svgtile qgis fill LAYER_SPEC -o OUT.gpkg --with-style (--exemplar X.svg | --styles T.toml)
           [--class-field F] --engine E [engine options] --boundary B --unit U --seed S [--avoid SPEC …]

with the interpreter :func:`install` recorded in ``svgtile_qgis.json`` beside the plugin, and
loads ``OUT.gpkg`` (styled by ``OUT.qml``).  That JSON file also lists every engine and its
public parameters (:func:`plugin_config`), from which the plugin builds its dialog.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import sys
from dataclasses import replace
from pathlib import Path

from svgtile.apps.load import load_exemplar
from svgtile.apps.mapfill import MapFill, Style, Styles, cellular_classes, fill_regions, read_styles
from svgtile.apps.mapread import AVOID_MARGIN, MapRegion, read_avoid_shape
from svgtile.core.region import BOUNDARY_MODES
from svgtile.engines import ENGINES, engines_with, public_params
from svgtile.engines.base import draws_cells
from svgtile.errors import ParameterError, RegionError, SvgtileError
from svgtile.files import write_file
from svgtile.gis import layers

#: The plugin's folder name (QGIS's plugin id) and files, as found in ``qgis_ext/``.
PLUGIN = "svgtile_qgis"
PLUGIN_FILES = ("__init__.py", "algorithm.py", "metadata.txt", "plugin.py", "provider.py")
#: Written by :func:`install` beside the plugin: the Python that runs svgtile, and the engines.
CONFIG_NAME = "svgtile_qgis.json"


class InstallError(SvgtileError):
    """The plugin cannot be installed or uninstalled where asked."""


# ----------------------------------------------------------------------------- install


def plugin_source() -> Path:
    """The folder holding :data:`PLUGIN_FILES` (source checkout, or a wheel's shared data)."""
    candidates = [
        Path(__file__).resolve().parents[2] / "qgis_ext" / PLUGIN,  # svgtile/apps/qgis.py
        Path(sys.prefix) / "share" / "svgtile" / "qgis" / PLUGIN,
    ]
    for folder in candidates:
        if all((folder / name).is_file() for name in PLUGIN_FILES):
            return folder
    raise InstallError("the QGIS plugin files are missing from this svgtile installation "
                       f"(looked in {', '.join(str(c) for c in candidates)})")  # fmt: skip


def profile_dir() -> Path:
    """QGIS's default user profile folder on this platform (the one holding ``python/plugins``)."""
    if sys.platform == "win32":
        base = Path(os.environ.get("APPDATA", Path.home() / "AppData" / "Roaming")) / "QGIS" / "QGIS3"
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Application Support" / "QGIS" / "QGIS3"
    else:
        base = Path(os.environ.get("XDG_DATA_HOME") or Path.home() / ".local" / "share") / "QGIS" / "QGIS3"
    return base / "profiles" / "default"


def plugin_config(python: str | None = None) -> dict:
    """What the plugin needs to know: the interpreter, the engines and their public parameters."""
    from svgtile import __version__

    type_names = {float: "float", int: "int", bool: "bool", str: "str"}
    # the plugin writes motif points: an engine of cells (cellular) is not offered, nor its parameters
    offered = [e.name for e in ENGINES.values() if not draws_cells(e)]
    params = [
        {"name": p.name, "type": type_names[p.type], "default": p.default, "help": p.help, "option": p.option,
         "choices": list(p.choices) if p.choices else None, "interval": list(p.interval) if p.interval else None,
         "engines": [e for e in engines_with(p.name) if e in offered]}
        for p in public_params().values()
        if any(e in offered for e in engines_with(p.name))
    ]  # fmt: skip
    return {"python": python or sys.executable, "svgtile": __version__, "boundary_modes": list(BOUNDARY_MODES),
            "engines": {n: ENGINES[n].summary for n in offered}, "params": params}  # fmt: skip


def enable_plugin(profile: Path) -> None:
    """Mark the plugin enabled in the profile's ``QGIS/QGIS3.ini`` (``[PythonPlugins] svgtile_qgis=true``).

    Only that one line is added or changed; the rest of the file is kept byte for byte (it is
    handled as bytes: Qt writes it in whatever encoding the platform's settings used).
    """
    ini = profile / "QGIS" / "QGIS3.ini"
    lines = ini.read_bytes().splitlines() if ini.is_file() else []
    entry = f"{PLUGIN}=true".encode()
    try:
        start = lines.index(b"[PythonPlugins]")
    except ValueError:
        lines += ([b""] if lines else []) + [b"[PythonPlugins]", entry]
    else:
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith(b"[")), len(lines))
        mine = [i for i in range(start + 1, end) if lines[i].split(b"=", 1)[0].strip() == PLUGIN.encode()]
        if mine:
            lines[mine[0]] = entry
        else:
            lines.insert(start + 1, entry)
    ini.parent.mkdir(parents=True, exist_ok=True)
    write_file(b"\n".join(lines) + b"\n", ini)


def install(profile: str | Path | None = None, *, python: str | None = None) -> Path:
    """Copy the plugin into ``<profile>/python/plugins/svgtile_qgis``, record ``python``, enable it.

    Parameters
    ----------
    profile : a QGIS user profile folder; :func:`profile_dir` if None
    python : the interpreter that runs svgtile for the plugin; this one if None

    Returns
    -------
    The plugin folder.  Installing again replaces the files (and the recorded Python).
    """
    profile = Path(profile) if profile is not None else profile_dir()
    source = plugin_source()
    target = profile / "python" / "plugins" / PLUGIN
    if target.exists() and not target.is_dir():
        raise InstallError("exists and is not a folder", source=str(target))
    if target.is_dir() and any(target.iterdir()) and not (target / CONFIG_NAME).is_file():
        raise InstallError("exists but was not made by 'svgtile qgis install'; remove it first", source=str(target))
    try:
        target.mkdir(parents=True, exist_ok=True)
        for name in PLUGIN_FILES:
            shutil.copyfile(source / name, target / name)
        write_file(json.dumps(plugin_config(python), indent=2) + "\n", target / CONFIG_NAME)
        enable_plugin(profile)
    except OSError as exc:
        raise InstallError(f"cannot install here ({exc.strerror or exc})", source=str(target)) from None
    return target


def uninstall(profile: str | Path | None = None) -> Path:
    """Remove what :func:`install` put into the profile; returns the plugin folder."""
    target = (Path(profile) if profile is not None else profile_dir()) / "python" / "plugins" / PLUGIN
    if not (target / CONFIG_NAME).is_file():
        raise InstallError("the svgtile QGIS plugin is not installed here", source=str(target))
    try:
        shutil.rmtree(target)
    except OSError as exc:
        raise InstallError(f"cannot remove ({exc.strerror or exc})", source=str(target)) from None
    return target


# ----------------------------------------------------------------------------- fill


def fill(
    spec: str, *, exemplar: str | None, styles_file: str | None, class_field: str | None, engine: str,
    params: dict, boundary: str, unit: float, seed: int, avoid: tuple[str, ...] = (),
    avoid_margin: float = AVOID_MARGIN, jobs: int = 1, max_motifs: float = math.inf,
) -> tuple[MapFill, str | None]:  # fmt: skip
    """Fill every polygon of a layer: with one exemplar, or by class from an exemplar table.

    Parameters
    ----------
    spec : the polygon layer (:mod:`svgtile.gis.layers` spec)
    exemplar : one exemplar SVG for every polygon (then ``engine``, ``params``, ``unit`` apply) …
    styles_file : … or a styles file (``svgtile map``'s) whose classes ``class_field`` names
    class_field : the field holding each polygon's class (written to the output's ``class``)
    boundary : for one exemplar, and for the table's classes that give none
    avoid : layer specs every motif keeps clear of, grown by ``avoid_margin`` map units
    jobs : polygons filled at once, in separate processes

    Returns
    -------
    The fill (regions that failed have ``None`` results and an entry in ``errors``; ``warnings``
    names a table's ``avoid``, which is not used), and the layer's CRS.

    Raises
    ------
    ParameterError, RegionError
        Neither or both of ``exemplar`` and ``styles_file``; a table without a class field; an
        avoid layer in another CRS (svgtile does not reproject).
    """
    if (exemplar is None) == (styles_file is None):
        raise ParameterError("give either --exemplar FILE.svg or --styles FILE.toml")
    if styles_file is not None and class_field is None:
        raise ParameterError("an exemplar table (--styles) needs --class-field naming the field of its classes")
    layers.common_crs(spec, avoid)
    feats, crs = layers.read_regions(spec, class_property=class_field)
    if styles_file is not None:
        styles = replace(read_styles(styles_file, boundary=boundary), class_property=class_field)
        regions = [MapRegion(f.ident, f.cls, f.shape) for f in feats if f.cls in styles.classes]
        if not regions:
            raise RegionError(f"no feature's {class_field!r} names a class of {styles_file}", source=spec)
    else:
        style = Style("", Path(exemplar), engine, dict(params), None, unit, boundary)
        regions = [MapRegion(f.ident, f.cls or "", f.shape) for f in feats]
        styles = Styles({r.cls: replace(style, cls=r.cls) for r in regions}, source=str(exemplar))
    cellular = cellular_classes(styles)
    if cellular:  # (fill_regions would drop the cells without a word)
        raise ParameterError(f"class {cellular[0]!r} is cellular, and its cells are polygons, which a point layer "
                             "cannot hold: fill the units with svgtile map -o FILE.svg")  # fmt: skip
    for path in sorted({str(st.exemplar) for st in styles.classes.values()}):
        load_exemplar(path)  # a bad exemplar is one error before any work, not one per polygon
    zone = None
    if avoid:
        import shapely

        zone = shapely.union_all([read_avoid_shape(a, avoid_margin) for a in avoid])
    results, errors, filled = fill_regions(regions, zone, styles, seed=seed, jobs=jobs, max_motifs=max_motifs)
    warnings = []
    if styles_file is not None and styles.avoid:  # ids in a map, or files: the dialog gives layers
        warnings.append(f"{styles_file}: its avoid = {list(styles.avoid)} is not used here; give those layers as --avoid")
    return MapFill(regions, results, errors, None, warnings, styles, filled), crs

