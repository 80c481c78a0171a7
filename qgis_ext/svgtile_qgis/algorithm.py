"""svgtile ▸ Fill polygons with texture — the Processing algorithm.

QGIS's Python has neither shapely nor scipy (and must not get them), so this module only
translates: it hands the polygon layer (as a file OGR reads, exported by Processing when it is
not one) to ``PYTHON -m svgtile qgis fill …``, run with the interpreter that ``svgtile qgis
install`` recorded in ``svgtile_qgis.json`` beside this file (the environment variable
``SVGTILE_PYTHON`` overrides it), and returns the point layer it writes.  The engine parameters
of the dialog are generated from the same file, which ``install`` fills from svgtile's engine
parameter classes, so the dialog, the command line and the styles files cannot drift apart.

A failure is raised as a QgsProcessingException (shown in the dialog's log and the Processing
history) and logged under *svgtile* in the Log Messages panel; the project is never touched
(no layer is added, none is changed).  The output layer carries ``OUT.qml`` beside it, which
QGIS loads as its default style; the post-processor below applies it explicitly as well.
"""

import json
import os
import subprocess

from qgis.core import (
    Qgis,
    QgsMessageLog,
    QgsProcessing,
    QgsProcessingAlgorithm,
    QgsProcessingException,
    QgsProcessingLayerPostProcessorInterface,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterField,
    QgsProcessingParameterFile,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
    QgsProcessingParameterVectorDestination,
    QgsProviderRegistry,
)

HERE = os.path.dirname(os.path.abspath(__file__))
CONFIG = os.path.join(HERE, "svgtile_qgis.json")
REINSTALL = "run 'svgtile qgis install' in the Python environment where svgtile is installed"
#: Formats svgtile reads and writes (by suffix); Processing exports other sources to GeoPackage.
FORMATS = ["gpkg", "shp", "geojson", "fgb"]
#: Single-layer formats: their spec never names a layer (``FILE.geojson#X`` means feature X).
SINGLE_LAYER = (".shp", ".geojson", ".json", ".fgb")
_KEEP = []  # post-processors must outlive processAlgorithm
POLL = 0.1  # seconds between looks at the cancel button


def load_config():
    """The install record: ``{"python": …, "svgtile": version, "boundary_modes": […], "engines":
    {name: summary}, "params": [{name, type, default, help, option, choices, interval, engines}]}``."""
    try:
        with open(CONFIG, encoding="utf-8") as fh:
            return json.load(fh)
    except (OSError, ValueError):
        return None


def _log(message, level=Qgis.Critical):
    QgsMessageLog.logMessage(message, "svgtile", level)


def _spec(path, layer_name):
    """A svgtile layer spec (``FILE#LAYER``) from an OGR path and layer name."""
    path = path.split("|", 1)[0]
    if layer_name and not path.lower().endswith(SINGLE_LAYER):
        return f"{path}#{layer_name}"
    return path


class StyleApplier(QgsProcessingLayerPostProcessorInterface):
    """Applies the ``.qml`` written beside the output when Processing loads it into the project."""

    def __init__(self, qml):
        super().__init__()
        self.qml = qml

    def postProcessLayer(self, layer, context, feedback):  # noqa: N802
        if layer is not None and os.path.isfile(self.qml):
            layer.loadNamedStyle(self.qml)
            layer.triggerRepaint()


class FillAlgorithm(QgsProcessingAlgorithm):
    INPUT, EXEMPLAR, STYLES, CLASS_FIELD, ENGINE = "INPUT", "EXEMPLAR", "STYLES", "CLASS_FIELD", "ENGINE"
    BOUNDARY, UNIT, SEED, AVOID, OUTPUT = "BOUNDARY", "UNIT", "SEED", "AVOID", "OUTPUT"

    def __init__(self):
        super().__init__()
        self.config = load_config() or {"engines": {"patch": ""}, "params": [], "boundary_modes": ["inside"]}

    def name(self):
        return "fill"

    def displayName(self):  # noqa: N802
        return "Fill polygons with texture"

    def createInstance(self):  # noqa: N802
        return FillAlgorithm()

    def shortHelpString(self):  # noqa: N802
        engines = "".join(f"<li><b>{n}</b>: {s}</li>" for n, s in self.config["engines"].items())
        return (
            "Fills each polygon with small vector motifs arranged like an exemplar SVG (svgtile), "
            "and returns one point per motif (kind, angle, scale, size, region, class) in the "
            "layer's CRS, drawn with the exemplar's own symbols.<br><br>"
            "Give one <b>exemplar</b> for every polygon, or an <b>exemplar table</b> (an svgtile "
            "styles file, TOML: [classes.NAME] exemplar = \"FILE.svg\" …) with the <b>class field</b> "
            "whose values name its classes. Engine parameters left empty take the engine's "
            "defaults; with an exemplar table the table's values are used.<br><br>"
            "<b>Exemplar units</b>: map units per user unit of the exemplar SVG.<br>"
            f"Engines:<ul>{engines}</ul>"
        )

    def initAlgorithm(self, config=None):  # noqa: N802
        cfg = self.config
        self.addParameter(QgsProcessingParameterFeatureSource(
            self.INPUT, "Polygon layer", [QgsProcessing.TypeVectorPolygon]))
        self.addParameter(QgsProcessingParameterFile(
            self.EXEMPLAR, "Exemplar (SVG)", extension="svg", optional=True))
        self.addParameter(QgsProcessingParameterFile(
            self.STYLES, "Exemplar table (svgtile styles file, TOML)", extension="toml", optional=True))
        self.addParameter(QgsProcessingParameterField(
            self.CLASS_FIELD, "Class field (its values name the table's classes)",
            parentLayerParameterName=self.INPUT, optional=True))
        engines = list(cfg["engines"])
        self.addParameter(QgsProcessingParameterEnum(
            self.ENGINE, "Engine", options=engines, defaultValue=engines.index("patch") if "patch" in engines else 0))
        for p in cfg["params"]:
            self.addParameter(self._engine_parameter(p))
        modes = cfg["boundary_modes"]
        self.addParameter(QgsProcessingParameterEnum(
            self.BOUNDARY, "Boundary (inside: only whole motifs, the right choice for markers)", options=modes,
            defaultValue=modes.index("inside") if "inside" in modes else 0))
        self.addParameter(QgsProcessingParameterNumber(
            self.UNIT, "Exemplar units (map units per exemplar user unit)", QgsProcessingParameterNumber.Double,
            defaultValue=1.0, minValue=1e-12))
        self.addParameter(QgsProcessingParameterNumber(
            self.SEED, "Random seed", QgsProcessingParameterNumber.Integer, defaultValue=1, minValue=0))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.AVOID, "Layers to keep clear of (labels, roads …)", QgsProcessing.TypeVectorAnyGeometry,
            optional=True))
        self.addParameter(QgsProcessingParameterVectorDestination(
            self.OUTPUT, "Texture points", QgsProcessing.TypeVectorPoint))

    def _engine_parameter(self, p):
        """A dialog parameter from an svgtile engine parameter (see :func:`load_config`)."""
        key = "P_" + p["name"].upper()
        text = f"{p['name'].replace('_', ' ').capitalize()} [{', '.join(p['engines'])}]"
        if p["type"] == "bool":
            param = QgsProcessingParameterBoolean(key, text, defaultValue=False)
        elif p["choices"]:
            param = QgsProcessingParameterEnum(key, text, options=["(engine default)"] + p["choices"], defaultValue=0)
        elif p["type"] in ("float", "int"):
            kind = QgsProcessingParameterNumber.Double if p["type"] == "float" else QgsProcessingParameterNumber.Integer
            param = QgsProcessingParameterNumber(key, text, kind, defaultValue=None, optional=True)
            if p.get("interval"):
                low, high = p["interval"]
                param.setMinimum(low)
                param.setMaximum(high)
        else:
            param = QgsProcessingParameterString(key, text, optional=True)
        param.setHelp(f"{p['help']} (default: {p['default']})")
        return param

    def _engine_args(self, parameters, context, engine):
        """Options for the parameters of ``engine`` the user set (the dialog shows every engine's)."""
        args = []
        for p in self.config["params"]:
            if engine not in p["engines"]:
                continue
            key = "P_" + p["name"].upper()
            if p["type"] == "bool":
                if self.parameterAsBoolean(parameters, key, context):
                    args.append(p["option"])
            elif p["choices"]:
                i = self.parameterAsEnum(parameters, key, context)
                if i > 0:
                    args += [p["option"], p["choices"][i - 1]]
            elif parameters.get(key) not in (None, ""):
                value = (self.parameterAsDouble if p["type"] == "float" else self.parameterAsInt)(parameters, key, context) \
                    if p["type"] in ("float", "int") else self.parameterAsString(parameters, key, context)
                args += [p["option"], str(value)]
        return args

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        cfg = load_config()
        python = os.environ.get("SVGTILE_PYTHON") or (cfg or {}).get("python")
        if not python or not os.path.exists(python):
            raise self._fail(f"svgtile's Python is not recorded or gone ({python}); {REINSTALL}")
        path, layer_name = self.parameterAsCompatibleSourceLayerPathAndLayerName(
            parameters, self.INPUT, context, FORMATS, "gpkg", feedback)
        out = self.parameterAsOutputLayer(parameters, self.OUTPUT, context).split("|", 1)[0]
        if os.path.splitext(out)[1].lower().lstrip(".") not in FORMATS:
            raise self._fail(f"svgtile writes {', '.join(FORMATS)} files, not {out}")
        exemplar = self.parameterAsFile(parameters, self.EXEMPLAR, context)
        styles = self.parameterAsFile(parameters, self.STYLES, context)
        if bool(exemplar) == bool(styles):
            raise self._fail("give either an exemplar SVG or an exemplar table (TOML), not both or neither")
        engine = list(self.config["engines"])[self.parameterAsEnum(parameters, self.ENGINE, context)]
        cmd = [python, "-m", "svgtile", "qgis", "fill", _spec(path, layer_name), "-o", out, "--with-style",
               "--engine", engine,
               "--boundary", self.config["boundary_modes"][self.parameterAsEnum(parameters, self.BOUNDARY, context)],
               "--unit", repr(self.parameterAsDouble(parameters, self.UNIT, context)),
               "--seed", str(self.parameterAsInt(parameters, self.SEED, context))]
        cmd += ["--exemplar", exemplar] if exemplar else ["--styles", styles]
        field = self.parameterAsFields(parameters, self.CLASS_FIELD, context)
        if field:
            cmd += ["--class-field", field[0]]
        cmd += self._engine_args(parameters, context, engine)
        for layer in self.parameterAsLayerList(parameters, self.AVOID, context):
            parts = QgsProviderRegistry.instance().decodeUri(layer.providerType(), layer.source())
            if layer.providerType() != "ogr" or not parts.get("path"):
                raise self._fail(f"layer to avoid {layer.name()!r} is not a file OGR reads; save it as a GeoPackage first")
            cmd += ["--avoid", _spec(parts["path"], parts.get("layerName"))]
        feedback.pushCommandInfo(" ".join(cmd))
        self._run(cmd, feedback)
        qml = os.path.splitext(out)[0] + ".qml"
        if context.willLoadLayerOnCompletion(out):
            applier = StyleApplier(qml)
            _KEEP.append(applier)
            context.layerToLoadOnCompletionDetails(out).setPostProcessor(applier)
        return {self.OUTPUT: out}

    def _run(self, cmd, feedback):
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
        try:
            proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                                    text=True, env=env)
        except OSError as exc:
            raise self._fail(f"cannot run svgtile ({exc}); {REINSTALL}") from None
        while True:  # read stderr as it comes: a full pipe (many warnings) would stall svgtile for ever
            try:
                _, err = proc.communicate(timeout=POLL)
                break
            except subprocess.TimeoutExpired:  # retrying loses no output
                if feedback.isCanceled():
                    proc.kill()
                    proc.communicate()
                    raise self._fail("canceled") from None
        lines = [line for line in err.splitlines() if line.strip()]
        for line in lines:
            feedback.pushInfo(line)
        if proc.returncode != 0:
            problem = next((line for line in reversed(lines) if "error" in line), lines[-1] if lines else "")
            raise self._fail(problem or f"svgtile exited with code {proc.returncode}")

    def _fail(self, message):
        _log(message)
        return QgsProcessingException(message)
