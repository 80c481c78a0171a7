"""Run inside QGIS desktop (``qgis --code tools/qgis_grab.py``): screenshots for the README.

Reads ``SVGTILE_GRAB`` (a folder holding ``units.gpkg`` and ``texture.gpkg`` with its ``.qml``),
adds both layers to the project, opens *svgtile ▸ Fill polygons with texture* with the units
layer chosen, and after a few seconds saves ``dialog.png`` (the algorithm's dialog) and
``result.png`` (QGIS's main window with the texture drawn), then quits.  Made by
``tools/make_qgis_pictures.py``.
"""

import os

import processing
from qgis.core import QgsProject, QgsVectorLayer
from qgis.PyQt.QtCore import QTimer
from qgis.PyQt.QtGui import QColor
from qgis.utils import iface

FOLDER = os.environ["SVGTILE_GRAB"]
units = QgsVectorLayer(os.path.join(FOLDER, "units.gpkg") + "|layername=units", "units", "ogr")
texture = QgsVectorLayer(os.path.join(FOLDER, "texture.gpkg"), "texture", "ogr")
units.renderer().symbol().setColor(QColor("#f3ead3"))  # a pale map unit, as on a geologic map
QgsProject.instance().addMapLayer(units)
QgsProject.instance().addMapLayer(texture)
_state = {}


def open_dialog():
    iface.mainWindow().showMaximized()
    extent = units.extent()
    extent.scale(0.55, extent.center().x() - 0.2 * extent.width(), extent.center().y() - 0.1 * extent.height())
    iface.mapCanvas().setExtent(extent)
    iface.mapCanvas().refresh()
    dialog = processing.createAlgorithmDialog("svgtile:fill", {
        "INPUT": units.id(), "EXEMPLAR": os.path.join(FOLDER, "gravel.svg"), "CLASS_FIELD": "unit", "SEED": 1,
        "UNIT": 1.0, "OUTPUT": os.path.join(FOLDER, "texture.gpkg")})
    _state["dialog"] = dialog
    dialog.resize(820, 760)
    dialog.show()
    QTimer.singleShot(5000, grab)


def grab():
    _state["dialog"].grab().save(os.path.join(FOLDER, "dialog.png"))
    _state["dialog"].hide()
    QTimer.singleShot(3000, grab_main)


def grab_main():
    iface.mainWindow().grab().save(os.path.join(FOLDER, "result.png"))
    os._exit(0)  # QGIS's own exit would ask about the project


QTimer.singleShot(4000, open_dialog)
