"""``svgtile analyze``: what synthesis must reproduce from an exemplar."""

from __future__ import annotations

import json

import click
import numpy as np

from svgtile.analysis.order import read_order
from svgtile.analysis.stats import Stats
from svgtile.cli.common import json_safe, load
from svgtile.core.exemplar import Exemplar
from svgtile.engines import ENGINES
from svgtile.engines.choose import choose
from svgtile.errors import ExemplarError


@click.command(name="analyze")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print machine-readable JSON.")
@click.option("--rings", "show_rings", is_flag=True,
              help="Also show the ring shapes the growth engine found (each motif's neighbours, Ijiri et al. 2008 §4).")
@click.option("--png", "png", default=None, metavar="FILE.png",
              help="Draw the exemplar's connectivity (motif centres and the edges of their ring shapes) to FILE.png.")
@click.option("--import", "as_tile", is_flag=True, help="EXEMPLAR is a seamless pattern tile: import it first.")
def analyze_cmd(exemplar, as_json, show_rings, png, as_tile):
    """Print what synthesis reproduces from EXEMPLAR: kinds, density, distances, orientations,
    and its order (rows, lattice, period, anisotropy, clustering, banding) with the engine
    ``--engine auto`` picks for it."""
    ex, stats = load(exemplar, as_tile=as_tile)
    report = stats_report(ex, stats)
    if show_rings and len(ex.motifs) == 0:
        raise ExemplarError("--rings shows the rings of motifs, and this pattern of cells has none",
                            source=exemplar)  # fmt: skip
    if show_rings:
        from svgtile.apps.rings import rings_report

        report["rings"] = rings_report(ex)
    if png is not None:
        from svgtile.apps.preview import render_png
        from svgtile.apps.rings import rings_svg
        from svgtile.files import check_output, write_file

        check_output(png, protect=(exemplar,))
        write_file(render_png(rings_svg(ex), 800), png, protect=(exemplar,))
    if as_json:
        click.echo(json.dumps(json_safe(report), indent=2, allow_nan=False))
    else:
        text = format_report(report)
        if show_rings:
            from svgtile.apps.rings import format_rings

            text += "\n" + format_rings(report["rings"])
        click.echo(text)


def stats_report(ex: Exemplar, stats: Stats) -> dict:
    """The analysis as plain data (what ``analyze --json`` prints)."""
    x0, y0, x1, y1 = ex.region.bounds
    counts = np.bincount(ex.motifs.kind, minlength=len(ex.kinds))
    order = read_order(ex)
    picked = choose(ex, stats, order=order, available=ENGINES)
    return {
        "exemplar": ex.source,
        "region": {"bounds": [x0, y0, x1, y1], "area": ex.region.area},
        "motifs": len(ex.motifs),
        "density": stats.density,
        "motifs_per_unit_area": stats.count_density,
        "kinds": [
            {
                "name": k.name,
                "count": int(counts[i]),
                "frequency": float(stats.frequency[i]),
                "area": k.prototype.area,
                "arc": {"start": float(stats.arc_start[i]), "width": float(stats.arc_width[i])},
            }
            for i, k in enumerate(ex.kinds)
        ],
        "distance": stats.distance.tolist(),
        "distance_measured": stats.measured.tolist(),
        "overlapping_pairs": stats.overlaps,
        "order": order.to_dict(),
        "auto": {"engine": picked.engine, "params": dict(picked.params), "rule": picked.rule, "why": picked.why},
    }


def readable(value: float) -> str:
    """A number as people read it: thousands separated and no exponent from 1000 up (``10,000``),
    four significant digits below (``12.57``)."""
    return f"{value:,.0f}" if abs(value) >= 1000 and abs(value) < 1e15 else f"{value:.4g}"


def format_report(r: dict) -> str:
    """The analysis as the table ``svgtile analyze`` prints."""
    x0, y0, x1, y1 = r["region"]["bounds"]
    lines = [
        f"exemplar      {r['exemplar']}",
        f"input region  {x1 - x0:g} x {y1 - y0:g} at ({x0:g}, {y0:g}), area {readable(r['region']['area'])}",
        f"motifs        {r['motifs']} in {len(r['kinds'])} kind(s)",
        f"density ρ     {r['density']:.4f} of the area covered, {r['motifs_per_unit_area']:.4g} motifs per unit²",
        "",
        f"  {'#':>2}  {'kind':<20} {'count':>5} {'share':>6} {'area':>8}   orientation arc",
    ]
    for i, k in enumerate(r["kinds"]):
        a = k["arc"]
        arc = f"{a['start']:+.1f}° … {a['start'] + a['width']:+.1f}° ({a['width']:.1f}°)"
        lines.append(f"  {i:>2}  {k['name']:<20} {k['count']:>5} {k['frequency']:>6.3f} {k['area']:>8.3f}   {arc}")
    lines += ["", "minimum distances d_ij (* = fallback, the exemplar has no such pair):"]
    names = [k["name"][:10] for k in r["kinds"]]
    lines.append("  " + " " * 12 + "".join(f"{n:>12}" for n in names))
    for i, row in enumerate(r["distance"]):
        cells = "".join(
            f"{v:>11.3f}{' ' if r['distance_measured'][i][j] else '*'}" for j, v in enumerate(row)
        )
        lines.append(f"  {names[i]:<12}{cells}")
    lines += ["", *format_order(r["order"]), f"auto          {r['auto']['why']} -> --engine {r['auto']['engine']}"
              + "".join(f" --{k.replace('_', '-')} {v:g}" if isinstance(v, float) else f" --{k.replace('_', '-')} {v}"
                        for k, v in r["auto"]["params"].items())]  # fmt: skip
    if r["overlapping_pairs"]:
        lines.append(f"\nwarning: {r['overlapping_pairs']} overlapping pair(s) in the exemplar")
    return "\n".join(lines)


def format_order(o: dict) -> list[str]:
    """The order lines of ``svgtile analyze`` (:func:`svgtile.analysis.order.read_order`)."""
    steps = "; ".join(f"{s['length']:.4g} at {s['angle']:.1f}° (support {s['support']:.2f})" for s in o["steps"])
    what = {"lattice": "a lattice", "rows": "rows", "scatter": "no rows or lattice"}[o["kind"]]
    period = f"{o['period'][0]:g} x {o['period'][1]:g}" if o["period"] else "none (drawn, not a repeating tile)"
    clustering = "n/a" if o["clustering"] != o["clustering"] else f"{o['clustering']:.2f}"
    return [
        f"order         {what}{': steps ' + steps if steps else ''}",
        f"period        {period}",
        f"anisotropy    {o['anisotropy']:.2f} (0 = nearest neighbours in every direction), along {o['anisotropy_angle']:.0f}°",
        f"clustering    R = {clustering} (Clark-Evans: <1 clustered, 1 random, >1 regular)",
        f"banding       {o['banding']:.2f} in strips at {o['band_angle']:.0f}° (0 = even), kinds {o['kind_banding']:.2f} (0 = mixed)",
    ]
