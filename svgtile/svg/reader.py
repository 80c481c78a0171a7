"""Reading an exemplar SVG into kinds, motif instances and an input region (almeraj2013 §3.1).

This is the only module that imports svgelements; it is used for what it does well — parsing path
data, shapes, transforms and lengths — while the document structure (``<symbol>``, ``<use>``,
groups, inherited style) is walked here with ElementTree, because svgelements ignores a symbol's
``viewBox`` and expands ``<use>`` elements, losing which kind an instance is.

Two kinds of exemplar are read:

* ``<symbol>``/``<use>`` exemplars: every ``<use>`` at any depth is a motif instance whose kind is
  the referenced element (with its ``viewBox`` mapping, and any skew, non-uniform scale or mirror of
  the instance folded into the kind); transforms of groups, of the ``<use>`` and its ``x``/``y``
  are composed and split into position, rotation and uniform scale.
* plain drawings: every top-level shape or group (inside Inkscape layers and lone wrapper groups)
  is a motif; motifs identical up to translation and rotation share a kind, and a ``<symbol>`` is
  generated for each kind in the output.

The input region is the element with ``id="region"``, else the root ``viewBox``, else
``width``/``height``, else the motifs' bounds.  Nothing outside the file is ever fetched.

Work is done once per kind: a referenced element's footprint is computed once per inherited style
and viewport, and each ``<use>`` only contributes its matrix.
"""


from __future__ import annotations

import copy
import json
import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.exemplar import Exemplar, Kind
from svgtile.core.footprint import Prototype, separated
from svgtile.errors import ExemplarError
from svgtile.svg.dialect import (
    CELLULAR_ATTR,
    CONTAINERS,
    GROUND_ATTR,
    GROUND_VALUE,
    INHERITED,
    INITIAL,
    MAX_COORDINATE,
    MAX_COORDINATES,
    MAX_KINDS,
    MAX_USE_DEPTH,
    ORIGIN_DECIMALS,
    PERIOD_ATTR,
    REGION_FLATNESS,
    SHAPE_TOLERANCE,
    SHAPES,
    SVG_NS,
    apply_matrix,
    cascade_style,
    check_tree,
    describe,
    drawable_children,
    element_matrix,
    fill_holes,
    flat_subpaths,
    fmt_number,
    geometry_error,
    holds_motifs,
    href_of,
    inherited_items,
    is_hidden,
    is_rendered,
    is_svg,
    leaf_footprint,
    linear_part,
    local_tag,
    matrix_attr,
    neutralise_external,
    number_attr,
    one_line,
    polygons_of,
    read_svg_bytes,
    shorten,
    tag_ns,
    translation,
)
from svgtile.svg.kinds import Shape, match_rotation, paint_key


def read_exemplar(path: str | Path) -> Exemplar:
    """Read an exemplar SVG file.

    Raises
    ------
    ExemplarError
        With the file name and a one-line description of what is wrong.
    """
    return parse_exemplar(read_svg_bytes(path), source=str(path))


def parse_exemplar(data: bytes | str, *, source: str = "<exemplar>") -> Exemplar:
    """Parse exemplar SVG text (see :func:`read_exemplar`)."""
    if isinstance(data, str):
        data = data.encode()
    try:
        root = ET.fromstring(data)
    except (ET.ParseError, ValueError, LookupError) as exc:  # LookupError: unknown encoding
        raise ExemplarError(f"not a well-formed XML file ({one_line(exc)})", source=source) from None
    if local_tag(root.tag) != "svg" or tag_ns(root.tag) not in ("", SVG_NS):
        raise ExemplarError(f"not an SVG document (root element is <{local_tag(root.tag)}>)", source=source)
    check_tree(root, source)
    try:
        return DocumentReader(root, source).read()
    except RecursionError:
        raise ExemplarError("elements are nested too deeply", source=source) from None
    except (shapely.errors.GEOSException, OverflowError, FloatingPointError) as exc:
        raise geometry_error(exc, source) from None


# ----------------------------------------------------------------------------- helpers


@dataclass
class _Instance:
    key: tuple  # what makes two instances the same kind (before plain-shape matching)
    geom: shapely.Geometry  # footprint in the instance frame, holes filled
    matrix: np.ndarray  # 3x3, instance frame -> world
    element: ET.Element
    style: dict[str, str]  # effective style of the element's parent (plain) or of the <use>

    @property
    def world(self) -> shapely.Geometry:
        return apply_matrix(self.matrix, self.geom)



@dataclass
class _PlainKinds:
    """The plain kinds found so far, with arrays for a quick first filter."""

    kind: list[int] = field(default_factory=list)
    rep: list[_Instance] = field(default_factory=list)
    shape: list[Shape] = field(default_factory=list)
    paint: list[tuple] = field(default_factory=list)
    area: list[float] = field(default_factory=list)
    radius: list[float] = field(default_factory=list)


class DocumentReader:
    """Walks one document; see the module docstring for the rules."""

    def __init__(self, root: ET.Element, source: str) -> None:
        self.root, self.source = root, source
        self.ids: dict[str, ET.Element] = {}
        for el in root.iter():
            ident = el.attrib.get("id")
            if ident is not None and ident not in self.ids:
                self.ids[ident] = el
        self.warnings: list[str] = []
        self.warned: set[str] = set()
        self.raw_cache: dict[tuple, shapely.Geometry | None] = {}  # referenced content, own frame
        self.kind_cache: dict[tuple, shapely.Geometry | None] = {}  # <use> footprint, use frame

    def error(self, message: str) -> ExemplarError:
        return ExemplarError(one_line(message), source=self.source)

    def warn(self, message: str) -> None:
        if message not in self.warned:
            self.warned.add(message)
            self.warnings.append(one_line(message))

    # -- document walk -------------------------------------------------------------------

    def read(self) -> Exemplar:
        self.refuse_external_references()
        if any(local_tag(el.tag) == "style" and (el.text or "").strip() for el in self.root.iter()):
            self.warn("CSS <style> sheets are not applied; use presentation attributes or style=")
        instances: list[_Instance] = []
        self._walk(self.root, np.eye(3), cascade_style(self.root, INITIAL), instances)
        cellular = self._cellular()
        if not instances:
            if cellular is not None:  # a cellular pattern of cells and lines only
                region = self._region(Arrangement.empty(), [])
                return Exemplar(self.source, (), Arrangement.empty(), region, (), tuple(self.warnings), self._period(),
                                cellular, self._ground())  # fmt: skip
            raise self.error("no motifs found (expected <use> elements or top-level shapes)")
        kinds, arrangement, defs = self._kinds(instances)
        region = self._region(arrangement, kinds)
        # boundary included: an imported tile may have a motif centred on its edge
        centroid_in = shapely.intersects_xy(region, arrangement.xy[:, 0], arrangement.xy[:, 1])
        if not centroid_in.any():
            raise self.error("no motif lies inside the input region")
        if not centroid_in.all():
            self.warn(f"{int((~centroid_in).sum())} motif(s) outside the input region are ignored")
            arrangement = arrangement.take(centroid_in)
        period = self._period()
        # outlines that meet where the drawing keeps its motifs apart are drawn finer
        protos = separated([k.prototype for k in kinds], [k.footprint for k in kinds], arrangement, period)
        kinds = [k if p is k.prototype else replace(k, prototype=p) for k, p in zip(kinds, protos, strict=True)]
        return Exemplar(self.source, tuple(kinds), arrangement, region, tuple(defs), tuple(self.warnings), period,
                        cellular, self._ground())  # fmt: skip

    def _cellular(self) -> dict | None:
        """The ``svgtile:cellular`` description of the region element, if any (see
        :attr:`Exemplar.cellular`)."""
        el = self.ids.get("region")
        text = None if el is None else el.attrib.get(CELLULAR_ATTR)
        if text is None:
            return None
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise self.error(f"unreadable svgtile:cellular ({exc.msg})") from None
        if not isinstance(data, dict):
            raise self.error("svgtile:cellular must be a JSON object")
        return data

    def _ground(self) -> str | None:
        """The ``svgtile:ground`` colour of the region element, if any (see :attr:`Exemplar.ground`)."""
        el = self.ids.get("region")
        text = None if el is None else el.attrib.get(GROUND_ATTR)
        if text is None:
            return None
        if not GROUND_VALUE.fullmatch(text.strip()):
            raise self.error(f"svgtile:ground {text[:40]!r} is not a colour (a name, #hex or rgb())")
        return text.strip()

    def _period(self) -> tuple[float, float] | None:
        """The ``svgtile:period`` of the region element, if any (see :attr:`Exemplar.period`)."""
        el = self.ids.get("region")
        text = None if el is None else el.attrib.get(PERIOD_ATTR)
        if text is None:
            return None
        try:
            w, h = (float(v) for v in re.split(r"[\s,]+", text.strip()))
        except ValueError:
            raise self.error(f"unreadable svgtile:period {text!r} (expected two numbers)") from None
        if not (w > 0 and h > 0 and math.isfinite(w) and math.isfinite(h)):
            raise self.error(f"svgtile:period {text!r} must be two positive numbers")
        return (w, h)

    def refuse_external_references(self) -> None:
        """A ``<use>`` may only reference this file (other hrefs are links, images … and never drawn)."""
        for el in self.root.iter():
            if not (is_svg(el) and local_tag(el.tag) == "use"):
                continue
            ref = href_of(el)
            if ref and not ref.startswith("#"):
                if ref.startswith("data:"):
                    raise self.error(f"{describe(el)} refers to a data: URL; only references to ids in this file are supported")
                raise self.error(
                    f"{describe(el)} refers to {shorten(ref)!r} outside this file; svgtile never fetches external files"
                )

    def _walk(self, el: ET.Element, m: np.ndarray, style: dict[str, str], out: list[_Instance]) -> None:
        """Collect motif instances below ``el`` (a container whose children may be motifs)."""
        drawable = drawable_children(el)
        for child in drawable:
            tag = local_tag(child.tag)
            cstyle = cascade_style(child, style)
            if is_hidden(cstyle):
                continue
            cm = m @ element_matrix(child, self.source)
            if tag == "use":
                inst = self._use_instance(child, cm, cstyle)
                if inst is not None:
                    out.append(inst)
            elif tag == "svg":
                if "viewBox" in child.attrib:
                    raise self.error(f"nested {describe(child)} with a viewBox is not supported; flatten it first")
                x, y = number_attr(child.attrib.get("x"), 0), number_attr(child.attrib.get("y"), 0)
                self._walk(child, m @ translation(x, y), cstyle, out)
            elif tag in CONTAINERS and holds_motifs(child, alone=len(drawable) == 1):
                self._walk(child, cm, cstyle, out)
            elif tag in SHAPES or tag in CONTAINERS:
                inst = self._plain_instance(child, m, style)
                if inst is not None:
                    out.append(inst)
            elif tag in ("text", "image"):
                self.warn(f"{describe(child)} is ignored (only shapes and <use> are motifs)")

    # -- instances -----------------------------------------------------------------------

    def _plain_instance(self, el: ET.Element, parent_m: np.ndarray, parent_style: dict[str, str]) -> _Instance | None:
        """A top-level shape or group drawn in place."""
        if abs(np.linalg.det(parent_m[:2, :2])) < 1e-12:
            return None
        geom = self._content(el, parent_style, np.eye(3), stack=())
        if geom is None:
            return None
        geom = fill_holes(geom)
        if geom.is_empty or geom.area <= 0:
            return None
        return _Instance(("plain", paint_key(el, parent_style)), geom, parent_m, el, parent_style)

    def target(self, use: ET.Element) -> tuple[str, ET.Element]:
        ref = href_of(use)
        if not ref:
            raise self.error(f"{describe(use)} has no href")
        target = self.ids.get(ref[1:])
        if target is None:
            raise self.error(f"{describe(use)} refers to {shorten(ref)!r}, which is not in the file")
        return ref, target

    def _use_instance(self, use: ET.Element, m: np.ndarray, style: dict[str, str]) -> _Instance | None:
        """A ``<use>`` motif: its footprint in the ``<use>``'s frame (after x/y), once per kind.

        The frame is the one the output ``<use>`` draws in: a symbol's viewBox mapping is applied by
        the ``width``/``height`` the output ``<use>`` carries, so it is part of the footprint, not
        of the instance matrix.
        """
        ref, target = self.target(use)
        x, y = number_attr(use.attrib.get("x"), 0.0), number_attr(use.attrib.get("y"), 0.0)
        m = m @ translation(x, y)
        if abs(np.linalg.det(m[:2, :2])) < 1e-12:
            self.warn(f"{describe(use)} is scaled to nothing; ignored")
            return None
        view, use_attrs = self.viewport(use, target)
        inherited = inherited_items(style)
        key = (ref, use_attrs, inherited)
        if key not in self.kind_cache:
            raw = self._referenced(ref, target, style, stack=())
            geom = None if raw is None else fill_holes(apply_matrix(view, raw))
            self.kind_cache[key] = geom if geom is not None and geom.area > 0 else None
            if geom is not None and local_tag(target.tag) == "symbol":
                self._check_overflow(target, geom)
        geom = self.kind_cache[key]
        if geom is None:
            self.warn(f"<use> elements referring to {shorten(ref)!r} draw nothing svgtile can measure; ignored")
            return None
        return _Instance(("use", ref[1:], use_attrs, inherited), geom, m, use, style)

    def _check_overflow(self, symbol: ET.Element, geom: shapely.Geometry) -> None:
        overflow = cascade_style(symbol, {}).get("overflow", symbol.attrib.get("overflow", "hidden"))
        x0, y0, _, _ = geom.bounds
        if overflow.strip() not in ("visible", "auto") and min(x0, y0) < -1e-9:
            self.warn(
                f"{describe(symbol)} draws at negative coordinates but has overflow hidden (the SVG "
                'default), so viewers clip it; add overflow="visible"'
            )

    def _referenced(self, ref: str, target: ET.Element, style: dict[str, str], stack: tuple[str, ...]) -> shapely.Geometry | None:
        """Footprint of a referenced element in its own frame, computed once per inherited style."""
        if ref in stack or len(stack) >= MAX_USE_DEPTH:
            raise self.error(f"{describe(target)} is referenced recursively (through {' → '.join((*stack, ref))})")
        key = (ref, inherited_items(style))
        if key not in self.raw_cache:
            self.raw_cache[key] = self._content(target, style, np.eye(3), (*stack, ref))
        return self.raw_cache[key]

    def viewport(self, use: ET.Element, target: ET.Element) -> tuple[np.ndarray, tuple[tuple[str, str], ...]]:
        """Matrix from a symbol's viewBox to the ``<use>`` viewport, and the attributes that make it."""
        if local_tag(target.tag) != "symbol":
            return np.eye(3), ()
        if "transform" in target.attrib:
            raise self.error(f"{describe(target)} has a transform attribute (SVG 2 only; viewers disagree); move it to the <use>")
        box = target.attrib.get("viewBox")
        if not box:
            return np.eye(3), ()
        try:
            vx, vy, vw, vh = (float(v) for v in re.split(r"[\s,]+", box.strip()))
        except ValueError:
            raise self.error(f"{describe(target)} has an unreadable viewBox {box!r}") from None
        if not (vw > 0 and vh > 0 and all(abs(v) <= MAX_COORDINATE for v in (vx, vy, vw, vh))):
            raise self.error(f"{describe(target)} has an empty or unbounded viewBox {box!r}")
        w = use.attrib.get("width") or target.attrib.get("width")
        h = use.attrib.get("height") or target.attrib.get("height")
        if not w or not h or "%" in w + h:
            raise self.error(
                f"{describe(target)} has a viewBox, so its <use> needs width and height "
                "(svgtile will not guess a percentage viewport)"
            )
        width, height = number_attr(w, 0), number_attr(h, 0)
        if not (0 < width <= MAX_COORDINATE and 0 < height <= MAX_COORDINATE):
            raise self.error(f"{describe(target)} is used with an empty or unbounded viewport ({w} x {h})")
        if not all(1 / MAX_COORDINATE <= r <= MAX_COORDINATE for r in (width / vw, height / vh)):
            raise self.error(f"{describe(target)}: its viewBox {box!r} in a {w} x {h} viewport scales by more than {MAX_COORDINATE:g}")
        par = (target.attrib.get("preserveAspectRatio") or "").split()
        if par and par[0] == "defer":
            par = par[1:]
        align = par[0] if par else "xMidYMid"
        if align != "none" and not re.fullmatch(r"x(Min|Mid|Max)Y(Min|Mid|Max)", align):
            align, par = "xMidYMid", []  # an invalid value means the default
        sx, sy = width / vw, height / vh
        tx = ty = 0.0
        if align != "none":
            s = max(sx, sy) if len(par) > 1 and par[1] == "slice" else min(sx, sy)
            fx = {"xMin": 0.0, "xMid": 0.5, "xMax": 1.0}[align[:4]]
            fy = {"YMin": 0.0, "YMid": 0.5, "YMax": 1.0}[align[4:]]
            tx, ty = fx * (width - vw * s), fy * (height - vh * s)
            sx = sy = s
        view = np.array([[sx, 0, tx - vx * sx], [0, sy, ty - vy * sy], [0, 0, 1.0]])
        return view, (("width", fmt_number(width)), ("height", fmt_number(height)))

    def _content(self, el: ET.Element, style: dict[str, str], m: np.ndarray, stack: tuple[str, ...]) -> shapely.Geometry | None:
        """Footprint of ``el`` (a shape, group, symbol or use) in the frame ``m`` maps it to."""
        est = cascade_style(el, style)
        if is_hidden(est):
            return None
        tag = local_tag(el.tag)
        if tag != "symbol":
            m = m @ element_matrix(el, self.source)
        if tag in SHAPES:
            geom = leaf_footprint(el, est, self.source)
            return None if geom is None else apply_matrix(m, geom)
        if tag == "use":
            ref, target = self.target(el)
            view, _ = self.viewport(el, target)
            offset = translation(number_attr(el.attrib.get("x"), 0), number_attr(el.attrib.get("y"), 0))
            raw = self._referenced(ref, target, est, stack)
            return None if raw is None else apply_matrix(m @ offset @ view, raw)
        if tag == "svg" and el is not self.root:
            if "viewBox" in el.attrib:
                raise self.error(f"nested {describe(el)} with a viewBox is not supported; flatten it first")
            m = m @ translation(number_attr(el.attrib.get("x"), 0), number_attr(el.attrib.get("y"), 0))
        if tag in (*CONTAINERS, "symbol", "svg"):
            parts = [self._content(c, est, m, stack) for c in el if is_rendered(c)]
            parts = [p for p in parts if p is not None and not p.is_empty]
            if sum(shapely.get_num_coordinates(p) for p in parts) > MAX_COORDINATES:
                raise self.error(f"{describe(el)} is too complex (over {MAX_COORDINATES} outline points)")
            return shapely.union_all(parts) if parts else None
        return None

    # -- kinds ---------------------------------------------------------------------------

    def _kinds(self, instances: list[_Instance]) -> tuple[list[Kind], Arrangement, list[ET.Element]]:
        """Group instances into kinds and express each instance in its kind's local frame."""
        kinds: list[Kind] = []
        kind_of_key: dict[tuple, int] = {}
        rows: list[tuple[int, float, float, float, float]] = []
        plain = _PlainKinds()
        for inst in instances:
            if inst.key[0] == "use":
                k, angle, scale, xy = self._use_kind(inst, kinds, kind_of_key)
            else:
                k, angle, scale, xy = self._plain_kind(inst, kinds, plain)
            rows.append((k, xy[0], xy[1], angle, scale))
            if len(kinds) > MAX_KINDS:  # the analysis compares every pair of kinds
                raise self.error(f"more than {MAX_KINDS} kinds of motif; an exemplar has a few (is it a "
                                 "drawing or a symbol set rather than an arrangement?)")  # fmt: skip
        table = np.array(rows, dtype=np.float64)
        arrangement = Arrangement(table[:, 0].astype(np.int64), table[:, 1:3], table[:, 3], table[:, 4])
        defs = self._defs(kinds, list(zip(plain.kind, plain.rep, strict=True)))
        return kinds, arrangement, defs

    def _use_kind(self, inst: _Instance, kinds: list[Kind], kind_of_key: dict[tuple, int]):
        """Split the instance matrix into translation · rotation · uniform scale · residual."""
        lin = inst.matrix[:2, :2]
        scale = math.sqrt(abs(float(np.linalg.det(lin))))
        angle = math.degrees(math.atan2(lin[1, 0], lin[0, 0]))
        rot = np.array([[math.cos(math.radians(angle)), -math.sin(math.radians(angle))],
                        [math.sin(math.radians(angle)), math.cos(math.radians(angle))]])  # fmt: skip
        residual = rot.T @ lin / scale
        if np.allclose(residual, np.eye(2), atol=1e-6):
            residual = np.eye(2)
        key = (*inst.key, tuple(np.round(residual, 6).ravel()))
        if key not in kind_of_key:
            # the footprint in the residual frame: the instance frame mapped by the residual only
            local = apply_matrix(linear_part(residual), inst.geom)
            c = np.round(np.array(local.centroid.coords[0]), ORIGIN_DECIMALS)
            exact = shapely.transform(local, lambda p: p - c)
            _, ref, use_attrs, inherited = inst.key
            variants = sum(1 for k in kinds if k.href == ref)
            name = ref if variants == 0 else f"{ref}~{variants}"
            kind_of_key[key] = len(kinds)
            kinds.append(Kind(name, ref, Prototype.from_geometry(exact), -c, residual, use_attrs + inherited, exact))
        k = kind_of_key[key]
        xy = inst.matrix[:2, 2] + scale * rot @ (-kinds[k].offset)
        return k, angle, scale, xy

    def _plain_kind(self, inst: _Instance, kinds: list[Kind], plain: _PlainKinds):
        """The kind of a plain motif: the first earlier one of the same paint and shape up to rotation."""
        world = inst.world
        c = np.round(np.array(world.centroid.coords[0]), ORIGIN_DECIMALS)
        shape = Shape.of(shapely.transform(world, lambda p: p - c))
        paint = inst.key[1]
        if plain.kind:
            area, radius = np.asarray(plain.area), np.asarray(plain.radius)
            similar = (np.abs(area - shape.area) <= 2 * SHAPE_TOLERANCE * area) & (
                np.abs(radius - shape.radius) <= SHAPE_TOLERANCE * radius
            )
            for i in np.flatnonzero(similar):
                if plain.paint[i] != paint:
                    continue
                angle = match_rotation(plain.shape[i], shape)
                if angle is not None:
                    return plain.kind[i], angle, 1.0, c
        k = len(kinds)
        ident = f"svgtile-kind-{len(plain.kind) + 1}"
        kinds.append(Kind(ident, ident, Prototype.from_geometry(shape.geom), -c, np.eye(2), (), shape.geom))
        for name, value in (("kind", k), ("rep", inst), ("shape", shape), ("paint", paint),
                            ("area", shape.area), ("radius", shape.radius)):  # fmt: skip
            getattr(plain, name).append(value)
        return k, 0.0, 1.0, c

    def _defs(self, kinds: list[Kind], reps: list[tuple[int, _Instance]]) -> list[ET.Element]:
        """Elements to copy to the output: referenced elements (closure), then generated symbols."""
        wanted: list[str] = []
        todo = [k.href for k in kinds if k.href in self.ids and not k.href.startswith("svgtile-kind-")]
        while todo:
            ident = todo.pop(0)
            if ident in wanted or ident not in self.ids:
                continue
            wanted.append(ident)
            for el in self.ids[ident].iter():
                ref = href_of(el)
                if ref and ref.startswith("#"):
                    todo.append(ref[1:])
                for value in el.attrib.values():
                    todo.extend(re.findall(r"url\(\s*#([^)\s]+)\s*\)", value))
        order = {id(el): i for i, el in enumerate(self.root.iter())}
        defs = sorted((self.ids[i] for i in wanted), key=lambda el: order[id(el)])
        # an element nested in another copied element is copied with it
        inside = {id(sub) for el in defs for sub in el.iter() if sub is not el}
        defs = [el for el in defs if id(el) not in inside]
        for k, rep in reps:
            symbol = ET.Element(f"{{{SVG_NS}}}symbol", {"id": kinds[k].href, "overflow": "visible"})
            wrapper = ET.SubElement(symbol, f"{{{SVG_NS}}}g")
            if not np.allclose(rep.matrix, np.eye(3)):
                wrapper.set("transform", matrix_attr(rep.matrix))
            for key, value in sorted(rep.style.items()):
                if key in INHERITED and INITIAL.get(key) != value:
                    wrapper.set(key, value)
            wrapper.append(copy.deepcopy(rep.element))
            defs.append(symbol)
        dropped = neutralise_external(defs)
        if dropped:
            self.warn(f"{len(dropped)} reference(s) to outside this file dropped from the copied symbols, so no "
                      f"viewer fetches them ({'; '.join(dropped[:3])}{' …' if len(dropped) > 3 else ''})")  # fmt: skip
        return defs

    # -- region --------------------------------------------------------------------------

    def _region(self, arrangement: Arrangement, kinds: list[Kind]) -> shapely.Polygon:
        el = self.ids.get("region")
        if el is not None:
            return self._region_element(el)
        box = self.root.attrib.get("viewBox")
        if box:
            try:
                x, y, w, h = (float(v) for v in re.split(r"[\s,]+", box.strip()))
            except ValueError:
                raise self.error(f"unreadable root viewBox {box!r}") from None
            if not all(map(math.isfinite, (x, y, w, h))):
                raise self.error(f"the root viewBox {box!r} is not finite")
            return self._checked_region(shapely.box(x, y, x + max(w, 0), y + max(h, 0)), "the root viewBox")
        w, h = self.root.attrib.get("width"), self.root.attrib.get("height")
        if w and h and "%" not in w + h:
            width, height = max(number_attr(w, 0), 0), max(number_attr(h, 0), 0)
            return self._checked_region(shapely.box(0, 0, width, height), "the root width/height")
        lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
        for k, kind in enumerate(kinds):  # the exact footprints' bounds, in bulk per kind
            arr = arrangement.take(arrangement.kind == k)
            turn = np.radians(arr.angle)
            c, s = np.cos(turn) * arr.scale, np.sin(turn) * arr.scale
            pts = shapely.get_coordinates(kind.footprint)
            x = c[:, None] * pts[:, 0] - s[:, None] * pts[:, 1] + arr.xy[:, :1]
            y = s[:, None] * pts[:, 0] + c[:, None] * pts[:, 1] + arr.xy[:, 1:]
            lo = np.minimum(lo, [x.min(initial=np.inf), y.min(initial=np.inf)])
            hi = np.maximum(hi, [x.max(initial=-np.inf), y.max(initial=-np.inf)])
        return self._checked_region(shapely.box(*lo, *hi), "the motifs' bounds")

    def _region_element(self, el: ET.Element) -> shapely.Polygon:
        tag = local_tag(el.tag)
        if tag not in ("rect", "circle", "ellipse", "polygon", "path"):
            raise self.error(f"{describe(el)} cannot be the input region (use rect, circle, ellipse, polygon or path)")
        m = np.eye(3)
        for node in self._ancestors(el):
            m = m @ element_matrix(node, self.source)
        rings = [
            shapely.make_valid(shapely.Polygon(p))
            for p, _ in flat_subpaths(el, self.source, REGION_FLATNESS)
            if len(np.unique(p, axis=0)) >= 3
        ]
        geom = shapely.union_all(rings) if rings else shapely.Polygon()
        return self._checked_region(apply_matrix(m, geom), describe(el))

    def _ancestors(self, el: ET.Element) -> list[ET.Element]:
        """``el`` and its ancestors, root first."""
        parents = {c: p for p in self.root.iter() for c in p}
        chain = [el]
        while chain[-1] in parents:
            chain.append(parents[chain[-1]])
        return chain[::-1]

    def _checked_region(self, geom: shapely.Geometry, what: str) -> shapely.Polygon:
        coords = shapely.get_coordinates(geom)
        if not (np.abs(coords) <= MAX_COORDINATE).all():  # also NaN: GEOS would overflow or fail
            raise self.error(f"the input region ({what}) has coordinates that are not finite or beyond ±{MAX_COORDINATE:g}")
        geom = shapely.union_all(polygons_of(shapely.make_valid(geom)))
        if geom.is_empty or geom.area <= 0:
            raise self.error(f"the input region ({what}) has no area")
        if isinstance(geom, shapely.MultiPolygon):
            raise self.error(f"the input region ({what}) must be one connected shape")
        return geom

