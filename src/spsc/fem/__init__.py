"""The solid models of an SPSC: follower cavity pressure, closed gas cavity with reservoir,
frictionless rigid plate (docs/design.md), in two discretisations driven by one engine.

* :mod:`.engine` — the nonlinear engine: load steps, Newton's method with the plate's active
  set, line search and stability check, the result; the ``Discretisation`` protocol.
* :mod:`.solid` — the 3D solid: P2/P1 mixed tetrahedra of the wall (or of any part), the
  chamber run.
* :mod:`.wall` — the wall model: the wall's meridian section, axisymmetric or swept, its
  curves and the material calibration.
* :mod:`.part` — any closed part: surface, mesh, mount selector, the part run.
* :mod:`.material` — the nearly incompressible law both discretisations use.

The modules at this package's top besides those (``solver``, ``linsolve``, ``run``, ``mesh``,
``model``, ``wall_model``, ``calibrate``, ``part_run``) only re-export the new paths for code
outside ``spsc.fem``.
"""

from spsc.core.gaslaw import GasLaw

from .engine import CloseValve, Inflate, Load, Press, Result, Settings, solve
from .material import NearlyIncompressible
from .solid.chamber import ChamberRun, chamber_run, run_chamber, to_curve, write_vtu
from .solid.mesh import TetMesh, block, cached_mesh, sphere_shell, spsc_wall
from .solid.model import FEMModel
from .solid.pressure import CavitySurface
from .solid.tetwild import spsc_wall_tetwild, tetwild_mesh

__all__ = [
    "CavitySurface",
    "ChamberRun",
    "chamber_run",
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
