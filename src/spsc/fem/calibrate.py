"""Moved to :mod:`spsc.fem.wall.calibrate`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .wall.calibrate import SCALE_RANGE, Calibration, calibrate, scaled

__all__ = ["SCALE_RANGE", "Calibration", "calibrate", "scaled"]
