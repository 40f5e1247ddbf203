"""Geometry and manufacturing: the SPSC parameters, solids, exports and the printability gate."""

from spsc.core.errors import ParameterError
from .geometry import TABLE1_VOLUME_CM3, TYPES, SPSCGeometry, preset

__all__ = ["ParameterError", "SPSCGeometry", "TABLE1_VOLUME_CM3", "TYPES", "preset"]
