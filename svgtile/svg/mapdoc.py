"""Map documents: shapes of an SVG map addressed by id (filled by their fill rule), text boxes."""

from __future__ import annotations

import io
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import shapely

from svgtile.core.region import FILL_RULES, winding_fill
from svgtile.errors import ExemplarError
from svgtile.files import read_input
from svgtile.svg.dialect import (
    CONTAINERS,
    INITIAL,
    LENGTH_RE,
    MAX_ELEMENTS,
    NOT_RENDERED,
    REGION_FLATNESS,
    SHAPES,
    SVG_NS,
    absolute_length,
    apply_matrix,
    cascade_style,
    check_tree,
    describe,
    element_matrix,
    flat_subpaths,
    is_hidden,
    is_svg,
    leaf_footprint,
    local_tag,
    number_attr,
    one_line,
    shorten,
    tag_ns,
)
from svgtile.svg.reader import DocumentReader

# The same flattening serves map regions and avoid zones (issue 5): a map SVG is not an exemplar,
# but its shapes are read with the helpers above, so svgelements stays in this module.

#: Text without a measurable font is taken as this many user units high (the CSS default).
DEFAULT_FONT_SIZE = 16.0
#: Width of an average glyph as a fraction of the font size, for estimated text boxes.
GLYPH_WIDTH = 0.6
#: A text line's box reaches this far above and below its baseline, in font sizes.
ASCENT, DESCENT = 0.8, 0.25


def _font_size(chain: list[ET.Element]) -> float:
    """The font size in user units inherited along ``chain`` (root first)."""
    size = DEFAULT_FONT_SIZE
    for node in chain:
        value = node.attrib.get("font-size")
        for decl in node.attrib.get("style", "").split(";"):
            if ":" in decl and decl.split(":", 1)[0].strip() == "font-size":
                value = decl.split(":", 1)[1]
        if value is not None:
            try:
                size = absolute_length(value)
            except ValueError:
                match = LENGTH_RE.match(value)
                if match and match.group(2) in ("em", "%"):  # relative to the parent's size
                    size *= float(match.group(1)) / (100.0 if match.group(2) == "%" else 1.0)
    return size


class SvgShapes:
    """Shapes of a map SVG as shapely geometry in the root's user units (map regions, avoid zones).

    Reads what :func:`read_exemplar` reads — paths, basic shapes and groups, transforms of the
    element and its ancestors, inherited style — plus text, as estimated boxes.
    """

    def __init__(self, data: bytes, source: str, *, comments: bool = False) -> None:
        """Parse ``data``; with ``comments`` the tree keeps comments and processing instructions
        (to be written back, as ``svgtile map`` does), and :attr:`namespaces` lists the prefixes
        the file declares."""
        try:
            builder = ET.TreeBuilder(insert_comments=comments, insert_pis=comments)
            root = ET.fromstring(data, parser=ET.XMLParser(target=builder))
            self.namespaces = [ns for _, ns in ET.iterparse(io.BytesIO(data), events=("start-ns",))]
        except (ET.ParseError, ValueError, LookupError) as exc:
            raise ExemplarError(f"not a well-formed XML file ({one_line(exc)})", source=source) from None
        if local_tag(root.tag) != "svg" or tag_ns(root.tag) not in ("", SVG_NS):
            raise ExemplarError(f"not an SVG document (root element is <{local_tag(root.tag)}>)", source=source)
        check_tree(root, source, max_elements=10 * MAX_ELEMENTS)  # a map may be large, never deep
        self.root, self.source = root, source
        self.reader = DocumentReader(root, source)
        self.parents = {c: p for p in root.iter() for c in p}

    @classmethod
    def read(cls, path: str | Path, *, comments: bool = False) -> SvgShapes:
        path = Path(path)
        data = read_input(path, error=ExemplarError)
        return cls(data, str(path), comments=comments)

    def error(self, message: str) -> ExemplarError:
        return ExemplarError(one_line(message), source=self.source)

    def element(self, ident: str) -> ET.Element:
        el = self.reader.ids.get(ident)
        if el is None:
            raise self.error(f"no element with id {shorten(ident)!r}")
        return el

    def chain(self, el: ET.Element) -> list[ET.Element]:
        """``el`` and its ancestors, root first."""
        out = [el]
        while out[-1] in self.parents:
            out.append(self.parents[out[-1]])
        return out[::-1]

    def matrix(self, el: ET.Element) -> np.ndarray:
        """(3, 3) matrix from ``el``'s own user space to the root's (its transform included)."""
        m = np.eye(3)
        for node in self.chain(el)[1:]:
            m = m @ element_matrix(node, self.source)
        return m

    def style(self, el: ET.Element) -> dict[str, str]:
        """Effective (cascaded) presentation properties of ``el``."""
        style = INITIAL
        for node in self.chain(el):
            style = cascade_style(node, style)
        return style

    def area(self, el: ET.Element) -> shapely.Geometry:
        """The area ``el`` (a closed shape or a group of them) encloses, holes by its fill rule.

        Every subpath counts as closed (as when SVG fills it), whatever the fill paint; a group
        is the union of its shapes.  Hidden elements and text are left out.
        """
        tag = local_tag(el.tag)
        if tag not in SHAPES and tag not in (*CONTAINERS, "svg"):
            raise self.error(f"{describe(el)} cannot be a region (use a closed shape or a group of them)")
        parent = self.parents.get(el)
        parent_style = self.style(parent) if parent is not None else INITIAL
        m = self.matrix(parent) if parent is not None else np.eye(3)
        geom = self._area(el, parent_style, m)
        return shapely.Polygon() if geom is None else geom

    def _area(self, el: ET.Element, parent_style: dict[str, str], m: np.ndarray) -> shapely.Geometry | None:
        style = cascade_style(el, parent_style)
        # as in keep_clear, id="region" is an ordinary element here: it only marks an exemplar's region
        if is_hidden(style) or not is_svg(el) or local_tag(el.tag) in NOT_RENDERED:
            return None
        m = m @ element_matrix(el, self.source)
        tag = local_tag(el.tag)
        if tag in SHAPES:
            rings = [pts for pts, _ in flat_subpaths(el, self.source, REGION_FLATNESS)]
            rule = style.get("fill-rule", "nonzero").strip()
            geom = winding_fill(rings, rule if rule in FILL_RULES else "nonzero")  # CSS: an invalid value is the initial one
            return apply_matrix(m, geom)
        if tag in (*CONTAINERS, "svg"):
            parts = [self._area(c, style, m) for c in el]
            parts = [p for p in parts if p is not None and not p.is_empty]
            return shapely.union_all(parts) if parts else None
        return None

    def keep_clear(self, el: ET.Element, margin: float) -> shapely.Geometry:
        """The zone motifs must keep out of around ``el``, grown by ``margin`` user units.

        A shape's footprint (its closed outlines' interior and its stroke band; a line is its
        stroke), a text's estimated box (:data:`GLYPH_WIDTH` per character, :data:`ASCENT` and
        :data:`DESCENT` about each line's baseline, ``text-anchor`` honoured), a group's union.
        """
        parts: list[shapely.Geometry] = []
        for node, style, m, tag in self._drawn(el):
            if tag == "text":
                parts.extend(apply_matrix(m, box) for box in self._text_boxes(node))
                continue
            geom = leaf_footprint(node, style, self.source)
            if geom is None:  # an unstroked line: the line itself, grown by the margin later
                geom = shapely.union_all([shapely.LineString(p) if len(p) > 1 else shapely.Point(p[0])
                                          for p, _ in flat_subpaths(node, self.source)])
            parts.append(apply_matrix(m, geom))
        parts = [p for p in parts if not p.is_empty]
        if not parts:
            return shapely.Polygon()
        grown = shapely.buffer(np.array(parts, dtype=object), margin, quad_segs=4) if margin > 0 else parts
        return shapely.union_all(grown)

    def strokes(self, el: ET.Element) -> list[tuple[np.ndarray, float]]:
        """The lines ``el`` draws (a shape, or a group's shapes in document order) as polylines.

        Returns
        -------
        list of ``(points, width)``: ``points`` a (k, 2) float array in the root's user units, in
        drawing order (a closed subpath ends where it began); ``width`` its stroke width in root
        user units (0 when unstroked), scaled by the transforms.  Hidden elements and text are
        left out.
        """
        out: list[tuple[np.ndarray, float]] = []
        for node, style, m, tag in self._drawn(el):
            if tag == "text":
                continue
            painted = style.get("stroke", INITIAL["stroke"]).strip() not in ("none", "")
            width = number_attr(style.get("stroke-width"), 1.0) * np.sqrt(abs(np.linalg.det(m[:2, :2]))) if painted else 0.0
            for pts, closed in flat_subpaths(node, self.source, REGION_FLATNESS):
                pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
                if closed and len(pts) > 1 and not np.array_equal(pts[0], pts[-1]):
                    pts = np.vstack([pts, pts[:1]])
                out.append((pts @ m[:2, :2].T + m[:2, 2], float(width)))
        return out

    def _drawn(self, el: ET.Element) -> Iterator[tuple[ET.Element, dict[str, str], np.ndarray, str]]:
        """The shapes and texts ``el`` draws, in document order: ``(node, style, matrix, tag)``,
        the matrix from the node's user space to the root's; hidden and unrendered elements (and
        what they hold) left out."""
        parent = self.parents.get(el)
        parent_style = self.style(parent) if parent is not None else INITIAL
        m = self.matrix(parent) if parent is not None else np.eye(3)
        yield from self._walk(el, parent_style, m)

    def _walk(self, el, parent_style, m):
        style = cascade_style(el, parent_style)
        if is_hidden(style) or not is_svg(el) or local_tag(el.tag) in NOT_RENDERED:
            return
        m = m @ element_matrix(el, self.source)
        tag = local_tag(el.tag)
        if tag in SHAPES or tag == "text":
            yield el, style, m, tag
        elif tag in (*CONTAINERS, "svg"):
            for child in el:
                yield from self._walk(child, style, m)

    def _text_boxes(self, text: ET.Element) -> list[shapely.Polygon]:
        """Estimated boxes of a ``<text>``'s lines in its own user space (a ``tspan`` with its
        own ``x`` or ``y`` starts a line, as Inkscape writes multi-line text)."""
        lines: list[list] = []  # [x, y, anchor, size, characters]

        def walk(node: ET.Element, x: float, y: float, anchor: str) -> None:
            chain = self.chain(node)
            size = _font_size(chain)
            anchor = self._text_anchor(node, anchor)
            if "x" in node.attrib or "y" in node.attrib or not lines:
                x = number_attr((node.attrib.get("x") or "").split(",")[0].split(" ")[0] or None, x)
                y = number_attr((node.attrib.get("y") or "").split(",")[0].split(" ")[0] or None, y)
                lines.append([x, y, anchor, size, 0])
            lines[-1][3] = max(lines[-1][3], size)
            lines[-1][4] += len((node.text or "").strip())
            for child in node:
                if local_tag(child.tag) == "tspan":
                    walk(child, lines[-1][0], lines[-1][1], anchor)
                lines[-1][4] += len((child.tail or "").strip())

        anchor = "start"
        for node in self.chain(text)[:-1]:  # text-anchor is inherited
            anchor = self._text_anchor(node, anchor)
        walk(text, 0.0, 0.0, anchor)
        boxes = []
        for x, y, anchor, size, chars in lines:
            if chars == 0:
                continue
            width = GLYPH_WIDTH * size * chars
            x0 = x - {"start": 0.0, "middle": 0.5, "end": 1.0}.get(anchor, 0.0) * width
            boxes.append(shapely.box(x0, y - ASCENT * size, x0 + width, y + DESCENT * size))
        return boxes

    @staticmethod
    def _text_anchor(node: ET.Element, inherited: str) -> str:
        value = node.attrib.get("text-anchor")
        for decl in node.attrib.get("style", "").split(";"):
            if ":" in decl and decl.split(":", 1)[0].strip() == "text-anchor":
                value = decl.split(":", 1)[1]
        return value.strip() if value else inherited
