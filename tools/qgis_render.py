"""Render GIS layers to a PNG with QGIS's own map renderer (PyQGIS), each with its default style.

Run with the Python that has PyQGIS (Debian: ``/usr/bin/python3``), headless::

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 tools/qgis_render.py [--gray RAW] OUT.png WIDTH HEIGHT LAYER…

The first layer is drawn on top; the map extent is the last layer's, grown by 5 %.  A layer
file with a ``.qml`` beside it (``svgtile … --with-style``) is drawn with that style, as QGIS
desktop would.  Prints one line per layer: its name, feature count and renderer/symbol layer type.
``--gray RAW`` also writes the image as 8-bit gray bytes, row by row (rows padded to 4 bytes), for
a test to look at without an image library.  Used by ``tests/test_qgis_e2e.py`` and to make the
README's pictures.
"""

import os
import sys

from qgis.core import QgsApplication, QgsMapRendererSequentialJob, QgsMapSettings, QgsVectorLayer
from qgis.PyQt.QtCore import QSize
from qgis.PyQt.QtGui import QColor, QImage


def main(out, width, height, paths, gray=None):
    app = QgsApplication([], False)
    app.initQgis()
    layers = []
    for path in paths:
        layer = QgsVectorLayer(path, path.rsplit("/", 1)[-1], "ogr")
        if not layer.isValid():
            print(f"invalid layer: {path}", file=sys.stderr)
            return 1
        kind = layer.renderer().type()
        sym = getattr(layer.renderer(), "symbol", lambda: None)()
        if sym is not None:
            kind += "/" + sym.symbolLayer(0).layerType()
        print(f"{layer.name()} {layer.featureCount()} {kind}")
        layers.append(layer)
    settings = QgsMapSettings()
    settings.setLayers(layers)
    settings.setBackgroundColor(QColor("white"))
    settings.setDestinationCrs(layers[-1].crs())
    extent = layers[-1].extent()
    extent.scale(1.05)
    settings.setExtent(extent)
    settings.setOutputSize(QSize(int(width), int(height)))
    job = QgsMapRendererSequentialJob(settings)
    job.start()
    job.waitForFinished()
    image = job.renderedImage()
    ok = image.save(out)
    if gray:
        g = image.convertToFormat(QImage.Format_Grayscale8)
        with open(gray, "wb") as fh:
            fh.write(g.constBits().asstring(g.bytesPerLine() * g.height()))
    # exitQgis() with layers still referenced crashes some PyQGIS builds at exit: leave directly
    sys.stdout.flush()
    os._exit(0 if ok else 1)


if __name__ == "__main__":
    args = sys.argv[1:]
    gray = None
    if args[:1] == ["--gray"]:
        gray, args = args[1], args[2:]
    sys.exit(main(args[0], args[1], args[2], args[3:], gray))
