"""The 3D FEM of any closed part (``spsc fem --part``) as a
:class:`~spsc.models.base.CurveModel`: the setup's body is a :class:`~spsc.fem.part.Part` (the
file, its mount, where and along what the plate presses, the FSR pockets, the motor), meshed
whole by fTetWild, inflated, its valve closed, pressed by the setup's rigid frictionless body.

It is no parametric chamber's model (``parametric`` False): ``spsc curve``, the sweeps, the
inverse design and the report do not offer it; ``spsc fem --part`` and the fingertip study
reach it through the registry."""

from __future__ import annotations

import functools
import json
import os
from dataclasses import dataclass

from spsc.core.errors import ParameterError

from .base import ModelBase, Outcome
from .meshed import force_option, mesh_size_option, solver_option, vtu_option

__all__ = ["PartCurveModel", "PartOptions", "estimate_counts", "part_surface_of"]



def refuse_contact(contact) -> None:
    """Friction and a compliant object are not built for parts: the contact's (a
    :class:`~spsc.core.setup.Contact`) refused in one line naming the first."""
    for flag, value, ok in (("--friction", contact.friction, contact.friction == "0"),
                            ("--object-stiffness", contact.object_stiffness,
                             contact.object_stiffness is None)):
        if not ok:
            raise ParameterError(flag, value, "not with --part (a part is pressed by a rigid "
                                 "frictionless body, --indenter, placed by --plate-at / "
                                 "--plate-normal)")

@dataclass(frozen=True)
class PartOptions:
    """``mesh_size`` (mm; fTetWild's edge length), ``force`` (beyond the size limits),
    ``solver`` (sparse linear solver), ``vtu`` (a folder for one VTU per converged step in
    the part's coordinates, or None)."""

    mesh_size: float = mesh_size_option(1.0)
    force: bool = force_option()
    solver: str = solver_option()
    vtu: str | None = vtu_option()


def estimate_counts(run, surface) -> dict:
    """Unknowns of the part mesh before meshing: fTetWild fills the solid at about 20 / size³
    tetrahedra per mm³ (measured on a dome and Type B at 1 mm: 17–22), 1.45 P2 nodes each."""
    from spsc.cad.meshtopo import signed_volume

    volume = abs(signed_volume(surface.vertices, surface.faces))
    tets = 20.0 * volume / run.mesh_size_mm ** 3
    nodes = 1.45 * tets
    return {"tetrahedra": int(tets), "nodes": int(nodes), "unknowns": int(3 * nodes + tets / 5)}


def part_surface_of(run):
    """The part's checked surface (:func:`~spsc.fem.part.load_part`), read once for the
    model's check and its solve (kept by the file's path, size and time, and the port)."""
    st = os.stat(run.part)
    port = json.dumps((run.design or {}).get("port"), sort_keys=True, default=float)
    return _surface(run.part, st.st_size, st.st_mtime_ns, port)


@functools.lru_cache(maxsize=4)
def _surface(path, size, mtime_ns, port):
    from spsc.fem.part import load_part

    return load_part(path, {"port": json.loads(port)})


@dataclass(frozen=True)
class PartCurveModel(ModelBase):
    """Any closed part in 3D, whole (minutes per curve)."""

    name: str = "part"
    help: str = "3D hyperelastic FEM of any closed part file (spsc fem --part)"
    module: str = "spsc.models.part"
    Options = PartOptions
    stroke_mm: float = 4.0
    points: int = 11
    bending: bool = True
    contact: bool = True
    fast: bool = False
    sweep: bool = False
    study: bool = False
    parametric: bool = False
    color: str = "C5"
    style: str = "s"
    seconds_per_point: float = 30.0

    def run_of(self, setup, options):
        """The engine's :class:`~spsc.fem.part.PartRun` of ``setup`` meshed at the options'
        size."""
        from spsc.fem.part.spec import PartRun

        return PartRun.of(setup, float(options.mesh_size))

    def load_steps(self, setup, options) -> int:
        load = setup.load
        return load.points - 1 + (self.run_of(setup, options).inflate_increments
                                  if load.pressure_kPa > 0 else 0)

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        """The part, its mount, the plate and the body against the part's surface, and the
        run's size, before any meshing: friction and a compliant object are not built for
        parts (one line naming them)."""
        from spsc.cad.heightfield import resolve
        from spsc.fem.part import check_part_run

        from .resources import FEM_MAX_UNKNOWNS, check_size, fem_memory_gib

        c = setup.contact
        refuse_contact(c)
        run = self.run_of(setup, options)
        surface = part_surface_of(run)
        check_part_run(run, surface)
        resolve(c.indenter)  # a body's file read before the part is meshed
        counts = estimate_counts(run, surface)
        check_size(verb, counts, self.load_steps(setup, options), limit=FEM_MAX_UNKNOWNS,
                   gib=fem_memory_gib(counts["unknowns"]), force=bool(options.force),
                   quiet=quiet, mesh_size=run.mesh_size_mm, points=run.load.points)

    def curve(self, setup, options, *, progress=None, cache_dir=None):
        """Mesh (cached in ``cache_dir`` by the file's hash, its port and the size), inflate,
        press; the Curve's ``series`` hold the force through each pocket and the motor's.
        ``state``: (FEMModel, Result, R, PartSurface)."""
        import time

        from spsc.fem.engine import Settings, solve
        from spsc.fem.engine.settings import PART_CONTACT
        from spsc.fem.part import part_curve, part_model, write_part_vtu

        run = self.run_of(setup, options)
        t0 = time.perf_counter()
        model, R, surface = part_model(run, cache_dir=cache_dir, surface=part_surface_of(run))
        mesh_seconds = time.perf_counter() - t0
        body = run.body(model, R)
        result = solve(model, run.steps(body), settings=Settings(solver=options.solver,
                                                                 **PART_CONTACT),
                       progress=progress)
        curve = part_curve(run, model, result, surface, mesh_seconds=mesh_seconds)
        extra = {}
        if options.vtu:
            extra["vtu"] = [p.name for p in write_part_vtu(model, result, R, options.vtu,
                                                           body)]
        return Outcome(curve, extra, (model, result, R, surface))
