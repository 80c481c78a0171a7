"""The written SVG: number format, document contract, round trip, atomic writing, golden files."""

from __future__ import annotations

import io
import os
import re
import stat
import sys
import types
import warnings
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import EXEMPLARS, SVG_HEAD, TINY, arrange

from svgtile.analysis.stats import analyze
from svgtile.cli.main import main
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.errors import OutputError
from svgtile.files import check_output, write_file
from svgtile.svg.dialect import SVG_NS, XLINK_NS
from svgtile.svg.reader import parse_exemplar, read_exemplar
from svgtile.svg.writer import fmt, fmt_array, path_data, svg_document, use_elements

GOLDEN = Path(__file__).parent / "golden"
HREF = f"{{{XLINK_NS}}}href"
META = "{urn:svgtile:run:1}run"


def synthesize(path: Path, size=(60.0, 40.0), seed: int = 1, **params):
    """The library pipeline the CLI runs: (exemplar, arrangement, region, SVG text)."""
    ex = read_exemplar(path)
    stats = analyze(ex)
    region = Region.rectangle(*size)
    arr = arrange("patch", ex, region, rng=np.random.default_rng(seed), stats=stats, **params)
    text = svg_document(ex, arr, region, boundary=params.get("boundary", "clip"), params={"seed": seed, **params})
    return ex, arr, region, text


def motif_group(root: ET.Element) -> ET.Element:
    groups = root.findall(f"{{{SVG_NS}}}g")
    assert len(groups) == 1
    return groups[0]


def canonical(el: ET.Element):
    """An element as comparable data, whitespace between elements ignored."""
    return el.tag, sorted(el.attrib.items()), (el.text or "").strip(), [canonical(c) for c in el]


# ----------------------------------------------------------------------------- numbers


@pytest.mark.parametrize(
    ("value", "text"),
    [
        (0.0, "0"), (-0.0, "0"), (1.0, "1"), (-2.0, "-2"), (0.5, "0.5"), (1.23456, "1.2346"),
        (-1.23454, "-1.2345"), (0.00004, "0"), (-0.00004, "0"), (1e-4, "0.0001"), (-1e-4, "-0.0001"),
        (12345.67891, "12345.6789"), (100.0, "100"), (1e11, "100000000000"), (-3e12, "-3000000000000"),
        (0.1 + 0.2, "0.3"), (59.99999, "60"),
    ],
)  # fmt: skip
def test_fmt(value, text):
    assert fmt(value) == text


def test_fmt_writes_the_largest_floats_without_overflow():
    # np.round(v, 4) scales by 1e4 and overflowed to inf near the largest floats (a 1e308 tile)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        texts = fmt_array(np.array([1e308, -1e308, 2.0**53 + 2, 2.0**50 + 0.25]))
    assert [float(t) for t in texts[:2]] == [1e308, -1e308] and not any("e" in t or "inf" in t for t in texts)
    assert texts[2:] == ["9007199254740994", "1125899906842624.25"]


def test_fmt_array_matches_fmt_and_rounds_to_four_decimals():
    rng = np.random.default_rng(0)
    values = np.concatenate([rng.normal(0, 1, 500), rng.normal(0, 1e4, 500), np.round(rng.normal(0, 100, 500), 4)])
    texts = fmt_array(values)
    assert texts == [fmt(v) for v in values]
    assert np.allclose([float(t) for t in texts], values, atol=5.0001e-5, rtol=0)
    assert all(re.fullmatch(r"0|-?[1-9]\d*|-?\d+\.\d{0,3}[1-9]", t) for t in texts)


# ----------------------------------------------------------------------------- the document


@pytest.mark.parametrize("name", sorted(EXEMPLARS))
def test_document_contract(write_svg, name):
    src = write_svg(EXEMPLARS[name], f"{name}.svg")
    ex, arr, _, text = synthesize(src, grid="hex", boundary="clip")
    root = ET.fromstring(text)
    assert text.startswith('<?xml version="1.0" encoding="UTF-8"?>\n<svg ')
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == ("60", "40", "0 0 60 40")
    assert root.find(f"{{{SVG_NS}}}metadata/{META}").attrib == {
        "seed": "1", "grid": "hex", "boundary": "clip"
    }  # fmt: skip

    # symbols: every kind's symbol is there once; the exemplar's are copied unchanged
    defs = root.find(f"{{{SVG_NS}}}defs")
    symbols = {s.get("id"): s for s in defs.findall(f"{{{SVG_NS}}}symbol")}
    assert {k.href for k in ex.kinds} <= set(symbols)
    original = ET.fromstring(EXEMPLARS[name])
    for s in original.iter(f"{{{SVG_NS}}}symbol"):
        assert canonical(symbols[s.get("id")]) == canonical(s)

    # one <use> per motif, in order, inside <g id="svgtile">
    group = motif_group(root)
    assert group.get("id") == "svgtile"
    assert len(arr) > 3 and len(group) == len(arr)
    assert all(u.tag == f"{{{SVG_NS}}}use" for u in group)
    assert [u.get(HREF) for u in group] == [f"#{ex.kinds[k].href}" for k in arr.kind]
    assert all(u.get("transform").startswith("translate(") for u in group)


def test_use_transform_is_written_in_the_fixed_format(write_svg):
    ex = read_exemplar(write_svg(TINY))
    arr = Arrangement([0, 1, 0], [[1.5, -2.0], [10.0, 20.123456], [0.0, 0.0]], [0.0, -30.5, 90.0], [1.0, 1.0, 2.0])
    assert use_elements(arr, ex.kinds, indent="") == [
        '<use xlink:href="#dot" transform="translate(1.5 -2)"/>',
        '<use xlink:href="#bar" transform="translate(10 20.1235) rotate(-30.5) translate(-2 -0.5)"/>',
        '<use xlink:href="#dot" transform="translate(0 0) rotate(90) scale(2)"/>',
    ]


@pytest.mark.parametrize("boundary", ["inside", "centroid", "clip", "none"])
def test_clip_path_only_for_clip(write_svg, boundary):
    text = synthesize(write_svg(TINY), boundary=boundary)[3]
    root = ET.fromstring(text)
    clips = root.findall(f".//{{{SVG_NS}}}clipPath")
    group = motif_group(root)
    if boundary == "clip":
        assert len(clips) == 1 and group.get("clip-path") == f"url(#{clips[0].get('id')})"
        path = clips[0].find(f"{{{SVG_NS}}}path").get("d")
        assert shapely.equals(shapely.box(0, 0, 60, 40), shapely.Polygon(_path_points(path)))
    else:
        assert clips == [] and "clip-path" not in group.attrib


def test_path_data_keeps_holes():
    ring = shapely.Polygon([(0, 0), (10, 0), (10, 10), (0, 10)], [[(2, 2), (4, 2), (4, 4.5)]])
    assert path_data(ring) == "M0 0 L10 0 L10 10 L0 10 Z M2 2 L4 2 L4 4.5 Z"


def _path_points(d: str) -> list[tuple[float, float]]:
    nums = [float(v) for v in d.replace("M", " ").replace("L", " ").replace("Z", " ").split()]
    return list(zip(nums[::2], nums[1::2], strict=True))


def test_ids_stay_unique_when_the_exemplar_uses_ours(write_svg):
    text = SVG_HEAD + """
      <defs><symbol id="svgtile"><circle r="1"/></symbol><symbol id="svgtile-clip"><circle r="1.2"/></symbol></defs>
      <use xlink:href="#svgtile" x="5" y="5"/><use xlink:href="#svgtile-clip" x="15" y="12"/>
      <use xlink:href="#svgtile" x="6" y="15"/></svg>"""
    _, arr, _, doc = synthesize(write_svg(text), boundary="clip")
    root = ET.fromstring(doc)
    ids = [el.get("id") for el in root.iter() if el.get("id")]
    assert len(ids) == len(set(ids))
    group = motif_group(root)
    assert group.get("id") != "svgtile" and len(group) == len(arr)
    clip_id = group.get("clip-path")[len("url(#") : -1]
    assert root.find(f".//*[@id='{clip_id}']").tag == f"{{{SVG_NS}}}clipPath"


def test_metadata_values_are_always_valid_xml(write_svg):
    ex = read_exemplar(write_svg(TINY))
    odd = 'a "quoted" <name> & ctrl\x01 surrogate\udcff é'
    doc = svg_document(ex, ex.motifs, Region.rectangle(20, 20), boundary="none", params={"exemplar": odd})
    run = ET.fromstring(doc).find(f"{{{SVG_NS}}}metadata/{META}")
    assert run.get("exemplar") == 'a "quoted" <name> & ctrl\ufffd surrogate\ufffd é'
    doc.encode("utf-8")


def test_empty_arrangement_gives_a_valid_empty_group(write_svg):
    ex = read_exemplar(write_svg(TINY))
    doc = svg_document(ex, Arrangement.empty(), Region.rectangle(5, 5), boundary="clip", params={})
    group = motif_group(ET.fromstring(doc))
    assert len(group) == 0
    assert '<g id="svgtile" clip-path="url(#svgtile-clip)">\n  </g>' in doc


def test_same_arrangement_same_bytes_other_seed_other_output(write_svg):
    src = write_svg(TINY)
    assert synthesize(src, seed=7)[3] == synthesize(src, seed=7)[3]
    a, b = synthesize(src, seed=7), synthesize(src, seed=8)
    assert a[3] != b[3]
    # the difference is in the motifs, not only in the recorded seed
    assert use_elements(a[1], a[0].kinds) != use_elements(b[1], b[0].kinds)


# ----------------------------------------------------------------------------- round trip


@pytest.mark.parametrize("name", sorted(EXEMPLARS))
@pytest.mark.parametrize(("grid", "boundary"), [("square", "centroid"), ("hex", "clip"), ("square", "none")])
def test_round_trip(write_svg, name, grid, boundary):
    """Reading the output back as an exemplar gives the arrangement that was written."""
    ex, arr, region, text = synthesize(write_svg(EXEMPLARS[name], f"{name}.svg"), grid=grid, boundary=boundary,
                                       vary_orientation=name == "tiny")  # fmt: skip
    back = parse_exemplar(text, source="out.svg")
    # the reader keeps motifs whose centre is in its region (the output's viewBox), in order
    inside = shapely.contains_xy(region.shape, arr.xy[:, 0], arr.xy[:, 1])
    expect = arr.take(inside)
    assert len(expect) > 3 and len(back.motifs) == len(expect)
    assert [back.kinds[k].href for k in back.motifs.kind] == [ex.kinds[k].href for k in expect.kind]
    assert np.abs(back.motifs.xy - expect.xy).max() < 1e-3
    turn = (back.motifs.angle - expect.angle + 180.0) % 360.0 - 180.0
    assert np.abs(turn).max() < 1e-3
    assert np.allclose(back.motifs.scale, expect.scale, atol=1e-6)
    for k in range(len(ex.kinds)):  # same footprints, same kinds
        same = [b for b in back.kinds if b.href == ex.kinds[k].href]
        assert same and abs(same[0].prototype.area - ex.kinds[k].prototype.area) < 1e-3 * ex.kinds[k].prototype.area


# ----------------------------------------------------------------------------- writing


def test_write_file_is_atomic_when_the_rename_fails(tmp_path, monkeypatch):
    out = tmp_path / "out.svg"
    out.write_text("old")

    def fail(src, dst):
        raise OSError(13, "Permission denied")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OutputError, match=r"out\.svg: cannot write \(Permission denied\)"):
        write_file("new document", out)
    assert out.read_text() == "old"
    assert os.listdir(tmp_path) == ["out.svg"]


def test_write_file_is_atomic_when_interrupted_while_writing(tmp_path, monkeypatch):
    out = tmp_path / "out.svg"
    out.write_text("old")

    def interrupted(fd):
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "fsync", interrupted)  # after the data went into the temporary file
    with pytest.raises(KeyboardInterrupt):
        write_file("new document", out)
    assert out.read_text() == "old"
    assert os.listdir(tmp_path) == ["out.svg"]


def test_write_file_replaces_and_writes_exact_bytes(tmp_path):
    out = tmp_path / "out.svg"
    out.write_text("old")
    write_file("line 1\nlíne 2\n", out)
    assert out.read_bytes() == "line 1\nlíne 2\n".encode()
    assert os.listdir(tmp_path) == ["out.svg"]


def test_new_file_gets_usual_permissions_and_replaced_file_keeps_its_own(tmp_path):
    old = os.umask(0o022)
    try:
        write_file("x", tmp_path / "new.svg")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "new.svg").stat().st_mode) == 0o644
    kept = tmp_path / "kept.svg"
    kept.write_text("old")
    kept.chmod(0o640)
    write_file("new", kept)
    assert stat.S_IMODE(kept.stat().st_mode) == 0o640 and kept.read_text() == "new"


def test_write_file_writes_into_a_fifo_instead_of_replacing_it(tmp_path):
    fifo = tmp_path / "out.svg"
    os.mkfifo(fifo)
    reader = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)  # so opening it for writing does not block
    try:
        write_file("<svg/>\n", fifo)
        received = os.read(reader, 1000)
    finally:
        os.close(reader)
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)  # not replaced by a regular file
    assert received == b"<svg/>\n"
    assert os.listdir(tmp_path) == ["out.svg"]


def test_write_file_writes_through_a_symlink(tmp_path):
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "out.svg"
    target.write_text("old")
    link = tmp_path / "link.svg"
    link.symlink_to(target)
    write_file("new", link)
    assert link.is_symlink() and target.read_text() == "new"
    assert sorted(os.listdir(tmp_path)) == ["link.svg", "real"]
    assert os.listdir(tmp_path / "real") == ["out.svg"]


@pytest.mark.parametrize("spelling", ["same", "dotdot", "hardlink"])
def test_write_file_protects_inputs(tmp_path, spelling):
    src = tmp_path / "in.svg"
    src.write_text("input")
    (tmp_path / "d").mkdir()
    out = {"same": src, "dotdot": tmp_path / "d" / ".." / "in.svg", "hardlink": tmp_path / "alias.svg"}[spelling]
    if spelling == "hardlink":
        os.link(src, out)
    with pytest.raises(OutputError, match="refusing to overwrite an input file"):
        write_file("output", out, protect=(src,))
    assert src.read_text() == "input"


PNG_LIKE = b"\x89PNG\r\n\x1a\n\x00\xff\r\n"  # not UTF-8, with CR LF that must stay as they are


def test_write_file_writes_bytes_exactly_and_atomically(tmp_path, monkeypatch):
    out = tmp_path / "out.png"
    write_file(PNG_LIKE, out)
    assert out.read_bytes() == PNG_LIKE

    def fail(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OutputError, match=r"out\.png: cannot write \(No space left on device\)$"):
        write_file(b"other", out)
    assert out.read_bytes() == PNG_LIKE
    assert os.listdir(tmp_path) == ["out.png"]  # no temporary file left


def test_write_file_bytes_keep_permissions_and_protect_inputs(tmp_path):
    # the PNG writers it replaces forced 0o644, and did not look at the inputs
    png = tmp_path / "sheet.png"
    png.write_bytes(b"old")
    png.chmod(0o600)
    write_file(PNG_LIKE, png)
    assert stat.S_IMODE(png.stat().st_mode) == 0o600
    with pytest.raises(OutputError, match="refusing to overwrite an input file"):
        write_file(b"new", tmp_path / "." / "sheet.png", protect=(png,))
    assert png.read_bytes() == PNG_LIKE


def test_write_file_bytes_to_a_text_only_stdout_is_refused(monkeypatch):
    text_only = io.StringIO()
    monkeypatch.setattr(sys, "stdout", text_only)
    with pytest.raises(OutputError, match=r"^-: standard output takes text only here$"):
        write_file(PNG_LIKE, "-")
    write_file("<svg/>\n", "-")
    assert text_only.getvalue() == "<svg/>\n"


def test_check_output_names_the_problem(tmp_path):
    (tmp_path / "f").write_text("")
    check_output("-")
    check_output(tmp_path / "ok.svg")
    with pytest.raises(OutputError, match=r"folder .* does not exist"):
        check_output(tmp_path / "no" / "out.svg")
    with pytest.raises(OutputError, match="not a folder"):
        check_output(tmp_path / "f" / "out.svg")
    with pytest.raises(OutputError, match="is a folder"):
        check_output(tmp_path)


def test_dash_writes_bytes_to_stdout(monkeypatch, tmp_path):
    raw = io.BytesIO()
    stdout = io.TextIOWrapper(raw, encoding="ascii", newline="\r\n")  # a hostile console
    monkeypatch.setattr(sys, "stdout", stdout)
    write_file("<svg>é</svg>\n", "-")
    assert raw.getvalue() == "<svg>é</svg>\n".encode()
    assert os.listdir(tmp_path) == []


def test_dash_reports_a_reader_that_left(monkeypatch):
    class Pipe:
        """Like stdout's buffer on a pipe whose reader exited: takes part and reports success."""

        def __init__(self):
            self.calls, self.data = 0, b""

        def write(self, b):
            self.calls += 1
            if self.calls > 1:
                raise BrokenPipeError(32, "Broken pipe")
            self.data += bytes(b[:10])
            return 10

        def flush(self):
            pass

    pipe = Pipe()
    monkeypatch.setattr(sys, "stdout", types.SimpleNamespace(buffer=pipe, flush=lambda: None))
    with pytest.raises(BrokenPipeError):
        write_file("x" * 100, "-")
    assert pipe.data == b"x" * 10


# ----------------------------------------------------------------------------- golden files

GOLDEN_RUNS = {
    "tiny-60x40-square-seed1.svg": ["--engine", "patch", "--grid", "square", "--seed", "1"],
    "tiny-60x40-hex-seed2.svg": ["--engine", "patch", "--grid", "hex", "--seed", "2", "--max-rotation", "45"],
    "tiny-60x40-auto-seed3.svg": ["--seed", "3"],  # the default engine, auto (issue 12)
}


@pytest.mark.parametrize("name", sorted(GOLDEN_RUNS))
def test_golden(tmp_path, capsys, update_golden, name):
    """Catch unintended change in the output; regenerate with ``pytest --update-golden``."""
    src = tmp_path / "tiny.svg"  # the name is recorded in the metadata
    src.write_text(TINY)
    out = tmp_path / name
    assert main(["synth", str(src), "-o", str(out), "--size", "60x40", *GOLDEN_RUNS[name]]) == 0
    err = capsys.readouterr().err
    if "--engine" in GOLDEN_RUNS[name]:
        assert err == ""
    else:  # auto says what it chose, in one line
        assert err.startswith("svgtile: auto: engine patch") and err.count("\n") == 1
    golden = GOLDEN / name
    if update_golden:
        golden.write_bytes(out.read_bytes())
    assert golden.exists(), f"{golden} is missing; create it with: pytest tests/test_output.py --update-golden"
    assert golden.stat().st_size < 10_000
    if out.read_bytes() != golden.read_bytes():
        pytest.fail(
            f"{name} differs from {golden} (first differing line: {_first_difference(out, golden)}).\n"
            "If the change is intended, review it and regenerate the snapshots with:\n"
            "    pytest tests/test_output.py --update-golden"
        )


def _first_difference(a: Path, b: Path) -> str:
    for n, (x, y) in enumerate(zip(a.read_text().splitlines(), b.read_text().splitlines(), strict=False), 1):
        if x != y:
            return f"{n}: {x.strip()!r} != {y.strip()!r}"
    return "lengths differ"
