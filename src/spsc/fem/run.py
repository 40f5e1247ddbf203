"""Moved to :mod:`spsc.fem.solid.chamber`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .solid.chamber import ChamberRun, run_chamber, to_curve, curve_points, solve_info, write_vtu

__all__ = ["ChamberRun", "run_chamber", "to_curve", "curve_points", "solve_info", "write_vtu"]
