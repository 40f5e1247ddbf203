"""3D hyperelastic FEM check of an SPSC: P2/P1 mixed tetrahedra of the wall, follower cavity
pressure, closed gas cavity with reservoir, frictionless rigid plate (docs/design.md)."""

from spsc.core.gaslaw import GasLaw
from .material import NearlyIncompressible
from .mesh import TetMesh, block, cached_mesh, sphere_shell, spsc_wall
from .tetwild import spsc_wall_tetwild, tetwild_mesh
from .model import FEMModel, Load
from .pressure import CavitySurface
from .run import ChamberRun, run_chamber, to_curve, write_vtu
from .engine import CloseValve, Inflate, Press, Result, Settings, solve

__all__ = [
    "CavitySurface",
    "ChamberRun",
    "CloseValve",
    "FEMModel",
    "GasLaw",
    "Inflate",
    "Load",
    "NearlyIncompressible",
    "Press",
    "Result",
    "Settings",
    "TetMesh",
    "block",
    "cached_mesh",
    "run_chamber",
    "solve",
    "sphere_shell",
    "spsc_wall",
    "spsc_wall_tetwild",
    "tetwild_mesh",
    "to_curve",
    "write_vtu",
]
