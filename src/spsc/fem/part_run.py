"""Moved to :mod:`spsc.fem.part.run`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .part.run import (ContactPatch, PartRun, check_part_run, part_curve, part_model,
                       press_rotation, run_part, write_part_vtu)

__all__ = ["ContactPatch", "PartRun", "check_part_run", "part_curve", "part_model",
           "press_rotation", "run_part", "write_part_vtu"]
