#!/usr/bin/env python3
"""Extensions ▸ Render ▸ svgtile ▸ Fill with Texture… — fill shapes with a texture like an exemplar.

Select the exemplar (a group of motifs: ``<use>`` clones of symbols, or plain shapes; optionally
holding the area they were drawn in as an element with id or label ``region``) and one or more
shapes to fill (path, rect, circle, ellipse, polygon, polyline; holes and transformed layers are
fine), then Apply.  Each shape gets a texture group right above it, in its own layer.

This script runs in Inkscape's Python, which has inkex but usually not svgtile's dependencies
(shapely, scipy).  So it only translates: it writes the selection to a temporary folder
(``exemplar.svg`` in document coordinates, ``containers.json`` with the shapes flattened to
rings in document coordinates), runs ``PYTHON -m svgtile inkscape fill …`` with the Python
recorded by ``svgtile inkscape install`` (``svgtile_fill.json`` next to this file; the environment
variable ``SVGTILE_PYTHON`` overrides it), and inserts the result.  See ``svgtile/inkscape.py``.

Everything that can fail happens before the document is touched, so an error leaves it exactly
as it was; the error is one message on stderr, which Inkscape shows in a dialog.  On success the
script prints nothing.  Works with inkex 1.2 (Inkscape 1.2) and later.
"""

import copy
import json
import os
import re
import subprocess
import tempfile

import inkex
from inkex.bezier import cspsubdiv
from lxml import etree

HERE = os.path.dirname(os.path.abspath(__file__))
CONFIG = os.path.join(HERE, "svgtile_fill.json")
SVG_NS = "http://www.w3.org/2000/svg"
XLINK_NS = "http://www.w3.org/1999/xlink"
XLINK_HREF = f"{{{XLINK_NS}}}href"
CONTAINER_TYPES = (inkex.PathElement, inkex.Rectangle, inkex.Circle, inkex.Ellipse, inkex.Polygon, inkex.Polyline)
MOTIF_TAGS = {"use", "path", "rect", "circle", "ellipse", "line", "polyline", "polygon"}
#: Coordinates and transform entries beyond this are refused (as by svgtile's reader).
MAX_COORDINATE = 1e100
#: Curves become polylines this close to the true outline, as a fraction of the shape's size.
FLATNESS = 1e-4
URL = re.compile(r"url\(\s*#([^)\s]+)\s*\)")
HOW_TO = "Select the exemplar group and the shapes to fill, then apply svgtile again."
REINSTALL = "run 'svgtile inkscape install' in the Python environment where svgtile is installed"


def _local(el):
    tag = el.tag if isinstance(el.tag, str) else ""
    return tag.rsplit("}", 1)[-1]


def _name(el):
    return "<{} id={!r}>".format(_local(el), el.get("id"))


def _references(el):
    """Ids ``el`` refers to by href or ``url(#…)``."""
    refs = []
    for key, value in el.attrib.items():
        if key in (XLINK_HREF, "href") and value.startswith("#"):
            refs.append(value[1:])
        refs.extend(URL.findall(value))
    return refs


def _own_transform(el):
    # the raw attribute: inkex's ``transform`` property rewrites it as a matrix when read
    return inkex.Transform(etree.ElementBase.get(el, "transform") or None)


def _composed_transform(el):
    """From ``el``'s user space (its own transform included) to the document's."""
    total = inkex.Transform()
    while el is not None and el.getparent() is not None:  # the root's own transform is not ours
        total = _own_transform(el) @ total
        el = el.getparent()
    return total


def _parent_transform(el):
    """From ``el``'s parent's user space to the document's (root) user space."""
    parent = el.getparent()
    return _composed_transform(parent) if parent is not None else inkex.Transform()


def _fill_rule(el):
    """The ``fill-rule`` that applies to ``el`` (style, then attribute, inherited; no CSS sheets).

    Read from the raw attributes: inkex's style accessors rewrite the attributes they read."""
    while el is not None:
        style = etree.ElementBase.get(el, "style") or ""
        found = re.findall(r"(?:^|;)\s*fill-rule\s*:\s*([a-z]+)", style)
        value = found[-1] if found else etree.ElementBase.get(el, "fill-rule")
        if value in ("nonzero", "evenodd"):
            return value
        el = el.getparent()
    return "nonzero"


def _rings(shape):
    """The shape's subpaths as polylines in document coordinates: [[[x, y], …], …].

    Absurd geometry (``scale(1e308)``, NaN) is refused before it is flattened: inkex's
    subdivision never ends on coordinates that overflow.
    """
    transform = _composed_transform(shape)
    if not all(abs(v) <= MAX_COORDINATE for row in transform.matrix for v in row):  # also NaN
        raise inkex.AbortExtension(f"svgtile: the shape {_name(shape)} has a transform that is not finite or "
                                   f"scales beyond {MAX_COORDINATE:g}; nothing was changed.")  # fmt: skip
    path = shape.path.to_absolute().transform(transform)
    box = path.bounding_box()
    size = max(box.width, box.height) if box is not None else 0.0
    corners = (box.left, box.top, box.right, box.bottom) if box is not None else ()
    if not all(abs(v) <= MAX_COORDINATE for v in (size, *corners)):
        raise inkex.AbortExtension(f"svgtile: the shape {_name(shape)} has coordinates that are not finite or "
                                   f"beyond ±{MAX_COORDINATE:g}; nothing was changed.")  # fmt: skip
    csp = path.to_superpath()
    cspsubdiv(csp, max(size * FLATNESS, 1e-9))
    return [[[float(node[1][0]), float(node[1][1])] for node in sub] for sub in csp if len(sub) > 1]


def find_python():
    """The interpreter that has svgtile, and where it came from (for messages)."""
    python = os.environ.get("SVGTILE_PYTHON")
    origin = "SVGTILE_PYTHON"
    if not python:
        try:
            with open(CONFIG, encoding="utf-8") as fh:
                python = json.load(fh)["python"]
            origin = "the Python recorded at install time"
        except (OSError, ValueError, KeyError, TypeError):
            raise inkex.AbortExtension(
                "svgtile: this extension does not know where svgtile is installed; " + REINSTALL + "."
            ) from None
    if not os.path.isfile(python):
        raise inkex.AbortExtension(f"svgtile: {origin} ({python}) does not exist any more; {REINSTALL}.")
    return python, origin


#: The engine parameters of the dialog, passed on to ``svgtile inkscape fill`` (a test checks them
#: against the .inx and svgtile's engine parameter classes).
ENGINE_OPTIONS = ("grid", "overlap", "max-rotation", "junction", "vary-orientation", "redraw-jitter", "rotation",
                  "priority", "relax-every", "passes", "neighbourhood")


class FillWithTexture(inkex.EffectExtension):
    """Fill the selected shapes with a texture synthesized from the selected exemplar group."""

    def add_arguments(self, pars):
        pars.add_argument("--tab", default="options")
        pars.add_argument("--engine", default="patch", choices=["patch", "tile", "random", "growth", "optimize"])
        pars.add_argument("--grid", default="square", choices=["square", "hex", "lattice"])
        pars.add_argument("--overlap", type=float, default=0.05)
        pars.add_argument("--max-rotation", type=float, default=30.0)
        pars.add_argument("--junction", type=float, default=0.6)
        pars.add_argument("--vary-orientation", type=inkex.Boolean, default=False)
        pars.add_argument("--redraw-jitter", type=inkex.Boolean, default=False)
        pars.add_argument("--passes", type=int, default=10)
        pars.add_argument("--neighbourhood", type=int, default=6)
        pars.add_argument("--rotation", default="auto", choices=["auto", "none", "fit", "flow"])
        pars.add_argument("--priority", default="")
        pars.add_argument("--relax-every", type=int, default=0)
        pars.add_argument("--boundary", default="clip", choices=["clip", "inside", "centroid", "none"])
        pars.add_argument("--seed", type=int, default=0)

    # -- selection ---------------------------------------------------------------------

    def roles(self):
        """(exemplar group, [container shapes]) from the selection, or abort saying what to select."""
        selected = list(self.svg.selection.values())
        if not selected:
            raise inkex.AbortExtension("svgtile: nothing is selected. " + HOW_TO)
        groups = [el for el in selected if isinstance(el, inkex.Group)]
        shapes = [el for el in selected if isinstance(el, CONTAINER_TYPES)]
        others = [el for el in selected if el not in groups and el not in shapes]
        if others:
            raise inkex.AbortExtension(
                "svgtile: cannot fill {}; the shapes to fill must be paths, rectangles, circles, "
                "ellipses, polygons or polylines. {}".format(", ".join(_name(el) for el in others), HOW_TO)
            )
        if not groups:
            raise inkex.AbortExtension(
                "svgtile: no exemplar selected; the exemplar is a group of motifs (Object ▸ Group). " + HOW_TO
            )
        if len(groups) > 1:
            raise inkex.AbortExtension(
                f"svgtile: select one exemplar group, not {len(groups)} "
                f"({', '.join(_name(el) for el in groups)}). {HOW_TO}"
            )
        exemplar = groups[0]
        if not shapes:
            raise inkex.AbortExtension("svgtile: no shape to fill is selected. " + HOW_TO)
        inside = [el for el in shapes if exemplar in el.iterancestors()]
        if inside:
            raise inkex.AbortExtension(
                f"svgtile: {_name(inside[0])} is part of the exemplar {_name(exemplar)}; the shapes to fill must lie outside it. {HOW_TO}"
            )
        region = self.region_element(exemplar)
        if not any(_local(el) in MOTIF_TAGS and el is not region for el in exemplar.iterdescendants()):
            raise inkex.AbortExtension(
                f"svgtile: the exemplar group {_name(exemplar)} holds no motifs (clones of symbols or shapes). {HOW_TO}"
            )
        return exemplar, shapes

    @staticmethod
    def region_element(exemplar):
        """The exemplar's input region: a descendant with id or label ``region``, if any."""
        for el in exemplar.iterdescendants():
            label = el.get("{http://www.inkscape.org/namespaces/inkscape}label") or ""
            if el.get("id") == "region" or label.strip().lower() == "region":
                return el
        return None

    # -- files for svgtile --------------------------------------------------------------

    def exemplar_svg(self, exemplar):
        """The exemplar as a standalone SVG in document coordinates, and the ids copied from the
        document (the elements it references, which the texture will reference too)."""
        inner = set(exemplar.iter())
        todo = [r for el in exemplar.iter() for r in _references(el)]
        wanted = []
        while todo:
            ident = todo.pop()
            el = self.svg.getElementById(ident)
            if el is None or el in inner or el in wanted:
                continue
            wanted.append(el)
            todo.extend(r for sub in el.iter() for r in _references(sub))
        # a referenced element inside another one is copied with it
        wanted = [el for el in wanted if not any(a in wanted for a in el.iterancestors())]
        order = {el: i for i, el in enumerate(self.svg.iter())}
        wanted.sort(key=lambda el: order.get(el, 0))
        copied_ids = {sub.get("id") for el in wanted for sub in el.iter() if sub.get("id")}

        group = copy.deepcopy(exemplar)
        region = self.region_element(group)
        if region is not None:  # svgtile reads the first element with this id: this one
            region.set("id", "region")
        root = etree.Element(f"{{{SVG_NS}}}svg", nsmap={None: SVG_NS, "xlink": XLINK_NS})
        wrap = etree.SubElement(root, f"{{{SVG_NS}}}g")
        wrap.set("transform", str(_parent_transform(exemplar)))
        group.tail = None
        wrap.append(group)
        defs = etree.SubElement(root, f"{{{SVG_NS}}}defs")
        for el in wanted:
            dup = copy.deepcopy(el)
            dup.tail = None
            defs.append(dup)
        return etree.tostring(root, xml_declaration=True, encoding="UTF-8"), copied_ids

    def run_svgtile(self, folder, exemplar, shapes):
        """Run svgtile on the selection; returns the texture documents, one per shape."""
        python, origin = find_python()
        data, copied = self.exemplar_svg(exemplar)
        ex_path = os.path.join(folder, "exemplar.svg")
        with open(ex_path, "wb") as fh:
            fh.write(data)
        containers = [{"id": el.get("id"), "fill_rule": _fill_rule(el), "rings": _rings(el)} for el in shapes]
        with open(os.path.join(folder, "containers.json"), "w", encoding="utf-8") as fh:
            json.dump({"containers": containers}, fh)
        o = self.options
        cmd = [python, "-m", "svgtile", "inkscape", "fill", "exemplar.svg", "containers.json",
               "--out-dir", ".", "--engine", o.engine, "--boundary", o.boundary, "--seed", str(o.seed)]  # fmt: skip
        for option in ENGINE_OPTIONS:  # svgtile keeps those the chosen engine has
            value = getattr(o, option.replace("-", "_"))
            if isinstance(value, bool):
                cmd += [f"--{option}"] if value else []
            else:
                cmd += [f"--{option}", repr(value) if isinstance(value, float) else str(value)]
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "PYTHONSTARTUP")}
        extra = {"creationflags": 0x08000000} if os.name == "nt" else {}  # CREATE_NO_WINDOW
        try:
            done = subprocess.run(cmd, cwd=folder, env=env, stdin=subprocess.DEVNULL,
                                  capture_output=True, **extra)  # fmt: skip
        except OSError as exc:
            raise inkex.AbortExtension(f"svgtile: cannot run {origin} ({python}): {exc}; {REINSTALL}.") from None
        if done.returncode != 0:
            raise inkex.AbortExtension(self.failure(done, python, origin, ex_path, exemplar))
        textures = []
        for i in range(len(shapes)):
            path = os.path.join(folder, f"texture-{i}.svg")
            try:
                textures.append(inkex.load_svg(path).getroot())
            except (OSError, etree.XMLSyntaxError) as exc:
                raise inkex.AbortExtension(f"svgtile: no usable texture for {_name(shapes[i])} ({exc})") from None
        return textures, copied

    @staticmethod
    def failure(done, python, origin, ex_path, exemplar):
        """The one-line message for a failed svgtile run."""
        text = done.stderr.decode("utf-8", "replace")
        lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
        if "No module named svgtile" in text:
            return f"svgtile: svgtile is not installed in {origin} ({python}); {REINSTALL}."
        errors = [ln for ln in lines if ln.startswith("svgtile: error:") or ln.startswith("svgtile: internal error:")]
        message = errors[-1] if errors else (lines[-1] if lines else f"exit status {done.returncode}")
        for spelling in (ex_path, "exemplar.svg"):
            message = message.replace(spelling, f"the exemplar group {exemplar.get('id')!r}")
        if not message.startswith("svgtile:"):
            message = "svgtile: " + message
        return message

    # -- insertion ------------------------------------------------------------------------

    def effect(self):
        exemplar, shapes = self.roles()
        with tempfile.TemporaryDirectory(prefix="svgtile-") as folder:
            textures, copied = self.run_svgtile(folder, exemplar, shapes)
        groups = [next(iter(t.iterchildren(f"{{{SVG_NS}}}g")), None) for t in textures]
        if not any(g is not None and len(g) for g in groups):
            raise inkex.AbortExtension(
                f"svgtile: no motif fits in the selected shape(s) with boundary {self.options.boundary!r}; try boundary "
                "'clip' or 'none', or a smaller exemplar."
            )
        taken = set(self.svg.xpath("//@id"))
        known = {}  # canonical XML of a def svgtile made -> its id in the document
        o = self.options
        for shape, texture, found in zip(shapes, textures, groups):  # noqa: B905 (Inkscape's Python may predate 3.10)
            if found is None or not len(found):
                continue
            renamed = self.merge_defs(texture, copied, taken, known)
            group = inkex.Group()
            group.set("id", _unique("svgtile-texture", taken))
            group.set("{http://www.inkscape.org/namespaces/inkscape}label",
                      f"svgtile texture ({o.engine}, seed {o.seed})")  # fmt: skip
            group.transform = -_parent_transform(shape)
            clip = URL.findall(found.get("clip-path") or "")
            if clip:
                group.set("clip-path", f"url(#{renamed.get(clip[0], clip[0])})")
            for use in list(found):
                if not isinstance(use.tag, str):
                    continue
                ref = use.get(XLINK_HREF) or use.get("href") or ""
                if ref.startswith("#") and ref[1:] in renamed:
                    use.set(XLINK_HREF, "#" + renamed[ref[1:]])
                group.append(use)
            shape.addnext(group)

    def merge_defs(self, texture, copied, taken, known):
        """Put the texture's new defs (generated symbols, clip path) into the document once.

        Elements copied from the document are already there.  A new element identical to one
        svgtile already put in the document (this run or an earlier one) is reused.  Returns the
        ids that changed, old -> new.
        """
        renamed = {}
        defs = next(iter(texture.iterchildren(f"{{{SVG_NS}}}defs")), None)
        for el in list(defs if defs is not None else ()):
            ident = el.get("id")
            if not isinstance(el.tag, str) or ident in copied:
                continue
            key = _canonical(el)
            there = self.svg.getElementById(ident) if ident else None
            if key in known:
                renamed[ident] = known[key]
                continue
            if there is not None and _canonical(there) == key:
                known[key] = ident
                continue
            new = ident if ident and ident not in taken else _unique(ident or "svgtile-def", taken)
            taken.add(new)
            if new != ident:
                renamed[ident] = new
            el.set("id", new)
            for sub in el.iterdescendants():
                if sub.get("id") in taken:
                    sub.set("id", _unique(sub.get("id"), taken))
            known[key] = new
            self.svg.defs.append(el)
        return renamed


def _canonical(el):
    """What ``el`` draws, as a hashable value: tags, attributes but ids, text, recursively."""
    attrs = tuple(sorted((k, v) for k, v in el.attrib.items() if k != "id"))
    kids = tuple(_canonical(c) for c in el if isinstance(c.tag, str))
    return (el.tag, attrs, (el.text or "").strip(), kids)


def _unique(base, taken):
    ident, n = base, 1
    while ident in taken:
        n += 1
        ident = f"{base}-{n}"
    taken.add(ident)
    return ident


if __name__ == "__main__":
    FillWithTexture().run()
