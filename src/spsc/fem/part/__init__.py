"""Any closed part in the 3D FEM: its surface read, checked and meshed (:mod:`.surface`), the
mount's selector (:mod:`.selector`) and the run — inflate, close the valve, press along any
direction, named contact patches, a motor as a rigid insert (:mod:`.run`)."""

from .spec import Part
from .run import (ContactPatch, PartRun, check_part_run, part_run, part_curve, part_model, press_rotation,
                  run_part, write_part_vtu)
from .selector import parse_selector
from .surface import PART_SUFFIXES, PartSurface, load_part, part_mesh, part_surface, read_surface

__all__ = ["PART_SUFFIXES", "ContactPatch", "Part", "PartRun", "PartSurface", "check_part_run",
           "load_part", "parse_selector", "part_curve", "part_mesh", "part_model", "part_run",
           "part_surface", "press_rotation", "read_surface", "run_part", "write_part_vtu"]
