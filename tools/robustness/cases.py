"""Hostile inputs for every svgtile command (issue 16 item 5): the corpus the runner classifies.

Each :class:`Case` is a few files, a command line and how its standard output is connected.
Placeholders in file contents and arguments are filled by the runner:

``@HTTP@``     a URL on the runner's own listener (any request is a *fetch attempted*)
``@SECRET@``   the path of a named pipe the runner watches (any open is a *fetch attempted*)
``@EXEMPLAR@`` a small valid exemplar (the repository's ``exemplars/gravel.svg``)

:func:`generate` makes every case; nothing here touches the disk until :func:`write_case`.
"""

from __future__ import annotations

import gzip
from collections.abc import Iterator
from dataclasses import dataclass, field

HEAD = '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 40 40">'
SYMBOL = '<defs><symbol id="d" overflow="visible"><circle r="1"/></symbol></defs>'


def uses(n: int = 6, extra: str = "") -> str:
    """``n`` well-spaced ``<use>`` of the dot symbol, each with ``extra`` attributes."""
    return "".join(f'<use xlink:href="#d" x="{4 + 6 * (i % 6)}" y="{4 + 6 * (i // 6)}" {extra}/>' for i in range(n))


def svg(body: str, head: str = HEAD) -> bytes:
    return (head + body + "</svg>").encode()


@dataclass
class Case:
    """One run: ``files`` written into an empty folder, then ``svgtile ARGS`` run there.

    stdout : ``file`` (captured), ``closed`` (``>&-``), ``full`` (``/dev/full``) or ``head``
        (a pipe whose reader leaves after a few bytes)
    special : extra files the runner makes: ``fifo:NAME``, ``loop:NAME`` (a symlink to itself),
        ``dev:NAME`` (a symlink to ``/dev/zero``), ``sparse:NAME`` (a 200 MB file of holes)
    """

    name: str
    group: str
    args: list[str]
    files: dict[str, bytes] = field(default_factory=dict)
    stdout: str = "file"
    special: tuple[str, ...] = ()


def exemplar_cases(group: str, name: str, data: bytes, *, commands=("analyze", "synth", "import")) -> Iterator[Case]:
    """``data`` as the exemplar (or tile) of each command."""
    for cmd in commands:
        args = {
            "analyze": ["analyze", "in.svg"],
            "synth": ["synth", "in.svg", "--size", "200x200", "--seed", "1", "-o", "out.svg"],
            "import": ["import", "in.svg", "-o", "out.svg"],
            "compare": ["compare", "in.svg", "--size", "60", "--engines", "patch,random", "--png", "previews"],
            "swatches": ["swatches", "in.svg", "-o", "sheet.svg"],
        }[cmd]
        yield Case(f"{name}.{cmd}", group, args, {"in.svg": data})


def numbers() -> Iterator[Case]:
    """Hostile numbers in transforms, coordinates, lengths and boxes."""
    transforms = {
        "nan": "translate(nan 3)", "inf": "translate(inf 3)", "minus-inf": "scale(-inf)",
        "huge-translate": "translate(1e308 1e308)", "huge-scale": "scale(1e308)", "tiny-scale": "scale(1e-308)",
        "singular": "matrix(0 0 0 0 5 5)", "rank-one": "matrix(1 1 1 1 5 5)", "skew90": "skewX(90)",
        "skew-almost90": "skewX(89.99999)", "rotate-nan": "rotate(nan)", "rotate-huge": "rotate(1e308)",
        "overflow-product": "scale(1e200) scale(1e200)", "matrix-inf": "matrix(1 0 0 1 inf 0)",
    }  # fmt: skip
    for name, t in transforms.items():
        yield from exemplar_cases("numbers", f"use-{name}", svg(SYMBOL + uses(5) + f'<use xlink:href="#d" x="20" y="30" transform="{t}"/>'))
        yield from exemplar_cases("numbers", f"group-{name}", svg(SYMBOL + f'<g transform="{t}">{uses(5)}</g>'),
                                  commands=("analyze", "synth"))
        yield from exemplar_cases("numbers", f"plain-{name}", svg(f'<circle cx="5" cy="5" r="1"/><rect x="10" y="10" width="2" height="2" transform="{t}"/>'),
                                  commands=("analyze",))
    paths = {
        "path-1e308": "M 0 0 L 1e308 0 L 1e308 1e308 Z", "path-nan": "M 0 0 L nan 1 L 1 1 Z",
        "path-decimals": "M 0.1234567890123456789012345 0 L 1.000000000000000000001 0.0000000000000000001 L 0.5 1.99999999999999999 Z",
        "path-1e-300": "M 0 0 L 1e-300 0 L 0 1e-300 Z", "path-arc-huge": "M 1 1 A 1e308 1e308 0 0 1 3 3 Z",
        "path-overflow-sum": "M 1e308 0 l 1e308 0 l 0 1 z",
    }  # fmt: skip
    for name, d in paths.items():
        body = f'<defs><symbol id="d" overflow="visible"><path d="{d}"/></symbol></defs>' + uses(4)
        yield from exemplar_cases("numbers", f"symbol-{name}", svg(body))
        yield from exemplar_cases("numbers", f"plain-{name}", svg(f'<circle cx="5" cy="5" r="1"/><path d="{d}"/>'), commands=("analyze", "import"))
    lengths = {"r-nan": '<circle r="nan"/>', "r-huge": '<circle r="1e308"/>', "stroke-huge": '<line x2="1" stroke="#000" stroke-width="1e308"/>',
               "rect-inf": '<rect width="inf" height="1"/>', "rect-negative": '<rect width="-5" height="1"/>'}  # fmt: skip
    for name, shape in lengths.items():
        yield from exemplar_cases("numbers", f"length-{name}", svg(f'<defs><symbol id="d" overflow="visible">{shape}</symbol></defs>' + uses(4)))
    for box in ("0 0 nan 40", "0 0 1e308 1e308", "0 0 0 0", "0 0 -1 40", "0 0 1e-300 1e-300", "inf 0 40 40"):
        head = HEAD.replace('viewBox="0 0 40 40"', f'viewBox="{box}"')
        yield from exemplar_cases("numbers", f"viewbox-{box.replace(' ', '_')}", svg(SYMBOL + uses(6), head),
                                  commands=("analyze", "synth"))
    yield from exemplar_cases("numbers", "region-huge", svg(SYMBOL + uses(6) + '<rect id="region" width="1e300" height="1e300" fill="none"/>'),
                              commands=("analyze", "synth"))
    yield from exemplar_cases("numbers", "symbol-viewbox-singular",
                              svg('<defs><symbol id="d" viewBox="0 0 1e-300 1e-300"><circle r="1"/></symbol></defs>' + uses(4, 'width="2" height="2"')))


def structure() -> Iterator[Case]:
    """Size, depth and fan-out: the inputs that made svgtile run away."""
    yield from exemplar_cases("structure", "empty-file", b"")
    yield from exemplar_cases("structure", "garbage", bytes(range(256)) * 8)
    yield from exemplar_cases("structure", "truncated", svg(SYMBOL + uses(6))[:150])
    yield from exemplar_cases("structure", "not-svg", b"<html><body/></html>")
    yield from exemplar_cases("structure", "no-motifs", svg(""))
    deep = "<g>" * 10_000 + '<circle r="1"/>' + "</g>" * 10_000
    yield from exemplar_cases("structure", "deep-10000", svg(deep))
    yield from exemplar_cases("structure", "deep-200", svg("<g>" * 200 + SYMBOL + uses(5) + "</g>" * 200))
    many = "".join(f'<circle cx="{i % 400 * 0.5}" cy="{i // 400 * 0.5}" r="0.1"/>' for i in range(100_000))
    yield from exemplar_cases("structure", "shapes-100k", svg(many, HEAD.replace("0 0 40 40", "0 0 200 125")))
    pts = " ".join(f"L {i * 1e-4:.4f} {(i % 2) * 0.5}" for i in range(1_000_000))
    yield from exemplar_cases("structure", "path-1M-points", svg(f'<defs><symbol id="d" overflow="visible"><path d="M 0 0 {pts} Z"/></symbol></defs>' + uses(4)),
                              commands=("analyze", "synth"))
    symbols = "".join(f'<symbol id="s{i}" overflow="visible"><rect width="{0.1 + i * 1e-4:.4f}" height="0.1"/></symbol>' for i in range(5000))
    spread = "".join(f'<use xlink:href="#s{i}" x="{i % 100 * 2}" y="{i // 100 * 2}"/>' for i in range(5000))
    yield from exemplar_cases("structure", "symbols-5000", svg(f"<defs>{symbols}</defs>{spread}", HEAD.replace("0 0 40 40", "0 0 200 100")))
    fan = '<symbol id="l0" overflow="visible"><circle r="0.5"/></symbol>' + "".join(
        f'<symbol id="l{i}" overflow="visible"><use xlink:href="#l{i - 1}"/><use xlink:href="#l{i - 1}" x="0.001"/></symbol>'
        for i in range(1, 31))  # fmt: skip
    yield from exemplar_cases("structure", "use-fanout-2^30", svg(f"<defs>{fan}</defs>" + '<use xlink:href="#l30" x="5" y="5"/><use xlink:href="#l30" x="20" y="20"/>'))
    yield from exemplar_cases("structure", "use-self", svg('<defs><symbol id="d"><use xlink:href="#d"/></symbol></defs>' + uses(3)))
    overlap = "".join(f'<use xlink:href="#d" x="{5 + (i % 50) * 0.6}" y="{5 + (i // 50) * 0.6}"/>' for i in range(2500))
    yield from exemplar_cases("structure", "overlap-2500", svg(SYMBOL + overlap))
    stacked = "".join('<use xlink:href="#d" x="20" y="20"/>' for _ in range(3000))
    yield from exemplar_cases("structure", "stacked-3000", svg(SYMBOL + stacked))
    yield from exemplar_cases("structure", "ids-duplicate", svg(SYMBOL + '<symbol id="d"><rect width="1" height="1"/></symbol>' + uses(5)))
    hatch = "".join(f'<line x1="0" y1="{i}" x2="40" y2="{i}" stroke="#000" stroke-width="0.2"/>' for i in range(40))
    yield from exemplar_cases("structure", "hatching", svg(hatch))


def encodings() -> Iterator[Case]:
    """One small valid exemplar in every encoding the XML parser takes, and some it refuses."""
    text = ('<?xml version="1.0" encoding="{enc}"?>' + HEAD + SYMBOL + uses(6) + "<title>Géologie</title></svg>")
    for enc, codec in (("UTF-16", "utf-16"), ("UTF-16BE", "utf-16-be"), ("ISO-8859-1", "latin-1"), ("UTF-8", "utf-8-sig")):
        yield from exemplar_cases("encodings", f"enc-{enc}", text.format(enc=enc).encode(codec),
                                  commands=("analyze", "synth", "import", "compare", "swatches"))
    yield from exemplar_cases("encodings", "enc-unknown", text.format(enc="X-NOPE").encode())
    yield from exemplar_cases("encodings", "enc-lying", text.format(enc="UTF-16").encode())
    yield from exemplar_cases("encodings", "svgz", gzip.compress(svg(SYMBOL + uses(6)), mtime=0))


def entities() -> Iterator[Case]:
    """Entity expansion and external entities: never expanded from outside, never fetched."""
    laughs = '<!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa">' + "".join(
        f'<!ENTITY {c} "{("&" + p + ";") * 10}">' for p, c in zip("abcdefgh", "bcdefghi", strict=True)) + "]>"  # fmt: skip
    yield from exemplar_cases("entities", "billion-laughs", (laughs + HEAD + SYMBOL + uses(4) + "<title>&i;</title></svg>").encode())
    for name, ref in (("file", "file://@SECRET@"), ("http", "@HTTP@/entity")):
        doc = f'<!DOCTYPE svg [<!ENTITY x SYSTEM "{ref}">]>' + HEAD + SYMBOL + uses(4) + "<title>&x;</title></svg>"
        yield from exemplar_cases("entities", f"external-entity-{name}", doc.encode())
    yield from exemplar_cases("entities", "external-dtd", ('<!DOCTYPE svg SYSTEM "@HTTP@/svg.dtd">' + HEAD + SYMBOL + uses(4) + "</svg>").encode())
    yield from exemplar_cases("entities", "parameter-entity", ('<!DOCTYPE svg [<!ENTITY % p SYSTEM "@HTTP@/p">%p;]>' + HEAD + SYMBOL + uses(4) + "</svg>").encode())


def references() -> Iterator[Case]:
    """External references in what svgtile copies to its output: dropped, never fetched."""
    refs = {
        "use-http": '<use xlink:href="@HTTP@/s.svg#d" x="30" y="30"/>',
        "use-file": '<use xlink:href="file://@SECRET@#d" x="30" y="30"/>',
        "fill-url-http": "", "feimage": "", "mask-http": "", "image": '<image xlink:href="@HTTP@/i.png" width="5" height="5"/>',
        "stylesheet-pi": "", "style-import": '<style>@import url(@HTTP@/x.css);</style>',
    }  # fmt: skip
    symbols = {
        "fill-url-http": '<symbol id="d" overflow="visible"><circle r="1" fill="url(@HTTP@/p.svg#g)"/></symbol>',
        "feimage": '<filter id="f"><feImage xlink:href="@HTTP@/f.png"/></filter><symbol id="d" overflow="visible"><circle r="1" filter="url(#f)"/></symbol>',
        "mask-http": '<symbol id="d" overflow="visible"><circle r="1" mask="url(@HTTP@/m.svg#m)" style="clip-path:url(@HTTP@/c.svg#c)"/></symbol>',
    }  # fmt: skip
    for name, extra in refs.items():
        defs = f"<defs>{symbols.get(name, SYMBOL[6:-7])}</defs>"
        head = ('<?xml-stylesheet href="@HTTP@/s.css"?>' + HEAD) if name == "stylesheet-pi" else HEAD
        yield from exemplar_cases("references", name, svg(defs + uses(6) + extra, head), commands=("analyze", "synth", "import", "compare"))


def file_kinds() -> Iterator[Case]:
    """What is not a regular file: pipes, devices, loops, folders, holes."""
    for kind in ("fifo", "loop", "dev", "sparse"):
        yield Case(f"{kind}.synth", "file kinds", ["synth", "in.svg", "--size", "50", "-o", "out.svg"], special=(f"{kind}:in.svg",))
        yield Case(f"{kind}.region", "file kinds", ["synth", "@EXEMPLAR@", "--region", "in.svg#r", "-o", "out.svg"], special=(f"{kind}:in.svg",))
        yield Case(f"{kind}.styles", "file kinds", ["map", "m.svg", "--styles", "in.toml", "-o", "out.svg"],
                   {"m.svg": svg('<rect class="a" width="9" height="9"/>')}, special=(f"{kind}:in.toml",))
    yield Case("folder.synth", "file kinds", ["synth", ".", "--size", "50", "-o", "out.svg"])
    yield Case("missing.synth", "file kinds", ["synth", "nothing.svg", "--size", "50", "-o", "out.svg"])
    yield Case("output-folder-missing", "file kinds", ["synth", "@EXEMPLAR@", "--size", "50", "-o", "no/out.svg"])
    yield Case("output-loop", "file kinds", ["synth", "@EXEMPLAR@", "--size", "50", "-o", "out.svg"], special=("loop:out.svg",))
    for mode in ("closed", "full", "head"):
        yield Case(f"stdout-{mode}", "file kinds", ["synth", "@EXEMPLAR@", "--size", "300", "--seed", "1", "-o", "-"], stdout=mode)


def maps_and_styles() -> Iterator[Case]:
    """Maps and styles files: depth, numbers, size."""
    styles = b'[classes.a]\nexemplar = "@EXEMPLAR@"\n'
    deep_map = svg("<g>" * 10_000 + '<rect class="a" width="9" height="9"/>' + "</g>" * 10_000)
    yield Case("map-deep-10000", "maps", ["map", "m.svg", "--styles", "s.toml", "-o", "out.svg"], {"m.svg": deep_map, "s.toml": styles})
    yield Case("map-nan-path", "maps", ["map", "m.svg", "--styles", "s.toml", "-o", "out.svg"],
               {"m.svg": svg('<path class="a" d="M 0 0 L nan 0 L 9 9 Z"/>'), "s.toml": styles})
    yield Case("map-huge-transform", "maps", ["map", "m.svg", "--styles", "s.toml", "-o", "out.svg"],
               {"m.svg": svg('<g transform="scale(1e308)"><rect class="a" width="9" height="9"/></g>'), "s.toml": styles})
    yield Case("map-unit-too-small", "maps", ["map", "m.svg", "--styles", "s.toml", "-o", "out.svg"],
               {"m.svg": svg('<rect class="a" width="1e-9" height="1e-9"/>'), "s.toml": styles})
    yield Case("map-all-fail", "maps", ["map", "m.svg", "--styles", "s.toml", "-o", "out.svg"],
               {"m.svg": svg('<rect class="a" width="9" height="9"/><rect class="a" x="20" width="9" height="9"/>'),
                "s.toml": b'[classes.a]\nexemplar = "bad.svg"\n', "bad.svg": b"<svg"})
    deep_toml = b"a = " + b"[" * 100_000 + b"]" * 100_000 + b"\n"
    yield Case("styles-deep-arrays", "maps", ["map", "m.svg", "--styles", "s.toml", "-o", "out.svg"],
               {"m.svg": svg('<rect class="a" width="9" height="9"/>'), "s.toml": deep_toml})
    deep_tables = b"x = " + b"{a = " * 50_000 + b"1" + b"}" * 50_000 + b"\n"
    yield Case("styles-deep-tables", "maps", ["map", "m.svg", "--styles", "s.toml", "-o", "out.svg"],
               {"m.svg": svg('<rect class="a" width="9" height="9"/>'), "s.toml": deep_tables})
    yield Case("region-deep", "maps", ["synth", "@EXEMPLAR@", "--region", "m.svg#r", "-o", "out.svg"],
               {"m.svg": svg("<g>" * 10_000 + '<rect id="r" width="9" height="9"/>' + "</g>" * 10_000)})
    yield Case("region-nan", "maps", ["synth", "@EXEMPLAR@", "--region", "m.svg#r", "-o", "out.svg"],
               {"m.svg": svg('<rect id="r" width="nan" height="9"/>')})
    gj = b'{"type":"Polygon","coordinates":[[[0,0],[1e308,0],[1e308,1e308],[0,0]]]}'
    yield Case("geojson-huge", "maps", ["synth", "@EXEMPLAR@", "--region", "r.geojson", "-o", "out.svg"], {"r.geojson": gj})
    deep_json = b"[" * 100_000 + b"]" * 100_000
    yield Case("geojson-deep", "maps", ["synth", "@EXEMPLAR@", "--region", "r.geojson", "-o", "out.svg"], {"r.geojson": deep_json})
    yield Case("size-near-limit", "maps", ["synth", "@EXEMPLAR@", "--size", "12000", "-o", "out.svg"])
    yield Case("swatches-all-refused", "maps", ["swatches", "a.svg", "b.svg", "-o", "sheet.svg"], {"a.svg": b"<svg", "b.svg": svg("")})
    yield Case("names-utf16", "maps", ["swatches", "@EXEMPLAR@", "--names", "n.csv", "-o", "sheet.svg"],
               {"n.csv": "name,code\nGravier,gravel\n".encode("utf-16")})


def clashes() -> Iterator[Case]:
    """An output that is an input: refused, nothing written, nothing changed."""
    m = svg('<rect id="qal" class="a" width="30" height="30"/><text id="labels" x="5" y="5">Qal</text>')
    gj = b'{"type":"Polygon","coordinates":[[[0,0],[30,0],[30,-30],[0,-30],[0,0]]]}'
    st = b'[classes.a]\nexemplar = "@EXEMPLAR@"\n'
    files = {"map.svg": m, "other.svg": m, "a.geojson": gj, "s.toml": st, "names.csv": b"name,code\nG,gravel\n"}
    lines = {
        "region": ["synth", "@EXEMPLAR@", "--region", "map.svg#qal", "-o", "map.svg"],
        "avoid": ["synth", "@EXEMPLAR@", "--size", "30", "--avoid", "map.svg#labels", "-o", "map.svg"],
        "region-geojson": ["synth", "@EXEMPLAR@", "--region", "a.geojson", "-o", "a.geojson"],
        "avoid-geojson": ["synth", "@EXEMPLAR@", "--size", "30", "--avoid", "a.geojson", "-o", "a.geojson"],
        "map-avoid": ["map", "map.svg", "--styles", "s.toml", "--avoid", "other.svg#labels", "-o", "other.svg"],
        "map-styles": ["map", "map.svg", "--styles", "s.toml", "-o", "s.toml"],
        "swatches-names": ["swatches", "@EXEMPLAR@", "--names", "names.csv", "-o", "names.csv"],
        "import-self": ["import", "map.svg", "-o", "./map.svg"],
        "compare-png": ["compare", "p/tile.svg", "--size", "30", "--engines", "patch,tile", "--png", "p"],
    }
    for name, args in lines.items():
        extra = {"p/tile.svg": b"@EXEMPLAR_BYTES@"} if name == "compare-png" else {}
        yield Case(f"clash-{name}", "clashes", args, {**files, **extra})


GROUPS = (numbers, structure, encodings, entities, references, file_kinds, maps_and_styles, clashes)


def generate() -> list[Case]:
    """Every case of the corpus, in a stable order."""
    return [case for group in GROUPS for case in group()]
