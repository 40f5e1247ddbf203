"""The 3D solid: the chamber wall (or any part) as P2/P1 mixed tetrahedra — the mesh and its
cache, elements and assembly, the cavity surface's volume and follower pressure, the rigid
insert, contact measurements, the :class:`~.model.FEMModel` (the engine's discretisation) and
the chamber run that turns a solve into a :class:`~spsc.core.curve.Curve`."""

from .chamber import ChamberRun, chamber_run, run_chamber, to_curve, write_vtu
from .insert import RigidInsert
from .mesh import TetMesh, block, cached_mesh, sphere_shell, spsc_wall
from .model import FEMModel
from .pressure import CavitySurface
from .tetwild import spsc_wall_tetwild, tetwild_mesh

__all__ = ["CavitySurface", "ChamberRun", "chamber_run", "FEMModel", "RigidInsert", "TetMesh", "block",
           "cached_mesh", "run_chamber", "sphere_shell", "spsc_wall", "spsc_wall_tetwild",
           "tetwild_mesh", "to_curve", "write_vtu"]
