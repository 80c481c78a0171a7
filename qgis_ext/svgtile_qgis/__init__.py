"""The svgtile QGIS plugin: a Processing provider, installed by ``svgtile qgis install``."""


def classFactory(iface):  # noqa: N802 - QGIS's name
    from .plugin import SvgtilePlugin

    return SvgtilePlugin(iface)
