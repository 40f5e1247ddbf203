"""The wall model: the chamber wall as a thick, nearly incompressible solid on its meridian
section — the axisymmetric dome (:mod:`.section`, :mod:`.section_solid`) or the stadium's swept
wall (:mod:`.swept`) — as the engine's discretisation (:mod:`.model`), its curves
(:mod:`.curve`: :func:`wall_curve`) and the material calibration against bench curves
(:mod:`.calibrate`)."""

from .curve import WallFailure, inflate, newton, wall_curve, wall_curves
from .model import WallModel, WallSettings

__all__ = ["WallFailure", "WallModel", "WallSettings", "inflate", "newton", "wall_curve",
           "wall_curves"]
