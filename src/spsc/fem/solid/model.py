"""The discrete model (mesh, law, supports, cavity) and its residual and tangent for one load.

A load is a cavity pressure (prescribed, or a :class:`~spsc.core.gaslaw.GasLaw` law of the
cavity volume) plus an optional rigid plate; the residual is

    r(x) = r_int(x) − p g(u),   K = K_int − p H − (dp/dV_full · symmetry) g gᵀ,

with g = ∂V_part/∂u (:mod:`spsc.fem.solid.pressure`). The rank-one gas term is returned separately
(coefficient c ≥ 0 and vector g) so the linear solve can use Sherman–Morrison.

The model is a :class:`~spsc.fem.engine.protocol.Discretisation` of the engine: the Newton
system is the whole mixed u–p system (m = n), its inertia has one negative pivot per pressure
unknown when the displacement problem is stable.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from spsc.materials import Material

from ..engine.result import NewtonFailure
from ..engine.settings import Settings
from ..engine.steps import Load
from ..engine.surface import ContactSurface
from ..material import NearlyIncompressible
from .assembly import (Discretisation, InvertedElement, assemble, deformation_gradient,
                       discretise)
from .contact import contact_area, group_forces
from .insert import InsertTie, RigidInsert
from .mesh import TetMesh
from .pressure import CavitySurface

__all__ = ["FEMModel", "Load", "CLAMPED_QUARTER", "Evaluation"]

#: Supports of the chamber wall, quarter model: clamped base, symmetry planes.
CLAMPED_QUARTER = {"base": (0, 1, 2), "sym_x": (0,), "sym_y": (1,)}


@dataclass(frozen=True, eq=False)
class Evaluation:
    r: np.ndarray
    K: object
    g: np.ndarray  # ∂V_part/∂u, flattened u dofs (mm²)
    c: float  # rank-one gas coefficient −dp/dV × symmetry (MPa/mm³), 0 without gas
    pressure: float  # gauge pressure (MPa)
    volume: float  # full gas volume (mm³): the cavity less a rigid insert


@dataclass(frozen=True, eq=False)
class FEMModel:
    """Mesh + nearly incompressible law + supports, with everything precomputed."""

    mesh: TetMesh
    law: NearlyIncompressible
    disc: Discretisation = field(repr=False)
    cavity: CavitySurface = field(repr=False)
    fixed: np.ndarray = field(repr=False)  # bool over all unknowns
    contact_nodes: np.ndarray = field(repr=False)  # outer-surface nodes the plate may touch
    cavity_slots: np.ndarray = field(repr=False)
    #: per node (mm): how far in front of the node the plate meets it (a rigid insert's
    #: thickness, e.g. an FSR on a pocket floor); zero elsewhere
    gap: np.ndarray = field(repr=False, default=None)
    #: named contact surfaces: name -> their contact nodes (the force through each is reported)
    groups: dict = field(repr=False, default_factory=dict)
    #: a rigid insert in the cavity (:mod:`spsc.fem.solid.insert`), or None
    insert: RigidInsert | None = field(repr=False, default=None)

    @classmethod
    def build(cls, mesh: TetMesh, material: Material, *, bulk_ratio: float = 2000.0,
              supports: dict | None = None, order: int = 2, clamped=None,
              gap=None, groups: dict | None = None,
              insert: RigidInsert | None = None) -> "FEMModel":
        """``supports``: facet tag -> fixed displacement components (default: clamped base and
        the two symmetry planes of the quarter model); ``clamped``: node indices fixed in all
        three components (a part's mount); ``gap`` (per node, mm) and ``groups`` (name -> node
        indices): contact surfaces met by the plate through a rigid insert of that thickness,
        whose forces are reported by name; ``insert``: a rigid insert in the cavity (its nodes
        must be free)."""
        supports = CLAMPED_QUARTER if supports is None else supports
        law = NearlyIncompressible(material, bulk_ratio)
        disc = discretise(mesh.nodes, mesh.tets, order=order)
        fixed = np.zeros(disc.n, bool)
        for tag, comps in supports.items():
            if tag in mesh.facets and len(mesh.facets[tag]):
                nodes = mesh.nodes_on(tag)
                for c in comps:
                    fixed[3 * nodes + c] = True
        if clamped is not None and len(clamped):
            fixed[(3 * np.asarray(clamped)[:, None] + np.arange(3)).ravel()] = True
        cavity = CavitySurface(mesh.facets.get("cavity", np.zeros((0, 6), np.int64)),
                               mesh.symmetry)
        contact = mesh.nodes_on("outer") if "outer" in mesh.facets else np.zeros(0, int)
        contact = contact[~fixed[3 * contact + 2]]
        slots = disc.pattern.slots_of(cavity.dofs)
        gap = np.zeros(len(mesh.nodes)) if gap is None else np.asarray(gap, float)
        groups = {k: np.intersect1d(v, contact) for k, v in (groups or {}).items()}
        if insert is not None:
            held = np.concatenate([insert.seat, insert.top])
            if fixed[3 * held + 2].any():
                raise ValueError(f"insert {insert.name}: a seat or top node is supported")
            below = mesh.nodes[insert.top, 2] < insert.z_top - 1e-6
            if below.any():
                raise ValueError(f"insert {insert.name}: {int(below.sum())} top node(s) start "
                                 f"below its face z = {insert.z_top:.4g} mm (inside it)")
        return cls(mesh, law, disc, cavity, fixed, contact, slots, gap, groups, insert)

    @property
    def symmetry(self) -> int:
        return self.mesh.symmetry

    # -- the engine's Discretisation ----------------------------------------------------
    #: a load fails (its increment is cut) on these; a line-search trial on the second
    recoverable = (NewtonFailure, np.linalg.LinAlgError, ValueError)
    inadmissible = (InvertedElement,)
    viscous = None  # an elastic solid: no history between loads
    floor = None  # the base under the cavity is not modelled in 3D

    @property
    def n(self) -> int:
        return self.disc.n

    @property
    def n_u(self) -> int:
        return self.disc.n_u

    @property
    def force_floor(self) -> float:
        """Smallest force scale of the convergence test (N): 1e-6 × μ0 (× 1 mm²)."""
        return 1e-6 * self.law.mu

    @cached_property
    def surface(self) -> ContactSurface:
        """The outer surface's nodes a body may press: their vertical unknowns, their (x, y)
        unknowns, each unknown's reference coordinate (its node's z on a vertical one, x or y
        on a lateral one: where a curved indenter is met) and the rigid inserts' gaps."""
        dofs = 3 * np.asarray(self.contact_nodes) + 2
        height = np.zeros(self.disc.n)
        height[:self.disc.n_u] = self.disc.X.ravel()
        gap = np.zeros(self.disc.n)
        gap[2:self.disc.n_u:3] = self.gap
        return ContactSurface(dofs, np.stack([dofs - 2, dofs - 1]), height, gap,
                              self.contact_area, self.group_forces)

    @cached_property
    def tie(self) -> InsertTie | None:
        return InsertTie(self.insert, self.disc.X) if self.insert is not None else None

    def default_settings(self) -> Settings:
        return Settings()

    def system_residual(self, ev: "Evaluation") -> np.ndarray:
        return ev.r

    def reuse(self, ev: "Evaluation", tangent_ev: "Evaluation") -> "Evaluation":
        """ev's residual with ``tangent_ev``'s tangent (a modified Newton step)."""
        return replace(ev, K=tangent_ev.K)

    def expand(self, ev: "Evaluation", dx) -> np.ndarray:
        return dx

    def pressure_error(self, ev: "Evaluation") -> float:
        """0: the pressure equations are in the Newton system (solved with the displacements;
        the convergence test reads the displacements' residual)."""
        return 0.0

    def admissible(self, x) -> bool:
        """No element inverted at x (det F > 0 at every quadrature point)."""
        J = np.linalg.det(deformation_gradient(self.disc, self.displacement(x)))
        return bool(np.all(J > 0))

    def unstable_modes(self, factor, c: float, gc) -> int | None:
        """Negative eigenvalues of the displacement problem: the LDLᵀ inertia minus the
        pressure unknowns (the mixed form's pressure block is negative definite). With a
        closed gas volume the factorised matrix lacks the positive rank-one gas term, which can
        remove one: one is taken off (at least zero)."""
        if factor.negative is None:
            return None
        return max(factor.negative - self.disc.n_p - (1 if c > 0.0 else 0), 0)

    def contact_area(self, x, plate: float, indenter=None) -> float:
        return contact_area(self, x, plate, indenter=indenter)

    def group_forces(self, r, active) -> dict:
        """Force (N, full part) through each named contact surface (``active``: contact
        unknowns)."""
        return group_forces(self, r, (np.asarray(active) - 2) // 3)

    def zero_state(self) -> np.ndarray:
        return np.zeros(self.disc.n)

    def displacement(self, x) -> np.ndarray:
        return x[: self.disc.n_u].reshape(-1, 3)

    @property
    def displaced(self) -> float:
        """Volume (mm³) the insert takes from the cavity's gas (0 without one)."""
        return self.insert.volume if self.insert is not None else 0.0

    def commit(self, x, load) -> None:
        """Nothing to close: the solid's law has no history."""

    def volume(self, x) -> float:
        """Full gas volume (mm³) in state x: the cavity less the insert."""
        return self.cavity.volume(self.disc.X, self.displacement(x)) - self.displaced

    def evaluate(self, x, load: Load, *, tangent: bool = True) -> Evaluation:
        d = self.disc
        u = self.displacement(x)
        volume = self.cavity.volume(d.X, u) - self.displaced
        p, dpdv = load.cavity_pressure(volume)
        c = -dpdv * self.symmetry if dpdv else 0.0
        if tangent:
            gn, H = self.cavity.gradient(d.X, u)
            extra = [(-p * H, self.cavity_slots)] if p != 0.0 else []
            r, K = assemble(d, self.law, x, extra=extra)
        else:
            gn = self.cavity.gradient(d.X, u, tangent=False)
            r, K = assemble(d, self.law, x, tangent=False), None
        g = gn.ravel()
        r[: d.n_u] -= p * g
        return Evaluation(r, K, g, c, p, volume)
