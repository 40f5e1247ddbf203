"""Residual and consistent tangent of a wall section: nearly incompressible hyperelastic
solid, mixed u–p with the pressure condensed element by element.

Kinematics (total Lagrangian, reference coordinates R, Z): with u = (u_R, u_Z),

    F = [[1 + u_R,R,  u_R,Z,  0], [u_Z,R, 1 + u_Z,Z, 0], [0, 0, F_θθ]],
    F_θθ = 1 + u_R/R (axisymmetric dome: the hoop stretch), F_θθ = 1 (plane-strain middle).

The energy is that of :class:`~spsc.fem.material.NearlyIncompressible`, the package's one law
W(Ī1, Ī2) plus p(J − 1) − p²/(2κ), with p discontinuous and linear in each element
(q = 1, R, Z: the Q2/P1ᵈ element, inf–sup stable, so a 1 mm wall does not lock at κ/μ = 2000).
The residuals are

    r_u = ∫ P(F, p) : B dV,    r_p = ∫ q (J − 1 − p/κ) dV = b(u) − M p/κ,   M = ∫ q qᵀ dV,

with B = ∂F/∂u (constant in the total Lagrangian form). p stays an unknown of the Newton
iteration (slaving it to J would turn the linear step's O(ε²) volume error into κ-sized stress),
but is condensed out of each linear solve, element by element:

    (K + κ Gᵀ M⁻¹ G) Δu = −(r_u + κ Gᵀ M⁻¹ r_p),   Δp = κ M⁻¹ (r_p + G Δu),
    K = ∫ Bᵀ 𝔸(F, p) B dV,   G = ∫ q J (F⁻ᵀ : B) dV,

𝔸 = ∂P/∂F at fixed p. The integrals carry the section's measure (2πR or 2l): residuals are
forces in N.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from .material import NearlyIncompressible
from .section import DOME, Section

__all__ = ["SectionSolid", "InvertedSection"]


class InvertedSection(ValueError):
    """A quadrature point with det F ≤ 0: the trial state is not admissible."""


def _strain_operator(s: Section) -> np.ndarray:
    """B = ∂F/∂u_e, shape (ne, nq, 9, 18): F flattened row-major, element unknowns node-major."""
    ne, nq = s.dV.shape
    B = np.zeros((ne, nq, 3, 3, 9, 2))
    B[:, :, 0, 0, :, 0] = s.dNdX[..., 0]
    B[:, :, 0, 1, :, 0] = s.dNdX[..., 1]
    B[:, :, 1, 0, :, 1] = s.dNdX[..., 0]
    B[:, :, 1, 1, :, 1] = s.dNdX[..., 1]
    if s.kind == DOME:
        B[:, :, 2, 2, :, 0] = s.N / s.Xq[..., 0][..., None]
    return B.reshape(ne, nq, 9, 18)


@dataclass(frozen=True, eq=False)
class SectionSolid:
    """A :class:`Section` with a nearly incompressible law: residual and tangent of u."""

    section: Section
    law: NearlyIncompressible
    B: np.ndarray = field(init=False, repr=False)
    q: np.ndarray = field(init=False, repr=False)
    M: np.ndarray = field(init=False, repr=False)
    Minv: np.ndarray = field(init=False, repr=False)
    rows: np.ndarray = field(init=False, repr=False)
    cols: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        s = self.section
        w = s.dV / s.dV.sum(axis=1, keepdims=True)
        centre = np.einsum("eq,eqi->ei", w, s.Xq)
        h = np.sqrt(s.dV.sum(axis=1) / s.measure(centre[:, 0]))[:, None, None]
        q = np.concatenate([np.ones(s.dV.shape + (1,)), (s.Xq - centre[:, None, :]) / h], -1)
        M = np.einsum("eqk,eql,eq->ekl", q, q, s.dV)
        dofs = s.element_dofs
        object.__setattr__(self, "B", _strain_operator(s))
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "M", M)
        object.__setattr__(self, "Minv", np.linalg.inv(M))
        object.__setattr__(self, "rows", np.repeat(dofs, 18, axis=1).ravel())
        object.__setattr__(self, "cols", np.tile(dofs, (1, 18)).ravel())

    def deformation(self, u) -> np.ndarray:
        """F at the quadrature points, (ne, nq, 3, 3)."""
        ue = np.asarray(u)[self.section.element_dofs]  # (ne, 18)
        F = np.einsum("eqcd,ed->eqc", self.B, ue).reshape(ue.shape[0], -1, 3, 3)
        F += np.eye(3)
        return F

    def zero_pressure(self) -> np.ndarray:
        """Pressure coefficients (ne, 3) of the undeformed state (MPa)."""
        return np.zeros((len(self.section.elements), 3))

    def _fields(self, u, pc):
        F = self.deformation(u)
        J = np.linalg.det(F)
        if np.any(J <= 0):
            raise InvertedSection("det F <= 0 in the wall section")
        p = np.einsum("eqk,ek->eq", self.q, pc)
        rp = (np.einsum("eqk,eq,eq->ek", self.q, J - 1.0, self.section.dV)
              - np.einsum("ekl,el->ek", self.M, pc) / self.law.kappa)
        return F, J, p, rp

    def pressure_error(self, rp) -> float:
        """max |M⁻¹ r_p|: the element-mean error of J − 1 − p/κ (dimensionless)."""
        return float(np.max(np.abs(np.einsum("ekl,el->ek", self.Minv, rp)), initial=0.0))

    def residual(self, u, pc):
        """(r_u, r_p): nodal forces (N), shape (2n,), and the pressure residual (ne, 3)."""
        F, _, p, rp = self._fields(u, pc)
        P = self.law.stress(F, p).reshape(F.shape[0], F.shape[1], 9)
        re = np.einsum("eqc,eqcd,eq->ed", P, self.B, self.section.dV)
        r = np.zeros(self.section.n_dofs)
        np.add.at(r, self.section.element_dofs, re)
        return r, rp

    def residual_tangent(self, u, pc):
        """(r_u, r_p, K, G): the residuals, the condensed tangent K + κ Gᵀ M⁻¹ G (N/mm, CSR)
        and the element blocks G (ne, 3, 18) for :meth:`condensed_rhs` and :meth:`recover`."""
        s = self.section
        F, J, p, rp = self._fields(u, pc)
        P, A = self.law.stress_tangent(F, p)
        ne, nq = p.shape
        P = P.reshape(ne, nq, 9)
        A = A.reshape(ne, nq, 9, 9)
        # batched matmul over elements: (18, nq·9) @ (nq·9, 18); einsum is 10x slower here
        BdV = self.B * s.dV[..., None, None]
        re = np.einsum("eqc,eqcd->ed", P, BdV)
        AB = (A @ self.B).reshape(ne, nq * 9, 18)
        Ke = np.swapaxes(BdV.reshape(ne, nq * 9, 18), 1, 2) @ AB
        JG = J[..., None] * np.swapaxes(np.linalg.inv(F), -1, -2).reshape(ne, nq, 9)
        JGB = (JG[:, :, None, :] @ BdV)[:, :, 0, :]  # (ne, nq, 18)
        G = np.swapaxes(self.q, 1, 2) @ JGB  # (ne, 3, 18)
        Ke += self.law.kappa * (np.swapaxes(G, 1, 2) @ (self.Minv @ G))
        r = np.zeros(s.n_dofs)
        np.add.at(r, s.element_dofs, re)
        K = sp.csr_matrix((Ke.ravel(), (self.rows, self.cols)), shape=(s.n_dofs,) * 2)
        return r, rp, K, G

    def condensed_rhs(self, G, rp) -> np.ndarray:
        """κ Gᵀ M⁻¹ r_p as nodal forces (N), to add to r_u in the condensed solve."""
        fe = self.law.kappa * np.einsum("ekd,ek->ed", G, np.einsum("ekl,el->ek", self.Minv, rp))
        f = np.zeros(self.section.n_dofs)
        np.add.at(f, self.section.element_dofs, fe)
        return f

    def recover(self, G, rp, du) -> np.ndarray:
        """Δp = κ M⁻¹ (r_p + G Δu), shape (ne, 3)."""
        Gdu = np.einsum("ekd,ed->ek", G, np.asarray(du)[self.section.element_dofs])
        return self.law.kappa * np.einsum("ekl,el->ek", self.Minv, rp + Gdu)
