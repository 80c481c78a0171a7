"""The exemplar's connectivity and ring shapes (Ijiri et al. 2008 §4), as ``svgtile analyze
--rings`` prints them and ``--png`` draws them."""

from __future__ import annotations

import numpy as np

from svgtile.core.exemplar import Exemplar
from svgtile.engines.growth.connectivity import edges_of, reference_rings, regularity, ring_classes


def rings_report(ex: Exemplar) -> dict:
    """Ring shapes as plain data: how many motifs have a whole ring, the ring sizes, the classes
    of alike rings and the regularity (1 for rows or a lattice)."""
    rings = reference_rings(ex)
    classes = ring_classes(rings)
    sizes, counts = np.unique(rings.size, return_counts=True)
    return {"motifs_with_a_ring": len(rings), "ring_sizes": {int(s): int(c) for s, c in zip(sizes, counts, strict=True)},
            "ring_classes": len(np.unique(classes)), "regularity": regularity(rings),
            "mean_edge_length": rings.mean_length, "shortest_edge": rings.short_length,
            "periodic": ex.period is not None}  # fmt: skip


def format_rings(r: dict) -> str:
    sizes = ", ".join(f"{c}×{s}" for s, c in r["ring_sizes"].items())
    return "\n".join([
        "",
        f"ring shapes   {r['motifs_with_a_ring']} motifs with a whole ring{' (periodic)' if r['periodic'] else ''}: "
        f"{sizes} neighbours",
        f"              {r['ring_classes']} class(es) of alike rings, regularity {r['regularity']:.2f} "
        f"({'rows or a lattice' if r['regularity'] >= 0.75 else 'irregular'}); mean edge {r['mean_edge_length']:.4g}",
    ])  # fmt: skip


def rings_svg(ex: Exemplar) -> str:
    """An SVG of the exemplar's motif centres (dots) and connectivity (lines), in its own user
    units; for a tile, the edges leaving the tile are drawn to the neighbouring copy."""
    xy = ex.motifs.xy
    m = len(xy)
    if ex.period is not None:
        w, h = ex.period
        da, db = (v.ravel() for v in np.meshgrid([0, -1, 1], [0, -1, 1]))
        pts = (xy[None] + np.stack([da * w, db * h], -1)[:, None]).reshape(-1, 2)
    else:
        pts = xy
    e = edges_of(pts)
    e = e[(e < m).any(1)]
    x0, y0, x1, y1 = ex.region.bounds
    pad = 0.05 * max(x1 - x0, y1 - y0)
    r = 0.01 * max(x1 - x0, y1 - y0)
    lines = "".join(f'<line x1="{pts[i, 0]:.4f}" y1="{pts[i, 1]:.4f}" x2="{pts[j, 0]:.4f}" y2="{pts[j, 1]:.4f}"/>'
                    for i, j in e)  # fmt: skip
    dots = "".join(f'<circle cx="{x:.4f}" cy="{y:.4f}" r="{r:.4f}"/>' for x, y in xy)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{x0 - pad:.4f} {y0 - pad:.4f} {x1 - x0 + 2 * pad:.4f} '
            f'{y1 - y0 + 2 * pad:.4f}"><rect x="{x0:.4f}" y="{y0:.4f}" width="{x1 - x0:.4f}" height="{y1 - y0:.4f}" '
            f'fill="none" stroke="#999" stroke-width="{r / 2:.4f}"/><g stroke="#c33" stroke-width="{r / 2:.4f}">{lines}</g>'
            f'<g fill="#000">{dots}</g></svg>')  # fmt: skip
