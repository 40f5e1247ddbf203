"""A chamber run as the user asks for it: inflate, close the valve, press — as a :class:`Curve`.

``run_chamber`` builds the quarter (or full) wall mesh of a parametric chamber, walks the steps
and returns the same :class:`~spsc.core.curve.Curve` (and JSON) as the membrane model, plus
the raw :class:`~spsc.fem.engine.Result`. ``pressure = 0`` is the open chamber (no gas, valve
open), whose force is the structural F_el(y).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from spsc.core.contact import (check_body, check_combination, check_friction,
                               check_object_stiffness, coefficient, with_indenter)
from spsc.cad.heightfield import resolve
from spsc.core.indenter import parse_indenter
from spsc.core.errors import ParameterError
from spsc.core.loadcase import LoadCase, WithLoadCase, check_load
from spsc.cad.geometry import SPSCGeometry
from spsc.core.curve import Curve, SolveInfo
from spsc.materials import Material

from ..engine import Result, Settings, load_steps, solve
from .contact import contact_tractions
from .element import TET_EDGES
from .mesh import cached_mesh, check_mesh_size, spsc_wall
from .model import FEMModel

__all__ = ["ChamberRun", "chamber_run", "run_chamber", "to_curve", "curve_points", "solve_info",
           "write_vtu", "contact_forces"]


@dataclass(frozen=True)
class ChamberRun(WithLoadCase):
    """Inputs of a chamber run: the chamber, the material, the load case every model shares
    (:class:`~spsc.core.loadcase.LoadCase`: kPa gauge, mm³, mm; ``points`` plate positions from
    first contact, points − 1 increments) and the mesh. ``mesh_size_mm``: element edge along
    the wall surfaces (``spsc fem --mesh-size``; not the preset footprint, which is
    ``--footprint`` and part of the geometry). ``friction`` (``"0"``, a Coulomb coefficient such as ``"0.3"`` or ``"stick"``) and
    ``object_stiffness`` (N/mm, None: rigid) describe what presses it
    (:mod:`spsc.core.contact`), ``indenter`` which body (``"plate"`` or a curved one such as
    ``"sphere:R=10"``, :mod:`spsc.core.indenter`, centred on the chamber's axis).
    ``inflate_increments``: the setup pressure in one increment (cut in halves where Newton
    fails): Types A–D at 40 and 60 kPa converge in it, 2–3 s sooner than in four, to 1e-9 of
    the same curve (issue 26).
    :func:`chamber_run` builds one from keywords."""

    geometry: SPSCGeometry
    material: Material
    load: LoadCase
    mesh_size_mm: float = 1.0
    layers: int = 2
    inflate_increments: int = 1
    full: bool = False
    bulk_ratio: float = 2000.0
    friction: str = "0"
    object_stiffness: float | None = None
    indenter: str = "plate"

    def __post_init__(self):
        if not isinstance(self.load, LoadCase):
            raise ParameterError("load", type(self.load).__name__,
                                 "a LoadCase (spsc.core.loadcase.check_load)")
        check_load(self.geometry, **self.load.as_dict())  # the same limits, on this chamber
        check_mesh_size(self.geometry, self.mesh_size_mm, self.layers)
        object.__setattr__(self, "friction", check_friction(self.friction))
        object.__setattr__(self, "object_stiffness",
                           check_object_stiffness(self.object_stiffness))
        check_combination(coefficient(self.friction), self.object_stiffness)
        body = check_body(self.indenter, self.friction, quarter=not self.full)
        object.__setattr__(self, "indenter", body.spec)

    @classmethod
    def of(cls, setup, **mesh) -> "ChamberRun":
        """The run of a checked :class:`~spsc.core.setup.Setup` with the mesh's keywords
        (``mesh_size_mm``, ``layers``, ``full``, ...)."""
        c = setup.contact
        return cls(setup.body, setup.material, setup.load, friction=c.friction,
                   object_stiffness=c.object_stiffness, indenter=c.indenter.spec, **mesh)

    def steps(self) -> list:
        return load_steps(self.load, self.inflate_increments, stick=self.friction != "0",
                          spring=self.object_stiffness, mu=coefficient(self.friction),
                          indenter=resolve(parse_indenter(self.indenter)))


def chamber_run(geometry: SPSCGeometry, material: Material, *, pressure_kPa: float = 40.0,
                reservoir_mm3: float = 0.0, stroke_mm: float = 4.0, points: int = 11,
                polytropic_n: float = 1.0, **mesh) -> ChamberRun:
    """A :class:`ChamberRun` from the load case's keywords (checked by
    :func:`~spsc.core.loadcase.check_load`) and the mesh's (``mesh_size_mm``, ``layers``,
    ``full``, ...)."""
    load = check_load(geometry, pressure_kPa=pressure_kPa, reservoir_mm3=reservoir_mm3,
                      stroke_mm=stroke_mm, points=points, polytropic_n=polytropic_n)
    return ChamberRun(geometry, material, load, **mesh)


def build_model(run: ChamberRun, *, cache_dir=None) -> FEMModel:
    mesh = cached_mesh(spsc_wall, cache_dir=cache_dir, g=run.geometry, size=run.mesh_size_mm,
                       layers=run.layers, full=run.full)
    return FEMModel.build(mesh, run.material, bulk_ratio=run.bulk_ratio)


def run_chamber(run: ChamberRun, *, settings: Settings | None = None, progress=None,
                cache_dir=None):
    """Solve ``run``; returns (Curve, Result, FEMModel). ``progress(done, total)`` is called per
    converged load point. The curve's ``solver`` is the run's
    :class:`~spsc.core.curve.SolveInfo`; its ``seconds`` include building (or loading) the
    mesh, the one timing field of the result."""
    t_start = time.perf_counter()
    model = build_model(run, cache_dir=cache_dir)
    mesh_seconds = time.perf_counter() - t_start
    result = solve(model, run.steps(), settings=settings, progress=progress)
    return to_curve(run, model, result, mesh_seconds=mesh_seconds), result, model


def _apex_height(model: FEMModel, x) -> float:
    X = model.disc.X
    cav = model.mesh.nodes_on("cavity")
    on_axis = cav[(np.abs(X[cav, 0]) < 1e-9) & (np.abs(X[cav, 1]) < 1e-9)]
    return float(np.max(X[on_axis, 2] + model.displacement(x)[on_axis, 2]))


def curve_points(run, result: Result) -> dict:
    """The curve's arrays from a result (a chamber's or a part's run: ``points``, ``stroke_mm``,
    ``pressure_kPa``, ``inflate_increments``): y = 0 at first contact with the inflated part,
    then one point per press increment; points not reached hold NaN with the reason. Also the
    start, inflated and press records."""
    start = result.records[0]
    inflated = result.of("inflate")[-1] if result.of("inflate") else start
    presses = result.of("press")
    n = int(run.points)
    y = np.linspace(0.0, run.stroke_mm, n)
    F, P, A, dV = (np.full(n, np.nan) for _ in range(4))
    conv = np.zeros(n, bool)
    msg = [""] * n
    if run.pressure_kPa == 0 or len(result.of("inflate")) == run.inflate_increments:
        F[0], P[0], A[0], dV[0], conv[0] = 0.0, inflated.pressure_kPa, 0.0, 0.0, True
    for k, rec in enumerate(presses, start=1):
        F[k], P[k], A[k] = rec.force, rec.pressure_kPa, rec.contact_area
        dV[k] = inflated.volume - rec.volume
        conv[k] = True
    for k in range(len(presses) + 1, n):
        msg[k] = result.message
    if not conv[0]:
        msg[0] = result.message
    return {"y": y, "F": F, "P": P, "A": A, "dV": dV, "conv": conv, "msg": tuple(msg),
            "start": start, "inflated": inflated, "presses": presses}


def solve_info(result: Result, model: FEMModel, pts: dict, mesh_seconds: float,
               details: dict) -> SolveInfo:
    """The curve's ``solver`` block: converged, message, instability, where it got to, seconds
    with ``mesh_seconds`` added, Newton iterations; ``details`` with the unknowns and
    tetrahedra first."""
    conv, y = pts["conv"], pts["y"]
    return SolveInfo(converged=result.converged, message=result.message,
                     y_reached_mm=y[conv][-1] if conv.any() else float("nan"),
                     instability=result.instability,
                     seconds=result.seconds + np.nan_to_num(mesh_seconds),
                     iterations=result.iterations,
                     details={"dofs": model.disc.n, "tetrahedra": model.mesh.n_tets, **details})


def to_curve(run: ChamberRun, model: FEMModel, result: Result, *,
             mesh_seconds: float = float("nan")) -> Curve:
    """The Curve of a run (:func:`curve_points`); ``solver`` is filled from ``result``
    (:func:`solve_info`) with the model's size in ``details`` (unknowns, tetrahedra, mesh
    size, layers, part)."""
    pts = curve_points(run, result)
    part = "full" if run.full else "quarter"
    setup = {"p_i_kPa": run.pressure_kPa, "reservoir_mm3": run.reservoir_mm3,
             "polytropic_n": run.polytropic_n, "mesh_size_mm": run.mesh_size_mm,
             "layers": run.layers, "dofs": model.disc.n, "model_part": part}
    if result.instability:
        setup["instability"] = result.instability
    setup |= {"indenter": run.indenter, "friction": run.friction}
    details = {"mesh_size_mm": run.mesh_size_mm, "layers": run.layers, "model_part": part,
               "bulk_ratio": run.bulk_ratio}
    if run.friction != "0":
        details.update(friction=run.friction, shear_N=[0.0] + [r.shear for r in pts["presses"]])
    info = solve_info(result, model, pts, mesh_seconds, details)
    inflated = pts["inflated"]
    curve = Curve(pts["y"], pts["F"], pts["P"], pts["A"], pts["dV"], model="fem",
                  geometry=run.geometry.as_dict(), material=run.material.name, setup=setup,
                  nominal_volume_mm3=pts["start"].volume, inflated_volume_mm3=inflated.volume,
                  inflated_height_mm=_apex_height(model, inflated.x), converged=pts["conv"],
                  message=pts["msg"], solver=info)
    return with_indenter(curve, run.object_stiffness, [r.indenter for r in pts["presses"]])


def contact_forces(model: FEMModel, rec, indenter=None) -> np.ndarray:
    """The plate's (or the curved ``indenter``'s) force on each node (n_nodes, 3; N, of the
    modelled part) at a record: the reaction −r of the nodes on it (within 1e-9 mm). On the
    plate its z is the contact force and its x and y the tangential traction a sticking plate
    carries (zero on a frictionless one); on a curved body it is along the body's normal.
    Components a symmetry plane supports are left out; zero elsewhere and without a plate.
    r is evaluated at the record's state and pressure."""
    out = np.zeros((model.disc.n_nodes, 3))
    if rec.plate is None:
        return out
    from ..engine import Load
    from ..engine.active_set import heights

    dofs = model.surface.dofs
    on = dofs[heights(model, rec.x, dofs, indenter) >= rec.plate - 1e-9]
    if on.size:
        r = model.evaluate(rec.x, Load(pressure=rec.pressure), tangent=False).r
        nodes = on // 3
        for c in range(3):
            dof = 3 * nodes + c
            out[nodes, c] = np.where(model.fixed[dof], 0.0, -r[dof])  # not the supports'
    return out


def write_vtu(model: FEMModel, result: Result, directory, indenter=None) -> list[Path]:
    """One VTU per converged record (quadratic tetrahedra, displacement and pressure fields,
    the plate's or the curved ``indenter``'s force per node ``contact_force_N``
    (:func:`contact_forces`), the contact pressure ``contact_pressure_MPa`` and tangential
    traction ``contact_shear_MPa`` recovered from it
    (:func:`~spsc.fem.solid.contact.contact_tractions`), warp by ``displacement`` in
    ParaView); returns the paths."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    paths = []
    pdof = model.disc.pressure_dof
    for i, rec in enumerate(result.records):
        grid = model.mesh.to_pyvista(model.displacement(rec.x))
        p = np.full(model.disc.n_nodes, np.nan)
        corner = pdof >= 0
        p[corner] = rec.x[model.disc.n_u:][pdof[corner]]
        # edge nodes: the mean of their two vertices (P1 field)
        for e, (a, b) in enumerate(TET_EDGES):
            mid = model.mesh.tets[:, 4 + e]
            p[mid] = 0.5 * (p[model.mesh.tets[:, a]] + p[model.mesh.tets[:, b]])
        grid.point_data["hydrostatic_pressure_MPa"] = p
        forces = contact_forces(model, rec, indenter)
        grid.point_data["contact_force_N"] = forces
        pressure, shear = contact_tractions(model, rec.x, forces, indenter)
        grid.point_data["contact_pressure_MPa"] = pressure
        grid.point_data["contact_shear_MPa"] = shear
        grid.field_data["cavity_pressure_kPa"] = np.array([rec.pressure_kPa])
        grid.field_data["plate_force_N"] = np.array([rec.force])
        path = directory / f"step-{i:03d}-{rec.kind}.vtu"
        grid.save(path)
        paths.append(path)
    return paths
