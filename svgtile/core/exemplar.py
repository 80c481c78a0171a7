"""The exemplar model: motif kinds, their instances and the input region (almeraj2013 §3.1).

Read from SVG by :mod:`svgtile.svg.reader`.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass

import numpy as np
import shapely

from svgtile.core.arrangement import Arrangement
from svgtile.core.footprint import Prototype


@dataclass(frozen=True, eq=False)
class Kind:
    """A motif kind (almeraj2013's primitive shape S_i) and how to draw it.

    The kind's local frame has its origin at the footprint centroid.  An instance at ``xy`` with
    ``angle`` and ``scale`` is written as
    ``<use href="#{href}" transform="translate(xy) rotate(angle) scale(scale)
    translate(offset) matrix(residual)" {use_attrs}/>``.

    Attributes
    ----------
    name : str
        Human-readable name (the symbol id, with a suffix for variants).
    href : str
        Id of the element the output ``<use>`` references.
    prototype : Prototype
        Footprint in the local frame.
    offset : (2,) float array
        Translation from the residual frame to the local frame (minus the centroid).
    residual : (2, 2) float array
        Linear part that is not rotation or uniform scale (identity for most kinds).
    use_attrs : tuple of (name, value)
        Attributes the output ``<use>`` must carry (viewport size, inherited style).
    footprint : shapely (Multi)Polygon or None
        The exact footprint in the local frame (the prototype is a simplified cover of it, see
        :meth:`Prototype.from_geometry`).
    """

    name: str
    href: str
    prototype: Prototype
    offset: np.ndarray
    residual: np.ndarray
    use_attrs: tuple[tuple[str, str], ...] = ()
    footprint: shapely.Geometry | None = None


@dataclass(frozen=True, eq=False)
class Exemplar:
    """A parsed exemplar.

    Attributes
    ----------
    source : str
        File name used in messages.
    kinds : tuple of Kind
    motifs : Arrangement
        The instances whose centroid lies in the region.
    region : shapely Polygon
        The input region, user units.
    defs : tuple of ET.Element
        Elements the output copies into its ``<defs>`` (referenced symbols and what they reference,
        or the generated symbols of a plain drawing), in a stable order.
    warnings : tuple of str
        Non-fatal problems (overlapping motifs, ignored elements …).
    period : (2,) tuple of float or None, user units
        The exemplar is one tile of a pattern that repeats with this horizontal and vertical
        period (given by ``svgtile:period="W H"`` on the region element, as ``svgtile import``
        writes it); :func:`svgtile.analysis.stats.analyze` then measures across the tile's edges.
    cellular : dict or None
        The description of a cellular pattern (``svgtile:cellular`` on the region element, JSON,
        as ``svgtile import`` writes it for bedded and brick tiles; see
        :mod:`svgtile.engines.cellular.tree`): such an exemplar may have no motifs.
    ground : str or None
        The colour the pattern is drawn on (``svgtile:ground`` on the region element, as
        ``svgtile import`` writes a tile's painted background: FGDC 659's black); the writers
        paint the region with it under the texture.  None: the page.
    """

    source: str
    kinds: tuple[Kind, ...]
    motifs: Arrangement
    region: shapely.Polygon
    defs: tuple[ET.Element, ...]
    warnings: tuple[str, ...] = ()
    period: tuple[float, float] | None = None
    cellular: dict | None = None
    ground: str | None = None

    @property
    def prototypes(self) -> list[Prototype]:
        return [k.prototype for k in self.kinds]


