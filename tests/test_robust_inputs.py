"""Issue 16 items 2–4: hostile input is refused at the reader in one line, work is bounded, and a
run ends cleanly (no temporary file, no fetchable reference, an exit code that says what happened)."""

from __future__ import annotations

import gzip
import io
import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import SVG_HEAD, TINY

import svgtile.files
from svgtile.analysis.crowding import check_crowding
from svgtile.cli.main import main
from svgtile.errors import ExemplarError, OutputError, SvgtileError
from svgtile.files import read_input, sweep_temporary, write_file
from svgtile.svg.dialect import MAX_DEPTH, neutralise_external
from svgtile.svg.reader import parse_exemplar
from svgtile.svg.tilepieces import parse_tile

SYMBOL = '<defs><symbol id="d" overflow="visible"><circle r="1"/></symbol></defs>'
USES = "".join(f'<use xlink:href="#d" x="{4 + 6 * i}" y="5"/>' for i in range(3))


def svg(body: str) -> str:
    return SVG_HEAD + body + "</svg>"


HOSTILE_TRANSFORMS = ["translate(nan 3)", "scale(-inf)", "scale(1e308)", "scale(1e200) scale(1e200)", "skewX(90)",
                      "skewX(89.99999)", "rotate(nan)", "rotate(1e308)", "matrix(1 0 0 1 inf 0)", "matrix(1 1 1"]


SINGULAR_TRANSFORMS = ["scale(0)", "scale(0 1)", "matrix(1 2 2 4 0 0)", "matrix(0 0 0 0 5 5)"]


@pytest.mark.parametrize("transform, why", [(t, "transform") for t in HOSTILE_TRANSFORMS]
                         + [(t, "that is singular") for t in SINGULAR_TRANSFORMS])  # fmt: skip
@pytest.mark.parametrize("where", ["use", "group", "tile"])
def test_hostile_transforms_are_refused_naming_the_element(transform, why, where):
    """Not finite, squashed or singular (SVG draws nothing under a singular transform: refused,
    not a motif silently gone)."""
    if where == "use":
        text, element = svg(SYMBOL + USES + f'<use id="bad" xlink:href="#d" transform="{transform}"/>'), "<use id='bad'>"
    else:
        text, element = svg(SYMBOL + f'<g id="bad" transform="{transform}">{USES}</g>'), "<g id='bad'>"
    read = parse_tile if where == "tile" else parse_exemplar
    with pytest.raises(ExemplarError, match="transform") as info:
        read(text, source="x.svg")
    assert element in str(info.value) and str(info.value).startswith("x.svg: ") and why in str(info.value)


@pytest.mark.parametrize("shape", ['<path d="M 0 0 L 1e308 0 L 1e308 1e308 Z"/>', '<path d="M 0 0 L nan 1 L 1 1 Z"/>',
                                   '<line x2="1" stroke="#000" stroke-width="1e308"/>'])  # fmt: skip
def test_hostile_coordinates_are_refused_naming_the_element(shape):
    text = svg(f'<defs><symbol id="d" overflow="visible">{shape}</symbol></defs>' + USES)
    with pytest.raises(ExemplarError, match=r"<(path|line)>"):
        parse_exemplar(text, source="x.svg")


def test_a_use_scaled_to_nothing_by_its_ancestors_is_dropped_with_a_warning():
    """Each transform is lawful (scale(1e-7)); together they leave nothing to draw."""
    ex = parse_exemplar(svg(SYMBOL + USES + '<g transform="scale(1e-7)"><use xlink:href="#d" transform="scale(1e-7)"/></g>'))
    assert len(ex.motifs) == 3 and any("scaled to nothing" in w for w in ex.warnings)


def test_a_map_element_with_a_singular_transform_is_refused(tmp_path, capsys):
    (tmp_path / "map.svg").write_text(svg('<g transform="scale(0)"><rect id="r" width="90" height="90"/></g>'))
    (tmp_path / "ex.svg").write_text(TINY)
    rc = main(["synth", str(tmp_path / "ex.svg"), "--region", f"{tmp_path / 'map.svg'}#r", "-o", str(tmp_path / "o.svg")])
    err = capsys.readouterr().err
    assert rc == 1 and "map.svg" in err and "singular" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "o.svg").exists()


def test_depth_and_size_limits_apply_to_maps_too(tmp_path, capsys):
    deep = "<g>" * (MAX_DEPTH + 5) + '<rect id="r" width="9" height="9"/>' + "</g>" * (MAX_DEPTH + 5)
    (tmp_path / "map.svg").write_text(svg(deep))
    (tmp_path / "ex.svg").write_text(TINY)
    rc = main(["synth", str(tmp_path / "ex.svg"), "--region", f"{tmp_path / 'map.svg'}#r", "-o", str(tmp_path / "o.svg")])
    err = capsys.readouterr().err
    assert rc == 1 and "nested too deeply" in err and "map.svg" in err and len(err.splitlines()) == 1
    (tmp_path / "s.toml").write_text("a = " + "[" * 5000 + "]" * 5000 + "\n")
    rc = main(["map", str(tmp_path / "map.svg"), "--styles", str(tmp_path / "s.toml"), "-o", str(tmp_path / "o.svg")])
    err = capsys.readouterr().err
    assert rc == 1 and "s.toml" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "o.svg").exists()


def test_read_input_refuses_what_is_not_a_bounded_regular_file(tmp_path, monkeypatch):
    os.mkfifo(tmp_path / "pipe.svg")  # no writer: reading it would block for ever
    with pytest.raises(SvgtileError, match="named pipe"):
        read_input(tmp_path / "pipe.svg")
    (tmp_path / "zero.svg").symlink_to("/dev/zero")
    with pytest.raises(SvgtileError, match="device"):
        read_input(tmp_path / "zero.svg")
    (tmp_path / "loop.svg").symlink_to("loop.svg")
    with pytest.raises(SvgtileError, match="cannot read"):
        read_input(tmp_path / "loop.svg")
    (tmp_path / "t.svgz").write_bytes(gzip.compress(TINY.encode()))
    with pytest.raises(SvgtileError, match="gzip"):
        read_input(tmp_path / "t.svgz")
    (tmp_path / "big.svg").write_text(TINY)
    with pytest.raises(SvgtileError, match="more than svgtile reads"):
        read_input(tmp_path / "big.svg", limit=100)
    assert read_input(tmp_path / "big.svg") == TINY.encode()


def test_a_pipe_as_exemplar_is_refused_at_once_by_the_command(tmp_path, capsys):
    os.mkfifo(tmp_path / "pipe.svg")
    rc = main(["analyze", str(tmp_path / "pipe.svg")])
    err = capsys.readouterr().err
    assert rc == 1 and "pipe.svg: is a named pipe" in err


def test_heavily_overlapping_motifs_are_refused_with_the_import_suggestion():
    stacked = "".join(f'<use xlink:href="#d" x="{10 + 0.2 * (i % 5)}" y="{10 + 0.2 * (i // 5)}"/>' for i in range(25))
    with pytest.raises(ExemplarError, match="svgtile import"):
        check_crowding(parse_exemplar(svg(SYMBOL + stacked), source="x.svg"))
    check_crowding(parse_exemplar(TINY))  # apart: nothing said


def test_external_references_are_dropped_from_copied_symbols_with_a_warning():
    text = svg('<defs><filter id="f"><feImage xlink:href="http://example.org/i.png"/></filter>'
               '<symbol id="d" overflow="visible"><circle r="1" fill="url(http://example.org/p#g)" filter="url(#f)" '
               'style="stroke:url(http://example.org/s#s);mask:url(other.svg#m)"/></symbol></defs>' + USES)  # fmt: skip
    ex = parse_exemplar(text, source="x.svg")
    copied = "".join(__import__("xml.etree.ElementTree", fromlist=["x"]).tostring(el, encoding="unicode") for el in ex.defs)
    assert "example.org" not in copied and "other.svg" not in copied
    assert 'filter="url(#f)"' in copied and 'fill="none"' in copied  # a local reference stays
    assert any("4 reference(s) to outside this file dropped" in w for w in ex.warnings)


def test_neutralise_external_keeps_local_references():
    import xml.etree.ElementTree as ET

    el = ET.fromstring('<g xmlns="http://www.w3.org/2000/svg"><circle fill="url(#grad)" clip-path="url( #c)"/></g>')
    assert neutralise_external([el]) == []
    assert el[0].get("fill") == "url(#grad)"


def test_a_killed_run_leaves_a_temporary_file_the_next_write_sweeps(tmp_path):
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    pid = int(dead.stdout)
    left = tmp_path / f".out.svg{svgtile.files.TMP_TAG}{pid}-abcd.tmp"
    alive = tmp_path / f".out.svg{svgtile.files.TMP_TAG}{os.getppid()}-efgh.tmp"
    other = tmp_path / f".other.svg{svgtile.files.TMP_TAG}{pid}-ijkl.tmp"
    for p in (left, alive, other):
        p.write_text("half")
    assert sweep_temporary(tmp_path / "out.svg") == [left]
    write_file("new", tmp_path / "out.svg")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([alive.name, other.name, "out.svg"])


@pytest.mark.parametrize("stop", [KeyboardInterrupt, "sigterm"])
def test_an_interrupted_write_removes_its_temporary_file_and_keeps_the_old_one(tmp_path, monkeypatch, stop):
    from svgtile.cli import main as cli_main

    (tmp_path / "out.svg").write_text("old")

    def interrupted(fd):
        if stop == "sigterm":
            cli_main._terminate(signal.SIGTERM, None)
        raise stop

    monkeypatch.setattr(svgtile.files.os, "fsync", interrupted)
    with pytest.raises(BaseException):  # noqa: B017 - KeyboardInterrupt or Terminated
        write_file("new", tmp_path / "out.svg")
    assert [p.name for p in tmp_path.iterdir()] == ["out.svg"] and (tmp_path / "out.svg").read_text() == "old"


def test_sigterm_ends_a_command_with_143_and_no_output(tmp_path, capsys, monkeypatch):
    from svgtile.cli import main as cli_main

    (tmp_path / "ex.svg").write_text(TINY)
    monkeypatch.setattr(svgtile.files.os, "fsync", lambda fd: cli_main._terminate(signal.SIGTERM, None))
    rc = main(["synth", str(tmp_path / "ex.svg"), "--size", "30", "--seed", "1", "-o", str(tmp_path / "o.svg")])
    assert rc == 143 and "stopped by SIGTERM" in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ex.svg"]


@pytest.mark.parametrize("stdout", ["closed", "full"])
def test_standard_output_closed_or_full_is_one_line(tmp_path, capsys, monkeypatch, stdout):
    (tmp_path / "ex.svg").write_text(TINY)
    if stdout == "closed":
        monkeypatch.setattr(sys, "stdout", None)
    else:
        full = open("/dev/full", "w")
        monkeypatch.setattr(sys, "stdout", full)
    rc = main(["synth", str(tmp_path / "ex.svg"), "--engine", "patch", "--size", "30", "--seed", "1", "-o", "-"])
    err = capsys.readouterr().err
    assert rc == 1 and "standard output" in err and len(err.splitlines()) == 1
    if stdout == "full":
        assert "No space left" in err
        full.close()


def test_swatches_with_every_input_refused_writes_nothing_and_fails(tmp_path, capsys):
    (tmp_path / "a.svg").write_text("<svg")
    (tmp_path / "b.svg").write_text(svg(""))
    rc = main(["swatches", str(tmp_path / "a.svg"), str(tmp_path / "b.svg"), "-o", str(tmp_path / "sheet.svg")])
    err = capsys.readouterr().err
    assert rc == 1 and "none of the 2 pattern(s)" in err and "nothing written" in err
    assert not (tmp_path / "sheet.svg").exists()


def test_map_with_every_unit_failed_writes_nothing(tmp_path, capsys):
    (tmp_path / "ex.svg").write_text(TINY)
    (tmp_path / "m.svg").write_text(svg('<rect class="a" width="1e6" height="1e6"/><rect class="a" x="5" width="1e6" height="1e6"/>'))
    (tmp_path / "s.toml").write_text('[classes.a]\nexemplar = "ex.svg"\n')
    rc = main(["map", str(tmp_path / "m.svg"), "--styles", str(tmp_path / "s.toml"), "-o", str(tmp_path / "o.svg"),
               "--seed", "1", "--jobs", "1"])  # fmt: skip
    err = capsys.readouterr().err
    assert rc == 1 and "nothing written" in err
    assert not (tmp_path / "o.svg").exists()


def test_output_clash_error_is_an_output_error():
    with pytest.raises(OutputError, match="refusing to overwrite the exemplar"):
        svgtile.files.check_paths([(__file__, "the exemplar")], [Path(__file__).parent / ".." / "tests" / Path(__file__).name])


@pytest.mark.parametrize("transform", ["scale(1e308)", "translate(1e150 0)", "matrix(1 0 0 1 1e308 1e308) scale(10)"])
def test_the_inkscape_extension_refuses_absurd_geometry_before_flattening(transform):
    inkex = pytest.importorskip("inkex", reason="inkex is not installed")
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "inkscape_ext"))
    import svgtile_fill

    doc = inkex.load_svg(io.BytesIO(
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><g transform="{transform}">'
        '<path id="box" d="M 0 0 C 1 0 1 1 0 1 Z"/></g></svg>'.encode()))  # fmt: skip
    shape = doc.getroot().getElementById("box")
    with pytest.raises(inkex.AbortExtension, match="nothing was changed"):
        svgtile_fill._rings(shape)
    ok = inkex.load_svg(io.BytesIO(b'<svg xmlns="http://www.w3.org/2000/svg"><path id="b" d="M 0 0 L 1 0 L 1 1 Z"/></svg>'))
    assert len(svgtile_fill._rings(ok.getroot().getElementById("b"))[0]) >= 3


def _running(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    return "\nState:\tZ" not in status


@pytest.mark.skipif(not Path("/proc").is_dir(), reason="needs /proc (Linux)")
@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_map_workers_end_with_their_parent(tmp_path, sig):
    import time

    (tmp_path / "ex.svg").write_text(TINY)
    units = "".join(f'<rect class="a" x="{i * 1300}" width="1200" height="1200"/>' for i in range(4))
    (tmp_path / "m.svg").write_text(svg(units))
    (tmp_path / "s.toml").write_text('[classes.a]\nexemplar = "ex.svg"\n')
    proc = subprocess.Popen([sys.executable, "-m", "svgtile", "map", "m.svg", "--styles", "s.toml", "-o", "o.svg",
                             "--seed", "1", "--jobs", "2"], cwd=tmp_path, stderr=subprocess.DEVNULL)  # fmt: skip
    workers: list[int] = []
    deadline = time.monotonic() + 60
    while len(workers) < 2 and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.2)
        children = Path(f"/proc/{proc.pid}/task/{proc.pid}/children")
        workers = [int(p) for p in children.read_text().split()] if children.exists() else []
    assert len(workers) >= 2, "the map ended before its workers could be seen"
    proc.send_signal(sig)
    proc.wait(30)
    deadline = time.monotonic() + 15
    while any(_running(w) for w in workers) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not any(_running(w) for w in workers)
    assert not (tmp_path / "o.svg").exists() and not list(tmp_path.glob(".o.svg*"))
    if sig == signal.SIGTERM:
        assert proc.returncode == 143


def test_an_output_that_is_a_symlink_loop_is_refused_and_kept(tmp_path, capsys):
    (tmp_path / "ex.svg").write_text(TINY)
    (tmp_path / "o.svg").symlink_to("o.svg")
    rc = main(["synth", str(tmp_path / "ex.svg"), "--size", "30", "--seed", "1", "-o", str(tmp_path / "o.svg")])
    assert rc == 1 and "loops" in capsys.readouterr().err
    assert (tmp_path / "o.svg").is_symlink()


@pytest.mark.parametrize("codec", ["utf-8", "utf-8-sig", "utf-16"])
def test_names_are_read_in_the_encodings_spreadsheets_write(tmp_path, codec):
    from svgtile.apps.swatches import read_names

    (tmp_path / "n.csv").write_bytes("name,code\nGrès,601\n".encode(codec))
    assert read_names(tmp_path / "n.csv") == {"601": "Grès"}
