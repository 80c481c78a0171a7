"""The svgtile Processing provider: one algorithm, Fill polygons with texture."""

from qgis.core import QgsProcessingProvider

from .algorithm import FillAlgorithm


class SvgtileProvider(QgsProcessingProvider):
    def id(self):
        return "svgtile"

    def name(self):
        return "svgtile"

    def longName(self):  # noqa: N802
        return "svgtile — vector textures like an exemplar"

    def loadAlgorithms(self):  # noqa: N802
        self.addAlgorithm(FillAlgorithm())
