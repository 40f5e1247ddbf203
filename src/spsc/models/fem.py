"""The 3D FEM of the printed wall (mixed P2/P1 tetrahedra, follower pressure, the gas with its
reservoir, the rigid plate) as a :class:`~spsc.models.base.CurveModel`."""

from __future__ import annotations

from dataclasses import dataclass

from .base import ModelBase, Outcome, option
from .meshed import force_option, layers_option, mesh_size_option, solver_option, vtu_option

__all__ = ["FEMCurveModel", "FEMOptions"]


@dataclass(frozen=True)
class FEMOptions:
    """``mesh_size`` (mm), ``layers`` through the wall, ``force`` (beyond the size limits),
    ``full`` (the whole chamber, not the quarter on the symmetry planes), ``solver`` (sparse
    linear solver), ``vtu`` (a folder for one VTU per converged step, or None). What presses
    the chamber is the setup's :class:`~spsc.core.setup.Contact`."""

    mesh_size: float = mesh_size_option(1.0)
    layers: int = layers_option(2)
    force: bool = force_option()
    full: bool = option(False, "--full", "full model instead of the quarter on the symmetry "
                        "planes", kind="flag")
    solver: str = solver_option()
    vtu: str | None = vtu_option()


@dataclass(frozen=True)
class FEMCurveModel(ModelBase):
    """The reference: the printed wall in 3D, quarter model by default (minutes per curve)."""

    name: str = "fem"
    help: str = "3D hyperelastic FEM of the printed wall (quarter model by default)"
    module: str = "spsc.models.fem"
    Options = FEMOptions
    stroke_mm: float = 4.0
    points: int = 11
    bending: bool = True
    meshed: bool = True
    contact: bool = True
    fast: bool = False
    sweep: bool = False
    color: str = "C3"
    style: str = "o"
    seconds_per_point: float = 12.0

    def load_steps(self, setup, options) -> int:
        from spsc.fem.solid.chamber import ChamberRun

        load = setup.load
        inflate = ChamberRun.inflate_increments if load.pressure_kPa > 0 else 0
        return load.points - 1 + inflate

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        from spsc.core.contact import check_body
        from spsc.fem.solid.mesh import check_mesh_size, wall_mesh_counts

        geometry, load, c = setup.body, setup.load, setup.contact
        check_body(c.indenter, c.friction, quarter=not options.full)
        from spsc.cad.heightfield import resolve

        resolve(c.indenter)  # a body's file read before the chamber is meshed
        from .resources import FEM_MAX_UNKNOWNS, check_size, fem_memory_gib

        size, layers = check_mesh_size(geometry, options.mesh_size, options.layers)
        counts = wall_mesh_counts(geometry, size, layers, full=bool(options.full))
        steps = load.points - 1 + (4 if load.pressure_kPa > 0 else 0)
        check_size(verb, counts, steps, limit=FEM_MAX_UNKNOWNS,
                   gib=fem_memory_gib(counts["unknowns"]), force=bool(options.force),
                   quiet=quiet, mesh_size=size, points=load.points)

    def curve(self, setup, options, *, progress=None, cache_dir=None):
        from spsc.fem.solid.chamber import ChamberRun, run_chamber, write_vtu
        from spsc.fem.engine.settings import SEMISMOOTH_CONTACT, Settings

        c = setup.contact
        spec = ChamberRun.of(setup, mesh_size_mm=options.mesh_size, layers=options.layers,
                             full=bool(options.full))
        # the wall's active-set choices (semi-smooth from the secant predictor): the report's
        # vented Type A curve 177 -> 102 Newton iterations, its pressurised Type B 70 -> 64
        # factorisations, the curves within 3e-10; each press load from the last one's
        # factorisation (``warm_start``), small set changes by updating it (``low_rank``)
        settings = Settings(solver=options.solver, warm_start=True, low_rank=16,
                            **SEMISMOOTH_CONTACT)
        curve, result, model = run_chamber(spec, settings=settings,
                                           progress=progress, cache_dir=cache_dir)
        extra = {}
        if options.vtu:
            from spsc.cad.heightfield import resolve

            extra["vtu"] = [p.name for p in write_vtu(model, result, options.vtu,
                                                      resolve(c.indenter))]
        return Outcome(curve, extra, (model, result))
