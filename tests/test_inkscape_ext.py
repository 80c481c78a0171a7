"""The Inkscape effect (inkscape_ext/svgtile_fill.py) under inkex's own tester.

inkex is not a dependency of svgtile (pip cannot install it without GTK headers); install it for
these tests with ``pip install --no-deps inkex`` (``.ci/run`` does).  The effect runs svgtile in
a subprocess: here it is this interpreter, through ``SVGTILE_PYTHON``.

Snapshots (``tests/inkscape_data/refs``) use the tile engine so they change only when the effect
or the output format does; refresh them with ``EXPORT_COMPARE=3 pytest tests/test_inkscape_ext.py``
and review the diff.
"""

from __future__ import annotations

import functools
import io
import os
import subprocess
import sys
import venv
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest

inkex = pytest.importorskip("inkex", reason="inkex is not installed (pip install --no-deps inkex)")

import shapely  # noqa: E402
from inkex.tester import ComparisonMixin, TestCase  # noqa: E402
from inkex.tester.filters import CompareNumericFuzzy, CompareWithoutIds  # noqa: E402
from inkex.tester.inx import InxMixin  # noqa: E402
from shapely import affinity  # noqa: E402

EXT = Path(__file__).resolve().parents[1] / "inkscape_ext"
DATA = Path(__file__).resolve().parent / "inkscape_data"
sys.path.insert(0, str(EXT))
import svgtile_fill  # noqa: E402
from svgtile_fill import FillWithTexture  # noqa: E402

XLINK_HREF = "{http://www.w3.org/1999/xlink}href"
#: The footprints of the test symbols in their own frame (fill.svg: dot and bar).
PROTOS = {"dot": shapely.Point(0, 0).buffer(1.5, 64), "bar": shapely.box(-2, -0.5, 2, 0.5)}


def _fill_area() -> shapely.Geometry:
    """The container of fill.svg in document coordinates, built here independently: an 80 x 60
    rectangle with a 30 x 20 hole, in a layer translate(60 30) rotate(10) scale(1.5)."""
    local = shapely.box(0, 0, 80, 60).difference(shapely.box(25, 20, 55, 40))
    return affinity.translate(affinity.rotate(affinity.scale(local, 1.5, 1.5, origin=(0, 0)), 10, origin=(0, 0)), 60, 30)


class _Base(TestCase):
    effect_class = FillWithTexture

    @classmethod
    def datadir(cls):
        return str(DATA)

    def setUp(self):
        super().setUp()
        self._env = os.environ.get("SVGTILE_PYTHON")
        os.environ["SVGTILE_PYTHON"] = sys.executable

    def tearDown(self):
        if self._env is None:
            os.environ.pop("SVGTILE_PYTHON", None)
        else:
            os.environ["SVGTILE_PYTHON"] = self._env
        super().tearDown()

    def fill(self, *args, doc="fill.svg"):
        return self.assertEffect("svg", doc, args=list(args))

    def fail_run(self, *args, doc="cases.svg"):
        """Run the effect expecting an error: (message, effect).  Checks that it exits with
        status, writes no document (so Inkscape keeps its own), leaves the input file and the
        loaded document byte-identical, and prints one line."""
        path = self.data_file("svg", doc)
        before = Path(path).read_bytes()
        effect = FillWithTexture()
        out, err, stdout = io.BytesIO(), io.StringIO(), io.StringIO()
        with redirect_stderr(err), redirect_stdout(stdout), pytest.raises(SystemExit) as exit_info:
            effect.run([path, *args], output=out)
        assert exit_info.value.code == inkex.utils.ABORT_STATUS != 0
        assert out.getvalue() == b"" and stdout.getvalue() == ""
        assert Path(path).read_bytes() == before
        pristine = inkex.load_svg(path).getroot()
        assert effect.svg.tostring() == pristine.tostring()
        message = err.getvalue().strip()
        assert message.startswith("svgtile: ") and "\n" not in message, message
        return message, effect


def _textures(svg):
    return svg.xpath("//svg:g[starts-with(@id, 'svgtile-texture')]")


def _footprints(group) -> list[tuple[str, shapely.Geometry]]:
    """(symbol id, footprint in document coordinates) of every <use> in a texture group."""
    out = []
    for use in group:
        href = use.get(XLINK_HREF)[1:]
        m = (group.composed_transform() @ use.transform).to_hexad()
        out.append((href, affinity.affine_transform(PROTOS[href], [m[0], m[2], m[1], m[3], m[4], m[5]])))
    return out


class FillComparison(ComparisonMixin, _Base):
    """Golden snapshots of the whole document after the effect (ids and float noise filtered)."""

    compare_file = "svg/fill.svg"
    comparisons = [  # noqa: RUF012 (inkex reads these class attributes)
        ("--id=exemplar", "--id=container", "--id=pond", "--engine=tile", "--max-rotation=0"),
        ("--id=exemplar", "--id=container", "--engine=tile", "--boundary=inside", "--seed=3"),
    ]
    compare_filters = [CompareWithoutIds(), CompareNumericFuzzy()]  # noqa: RUF012


#: Engines the Fill dialog does not offer (their output is more than <use> motifs).
NOT_IN_DIALOG = ("cellular",)


class FillInx(InxMixin, TestCase):
    def test_inx_agrees_with_the_script(self):
        here = os.getcwd()
        self.addCleanup(os.chdir, here)
        os.chdir(EXT)
        self.assertInxIsGood("svgtile_fill.inx")
        self.assertInxSchemaValid("svgtile_fill.inx")

    def test_inx_and_script_follow_the_engine_parameter_classes(self):
        """The dialog cannot drift from the engines: every public parameter of every engine is in
        the .inx with its default, interval, choices and help, the script passes each on with the
        same default, and the .inx has nothing else but engine, boundary, seed and the tabs."""
        from svgtile.core.region import BOUNDARY_MODES
        from svgtile.engines import ENGINES, public_params

        inx = inkex.inx.InxFile(str(EXT / "svgtile_fill.inx"))
        params = {p.name: p for p in inx.params if p.param_type != "notebook"}
        # the cellular engine's cells and lines do not go through the Inkscape bridge (it writes
        # <use> motifs only), so the dialog does not offer that engine nor its parameters
        offered = [e for e in ENGINES if e not in NOT_IN_DIALOG]
        theirs = {p.name for e in NOT_IN_DIALOG for p in ENGINES[e].Params.public()}
        theirs -= {p.name for e in offered for p in ENGINES[e].Params.public()}
        public = {p.option.removeprefix("--"): p for p in public_params().values() if p.name not in theirs}
        assert set(params) == {*public, "engine", "boundary", "seed"}
        assert svgtile_fill.ENGINE_OPTIONS == tuple(public)
        assert params["engine"].options == offered
        assert sorted(params["boundary"].options) == sorted(BOUNDARY_MODES)
        elements = {el.get("name"): el for el in inx.xml.xpath("//*[local-name()='param']")}
        script = FillWithTexture().arg_parser.parse_args([])
        for name, p in public.items():
            el, value = elements[name], getattr(script, name.replace("-", "_"))
            assert el.get("gui-description").startswith(p.help), name
            if p.type is bool:
                assert (el.get("type"), el.text, value) == ("bool", str(p.default).lower(), p.default), name
            elif p.choices:
                assert (params[name].options, value) == (list(p.choices), p.default), name
            elif p.type is str:
                assert (el.get("type"), el.text or "", value) == ("string", p.default, p.default), name
            else:
                assert (float(el.text), value) == (p.default, p.default), name
                low, high = p.interval
                assert float(el.get("min")) == low and float(el.get("max")) <= high, name

class FillBehaviour(_Base):
    def test_container_with_a_hole_in_a_transformed_layer_centroid(self):
        eff = self.fill("--id=exemplar", "--id=container", "--boundary=centroid", "--seed=2")
        (group,) = _textures(eff.svg)
        assert group.getprevious().get("id") == "container"  # right above it, in its layer
        assert group.getparent().get("id") == "layer-map"
        assert group.get("clip-path") is None
        area = _fill_area()
        found = _footprints(group)
        assert len(found) > 100
        centres = shapely.points([fp.centroid.coords[0] for _, fp in found])
        assert shapely.contains(area.buffer(1e-3), centres).all()
        assert {href for href, _ in found} == {"dot", "bar"}

    def test_inside_keeps_whole_motifs_only(self):
        eff = self.fill("--id=container", "--id=exemplar", "--boundary=inside", "--seed=2")
        (group,) = _textures(eff.svg)
        area = _fill_area().buffer(1e-3)
        found = _footprints(group)
        assert len(found) > 100
        assert all(area.contains(fp) for _, fp in found)

    def test_clip_cuts_at_the_container(self):
        eff = self.fill("--id=exemplar", "--id=container", "--seed=2")
        (group,) = _textures(eff.svg)
        clip_id = group.get("clip-path")[5:-1]
        clip = eff.svg.getElementById(clip_id)
        assert clip.TAG == "clipPath" and clip.getparent() is eff.svg.defs
        (path,) = clip
        rings = [[node[1] for node in sub] for sub in path.path.to_superpath()]
        clip_area = functools.reduce(shapely.symmetric_difference, [shapely.Polygon(r) for r in rings])
        # the clip path is in the group's user space, which is the document's
        clip_area = affinity.affine_transform(clip_area, _affine(group.composed_transform()))
        area = _fill_area()
        assert clip_area.symmetric_difference(area).area < 1e-3 * area.area
        found = _footprints(group)
        assert all(area.intersects(fp) for _, fp in found)
        assert any(not area.contains(fp) for _, fp in found)  # some motifs are cut

    def test_none_lets_motifs_stick_out(self):
        eff = self.fill("--id=exemplar", "--id=container", "--boundary=none", "--seed=2")
        (group,) = _textures(eff.svg)
        assert group.get("clip-path") is None
        area = _fill_area()
        found = _footprints(group)
        assert all(area.intersects(fp) for _, fp in found)
        assert any(not area.contains(fp) for _, fp in found)

    def test_uses_clone_the_documents_symbols_and_add_none(self):
        eff = self.fill("--id=exemplar", "--id=container", "--id=pond", "--seed=5")
        groups = _textures(eff.svg)
        assert [g.getprevious().get("id") for g in groups] == ["container", "pond"]
        assert len(eff.svg.xpath("//svg:symbol")) == 2
        clips = [g.get("clip-path") for g in groups]
        assert len(set(clips)) == 2
        for g in groups:
            assert all(u.TAG == "use" and u.get(XLINK_HREF) in ("#dot", "#bar") for u in g)
            assert all(u.get("href") is None for u in g)
        assert len(eff.svg.xpath("//svg:clipPath")) == 2

    def test_selection_order_does_not_matter_and_seed_does(self):
        a = self.fill("--id=exemplar", "--id=container", "--seed=7").test_output.getvalue()
        b = self.fill("--id=container", "--id=exemplar", "--seed=7").test_output.getvalue()
        c = self.fill("--id=container", "--id=exemplar", "--seed=8").test_output.getvalue()
        assert a == b
        assert a != c

    def test_plain_shape_exemplar_gets_symbols_once(self):
        eff = self.fill("--id=plain-exemplar", "--id=box", "--id=box2", "--seed=1", doc="cases.svg")
        groups = _textures(eff.svg)
        assert len(groups) == 2
        symbols = eff.svg.xpath("//svg:symbol[starts-with(@id, 'svgtile-kind')]")
        assert len(symbols) == 2  # triangle and ring, once for both containers
        hrefs = {u.get(XLINK_HREF)[1:] for g in groups for u in g}
        assert hrefs == {s.get("id") for s in symbols}
        ids = eff.svg.xpath("//@id")
        assert len(ids) == len(set(ids))
        # a second run on the result reuses the symbols it made
        again = self.temp_file(suffix=".svg")
        Path(again).write_bytes(eff.test_output.getvalue())
        eff2 = self.assertEffect(again, args=["--id=plain-exemplar", "--id=box", "--seed=2"])
        assert len(eff2.svg.xpath("//svg:symbol[starts-with(@id, 'svgtile-kind')]")) == 2
        ids = eff2.svg.xpath("//@id")
        assert len(ids) == len(set(ids))

    def test_plain_exemplar_region_by_label_is_not_a_motif(self):
        eff = self.fill("--id=plain-exemplar", "--id=box2", "--engine=tile", "--max-rotation=0", doc="cases.svg")
        (group,) = _textures(eff.svg)
        # tile copies the 4 motifs of each 20 x 20 exemplar: 50 x 50 holds about 6.25 copies
        assert 20 <= len(group) <= 40

    def test_exemplar_of_positioned_uses(self):
        eff = self.fill("--id=dots", "--id=box2", "--seed=1", doc="cases.svg")
        (group,) = _textures(eff.svg)
        assert len(group) > 5 and {u.get(XLINK_HREF) for u in group} == {"#dot"}


def _affine(t) -> list[float]:
    a, b, c, d, e, f = t.to_hexad()
    return [a, c, b, d, e, f]


class FillErrors(_Base):
    """Every error: inkex's abort status, one line saying what to select, the document untouched."""

    @pytest.fixture(autouse=True)
    def _tmp(self, tmp_path):
        self.tmp = tmp_path

    def test_nothing_selected(self):
        message, _ = self.fail_run()
        assert "nothing is selected" in message and "Select the exemplar group" in message

    def test_no_exemplar(self):
        message, _ = self.fail_run("--id=box")
        assert "no exemplar selected" in message

    def test_no_container(self):
        message, _ = self.fail_run("--id=dots")
        assert "no shape to fill" in message

    def test_two_groups(self):
        message, _ = self.fail_run("--id=dots", "--id=plain-exemplar", "--id=box")
        assert "select one exemplar group, not 2" in message and "'dots'" in message

    def test_unfillable_element(self):
        message, _ = self.fail_run("--id=dots", "--id=label")
        assert "cannot fill <text id='label'>" in message

    def test_exemplar_without_motifs(self):
        for group in ("empty-group", "only-region"):
            message, _ = self.fail_run(f"--id={group}", "--id=box")
            assert f"the exemplar group <g id='{group}'> holds no motifs" in message

    def test_exemplar_svgtile_cannot_read(self):
        message, _ = self.fail_run("--id=ghost", "--id=box")
        assert message.startswith("svgtile: error: the exemplar group 'ghost': no motifs found"), message

    def test_container_without_area(self):
        message, _ = self.fail_run("--id=dots", "--id=flat")
        assert "the shape 'flat' encloses no area" in message

    def test_no_motif_fits(self):
        message, _ = self.fail_run("--id=dots", "--id=tiny", "--boundary=inside")
        assert "no motif fits" in message and "'inside'" in message

    def test_recorded_python_is_gone(self):
        os.environ["SVGTILE_PYTHON"] = str(self.tmp / "no-such-python")
        message, _ = self.fail_run("--id=dots", "--id=box")
        assert "does not exist any more" in message and "svgtile inkscape install" in message

    def test_python_without_svgtile(self):
        venv.create(self.tmp / "bare", with_pip=False)
        python = self.tmp / "bare" / ("Scripts/python.exe" if os.name == "nt" else "bin/python")
        os.environ["SVGTILE_PYTHON"] = str(python)
        message, _ = self.fail_run("--id=dots", "--id=box")
        assert "svgtile is not installed in SVGTILE_PYTHON" in message

    def test_not_installed(self):
        os.environ.pop("SVGTILE_PYTHON")
        assert not os.path.exists(svgtile_fill.CONFIG)
        message, _ = self.fail_run("--id=dots", "--id=box")
        assert "does not know where svgtile is installed" in message

    def test_svgtile_crash_is_one_line(self):
        script = self.tmp / "python"
        script.write_text("#!/bin/sh\necho 'Traceback (most recent call last):' >&2\necho 'boom' >&2\nexit 3\n")
        script.chmod(0o755)
        if subprocess.run([str(script)], capture_output=True).returncode != 3:
            pytest.skip("no /bin/sh")
        os.environ["SVGTILE_PYTHON"] = str(script)
        message, _ = self.fail_run("--id=dots", "--id=box")
        assert message == "svgtile: boom"
