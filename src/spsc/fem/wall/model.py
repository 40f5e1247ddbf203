"""The wall model's discretisation: its settings and its parts — the axisymmetric dome
(l = 0) or the stadium's swept wall (l > 0, :mod:`spsc.fem.wall.swept`) — with the cavity volume,
follower pressure and contact surface, as a :class:`~spsc.fem.engine.protocol.Discretisation`
of the engine (:mod:`spsc.fem.wall` walks the load path with it).

The Newton system is on the displacements (m = n_u): each element's pressure coefficients are
condensed out of the element tangent (:mod:`spsc.fem.wall.section_solid`) and recovered from the
displacement step, so the factorised tangent is the displacement problem's own and its inertia
counts the unstable modes directly.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from spsc.cad.geometry import SPSCGeometry
from spsc.core.errors import ParameterError, require
from spsc.materials import Material

from ..engine.linsolve import available_solvers
from ..engine.settings import SEMISMOOTH_CONTACT, Settings
from ..engine.steps import Load
from ..engine.surface import ContactSurface
from ..material import NearlyIncompressible
from ..material_kernel import determinant
from ..mullins import MullinsLaw
from ..viscous import ViscousLaw
from .pattern import Pattern
from .section import section_mesh
from .section_solid import InvertedSection, section_solid
from .swept import SweptWall, sweep_stations

__all__ = ["WallSettings", "WallModel"]

#: PARDISO (symbolic analysis once per curve: 5× faster per factorisation than SuperLU here,
#: the same curves to 1e-14), Cholesky first while the wall is stable and LDLᵀ with the
#: inertia where it is not (``pardiso-spd``), SuperLU's symmetric mode where pypardiso is absent. Probed at
#: import on purpose: MKL first loaded inside wall_curve's one-BLAS-thread limit
#: (threadpoolctl) made PARDISO's factorisation segfault on the next curve (stop 33).
_SOLVER = "pardiso-spd" if "pardiso" in available_solvers() else "superlu-sym"

#: default element length along the profile (mm): the dome's 2D section is cheap, the
#: stadium's swept hexahedra are not (both within 0.5 % of their converged answer, docs/theory/wall.md)
DOME_MESH_MM, STADIUM_MESH_MM = 0.5, 1.0


@dataclass(frozen=True)
class WallSettings:
    """Discretisation and solver controls of the wall model.

    mesh_size_mm : element length along the profile (mm; None: 0.5 on a dome, 1.0 on a
    stadium); layers : quadratic elements through the wall; sweep_size_mm : quadratic
    element length along the stadium's sweep (mm; the middle's half-length and the half-dome's
    outer quarter arc, at least two elements on the arc); bulk_ratio : κ/μ0; rtol : residual
    against the load's force scale; max_iterations : Newton iterations per increment;
    min_fraction : smallest increment as a fraction of the nominal one; contact_tolerance :
    penetration that activates a node (mm); inflate_increments : pressure increments of the
    inflation; modified_newton : residual fraction below which a load's tail reuses the last
    factorisation (:class:`~spsc.fem.engine.settings.Settings`; 0: full Newton throughout);
    apex_size_mm : element length at the dome's apex, graded up to ``mesh_size_mm`` (mm;
    None: even; a sharp probe on the axis, :mod:`spsc.fem.wall.puncture`).
    """

    mesh_size_mm: float | None = None
    layers: int = 2
    sweep_size_mm: float = 10.0
    bulk_ratio: float = 2000.0
    rtol: float = 1e-9
    max_iterations: int = 25
    min_fraction: float = 1.0 / 64
    contact_tolerance: float = 1e-7
    inflate_increments: int = 2
    modified_newton: float = 1e-3
    apex_size_mm: float | None = None

    def __post_init__(self):
        if self.mesh_size_mm is not None:
            require("mesh_size", self.mesh_size_mm, gt=0, le=5, unit="mm")
        require("layers", self.layers, ge=1, le=16)
        require("sweep_size", self.sweep_size_mm, gt=0, le=50, unit="mm")
        require("bulk_ratio", self.bulk_ratio, ge=10)
        require("rtol", self.rtol, gt=0, lt=1)
        require("max_iterations", self.max_iterations, ge=2)
        require("min_fraction", self.min_fraction, gt=0, le=1)
        require("inflate_increments", self.inflate_increments, ge=1)
        require("modified_newton", self.modified_newton, ge=0, lt=1)
        if self.apex_size_mm is not None:
            require("apex_size", self.apex_size_mm, gt=0, le=5, unit="mm")

    def newton_settings(self) -> Settings:
        """The engine's settings for the wall: these tolerances with the wall's own choices —
        PARDISO's LDLᵀ on the condensed tangent with its analysis reused across the whole
        curve (SuperLU in symmetric mode where pypardiso is absent; both give the inertia:
        :mod:`spsc.fem.engine.linsolve`), the admissible line
        search, the semi-smooth active set (updated from the step's multipliers; 1e-2 of the
        scale before the first; 40 changes), the running force scale, a fresh inertia at
        convergence, the secant predictor, gᵀs over the constrained unknowns, snap-throughs
        followed to the stable branch (:mod:`spsc.fem.engine.snap`) and modified Newton in
        each load's tail."""
        return Settings(rtol=self.rtol, max_iterations=self.max_iterations,
                        min_fraction=self.min_fraction, contact_tolerance=self.contact_tolerance,
                        solver=_SOLVER, search="admissible", scale="running",
                        fresh_inertia=True, gas_shift="constrained", snap_through=True,
                        modified_newton=self.modified_newton, **SEMISMOOTH_CONTACT)

    def profile_size(self, stadium: bool) -> float:
        """The element length along the profile (mm) for a dome or a stadium."""
        if self.mesh_size_mm is not None:
            return self.mesh_size_mm
        return STADIUM_MESH_MM if stadium else DOME_MESH_MM


class _Dome:
    """The axisymmetric dome of an l = 0 chamber: the body of revolution of the section."""

    def __init__(self, section, law):
        self.section, self.solid = section, section_solid(section, law)
        self.dofs = np.arange(section.n_dofs)
        self.fixed = section.fixed
        self.reference = section.nodes.ravel()
        self.zdofs = 2 * section.outer + 1

    def volume(self, u) -> float:
        return self.section.volume(u)

    def volume_gradient(self, u, hessian=True):
        if not hessian:
            return self.section.volume_gradient(u, hessian=False)
        g, H = self.section.volume_gradient(u)
        return g, H, self.section.cavity_edge_dofs

    def contact_area(self, u, plate, indenter=None) -> float:
        return self.section.contact_area(u, plate, indenter=indenter)

    def apex(self, u) -> float:
        return float(self.section.positions(u)[self.section.cavity[0], 1])


class WallModel:
    """The wall of one chamber and its loads. l = 0: the axisymmetric dome. l > 0 (or
    ``stadium=True``): the swept wall of the quarter (:class:`~spsc.fem.wall.swept.SweptWall`).
    ``base``: ``"clamped"`` (the chamber) or ``"sliding"`` (u_z = 0 only, for the exact
    thick-sphere check).

    Unknowns x: the displacements (n_u) then the solid's pressure coefficients."""

    symmetry = 1  # forces and areas are the whole chamber's
    tie = None
    #: a load fails (its increment is cut) on these; a line-search trial on the second
    recoverable = (RuntimeError, np.linalg.LinAlgError, InvertedSection)
    inadmissible = (InvertedSection,)

    def __init__(self, geometry: SPSCGeometry, material: Material,
                 settings: WallSettings | None = None, *, base: str = "clamped",
                 stadium: bool | None = None, prony=None, mullins=None, floor: bool = False):
        self.geometry, self.material = geometry, material
        self.settings = settings = settings or WallSettings()
        law = NearlyIncompressible(material, settings.bulk_ratio)
        #: the first-loading softening (:mod:`spsc.fem.mullins`) with ``mullins`` constants
        self.mullins = None if mullins is None else MullinsLaw(law, mullins)
        law = self.mullins or law
        #: the rate-dependent law (:mod:`spsc.fem.viscous`) with ``prony`` terms, else None
        self.viscous = None if prony is None else ViscousLaw(law, prony)
        law = self.viscous or law
        self.stadium = stadium = geometry.l > 0 if stadium is None else bool(stadium)
        self.mesh_size_mm = settings.profile_size(stadium)
        section = section_mesh(geometry, size=self.mesh_size_mm, layers=settings.layers,
                               base=base, apex=settings.apex_size_mm)
        if stadium:
            self.part = SweptWall(section, sweep_stations(geometry, settings.sweep_size_mm),
                                  law, base=base)
        else:
            self.part = _Dome(section, law)
        self.solid = self.part.solid
        self.n_u = len(self.part.dofs)
        self.n = self.n_u + self.solid.n_pressure
        self.fixed = np.asarray(self.part.fixed, bool).copy()
        self.reference = np.asarray(self.part.reference, float)
        zdofs = np.unique(self.part.zdofs)
        dofs = zdofs[~self.fixed[zdofs]]
        #: each contact unknown's lateral ones: the radial displacement on the dome's section
        #: (2 unknowns a node), x and y on the swept wall (3 a node)
        per_node = 3 if stadium else 2
        self.surface = ContactSurface(
            dofs, np.stack([dofs - per_node + 1 + k for k in range(per_node - 1)]),
            self.reference, np.zeros(self.n_u), self.contact_area)
        #: the cavity wall that may come down onto the base z = 0 (``floor``: the dome's
        #: cavity nodes, :class:`~spsc.fem.engine.bodies.Floor`), else None
        self.floor = self._floor(per_node) if floor else None
        self.mu = law.mu
        #: smallest force scale of the convergence test (N): 1e-9 μ0 t0²
        self.force_floor = 1e-9 * self.mu * self.geometry.t0 ** 2
        _, _, cavity = self.part.volume_gradient(np.zeros(self.n_u))
        self._pattern = Pattern(self.n_u, self.solid.element_dofs, cavity,
                                per_node=per_node)

    def _floor(self, per_node: int) -> ContactSurface:
        """The cavity boundary's vertical unknowns over the base (the dome's section)."""
        if self.stadium:
            raise ParameterError("floor", "on a stadium", "the dome's (l = 0) only: the swept "
                                 "wall's base contact is not built")
        z = per_node * np.asarray(self.part.section.cavity) + 1
        dofs = np.unique(z[~self.fixed[z]])
        return ContactSurface(dofs, (dofs - 1)[None, :], self.reference, np.zeros(self.n_u))

    @property
    def kind(self) -> str:
        return "swept" if self.stadium else "dome"

    def displacements(self, x) -> np.ndarray:
        return x[:self.n_u]

    def pressures(self, x) -> np.ndarray:
        """Hydrostatic pressure coefficients (ne, k) of the solid (MPa)."""
        return x[self.n_u:].reshape(len(self.solid.element_dofs), -1)

    def zero_state(self) -> np.ndarray:
        return np.zeros(self.n)

    def admissible(self, x) -> bool:
        """No element inverted at ``x`` (det F > 0 at every quadrature point)."""
        return bool(np.all(determinant(self.solid.deformation(self.displacements(x))) > 0))

    def volume(self, x) -> float:
        """Cavity volume (mm³)."""
        return self.part.volume(self.displacements(x))

    def contact_area(self, x, plate: float, indenter=None) -> float:
        """Outer surface on the plate, or on the curved ``indenter`` whose tip is at
        ``plate`` (mm²)."""
        return self.part.contact_area(self.displacements(x), plate, indenter=indenter)

    def apex(self, x) -> float:
        """Height of the cavity apex (mm)."""
        return self.part.apex(self.displacements(x))

    def top(self, x) -> float:
        """Highest point of the outer surface (mm): where the plate first touches."""
        dofs = self.surface.dofs
        return float(np.max(self.reference[dofs] + x[dofs]))

    def evaluate(self, x, load, *, tangent: bool = True) -> "_Evaluation":
        """Residuals under ``load`` (a :class:`~spsc.fem.engine.steps.Load`, or a gauge
        pressure in MPa): r_u = r_int − p g (N) with p the prescribed pressure or the gas's at
        the cavity volume, the pressure residuals, and with ``tangent`` the condensed
        K_int − p H (N/mm) and the blocks G; g = ∂V/∂u (mm²), c = −dp/dV (MPa/mm³)."""
        if not isinstance(load, Load):
            load = Load(pressure=load)
        if self.viscous is not None:
            self.viscous.set_time(load.time)
        volume = self.volume(x)
        pressure, dpdv = load.cavity_pressure(volume)
        c = -dpdv if dpdv else 0.0
        u, pc = self.displacements(x), self.pressures(x)
        K = G = None
        if tangent:
            r, rp, Ke, G = self.solid.element_tangent(u, pc)
            g, H, _ = self.part.volume_gradient(u)
            K = self._pattern.matrix(Ke, -pressure * H if pressure != 0.0 else None)
        else:
            r, rp = self.solid.residual(u, pc)
            g = self.part.volume_gradient(u, hessian=False)
        return _Evaluation(r - pressure * g, rp, K, G, g, c, pressure, volume)

    def commit(self, x, load) -> None:
        """Close a converged step of a wall with a history (its internal variables)."""
        if self.viscous is None and self.mullins is None:
            return
        F = self.solid.deformation(self.displacements(x))
        if self.viscous is not None:
            self.viscous.set_time(load.time)
            self.viscous.commit(F)
        if self.mullins is not None:
            self.mullins.commit(F)

    def reuse(self, ev: "_Evaluation", tangent_ev: "_Evaluation") -> "_Evaluation":
        """ev's residuals with ``tangent_ev``'s tangent and coupling blocks: the condensed
        right-hand side and the pressure recovery of a modified Newton step."""
        return dataclasses.replace(ev, K=tangent_ev.K, G=tangent_ev.G)

    def potential(self, x, load) -> float:
        """The total potential Π (mJ) at x under ``load`` up to a constant: the wall's stored
        energy less the gas's work on it (p V at a prescribed pressure, ∫ p dV from the
        valve's closing for the closed gas); ∂Π/∂u is the residual r_u where the element
        pressures are settled. The plate is a constraint: it adds nothing."""
        volume = self.volume(x)
        stored = self.solid.energy(self.displacements(x), self.pressures(x))
        if load.gas is None:
            return stored - float(load.pressure) * volume
        return stored - load.gas.work(load.gas.v_closed, volume)

    def pressure_error(self, ev: "_Evaluation") -> float:
        return self.solid.pressure_error(ev.rp)

    def condensed(self, ev: "_Evaluation") -> np.ndarray:
        """r_u + κ Gᵀ M⁻¹ r_p: the right-hand side of the condensed Newton system (N)."""
        return ev.r + self.solid.condensed_rhs(ev.G, ev.rp)

    def recover(self, ev: "_Evaluation", du) -> np.ndarray:
        """Δp of the solid (flattened, MPa) from the displacement step ``du``."""
        return self.solid.recover(ev.G, ev.rp, du).ravel()

    # -- the rest of the engine's Discretisation ------------------------------------------
    def default_settings(self) -> Settings:
        return self.settings.newton_settings()

    def system_residual(self, ev: "_Evaluation") -> np.ndarray:
        return self.condensed(ev)

    def expand(self, ev: "_Evaluation", du) -> np.ndarray:
        """The step of all unknowns: ``du`` and the pressures' Δp recovered from it."""
        return np.concatenate([du, self.recover(ev, du)])

    def unstable_modes(self, factor, c: float, gc) -> int | None:
        """Negative eigenvalues of K + c g gᵀ on the free displacements from the inertia of
        the factorised K: the gas term removes one iff 1 + c gᵀK⁻¹g < 0."""
        negative = factor.negative
        if negative is not None and c > 0.0:
            negative -= int(1.0 + c * float(gc @ factor(gc)) < 0.0)
        return negative


@dataclass(frozen=True, eq=False)
class _Evaluation:
    r: np.ndarray  # displacement residual (N)
    rp: list  # the elements' pressure residuals
    K: object  # condensed tangent (N/mm)
    G: list  # the elements' coupling blocks
    g: np.ndarray  # ∂V/∂u (mm²)
    c: float = 0.0  # the gas's −dp/dV (MPa/mm³), 0 without gas
    pressure: float = 0.0  # gauge pressure (MPa)
    volume: float = float("nan")  # cavity volume (mm³)

