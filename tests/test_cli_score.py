"""``svgtile score`` and ``svgtile compare``: a texture read back scores as the arrangement it was
written from, one-line errors, the table, PNG previews and the contact sheet."""

from __future__ import annotations

import dataclasses
import json
import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely
from conftest import arrange

import svgtile.cli.compare
import svgtile.cli.main
from svgtile import metrics
from svgtile.analysis.stats import analyze
from svgtile.apps.compare import FIGURES, OPTIONAL, compare, format_table
from svgtile.cli.main import main
from svgtile.core.arrangement import Arrangement
from svgtile.core.region import Region
from svgtile.errors import ExemplarError, ParameterError
from svgtile.metrics import Score
from svgtile.svg.dialect import SVG_NS, XLINK_NS, parse_matrix
from svgtile.svg.reader import parse_exemplar, read_exemplar
from svgtile.svg.texture import _own_use_block, kind_key, read_own_texture, read_texture
from svgtile.svg.writer import svg_document

EXEMPLARS = Path(__file__).resolve().parents[1] / "exemplars"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run(capsys, *args) -> tuple[int, str, str]:
    rc = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return rc, out, err


def write_texture(path: Path, name: str, region: Region, engine: str = "patch", seed: int = 2):
    ex = read_exemplar(EXEMPLARS / f"{name}.svg")
    stats = analyze(ex)
    arr = arrange(engine, ex, region, rng=np.random.default_rng(seed), stats=stats)
    path.write_text(svg_document(ex, arr, region, boundary="clip", params={"engine": engine}))
    return ex, stats, arr


# ----------------------------------------------------------------------------- reading back


@pytest.mark.parametrize("name", ["breccia-plain", "chert-nodules", "till"])
def test_texture_reads_back_as_written(tmp_path, name):
    """Kinds are renumbered to the exemplar's (breccia-plain's texture lists them in another
    order), positions and angles survive the file, and the score is the arrangement's."""
    region = Region.rectangle(260, 200)
    ex, stats, arr = write_texture(tmp_path / "t.svg", name, region)
    back, back_region = read_texture(tmp_path / "t.svg", ex)
    assert back_region.shape.equals(region.shape)
    inside = shapely.contains_xy(region.shape, arr.xy[:, 0], arr.xy[:, 1])
    want = arr.take(inside)
    order_a = np.lexsort((want.xy[:, 0], want.xy[:, 1], want.kind))
    order_b = np.lexsort((back.xy[:, 0], back.xy[:, 1], back.kind))
    assert np.array_equal(want.kind[order_a], back.kind[order_b])
    assert np.allclose(want.xy[order_a], back.xy[order_b], atol=2e-4)
    assert np.allclose(np.cos(np.radians(want.angle[order_a] - back.angle[order_b])), 1.0, atol=1e-6)
    a = metrics.score(ex, stats, want, region)
    b = metrics.score(ex, stats, back, back_region)
    for key in ("motifs", "overlaps", "violators", "kind_mix_tv", "density_ratio", "gap_distance", "repetition"):
        assert getattr(b, key) == pytest.approx(getattr(a, key), rel=1e-3, abs=1e-3), key


def test_region_is_the_clip_path_with_its_hole(tmp_path):
    outer = shapely.box(0, 0, 300, 200)
    region = Region.from_geometry(outer.difference(shapely.box(100, 60, 180, 140)))
    ex, _, _ = write_texture(tmp_path / "t.svg", "gravel", region)
    _, back = read_texture(tmp_path / "t.svg", ex)
    assert back.area == pytest.approx(300 * 200 - 80 * 80)
    assert not back.shape.contains(shapely.Point(140, 100))


def test_unclipped_texture_uses_its_viewbox(tmp_path):
    ex = read_exemplar(EXEMPLARS / "sand.svg")
    arr = arrange("tile", ex, Region.rectangle(120, 90), rng=np.random.default_rng(0))
    (tmp_path / "t.svg").write_text(svg_document(ex, arr, Region.rectangle(120, 90), boundary="inside", params={}))
    _, back = read_texture(tmp_path / "t.svg", ex)
    assert back.bounds == (0.0, 0.0, 120.0, 90.0)


def test_texture_of_another_exemplar_is_refused(tmp_path):
    write_texture(tmp_path / "t.svg", "breccia-plain", Region.rectangle(100, 100))
    with pytest.raises(ExemplarError, match=r"t\.svg: motif kind 'svgtile-kind-\d' is not in the exemplar"):
        read_texture(tmp_path / "t.svg", read_exemplar(EXEMPLARS / "gravel.svg"))


# ----------------------------------------------------------------------------- svgtile score


def test_score_json_matches_the_library(tmp_path, capsys):
    ex, stats, arr = write_texture(tmp_path / "t.svg", "shale", Region.rectangle(300, 300))
    rc, out, err = run(capsys, "score", EXEMPLARS / "shale.svg", tmp_path / "t.svg", "--json")
    assert rc == 0, err
    got = json.loads(out)
    want = metrics.score(ex, stats, arr, Region.rectangle(300, 300))
    assert got["texture"] == "t.svg"
    assert got["motifs"] == want.motifs > 0
    assert got["overlaps"] == got["violators"] == 0
    assert got["kind_mix_tv"] == pytest.approx(want.kind_mix_tv, abs=1e-9)
    assert got["gap_distance"] == pytest.approx(want.gap_distance, rel=1e-3)


def test_score_table_tells_tile_from_random(tmp_path, capsys):
    region = Region.rectangle(360, 360)
    write_texture(tmp_path / "tile.svg", "gravel", region, engine="tile")
    write_texture(tmp_path / "random.svg", "gravel", region, engine="random")
    rows = {}
    for engine in ("tile", "random"):
        rc, out, err = run(capsys, "score", EXEMPLARS / "gravel.svg", tmp_path / f"{engine}.svg")
        assert rc == 0, err
        line = next(s for s in out.splitlines() if s.startswith("repetition"))
        rows[engine] = float(line.split()[-1])
        assert "pebble-round → pebble-oblong" in out
    assert rows["tile"] > 0.9 > 0.2 > rows["random"]


@pytest.mark.parametrize(
    "texture, message",
    [
        ("missing.svg", "missing.svg"),
        ("other", "is not in the exemplar"),
        ("broken", "broken.svg"),
    ],
)
def test_score_errors_are_one_line(tmp_path, capsys, texture, message):
    if texture == "other":
        write_texture(tmp_path / "other.svg", "till", Region.rectangle(80, 80))
        texture = "other.svg"
    elif texture == "broken":
        (tmp_path / "broken.svg").write_text("<svg><g></svg")
        texture = "broken.svg"
    rc, out, err = run(capsys, "score", EXEMPLARS / "gravel.svg", tmp_path / texture)
    assert rc == 1
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("svgtile: error: ") and message in err


# ----------------------------------------------------------------------------- svgtile compare


def test_compare_library_columns_and_errors():
    ex = read_exemplar(EXEMPLARS / "sand.svg")
    stats = analyze(ex)
    results = compare(ex, stats, Region.rectangle(200, 200), engines=["tile", "random"], seed=3)
    assert [r.engine for r in results] == ["tile", "random"]
    table = format_table(results).splitlines()
    assert table[0].split()[-2:] == ["tile", "random"]
    assert len(table) == 1 + len(FIGURES) - len(OPTIONAL)  # sand pools no kinds: no per-kind rows
    assert results[0].score.repetition > 0.9 > results[1].score.repetition
    for bad in (["tile", "nope"], [], ["tile", "tile"]):
        with pytest.raises(ParameterError, match="--engines"):
            compare(ex, stats, Region.rectangle(50, 50), engines=bad)


def test_compare_json_same_seed_same_figures(capsys):
    args = ("compare", EXEMPLARS / "marsh.svg", "--size", "180x150", "--engines", "random,patch", "--seed", "4", "--json")
    rc, out, err = run(capsys, *args)
    assert rc == 0, err
    first = json.loads(out)
    assert list(first["engines"]) == ["random", "patch"]
    assert first["engines"]["patch"]["overlaps"] == 0
    rc, again, _ = run(capsys, *args)
    assert json.loads(again) == first


def test_compare_bad_engine_is_one_line(capsys):
    rc, out, err = run(capsys, "compare", EXEMPLARS / "sand.svg", "--size", "100", "--engines", "patch,magic")
    assert rc == 1 and out == ""
    assert err.count("\n") == 1 and "unknown engine 'magic'" in err


def test_compare_refuses_a_size_above_the_motif_limit(capsys, monkeypatch):
    monkeypatch.setattr(svgtile.cli.compare, "MAX_MOTIFS", 5)  # sand 100x100 holds about 360 motifs
    rc, out, err = run(capsys, "compare", EXEMPLARS / "sand.svg", "--size", "100")
    assert rc == 1 and out == ""
    assert err.count("\n") == 1 and "--size 100 would hold about" in err and "(limit 5)" in err
    assert "--force" not in err  # compare has no --force


def test_compare_png_writes_textures_and_a_labelled_contact_sheet(tmp_path, capsys):
    pytest.importorskip("resvg_py", reason="the optional renderer (pip install 'svgtile[png]') is not installed")
    out_dir = tmp_path / "previews"
    rc, out, err = run(capsys, "compare", EXEMPLARS / "gravel.svg", "--size", "120x90", "--png", out_dir)
    assert rc == 0, err
    assert out.startswith("gravel.svg on 120 x 90, seed 1\n")
    for engine in ("patch", "tile", "random"):
        assert (out_dir / f"{engine}.png").read_bytes().startswith(PNG_MAGIC)
        assert read_exemplar(out_dir / f"{engine}.svg").motifs is not None
    sheet = ET.parse(out_dir / "contact-sheet.svg").getroot()
    labels = [t.text for t in sheet.iter(f"{{{SVG_NS}}}text")]
    assert labels == ["exemplar gravel", "patch", "tile", "random"]
    panels = sheet.findall(f"{{{SVG_NS}}}svg")
    assert len(panels) == 4
    ids = [el.get("id") for el in sheet.iter() if el.get("id")]
    assert len(ids) == len(set(ids)), "panel ids must not collide"
    assert all(i.startswith(("p0-", "p1-", "p2-", "p3-")) for i in ids)
    png = (out_dir / "contact-sheet.png").read_bytes()
    assert png.startswith(PNG_MAGIC)
    width = int.from_bytes(png[16:20], "big")
    assert width == round(float(sheet.get("width")))


def test_compare_png_without_renderer_is_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "resvg_py", None)  # import fails as if not installed
    rc, out, err = run(capsys, "compare", EXEMPLARS / "sand.svg", "--size", "100", "--png", tmp_path / "p")
    assert rc == 1 and out == ""
    assert err.count("\n") == 1 and "pip install 'svgtile[png]'" in err
    assert not (tmp_path / "p").exists()


def test_compare_png_into_a_file_is_refused(tmp_path, capsys):
    (tmp_path / "f").write_text("x")
    rc, _, err = run(capsys, "compare", EXEMPLARS / "sand.svg", "--size", "100", "--png", tmp_path / "f")
    assert rc != 0 and err.count("\n") == 1
    assert (tmp_path / "f").read_text() == "x"


def test_clip_region_found_when_the_exemplar_takes_svgtiles_ids(tmp_path):
    # symbols named like svgtile's own group and clip path push those to "svgtile-2" …
    (tmp_path / "ex.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 20 20">'
        '<defs><symbol id="svgtile" overflow="visible"><circle r="1"/></symbol>'
        '<symbol id="svgtile-clip" overflow="visible"><rect width="2" height="1"/></symbol></defs>'
        '<use xlink:href="#svgtile" x="4" y="4"/><use xlink:href="#svgtile-clip" x="12" y="6"/>'
        '<use xlink:href="#svgtile" x="8" y="15"/><use xlink:href="#svgtile-clip" x="15" y="14"/></svg>'
    )
    ex = read_exemplar(tmp_path / "ex.svg")
    region = Region.from_geometry(shapely.box(0, 0, 120, 80).difference(shapely.box(40, 20, 80, 60)))
    arr = arrange("random", ex, region, rng=np.random.default_rng(1))
    text = svg_document(ex, arr, region, boundary="clip", params={})
    assert 'id="svgtile-2"' in text and 'id="svgtile-clip-2"' in text
    (tmp_path / "t.svg").write_text(text)
    back, back_region = read_texture(tmp_path / "t.svg", ex)
    assert back_region.area == pytest.approx(120 * 80 - 40 * 40)
    # every motif whose centroid is in the viewBox is read back
    assert sorted(np.bincount(back.kind).tolist()) == sorted(np.bincount(arr.kind[shapely.contains_xy(shapely.box(0, 0, 120, 80), arr.xy[:, 0], arr.xy[:, 1])]).tolist())


# ----------------------------------------------------------------------------- the bulk reader

#: An exemplar whose kinds need every part of a <use> svgtile writes: a symbol with a viewBox
#: (width/height on the <use>), a skewed instance (a matrix() suffix), scaled instances and an
#: inherited fill (an attribute on the <use>).
VARIED = f"""<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="{XLINK_NS}" viewBox="0 0 40 40">
<defs><symbol id="box" viewBox="0 0 10 10" overflow="visible"><rect width="10" height="10"/></symbol>
<symbol id="dot" overflow="visible"><circle r="1"/></symbol></defs>
<use xlink:href="#box" width="2" height="2" transform="translate(5 5) rotate(20)"/>
<use xlink:href="#box" width="2" height="2" transform="translate(30 8) matrix(1 0 0.5 1 0 0)"/>
<use xlink:href="#box" width="2" height="2" transform="translate(18 30) matrix(1 0 0.5 1 0 0) rotate(-35)"/>
<use xlink:href="#dot" transform="translate(20 15) scale(1.5)"/>
<use xlink:href="#dot" transform="translate(8 25) rotate(70) scale(0.75)"/>
<g fill="#a00"><use xlink:href="#dot" transform="translate(32 30)"/><use xlink:href="#dot" transform="translate(30 20)"/></g>
</svg>"""


def _general(path: Path):
    """The texture as the exemplar reader reads it, motif by motif."""
    texture = read_exemplar(path)
    return texture.kinds, texture.motifs, texture.region


def _same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return a.dtype == b.dtype and a.shape == b.shape and np.ascontiguousarray(a).tobytes() == np.ascontiguousarray(b).tobytes()


@pytest.mark.parametrize(
    ("name", "engine", "options"),
    [
        ("gravel", "patch", {}),
        ("till", "patch", {"grid": "hex"}),
        ("breccia-plain", "patch", {"vary_orientation": True}),
        ("chert-nodules", "tile", {}),
        ("shale", "random", {}),
        ("varied", "tile", {}),
        ("varied", "random", {}),
    ],
)
@pytest.mark.parametrize("boundary", ["clip", "inside", "none"])
def test_bulk_reader_equals_the_exemplar_reader(tmp_path, name, engine, options, boundary):
    """On every texture svgtile writes, the bulk read is the exemplar reader's, bit for bit."""
    ex = parse_exemplar(VARIED) if name == "varied" else read_exemplar(EXEMPLARS / f"{name}.svg")
    region = Region.rectangle(150, 110, x=-3.5, y=2.25)
    arr = arrange(engine, ex, region, rng=np.random.default_rng(4), stats=analyze(ex), boundary=boundary, **options)
    path = tmp_path / "t.svg"
    path.write_text(svg_document(ex, arr, region, boundary=boundary, params={}))
    own = read_own_texture(ET.parse(path).getroot(), str(path))
    assert own is not None, "svgtile's own texture must take the bulk path"
    kinds, motifs, shape = own
    want_kinds, want, want_shape = _general(path)
    assert [kind_key(k) for k in kinds] == [kind_key(k) for k in want_kinds]
    assert [k.offset.tolist() for k in kinds] == [k.offset.tolist() for k in want_kinds]
    for field in ("kind", "xy", "angle", "scale"):
        assert _same_bits(getattr(motifs, field), getattr(want, field)), field
    assert shape.equals(want_shape)
    # the same from the text scan of the <use> lines and the document cut to one <use> per kind
    cut = _own_use_block(path.read_bytes())
    assert cut is not None, "svgtile's own texture must take the text scan"
    skeleton, lines = cut
    assert skeleton.count(b"<use ") == len(lines.first) == len(want_kinds) < skeleton.count(b"\n")
    scanned = read_own_texture(ET.fromstring(skeleton), str(path), lines=lines)
    assert scanned is not None
    assert [kind_key(k) for k in scanned[0]] == [kind_key(k) for k in want_kinds]
    for field in ("kind", "xy", "angle", "scale"):
        assert _same_bits(getattr(scanned[1], field), getattr(want, field)), field
    assert scanned[2].equals(want_shape)
    if name == "varied":  # the parts of the <use> the bundled exemplars lack were written
        text = path.read_text()
        assert "matrix(" in text and "scale(" in text and 'width="2"' in text and 'fill="#a00"' in text


def _edit(text: str, how: str) -> str:
    """A hand edit of a texture: its first <use> given as a matrix(), or the motifs in a moved group."""
    if how == "matrix":
        head, _, rest = text.partition("<use ")
        use, _, tail = rest.partition("/>")
        m = re.search(r'transform="([^"]*)"', use)
        mat = parse_matrix(m.group(1))
        written = "matrix({})".format(" ".join(repr(float(v)) for v in (mat[0, 0], mat[1, 0], mat[0, 1], mat[1, 1], mat[0, 2], mat[1, 2])))
        return head + "<use " + use.replace(m.group(0), f'transform="{written}"') + "/>" + tail
    head, _, rest = text.partition('<g id="svgtile"')
    body, _, tail = rest.partition("</g>")
    return head + '<g id="svgtile"><g transform="translate(7 -3)"' + body + "</g></g>" + tail


@pytest.mark.parametrize("how", ["matrix", "group"])
def test_a_hand_edited_texture_is_read_by_the_exemplar_reader(tmp_path, how):
    region = Region.rectangle(120, 90)
    ex, _, _ = write_texture(tmp_path / "t.svg", "gravel", region)
    (tmp_path / "e.svg").write_text(_edit((tmp_path / "t.svg").read_text(), how))
    assert read_own_texture(ET.parse(tmp_path / "e.svg").getroot(), "e.svg") is None
    orig, _ = read_texture(tmp_path / "t.svg", ex)
    back, back_region = read_texture(tmp_path / "e.svg", ex)
    assert back_region.shape.equals(region.shape)
    shift = np.array([7.0, -3.0]) if how == "group" else np.zeros(2)
    moved = Arrangement(orig.kind, orig.xy + shift, orig.angle, orig.scale)
    box = shapely.box(0, 0, 120, 90)
    kept = moved.take(shapely.intersects_xy(box, moved.xy[:, 0], moved.xy[:, 1]))
    # motifs the group moved into the viewBox from outside it are read too; compare the others
    back = back.take(shapely.intersects_xy(box, back.xy[:, 0] - shift[0], back.xy[:, 1] - shift[1]))
    assert len(back) == len(kept) > 100
    assert np.array_equal(back.kind, kept.kind)
    assert np.allclose(back.xy, kept.xy, atol=1e-9)
    assert np.allclose(np.cos(np.radians(back.angle - kept.angle)), 1.0, atol=1e-12)


def _second_use(text: str, old: str, new: str) -> str:
    first = text.index("<use ")
    second = text.index("<use ", first + 1)
    end = text.index("/>", second)
    return text[:second] + text[second:end].replace(old, new, 1) + text[end:]


@pytest.mark.parametrize(
    "how",
    [
        "comment",  # a comment before the motifs could hide what the scan sees
        "blank line",  # not one <use> per line
        "crlf",  # other line ends
        "attribute order",  # transform before href
        "escaped href",  # a dropped line that would be a <use> of the same kind as written otherwise
    ],
)
def test_the_text_scan_leaves_other_forms_to_the_parser(tmp_path, how):
    """What the scan does not take is parsed whole, with the same motifs, bit for bit."""
    ex, _, _ = write_texture(tmp_path / "t.svg", "gravel", Region.rectangle(60, 50))
    text = (tmp_path / "t.svg").read_text()
    if how == "comment":
        text = text.replace("<metadata>", "<!-- a note --><metadata>", 1)
    elif how == "blank line":
        text = text.replace("/>\n    <use ", "/>\n\n    <use ", 1)
    elif how == "crlf":
        text = text.replace("\n", "\r\n")
    elif how == "attribute order":
        text = re.sub(r'<use (xlink:href="[^"]*") (transform="[^"]*")', r"<use \2 \1", text, count=1)
    else:
        text = _second_use(text, 'xlink:href="#p', 'xlink:href="#&#112;')
    path = tmp_path / "e.svg"
    path.write_bytes(text.encode())
    cut = _own_use_block(path.read_bytes())
    if how == "escaped href":  # the scan takes it, the cut document's check refuses it
        assert cut is not None and read_own_texture(ET.fromstring(cut[0]), "e.svg", lines=cut[1]) is None
    else:
        assert cut is None
    arr, _ = read_texture(path, ex)
    own = read_own_texture(ET.parse(path).getroot(), "e.svg")
    want = _general(path)[1] if own is None else own[1]
    assert len(arr) > 50
    for field in ("xy", "angle", "scale"):
        assert _same_bits(getattr(arr, field), getattr(want, field)), field


def test_every_table_row_is_a_score_field():
    fields = {f.name for f in dataclasses.fields(Score)}
    assert [key for key, _, _ in FIGURES if key not in fields] == []


def test_figures_from_few_motifs_are_flagged(capsys):
    rc, _, err = run(capsys, "compare", EXEMPLARS / "gravel.svg", "--size", "160x160")
    assert rc == 0 and "measured on only" in err and "fewer than 200" in err
    rc, _, err = run(capsys, "compare", EXEMPLARS / "sand.svg", "--size", "300x300", "--engines", "tile")
    assert rc == 0 and "measured on only" not in err


def test_contact_sheet_shows_at_least_two_pixels_per_unit(capsys, tmp_path):
    pytest.importorskip("resvg_py")
    rc, _, _ = run(capsys, "compare", EXEMPLARS / "sand.svg", "--size", "400x300", "--engines", "tile",
                   "--png", tmp_path / "p")  # fmt: skip
    assert rc == 0
    png = (tmp_path / "p" / "tile.png").read_bytes()
    assert int.from_bytes(png[16:20], "big") >= 800  # 400 units at 2 px


def test_score_help_says_what_each_figure_means(capsys):
    rc, out, _ = run(capsys, "score", "--help")
    assert rc == 0
    labels = {lab.strip().split(" (")[0] for _, lab, _ in FIGURES} - {"motifs in the interior", "its sampling noise"}
    labels = {lab.replace(" over windows", ", min, max") for lab in labels if not lab.startswith("window density")}
    missing = [lab for lab in labels if lab not in out]
    assert not missing, missing


def test_kind_pair_rows_keep_their_columns_with_long_names(capsys, tmp_path):
    texture = tmp_path / "t.svg"
    assert main(["synth", str(EXEMPLARS / "gravel.svg"), "-o", str(texture), "--size", "400x300", "--seed", "1"]) == 0
    rc, out, _ = run(capsys, "score", EXEMPLARS / "gravel.svg", texture)
    assert rc == 0 and "motifs centred in its region" in out
    rows = out[out.index("structure per kind pair"):].splitlines()[1:]
    assert len(rows) == 4 and len({len(r) for r in rows}) == 1  # every row as wide: the columns line up


@pytest.mark.parametrize("scale, refused", [("1e-7", False), ("0", True)])
def test_a_use_scaled_to_nothing_reads_as_the_exemplar_reader_reads_it(tmp_path, scale, refused):
    """The fast reader of svgtile's own output hands such a texture to the general reader, which
    drops a <use> too small to draw (with a warning) and refuses a singular transform."""
    region = Region.rectangle(120, 90)
    ex, _, _ = write_texture(tmp_path / "t.svg", "gravel", region)
    text = (tmp_path / "t.svg").read_text()
    m = re.search(r'<use [^>]*transform="translate\([2-8]\d\.\d+ [2-6]\d\.\d+\)[^"]*"', text)  # well inside
    (tmp_path / "e.svg").write_text(text.replace(m.group(0), m.group(0)[: -1] + f' scale({scale})"', 1))
    assert read_own_texture(ET.parse(tmp_path / "e.svg").getroot(), "e.svg") is None
    if refused:
        with pytest.raises(ExemplarError, match="singular"):
            read_texture(tmp_path / "e.svg", ex)
    else:
        orig, _ = read_texture(tmp_path / "t.svg", ex)
        back, _ = read_texture(tmp_path / "e.svg", ex)
        assert len(back) == len(orig) - 1


def test_compare_says_which_columns_are_sampled_as_its_json_does(capsys, monkeypatch):
    """A large texture's structure figures are measured on sample windows; the table says so, as
    ``svgtile score`` does and as compare's --json does (``"sampled"``)."""
    from svgtile.metrics import window

    monkeypatch.setattr(window, "SAMPLE_ABOVE", 300)  # gravel 400x400: about 1,500 motifs inside
    monkeypatch.setattr(window, "SAMPLE_MOTIFS", 600)
    args = ("compare", EXEMPLARS / "gravel.svg", "--size", "400x400", "--engines", "tile,random")
    rc, out, err = run(capsys, *args, "--json")
    assert rc == 0, err
    sampled = {e for e, s in json.loads(out)["engines"].items() if "sampled" in s}
    assert sampled == {"tile", "random"}
    rc, out, err = run(capsys, *args)
    assert rc == 0, err
    lines = [t for t in out.splitlines() if t.startswith("sampled (")]
    assert [t.split(")")[0].removeprefix("sampled (") for t in lines] == ["tile", "random"]
    assert all(re.search(r"\): \d+ windows of [\d.]+ × [\d.]+, [\d,]+ of [\d,]+ motifs", t) for t in lines), lines


#: A region with a hole (a lake): its clip path has two rings, and motifs lie around the hole.
HOLED = shapely.box(-3.5, 2.25, 146.5, 112.25).difference(shapely.Point(70, 55).buffer(22))


@pytest.mark.parametrize(
    ("name", "engine", "options"),
    [
        ("gravel", "patch", {}),  # every motif rotated
        ("gravel", "growth", {"rotation": "fit"}),
        ("till", "optimize", {"passes": 2}),
        ("breccia-plain", "patch", {"vary_orientation": True}),
        ("varied", "random", {}),  # scaled uses, a matrix() suffix, <use> attributes
        ("varied", "tile", {}),
    ],
)
def test_texture_read_equals_the_exemplar_reader_around_a_hole(tmp_path, name, engine, options):
    """read_texture on what ``synthesize`` and the writer make, engine by engine, in a region with
    a hole: the text scan is taken, and it gives the exemplar reader's motifs bit for bit (kinds
    renumbered to the exemplar's) and the region with its hole."""
    from svgtile.engines import synthesize

    ex = parse_exemplar(VARIED) if name == "varied" else read_exemplar(EXEMPLARS / f"{name}.svg")
    region = Region.from_geometry(HOLED)
    result = synthesize(ex, region, engine, seed=3, params=options)
    path = tmp_path / "t.svg"
    path.write_text(svg_document(ex, result.arrangement, region, boundary="clip", params={}))
    assert _own_use_block(path.read_bytes()) is not None, "svgtile's own texture must take the text scan"
    got, got_region = read_texture(path, ex)
    want_kinds, want, _ = _general(path)
    # each kind the exemplar reader finds in the texture is the exemplar's kind that draws the same
    # element the same way, up to the writer's 4 decimals (a skewed, turned kind: 1.2779 ↔ 1.2778)
    mapping = np.array([
        min((i for i, k in enumerate(ex.kinds) if (k.href, k.use_attrs) == (w.href, w.use_attrs)),
            key=lambda i: np.abs(ex.kinds[i].residual - w.residual).max())
        for w in want_kinds
    ])  # fmt: skip
    assert all(np.abs(ex.kinds[i].residual - w.residual).max() < 1e-3 for i, w in zip(mapping, want_kinds, strict=True))
    assert len(got) == len(want) > 20
    assert _same_bits(got.kind, mapping[want.kind])
    for field in ("xy", "angle", "scale"):
        assert _same_bits(getattr(got, field), getattr(want, field)), field
    assert got_region.shape.symmetric_difference(region.shape).area < 1e-6 * region.shape.area
    assert len(got_region.shape.interiors) == 1
    if engine != "tile":  # the texture's own turns and scales were read, not the identity
        assert np.ptp(got.angle) > 1 or np.ptp(got.scale) > 0


def test_the_use_scan_without_possessive_quantifiers_matches_the_same_lines(tmp_path):
    """Python 3.10 has no possessive quantifiers: the scan's greedy form (what ``_possessive``
    gives there) must compile and find the same columns in a texture svgtile wrote."""
    import re

    from svgtile.svg import uselines as texture

    out = tmp_path / "t.svg"
    assert main(["synth", str(EXEMPLARS / "gravel.svg"), "-o", str(out), "--size", "120x90", "--seed", "2",
                 "--engine", "patch", "--vary-orientation"]) == 0  # fmt: skip
    body = out.read_text()
    greedy = re.compile(re.sub(r"([+*?])\+", r"\1", texture._OWN_USE.pattern), re.M)
    assert "++" not in greedy.pattern and "*+" not in greedy.pattern and "?+" not in greedy.pattern
    found = texture._OWN_USE.findall(body)
    assert len(found) == body.count("<use ") > 0
    assert greedy.findall(body) == found
