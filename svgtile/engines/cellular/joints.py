"""Joints drawn once: the line weight of outlined cells (legakis2001 §5.4, mortar of width 0).

A map pattern of bricks draws its joints as single strokes.  Cells outlined one by one draw every
joint twice — the two cells on either side of it each stroke it — and draw the unit's boundary,
which a tile never draws (the map's own linework does).  Two coincident strokes are the same
vector, but a renderer composes their anti-aliased edges twice: at the sizes a legend or a screen
shows them, joints of width 0.3 looked half again as dark as the tile's (FGDC 627: 1.67 times the
tile's ink at 1.4 pixels per unit, 1.06 at 8).

So when cells have no mortar and an outline-only style, :func:`draw_joints` strokes the union of
their outlines once, less the unit's boundary, as lines; the cells stay (polygons in GeoJSON,
unstroked paths in SVG that a user may fill).
"""

from __future__ import annotations

import numpy as np
import shapely

from svgtile.core.cells import LINE, Cellwork, geometry_array

#: The style of a cell whose outline is drawn by the joints.
UNSTROKED = "fill:none;stroke:none"


def outline_only(css: str) -> bool:
    """True if the CSS style draws a stroke and no fill (``fill:none;stroke:#000…``)."""
    decl = _declarations(css)
    return decl.get("fill") == "none" and decl.get("stroke", "none") != "none"


def _declarations(css: str) -> dict[str, str]:
    out = {}
    for item in css.split(";"):
        key, sep, value = item.partition(":")
        if sep:
            out[key.strip().lower()] = value.strip().lower()
    return out


def draw_joints(work: Cellwork, face: shapely.Geometry, tolerance: float) -> Cellwork:
    """``work`` with the outlines of its outline-only cells drawn as joints, each once.

    Parameters
    ----------
    work : the cells (mortar 0: neighbours share their sides) and lines
    face : the unit, user units; its boundary is not drawn
    tolerance : user units; outlines within this of each other are one joint, and of the face's
        boundary are the boundary

    Returns
    -------
    The cells of those styles restyled :data:`UNSTROKED`, and per style one MultiLineString of
    its joints (feature ``LINE``) after the rest.
    """
    cell = work.feature != LINE
    outlined = np.array([outline_only(css) for css in work.styles], dtype=bool)
    sel = cell & outlined[work.style]
    if not sel.any():
        return work
    edge = shapely.buffer(shapely.boundary(face), tolerance)
    # a side shared by cells of two styles is drawn once, in the style of the cell textured first
    # (corners, then edges, then the face: §4.2's order); with one style, one union does
    one_style = len(np.unique(work.style[sel])) == 1
    pairs = np.unique(np.stack([work.feature[sel], work.style[sel]], axis=1), axis=0).tolist()
    groups = [(None, int(work.style[sel][0]))] if one_style else [(int(f), int(k)) for f, k in pairs]
    nets: dict[int, list[shapely.Geometry]] = {}
    done = None
    for n, (f, k) in enumerate(groups):
        mine = sel & (work.style == k) & (True if f is None else work.feature == f)
        # noding the outlines on a grid merges the two copies of each shared side into one
        net = shapely.difference(shapely.union_all(shapely.boundary(work.shapes[mine]), grid_size=tolerance), edge)
        if done is not None:
            net = shapely.difference(net, done)
        nets.setdefault(k, []).append(net)
        if n < len(groups) - 1:
            grown = shapely.buffer(net, tolerance, cap_style="flat")
            done = grown if done is None else shapely.union(done, grown)
    styles = list(work.styles)
    if UNSTROKED not in styles:
        styles.append(UNSTROKED)
    style = np.where(sel, styles.index(UNSTROKED), work.style)
    lines, line_style = [], []
    for k in sorted(nets):
        parts = shapely.get_parts(shapely.line_merge(shapely.union_all(nets[k])))
        parts = parts[(shapely.get_type_id(parts) == 1) & (shapely.length(parts) > tolerance)]
        if len(parts):  # the joints of a style are one drawing: one path
            lines.append(shapely.multilinestrings(parts))
            line_style.append(k)
    if not lines:
        return work
    return Cellwork(np.concatenate([work.shapes, geometry_array(lines)]), np.r_[work.feature, np.full(len(lines), LINE)],
                    np.r_[style, line_style].astype(np.int64), tuple(styles))  # fmt: skip

