"""The models behind ``spsc curve --model``: one :class:`Model` entry each — its default stroke
and points, its own options (an argparse group), the checks of its limits and size before any
work, and a function from the setup (:class:`Job`) to a :class:`Computed` Curve.

Adding a model is one entry of :data:`MODELS`. Pressures kPa gauge, volumes mm³, lengths mm.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import Callable

from .options import integer, number

__all__ = ["MODELS", "Model", "Job", "Computed", "mesh_options", "wall_size_check"]


@dataclass(frozen=True)
class Job:
    """What every model receives: the chamber, the material and the setup (mm, kPa, mm³), the
    parsed arguments (for its own options) and whether to show progress."""

    geometry: object
    material: object
    pressure_kPa: float
    reservoir_mm3: float
    stroke_mm: float
    points: int
    polytropic_n: float
    args: object
    quiet: bool
    verb: str


@dataclass
class Computed:
    """A model's outcome: the Curve (its ``solver`` says how the solve went), model-specific
    JSON additions (``extra``) and, for the plot, the membrane's shapes (or None)."""

    curve: object
    extra: dict = field(default_factory=dict)
    shapes: object = None


@dataclass(frozen=True)
class Model:
    """One entry of the model table.

    name, help : the ``--model`` value and its one-line description
    stroke_mm, points : default stroke (mm) and plate positions
    add_options : registers the model's own options on an argparse group (dest default None)
    defaults : dest -> value of those options when the model runs and they are not given
    compute : Job -> Computed
    check : Job -> None, the model's own limits and what the run will cost, before any work
        (ParameterError when refused); None: the shared load case is all it needs
    """

    name: str
    help: str
    stroke_mm: float
    points: int
    add_options: Callable | None
    defaults: dict
    compute: Callable
    check: Callable | None = None


# -- the models ----------------------------------------------------------------------------
def _membrane_options(g) -> None:
    g.add_argument("--meridians", action="store_true", default=None,
                   help="add the deformed meridians (x, rho, eta per position) to the JSON")
    g.add_argument("--wrinkling", choices=("on", "off"), default=None,
                   help="on (default): tension-field membrane, it wrinkles instead of carrying "
                   "compression; off: the paper's taut law (hoop compression carried; fails "
                   "to converge on 13 of 24 3D-checked cases, README)")


def _membrane(job: Job) -> Computed:
    from spsc.membrane.solver import SolverSettings, solve

    r = solve(job.geometry, job.material, pressure_kPa=job.pressure_kPa,
              reservoir_mm3=job.reservoir_mm3, stroke_mm=job.stroke_mm, points=job.points,
              polytropic_n=job.polytropic_n,
              settings=SolverSettings(wrinkling=job.args.wrinkling != "off"))
    extra = {}
    if job.args.meridians:
        extra["meridians_mm"] = [None if sh is None else dict(zip(("x", "rho", "eta"), (
            [round(float(v), 6) for v in a] for a in sh.meridian()))) for sh in r.shapes]
    return Computed(r.curve, extra, r)


def _membrane_check(job: Job) -> None:
    from spsc.membrane.solver import check_membrane_pressure

    check_membrane_pressure(job.pressure_kPa, job.stroke_mm)


def _simplified(job: Job) -> Computed:
    from spsc.membrane.simplified import simplified_curve

    return Computed(simplified_curve(job.geometry, pressure_kPa=job.pressure_kPa,
                                     reservoir_mm3=job.reservoir_mm3, stroke_mm=job.stroke_mm,
                                     points=job.points, polytropic_n=job.polytropic_n,
                                     material=job.material.name))


def mesh_options(g) -> None:
    """The discretisation of the solid models (fem, wall), each with its own defaults."""
    g.add_argument("--mesh-size", type=number("mesh size", "mm"), default=None, metavar="MM",
                   help="element edge along the wall, mm (default: fem 1.0, wall 0.5 on a dome, "
                   "1.0 on a stadium)")
    g.add_argument("--layers", type=integer("layers"), default=None, metavar="N",
                   help="quadratic elements through the wall thickness (default: fem 2, "
                   "wall 2)")
    g.add_argument("--force", action="store_true", default=None,
                   help="run a model beyond the size limits (the estimate of unknowns, "
                   "memory and load steps is printed and checked before the run)")


def _check_solid(job: Job, limit: int, counts: dict, steps: int, gib: float | None) -> None:
    """Refuse a solid model whose estimated size is beyond ``limit`` unknowns (or the memory
    this machine has) unless --force; print the estimate on stderr unless --quiet."""
    from .resources import check_size

    check_size(job.verb, counts, steps, limit=limit, gib=gib, force=bool(job.args.force),
               quiet=job.quiet, mesh_size=counts["mesh_size"], points=job.points)


def _fem_check(job: Job) -> None:
    from spsc.fem.mesh import check_mesh_size, wall_mesh_counts

    from .resources import FEM_MAX_UNKNOWNS, fem_memory_gib

    size, layers = check_mesh_size(job.geometry, job.args.mesh_size, job.args.layers)
    counts = wall_mesh_counts(job.geometry, size, layers, full=bool(job.args.full))
    counts["mesh_size"] = size
    steps = job.points - 1 + (4 if job.pressure_kPa > 0 else 0)
    _check_solid(job, FEM_MAX_UNKNOWNS, counts, steps, fem_memory_gib(counts["unknowns"]))


def _wall_check(job: Job) -> None:
    wall_size_check(job.verb, job.geometry, job.args.mesh_size, job.args.layers,
                    job.points - 1 + (2 if job.pressure_kPa > 0 else 0),
                    force=bool(job.args.force), quiet=job.quiet, points=job.points)


def wall_size_check(verb: str, geometry, mesh_size, layers, steps: int, *, force: bool,
                    quiet: bool, points: int) -> None:
    """The wall model's discretisation checked and its size estimated before any work
    (ParameterError beyond the limits unless ``force``; the estimate on stderr unless
    ``quiet``). ``mesh_size`` None: the model's default for the chamber."""
    from spsc.fem.mesh import check_mesh_size
    from spsc.fem.wall_model import WallSettings

    from .resources import WALL_MAX_UNKNOWNS, check_size, wall_counts

    size = mesh_size if mesh_size is not None else \
        WallSettings().profile_size(geometry.l > 0)
    size, layers = check_mesh_size(geometry, size, layers)
    counts = wall_counts(geometry, size, layers, WallSettings().sweep_size_mm)
    check_size(verb, counts, steps, limit=WALL_MAX_UNKNOWNS, gib=None, force=force,
               quiet=quiet, mesh_size=size, points=points)


def _fem_options(g) -> None:
    g.add_argument("--full", action="store_true", default=None,
                   help="full model instead of the quarter on the symmetry planes")
    g.add_argument("--solver", default=None,
                   choices=("auto", "pardiso", "superlu", "superlu-mmd"),
                   help="sparse linear solver (default auto: pardiso if installed)")
    g.add_argument("--vtu", metavar="DIR", default=None,
                   help="write one VTU per converged step into this folder (for ParaView)")


def _fem(job: Job) -> Computed:
    from tqdm import tqdm

    from spsc.fem.run import ChamberRun, run_chamber, write_vtu
    from spsc.fem.solver import Settings

    a = job.args
    spec = ChamberRun(job.geometry, job.material, pressure_kPa=job.pressure_kPa,
                      reservoir_mm3=job.reservoir_mm3, stroke_mm=job.stroke_mm,
                      points=job.points, mesh_size_mm=a.mesh_size, layers=a.layers,
                      polytropic_index=job.polytropic_n, full=bool(a.full))
    total = spec.points - 1 + (spec.inflate_increments if spec.pressure_kPa > 0 else 0)
    bar = tqdm(total=total, desc=f"spsc {job.verb}", unit="step", disable=job.quiet,
               file=sys.stderr)

    def progress(done, total):
        bar.total = total
        bar.update(done - bar.n)

    try:
        curve, result, model = run_chamber(spec, settings=Settings(solver=a.solver),
                                           progress=progress)
    finally:
        bar.close()
    extra = {}
    if a.vtu:
        extra["vtu"] = [p.name for p in write_vtu(model, result, a.vtu)]
    return Computed(curve, extra)


def _wall(job: Job) -> Computed:
    from tqdm import tqdm

    from spsc.fem.wall import WallSettings, wall_curve

    a = job.args
    settings = WallSettings(mesh_size_mm=a.mesh_size, layers=a.layers)
    total = job.points - 1 + (settings.inflate_increments if job.pressure_kPa > 0 else 0)
    bar = tqdm(total=total, desc=f"spsc {job.verb}", unit="step", disable=job.quiet,
               file=sys.stderr)
    try:
        curve = wall_curve(job.geometry, job.material, pressure_kPa=job.pressure_kPa,
                           reservoir_mm3=job.reservoir_mm3, stroke_mm=job.stroke_mm,
                           points=job.points, polytropic_n=job.polytropic_n,
                           settings=settings, progress=lambda: bar.update(1))
    finally:
        bar.close()
    return Computed(curve)


#: The models behind ``spsc curve --model``. Adding one is one entry here: a compute function
#: Job -> Computed, its defaults and, if it has any, its options and its checks.
MODELS: dict[str, Model] = {m.name: m for m in (
    Model("membrane", "axisymmetric membrane: inflation and plate contact (fast)", 6.0, 41,
          _membrane_options, {"meridians": False, "wrinkling": "on"}, _membrane,
          _membrane_check),
    Model("simplified", "the nominal chamber cut by the plate, with the air spring", 6.0, 41,
          None, {}, _simplified, _membrane_check),
    Model("wall", "the thick wall as a solid (axisymmetric dome; swept stadium) with gas and "
          "plate: pressure and bending in one solve (seconds)", 6.0, 25,
          None, {"mesh_size": None, "layers": 2, "force": False}, _wall, _wall_check),
    Model("fem", "3D hyperelastic FEM of the printed wall (quarter model by default)", 4.0, 11,
          _fem_options, {"mesh_size": 1.0, "layers": 2, "force": False, "full": False,
                         "solver": "auto", "vtu": None}, _fem, _fem_check),
)}
