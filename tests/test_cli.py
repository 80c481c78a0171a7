"""The ``svgtile`` command line: options, one-line errors, nothing written on failure, streams.

Most tests call :func:`svgtile.cli.main.main` in-process (fast, and monkeypatchable); a few run
``python -m svgtile`` in a subprocess to check what a shell user really sees.
"""

from __future__ import annotations

import dataclasses
import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import click
import numpy as np
import pytest
from conftest import OVERLAPPING, SVG_HEAD, fake_engine

import svgtile.apps.load
import svgtile.cli.analyze
import svgtile.cli.main
import svgtile.cli.synth
from svgtile.analysis.stats import analyze
from svgtile.cli.main import cli, main
from svgtile.engines import ENGINES
from svgtile.svg.dialect import SVG_NS, XLINK_NS
from svgtile.svg.reader import read_exemplar

META = "{urn:svgtile:run:1}run"


def run(capsys, *args: str | Path) -> tuple[int, str, str]:
    """Run ``svgtile ARGS`` in-process: (exit code, stdout, stderr)."""
    rc = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return rc, out, err


def synth(capsys, exemplar: Path, out: Path | str, *extra: str, size: str = "60x40"):
    """Run ``svgtile synth``; the line in which ``--engine auto`` says its choice (tests/test_order.py)
    is dropped from stderr, so the tests here see what they are about."""
    rc, out_text, err = run(capsys, "synth", exemplar, "-o", out, "--size", size, *extra)
    lines = err.splitlines(keepends=True)
    said = [line for line in lines if line.startswith("svgtile: auto: ")]
    assert len(said) <= 1 and ("--engine" not in extra or not said)
    return rc, out_text, "".join(line for line in lines if line not in said)


def uses(path: Path) -> list[ET.Element]:
    root = ET.parse(path).getroot()
    group = root.find(f"{{{SVG_NS}}}g[@id='svgtile']")
    return list(group)


# ----------------------------------------------------------------------------- bad input

SHAPE = '<circle cx="5" cy="5" r="1"/>'
BAD_FILES = {
    "not-xml": ("<svg><circle r='1'></svg", "not a well-formed XML"),
    "not-svg": ('<html xmlns="http://www.w3.org/1999/xhtml"><body/></html>', "not an SVG"),
    "no-motifs": (SVG_HEAD + "<text x='1' y='1'>no shapes here</text></svg>", "no motifs"),
    "missing-use": (SVG_HEAD + '<use xlink:href="#nowhere"/></svg>', "#nowhere"),
    "degenerate-region": (SVG_HEAD + f'<rect id="region" width="10" height="0"/>{SHAPE}</svg>', "no area"),
    "external-reference": (SVG_HEAD + '<use xlink:href="other.svg#dot"/></svg>', "other.svg"),
}

BAD_OPTIONS = {
    "size-zero": (["--size", "0x10"], "--size"),
    "size-negative": (["--size", "-5x5"], "--size"),
    "size-malformed": (["--size", "wide"], "--size"),
    "size-half": (["--size", "60x"], "--size"),
    "size-nan": (["--size", "nanxnan"], "--size"),
    "size-infinite": (["--size", "1e400x10"], "--size"),
    "size-absurd": (["--size", "20000x20000"], "--force"),
    "size-absurd-square": (["--size", "1e6"], "--size"),
    "size-beyond-force": (["--size", "1e300x1e300", "--force"], "--size"),
    "size-thin-strip": (["--size", "1e-300x1e300", "--force"], "--size"),  # area 1, yet countless copies
    "size-thin-long": (["--size", "0.01x1e8"], "--force"),
    "overlap-low": (["--overlap", "-0.1"], "--overlap"),
    "overlap-high": (["--overlap", "0.6"], "--overlap"),
    "overlap-nan": (["--overlap", "nan"], "--overlap"),
    "rotation-low": (["--max-rotation", "-1"], "--max-rotation"),
    "rotation-high": (["--max-rotation", "180.5"], "--max-rotation"),
    "rotation-nan": (["--max-rotation", "nan"], "--max-rotation"),
    "junction-low": (["--junction", "-0.1"], "--junction"),
    "junction-one": (["--junction", "1"], "--junction"),
    "junction-nan": (["--junction", "nan"], "--junction"),
    "avoid-margin-nan": (["--avoid-margin", "nan"], "--avoid-margin"),
    "avoid-margin-huge": (["--avoid-margin", "1e300"], "--avoid-margin"),  # grown zones overflow
    "seed-negative": (["--seed", "-1"], "--seed"),
    "seed-not-a-number": (["--seed", "one"], "--seed"),
    "grid-unknown": (["--grid", "triangle"], "--grid"),
    "boundary-unknown": (["--boundary", "soft"], "--boundary"),
}


def assert_failed_cleanly(rc: int, err: str, folder: Path, before: set[str], out: Path, *words: str):
    assert rc != 0
    lines = err.splitlines()
    assert len(lines) == 1 and err.endswith("\n"), err
    assert lines[0].startswith("svgtile: error: "), err
    assert "Traceback" not in err and "internal error" not in err
    for word in words:
        assert word in lines[0], (word, err)
    assert not out.exists()
    assert set(os.listdir(folder)) == before  # no temporary file either


@pytest.mark.parametrize("case", sorted(BAD_FILES))
def test_bad_exemplar_is_one_line_naming_file_and_problem(capsys, write_svg, tmp_path, case):
    text, problem = BAD_FILES[case]
    src = write_svg(text, f"{case}.svg")
    data, before, out = src.read_bytes(), set(os.listdir(tmp_path)), tmp_path / "out.svg"
    rc, stdout, err = synth(capsys, src, out, "--seed", "1")
    assert rc == 1 and stdout == ""
    assert_failed_cleanly(rc, err, tmp_path, before, out, f"{case}.svg", problem)
    assert src.read_bytes() == data


@pytest.mark.parametrize("case", sorted(BAD_OPTIONS))
def test_bad_option_is_one_line_naming_option(capsys, tiny, tmp_path, case):
    args, word = BAD_OPTIONS[case]
    data, before, out = tiny.read_bytes(), set(os.listdir(tmp_path)), tmp_path / "out.svg"
    rc = main(["synth", str(tiny), "-o", str(out), "--size", "60x40", "--seed", "1", *args])
    _, err = capsys.readouterr()
    assert_failed_cleanly(rc, err, tmp_path, before, out, word)
    assert tiny.read_bytes() == data


def test_missing_exemplar_names_it(capsys, tmp_path):
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tmp_path / "nothing.svg", out)
    assert_failed_cleanly(rc, err, tmp_path, set(), out, "nothing.svg", "cannot read")


@pytest.mark.parametrize("spelling", ["same", "dotdot", "symlink"])
def test_refuses_to_overwrite_the_exemplar(capsys, tiny, tmp_path, spelling):
    (tmp_path / "sub").mkdir()
    target = {
        "same": str(tiny),
        "dotdot": os.path.join(str(tmp_path), "sub", "..", "tiny.svg"),
        "symlink": str(tmp_path / "link.svg"),
    }[spelling]
    if spelling == "symlink":
        os.symlink(tiny, target)
    data, before = tiny.read_bytes(), set(os.listdir(tmp_path))
    rc, _, err = synth(capsys, tiny, target, "--seed", "1")
    assert rc == 1
    assert err.count("\n") == 1 and "refusing to overwrite the exemplar" in err and target in err
    assert tiny.read_bytes() == data
    assert set(os.listdir(tmp_path)) == before


def test_refuses_relative_spelling_of_the_exemplar(capsys, tiny, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sub").mkdir()
    data = tiny.read_bytes()
    rc, _, err = synth(capsys, Path("tiny.svg"), "./sub/../tiny.svg", "--seed", "1")
    assert rc == 1 and "refusing to overwrite the exemplar" in err
    assert tiny.read_bytes() == data


@pytest.mark.parametrize("where", ["missing-folder", "folder-is-a-file", "output-is-a-folder"])
def test_unusable_output_fails_before_synthesis(capsys, tiny, tmp_path, monkeypatch, where):
    def engine_must_not_run(*args, **kwargs):
        raise AssertionError("synthesis ran although the output cannot be written")

    monkeypatch.setitem(ENGINES, "patch", fake_engine(engine_must_not_run))
    (tmp_path / "file.txt").write_text("x")
    (tmp_path / "folder").mkdir()
    out, problem = {
        "missing-folder": (tmp_path / "nowhere" / "out.svg", "does not exist"),
        "folder-is-a-file": (tmp_path / "file.txt" / "out.svg", "not a folder"),
        "output-is-a-folder": (tmp_path / "folder", "folder"),
    }[where]
    before = set(os.listdir(tmp_path))
    rc, _, err = synth(capsys, tiny, out, "--seed", "1")
    assert rc == 1
    assert err.count("\n") == 1 and err.startswith("svgtile: error: ") and str(out) in err and problem in err
    assert set(os.listdir(tmp_path)) == before


def test_size_limit_refuses_without_force(capsys, tiny, tmp_path):
    stats = analyze(read_exemplar(tiny))
    side = (2 * svgtile.apps.load.MAX_MOTIFS / stats.count_density) ** 0.5  # twice the limit
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", size=f"{side:.0f}x{side:.0f}")
    assert_failed_cleanly(rc, err, tmp_path, {"tiny.svg"}, out, "--force", f"{svgtile.apps.load.MAX_MOTIFS:,}")


def test_force_runs_above_the_limit(capsys, tiny, tmp_path, monkeypatch):
    monkeypatch.setattr(svgtile.cli.synth, "MAX_MOTIFS", 5)  # 60x40 holds about 30 motifs
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1")
    assert rc == 1 and "--force" in err and not out.exists()
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--force")
    assert rc == 0 and err == ""
    assert len(uses(out)) > 5


def test_overlapping_exemplar_warns_and_continues(capsys, write_svg, tmp_path):
    src = write_svg(OVERLAPPING, "overlap.svg")
    data, out = src.read_bytes(), tmp_path / "out.svg"
    rc, _, err = synth(capsys, src, out, "--seed", "3")
    assert rc == 0
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"svgtile: warning: {src}: ") and "overlap" in lines[0]
    assert out.exists() and len(uses(out)) > 0
    assert src.read_bytes() == data


def test_region_without_motifs_warns_and_writes_empty_texture(capsys, tiny, tmp_path):
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--boundary", "inside", size="0.5x0.5")
    assert rc == 0
    assert err.count("\n") == 1 and err.startswith("svgtile: warning: no motif fits")
    assert uses(out) == []


# ----------------------------------------------------------------------------- success paths


def test_synth_writes_svg_and_nothing_else(capsys, tiny, tmp_path):
    data, out = tiny.read_bytes(), tmp_path / "out.svg"
    rc, stdout, err = synth(capsys, tiny, out, "--seed", "5")
    assert (rc, stdout, err) == (0, "", "")
    assert sorted(os.listdir(tmp_path)) == ["out.svg", "tiny.svg"]
    root = ET.parse(out).getroot()
    assert root.tag == f"{{{SVG_NS}}}svg"
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == ("60", "40", "0 0 60 40")
    hrefs = {u.get(f"{{{XLINK_NS}}}href") for u in uses(out)}
    assert hrefs == {"#dot", "#bar"}
    assert tiny.read_bytes() == data


def test_options_are_recorded_in_metadata(capsys, tiny, tmp_path):
    out = tmp_path / "out.svg"
    args = ["--seed", "11", "--grid", "hex", "--overlap", "0.2", "--max-rotation", "15", "--junction", "0.3",
            "--vary-orientation", "--boundary", "centroid"]  # fmt: skip
    rc, _, _ = synth(capsys, tiny, out, *args, size="50x30")
    assert rc == 0
    run_ = ET.parse(out).getroot().find(f"{{{SVG_NS}}}metadata/{META}")
    assert run_.attrib == {
        "engine": "patch", "seed": "11", "exemplar": "tiny.svg", "size": "50x30", "grid": "hex",
        "overlap": "0.2", "max_rotation": "15.0", "junction": "0.3", "vary_orientation": "True",
        "boundary": "centroid", "motifs": str(len(uses(out))),
    }  # fmt: skip


@pytest.mark.parametrize("boundary", ["inside", "centroid", "clip", "none"])
def test_only_clip_boundary_adds_a_clip_path(capsys, tiny, tmp_path, boundary):
    out = tmp_path / "out.svg"
    assert synth(capsys, tiny, out, "--seed", "2", "--boundary", boundary)[0] == 0
    root = ET.parse(out).getroot()
    clips = root.findall(f".//{{{SVG_NS}}}clipPath")
    group = root.find(f"{{{SVG_NS}}}g[@id='svgtile']")
    if boundary == "clip":
        assert len(clips) == 1 and group.get("clip-path") == f"url(#{clips[0].get('id')})"
    else:
        assert clips == [] and group.get("clip-path") is None


def test_same_seed_same_bytes_other_seed_other_output(capsys, tiny, tmp_path):
    a, b, c = (tmp_path / n for n in ("a.svg", "b.svg", "c.svg"))
    assert synth(capsys, tiny, a, "--seed", "42")[0] == 0
    assert synth(capsys, tiny, b, "--seed", "42")[0] == 0
    assert synth(capsys, tiny, c, "--seed", "43")[0] == 0
    assert a.read_bytes() == b.read_bytes()
    assert a.read_bytes() != c.read_bytes()
    # not just the recorded seed: the motifs differ
    assert [u.attrib for u in uses(a)] != [u.attrib for u in uses(c)]


def test_without_seed_a_printed_seed_reproduces_the_file(capsys, tiny, tmp_path):
    first, again = tmp_path / "first.svg", tmp_path / "again.svg"
    rc, _, err = synth(capsys, tiny, first)
    assert rc == 0
    match = re.fullmatch(r"svgtile: seed (\d+)\n", err)
    assert match, err
    rc, _, err = synth(capsys, tiny, again, "--seed", match.group(1))
    assert (rc, err) == (0, "")
    assert first.read_bytes() == again.read_bytes()


def test_dash_writes_the_document_to_stdout(capsys, tiny, tmp_path):
    out = tmp_path / "out.svg"
    assert synth(capsys, tiny, out, "--seed", "9")[0] == 0
    before = set(os.listdir(tmp_path))
    rc = main(["synth", str(tiny), "-o", "-", "--size", "60x40", "--seed", "9"])
    captured = capsys.readouterr()
    assert (rc, captured.err.startswith("svgtile: auto: "), captured.err.count("\n")) == (0, True, 1)
    assert captured.out == out.read_text(encoding="utf-8")
    assert set(os.listdir(tmp_path)) == before


def test_failed_write_reports_one_line_and_keeps_the_old_file(capsys, tiny, tmp_path, monkeypatch):
    out = tmp_path / "out.svg"
    out.write_text("old contents")

    def full_disk(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "replace", full_disk)
    rc, _, err = synth(capsys, tiny, out, "--seed", "1")
    assert rc == 1
    assert err == f"svgtile: error: {out}: cannot write (No space left on device)\n"
    assert out.read_text() == "old contents"
    assert sorted(os.listdir(tmp_path)) == ["out.svg", "tiny.svg"]


# ----------------------------------------------------------------------------- the shell


def test_no_arguments_prints_help(capsys):
    rc, out, err = run(capsys)
    assert rc == 0 and err == ""
    assert out.startswith("Usage: svgtile") and "synth" in out and "analyze" in out


def test_version(capsys):
    rc, out, _ = run(capsys, "--version")
    assert rc == 0 and svgtile.__version__ in out


@pytest.mark.parametrize(
    "args",
    [["--bogus"], ["synth", "--bogus"], ["synthesize"], ["synth"], ["analyze"], ["synth", "x.svg", "--size", "9"]],
)
def test_usage_errors_are_one_line(capsys, args):
    rc, out, err = run(capsys, *args)
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("svgtile: error: ") and "--help" in err


def test_interrupt_is_one_line(capsys, tiny, tmp_path, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setitem(ENGINES, "patch", fake_engine(interrupted))
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1")
    assert (rc, err) == (130, "svgtile: interrupted\n")
    assert sorted(os.listdir(tmp_path)) == ["tiny.svg"]


def test_messages_after_progress_start_on_a_clean_line(capsys, tiny, tmp_path, monkeypatch):
    def interrupted_midway(ctx, params):
        ctx.progress("grid", 0.1)
        raise KeyboardInterrupt

    monkeypatch.setitem(ENGINES, "patch", fake_engine(interrupted_midway))
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    rc, _, err = synth(capsys, tiny, tmp_path / "out.svg", "--seed", "1")
    assert rc == 130
    assert err == "\rsvgtile: grid        10%\r\033[Ksvgtile: interrupted\n"


def test_progress_line_is_erased_even_if_the_engine_never_says_done(capsys, tiny, tmp_path, monkeypatch):
    real = ENGINES["patch"]

    def quiet_finish(ctx, params):
        ctx.progress("grid", 0.5)
        return real.place(dataclasses.replace(ctx, progress=lambda stage, fraction: None), params)

    monkeypatch.setitem(ENGINES, "patch", fake_engine(quiet_finish))
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    rc, _, err = synth(capsys, tiny, tmp_path / "out.svg", "--seed", "1")
    assert (rc, err) == (0, "\rsvgtile: grid        50%\r\033[K")


def test_reader_leaving_stdout_is_quiet(capsys, tiny, monkeypatch):
    def reader_left(text, out, **kwargs):
        raise BrokenPipeError(32, "Broken pipe")

    monkeypatch.setattr(svgtile.cli.synth, "write_file", reader_left)
    rc, out, err = synth(capsys, tiny, "-", "--seed", "1")
    assert (rc, out, err) == (1, "", "")


def test_internal_error_is_one_line_unless_debug(capsys, tiny, tmp_path, monkeypatch):
    def broken(*args, **kwargs):
        raise ZeroDivisionError("division by zero\nsecond line")

    monkeypatch.setitem(ENGINES, "patch", fake_engine(broken))
    rc, _, err = synth(capsys, tiny, tmp_path / "out.svg", "--seed", "1")
    assert rc == 70 and err.count("\n") == 1 and "ZeroDivisionError" in err and "--debug" in err
    with pytest.raises(ZeroDivisionError):
        main(["synth", str(tiny), "-o", str(tmp_path / "out.svg"), "--size", "9x9", "--debug"])


def test_python_warnings_become_one_line(capsys, tiny, tmp_path, monkeypatch):
    real = ENGINES["patch"]

    def noisy(ctx, params):
        np.float64(1.0) / np.float64(0.0)  # numpy's RuntimeWarning: divide by zero
        return real.place(ctx, params)

    monkeypatch.setitem(ENGINES, "patch", fake_engine(noisy))
    rc, _, err = synth(capsys, tiny, tmp_path / "out.svg", "--seed", "1")
    assert rc == 0
    assert err.count("\n") == 1 and err.startswith("svgtile: warning: ") and "RuntimeWarning" in err


def test_progress_line_on_a_terminal_only(capsys, tiny, tmp_path, monkeypatch):
    # not a terminal (pytest's capture): only the seed line
    rc, _, err = synth(capsys, tiny, tmp_path / "a.svg")
    assert rc == 0 and re.fullmatch(r"svgtile: seed \d+\n", err)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    rc, _, err = synth(capsys, tiny, tmp_path / "b.svg", "--seed", "1")
    assert rc == 0
    assert "\rsvgtile: " in err and "%" in err  # the progress line …
    assert err.endswith("\r\033[K")  # … erased when done
    assert (tmp_path / "b.svg").read_bytes().startswith(b"<?xml")


@pytest.mark.skipif(sys.platform == "win32", reason="needs a pseudo-terminal")
def test_progress_line_on_a_real_terminal(tiny, tmp_path):
    import pty

    master, slave = pty.openpty()
    try:
        p = subprocess.run(
            [sys.executable, "-m", "svgtile", "synth", "tiny.svg", "-o", "out.svg", "--size", "60x40", "--seed", "4"],
            stderr=slave, stdout=subprocess.PIPE, cwd=tmp_path, timeout=120,
        )  # fmt: skip
    finally:
        os.close(slave)
    seen = b""
    try:
        while chunk := os.read(master, 4096):
            seen += chunk
    except OSError:  # EIO: the terminal's other side is closed
        pass
    finally:
        os.close(master)
    assert p.returncode == 0 and p.stdout == b""
    assert b"\rsvgtile: " in seen and b"%" in seen and seen.endswith(b"\r\x1b[K")
    assert (tmp_path / "out.svg").exists()


def test_help_explains_every_option(capsys):
    for name, command in cli.commands.items():
        rc, out, _ = run(capsys, name, "--help")
        assert rc == 0 and out.startswith(f"Usage: svgtile {name}")
        flat = " ".join(out.split())
        for param in command.params:
            if isinstance(param, click.Option):
                assert param.help, f"{name} {param.opts} has no help"
                assert param.opts[-1] in flat
                assert " ".join(param.help.split()) in flat


def test_python_dash_m_svgtile(tmp_path, tiny):
    """What a shell user sees: exit codes, one stderr line, no traceback, reproducible seed."""
    cmd = [sys.executable, "-m", "svgtile"]

    def shell(*args):
        return subprocess.run([*cmd, *map(str, args)], capture_output=True, text=True, cwd=tmp_path)

    bad = tmp_path / "bad.svg"
    bad.write_text("this is not XML")
    p = shell("synth", bad, "-o", tmp_path / "out.svg", "--size", "60x40")
    assert p.returncode == 1 and p.stdout == ""
    assert p.stderr.count("\n") == 1 and "bad.svg" in p.stderr and "Traceback" not in p.stderr
    assert not (tmp_path / "out.svg").exists()

    p = shell("synth", "tiny.svg", "-o", "out.svg", "--size", "60x40")
    assert p.returncode == 0
    auto = r"svgtile: auto: engine patch: [^\n]*\n"  # auto's choice (tests/test_order.py)
    match = re.fullmatch(auto + r"svgtile: seed (\d+)\n", p.stderr)  # not a terminal: no progress line
    assert match, p.stderr
    p = shell("synth", "tiny.svg", "-o", "-", "--size", "60x40", "--seed", match.group(1))
    assert p.returncode == 0 and re.fullmatch(auto, p.stderr)
    assert p.stdout == (tmp_path / "out.svg").read_text(encoding="utf-8")

    p = shell()
    assert p.returncode == 0 and p.stdout.startswith("Usage: svgtile")


# ----------------------------------------------------------------------------- analyze


def test_analyze_prints_a_table(capsys, tiny):
    rc, out, err = run(capsys, "analyze", tiny)
    assert (rc, err) == (0, "")
    stats = analyze(read_exemplar(tiny))
    assert "motifs        5 in 2 kind(s)" in out
    assert f"{stats.density:.4f}" in out
    rows = {line.split()[1]: line.split() for line in out.splitlines() if re.match(r"\s+\d+\s+(dot|bar)\s", line)}
    assert rows["dot"][2:4] == ["3", "0.600"] and rows["bar"][2:4] == ["2", "0.400"]
    assert "-20.0° … +30.0° (50.0°)" in " ".join(rows["bar"])
    assert "d_ij" in out
    assert f"{stats.distance[0, 1]:.3f}" in out


def test_analyze_json(capsys, tiny):
    rc, out, err = run(capsys, "analyze", "--json", tiny)
    assert (rc, err) == (0, "")
    report = json.loads(out)
    stats = analyze(read_exemplar(tiny))
    assert [k["name"] for k in report["kinds"]] == ["dot", "bar"]
    assert [k["count"] for k in report["kinds"]] == [3, 2]
    assert report["motifs"] == 5
    assert report["density"] == pytest.approx(stats.density)
    assert report["motifs_per_unit_area"] == pytest.approx(5 / 400)
    assert np.allclose(report["distance"], stats.distance)
    assert np.allclose(report["distance"], np.transpose(report["distance"]))
    bar = report["kinds"][1]["arc"]
    assert bar["start"] == pytest.approx(-20) and bar["width"] == pytest.approx(50)


def test_analyze_json_is_strict_json_even_for_odd_numbers(capsys, tiny, monkeypatch):
    real = svgtile.cli.analyze.stats_report

    def odd(ex, stats):
        return {**real(ex, stats), "density": float("nan"), "distance": [[float("inf")]]}

    monkeypatch.setattr(svgtile.cli.analyze, "stats_report", odd)
    rc, out, _ = run(capsys, "analyze", "--json", tiny)
    assert rc == 0
    report = json.loads(out, parse_constant=lambda c: pytest.fail(f"{c} is not JSON"))
    assert report["density"] is None and report["distance"] == [[None]]


def test_analyze_bad_file_is_one_line(capsys, write_svg):
    src = write_svg("<svg", "broken.svg")
    rc, out, err = run(capsys, "analyze", "--json", src)
    assert rc == 1 and out == ""
    assert err.count("\n") == 1 and "broken.svg" in err and "XML" in err


def test_analyze_warns_about_overlaps(capsys, write_svg):
    src = write_svg(OVERLAPPING, "overlap.svg")
    rc, out, err = run(capsys, "analyze", "--json", src)
    assert rc == 0 and json.loads(out)["overlapping_pairs"] == 1
    assert err.count("\n") == 1 and "overlap" in err



@pytest.mark.parametrize(("value", "text"), [(1e4, "10,000"), (123456.7, "123,457"), (12.5664, "12.57"), (0.5, "0.5"),
                                            (3e20, "3e+20")])  # fmt: skip
def test_areas_are_printed_readably(value, text):
    from svgtile.cli.analyze import readable

    assert readable(value) == text


def test_analyze_prints_a_large_area_without_an_exponent(capsys):
    assert main(["analyze", str(Path(__file__).parents[1] / "exemplars" / "gravel.svg")]) == 0
    line = next(s for s in capsys.readouterr().out.splitlines() if s.startswith("input region"))
    assert "e+" not in line and ", area " in line and "," in line.split("area ")[1]


@pytest.mark.parametrize("name", ["x.pdf", "x.txt", "x.svg.bak"])
def test_an_output_suffix_svgtile_does_not_write_is_refused(capsys, tiny, tmp_path, name):
    out = tmp_path / name
    rc, _, err = synth(capsys, tiny, out, "--seed", "1")
    assert rc == 1 and not out.exists()
    assert err.count("\n") == 1 and "svgtile writes .svg, .geojson, .png" in err


def test_a_png_output_is_a_picture_not_svg_text(capsys, tiny, tmp_path):
    pytest.importorskip("resvg_py")
    out = tmp_path / "x.png"
    rc, _, _ = synth(capsys, tiny, out, "--seed", "1")
    assert rc == 0 and out.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    width = int.from_bytes(out.read_bytes()[16:20], "big")
    assert width == 120  # 60 user units, 2 pixels each


def test_map_refuses_a_png_output(capsys, tiny, tmp_path):
    rc = main(["map", str(tiny), "--styles", str(tmp_path / "none.toml"), "-o", str(tmp_path / "m.png")])
    assert rc == 1 and "svgtile writes .svg, .geojson" in capsys.readouterr().err


@pytest.mark.parametrize("engine", ["growth", "optimize"])
def test_work_limit_refuses_a_run_of_minutes_before_it_starts(capsys, tiny, tmp_path, engine):
    """Under the motif limit, yet minutes of work for this engine: refused at once with the estimate.
    (For patch, tile and random the motif limit comes first.)"""
    from svgtile.engines import get_engine
    from svgtile.engines.base import seconds_per_motif

    stats = analyze(read_exemplar(tiny))
    motifs = 3 * svgtile.apps.load.MAX_WORK_SECONDS / seconds_per_motif(get_engine(engine))  # three times the limit
    assert motifs < svgtile.apps.load.MAX_MOTIFS, "the motif limit would refuse it first"
    side = (motifs / stats.count_density) ** 0.5
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--engine", engine, size=f"{side:.0f}x{side:.0f}")
    assert_failed_cleanly(rc, err, tmp_path, {"tiny.svg"}, out, "--force", f"engine {engine!r}", "of work")


def test_work_limit_counts_refinement_and_is_forced(capsys, tiny, tmp_path, monkeypatch):
    stats = analyze(read_exemplar(tiny))
    side = (2000 / stats.count_density) ** 0.5  # a few seconds of patch, minutes with 50 iterations of refinement
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--engine", "patch", size=f"{side:.0f}x{side:.0f}")
    assert rc == 0, err
    out.unlink()
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--engine", "patch", "--refine", "500", size=f"{side:.0f}x{side:.0f}")
    assert_failed_cleanly(rc, err, tmp_path, {"tiny.svg"}, out, "--refine 500", "--force")
    monkeypatch.setattr(svgtile.cli.synth, "MAX_WORK_SECONDS", 0.0)  # every run is over it
    rc, _, err = synth(capsys, tiny, out, "--seed", "1")
    assert rc == 1 and "of work" in err and not out.exists()
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--force")
    assert rc == 0 and out.exists()


@pytest.mark.parametrize("engine, extra, refused", [
    ("optimize", ("--tile-size", "20", "--jobs", "2"), True),  # not tile-exact: run whole, on one worker
    ("tile", ("--scheduler", "local", "--jobs", "2"), True),  # no --tile-size: one whole tile
    ("tile", ("--tile-size", "20", "--jobs", "2", "--refine", "1"), True),  # refined: run whole
    ("tile", ("--tile-size", "20", "--jobs", "2"), False),  # really cut into tiles: shared by two workers
], ids=["not-tile-exact", "no-tile-size", "refined", "tiled"])
def test_work_limit_shares_the_work_only_among_workers_of_a_run_cut_into_tiles(capsys, tiny, tmp_path, monkeypatch,
                                                                                 engine, extra, refused):  # fmt: skip
    """--jobs divides the estimate only when the region is cut into tiles (runners.tiling.plan);
    a run that goes whole runs on one worker, and adding --scheduler or --tile-size must not let
    it past the guard."""
    from svgtile.apps.load import check_motif_count, check_work
    from svgtile.core.region import Region

    ex = read_exemplar(tiny)
    estimate = check_motif_count(ex, analyze(ex), Region.rectangle(60, 40), "--size 60x40")
    whole = check_work(estimate, engine, "--size 60x40", refine=1 if "--refine" in extra else 0)
    monkeypatch.setattr(svgtile.cli.synth, "MAX_WORK_SECONDS", 0.75 * whole)  # over it whole, under it halved
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--engine", engine, *extra)
    if refused:
        assert_failed_cleanly(rc, err, tmp_path, {"tiny.svg"}, out, "of work", "--force")
    else:
        assert rc == 0 and out.exists(), err


def test_work_limit_counts_the_optimize_engines_passes(capsys, tiny, tmp_path, monkeypatch):
    """optimize declares its cost at its default passes; --passes 100 is ten times the
    iterations and must count as such, as --refine does."""
    from svgtile.apps.load import check_motif_count, check_work
    from svgtile.core.region import Region

    ex = read_exemplar(tiny)
    estimate = check_motif_count(ex, analyze(ex), Region.rectangle(60, 40), "--size 60x40")
    monkeypatch.setattr(svgtile.cli.synth, "MAX_WORK_SECONDS", 2 * check_work(estimate, "optimize", "--size 60x40"))
    out = tmp_path / "out.svg"
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--engine", "optimize", "--passes", "100")
    assert_failed_cleanly(rc, err, tmp_path, {"tiny.svg"}, out, "of work", "with --passes 100", "--force")
    rc, _, err = synth(capsys, tiny, out, "--seed", "1", "--engine", "optimize", "--passes", "3")  # fewer: as declared
    assert rc == 0 and out.exists(), err


def test_every_engine_declares_what_a_motif_costs():
    """The work guard's figures come from benchmarks/work_per_motif.py; an engine without one would
    be guessed at."""
    from svgtile.engines import ENGINES

    for name, engine in ENGINES.items():
        assert 0 < getattr(engine, "seconds_per_motif", 0) < 1, name
    assert 0 < ENGINES["optimize"].refine_seconds_per_motif < 1
