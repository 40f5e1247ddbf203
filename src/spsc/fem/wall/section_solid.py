"""Residual and consistent tangent of a wall section: nearly incompressible hyperelastic
solid, mixed u–p with the pressure condensed element by element.

Kinematics (total Lagrangian, reference coordinates R, Z): with u = (u_R, u_Z),

    F = [[1 + u_R,R,  u_R,Z,  0], [u_Z,R, 1 + u_Z,Z, 0], [0, 0, F_θθ]],
    F_θθ = 1 + u_R/R (the hoop stretch of the axisymmetric dome).

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

𝔸 = ∂P/∂F at fixed p. The integrals carry the section's measure 2πR: residuals are
forces in N.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..material import NearlyIncompressible
from ..material_kernel import cofactor, determinant
from .section import Section

__all__ = ["MixedSolid", "section_solid", "InvertedSection"]


class InvertedSection(ValueError):
    """A quadrature point with det F ≤ 0: the trial state is not admissible."""


def _hoop_free_operator(s: Section) -> np.ndarray:
    """∂F/∂u of the in-plane components only (no hoop term), shape (ne, nq, 3, 3, 9, 2)."""
    ne, nq = s.dV.shape
    B = np.zeros((ne, nq, 3, 3, 9, 2))
    B[:, :, 0, 0, :, 0] = s.dNdX[..., 0]
    B[:, :, 0, 1, :, 0] = s.dNdX[..., 1]
    B[:, :, 1, 0, :, 1] = s.dNdX[..., 0]
    B[:, :, 1, 1, :, 1] = s.dNdX[..., 1]
    return B


def _pressure_basis(dV, Xq, measure):
    """q = (1, (R − R_c)/h, (Z − Z_c)/h) at the quadrature points, (ne, nq, 3)."""
    w = dV / dV.sum(axis=1, keepdims=True)
    centre = np.einsum("eq,eqi->ei", w, Xq)
    h = np.sqrt(dV.sum(axis=1) / measure(centre[:, 0]))[:, None, None]
    return np.concatenate([np.ones(dV.shape + (1,)), (Xq - centre[:, None, :]) / h], -1)


def _strain_operator(s: Section) -> np.ndarray:
    """B = ∂F/∂u_e, shape (ne, nq, 9, 18): F flattened row-major, element unknowns node-major."""
    ne, nq = s.dV.shape
    B = _hoop_free_operator(s)
    B[:, :, 2, 2, :, 0] = s.N / s.Xq[..., 0][..., None]
    return B.reshape(ne, nq, 9, 18)


@dataclass(frozen=True, eq=False)
class MixedSolid:
    """A 2D (or 2.5D) nearly incompressible solid given by its arrays: the strain operator
    ``B`` (ne, nq, 9, nd) = ∂F/∂u_e, weights × measure ``dV`` (ne, nq) in mm³, the pressure
    basis ``q`` (ne, nq, 3), the element unknowns ``element_dofs`` (ne, nd) among ``n_dofs``.
    F = I + B u_e (total Lagrangian, linear in u)."""

    law: NearlyIncompressible
    B: np.ndarray = field(repr=False)
    dV: np.ndarray = field(repr=False)
    q: np.ndarray = field(repr=False)
    element_dofs: np.ndarray = field(repr=False)
    n_dofs: int
    M: np.ndarray = field(init=False, repr=False)
    Minv: np.ndarray = field(init=False, repr=False)
    rows: np.ndarray = field(init=False, repr=False)
    cols: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        M = np.einsum("eqk,eql,eq->ekl", self.q, self.q, self.dV)
        dofs, nd = self.element_dofs, self.element_dofs.shape[1]
        object.__setattr__(self, "M", M)
        object.__setattr__(self, "Minv", np.linalg.inv(M))
        object.__setattr__(self, "rows", np.repeat(dofs, nd, axis=1).ravel())
        object.__setattr__(self, "cols", np.tile(dofs, (1, nd)).ravel())
        if self.B is not None:  # the constant operands of the tangent, made once per mesh
            ne, nq = self.dV.shape
            # the components of F that u moves (the dome's 5 of 9: no F_Rθ, F_θZ, ...): the
            # products run on those alone, (5/9)² of the tangent's work
            live = np.flatnonzero(np.any(self.B != 0, axis=(0, 1, 3)))
            Bl = np.ascontiguousarray(self.B[:, :, live])
            BdV = Bl * self.dV[..., None, None]
            object.__setattr__(self, "_live", live)
            object.__setattr__(self, "_Bl", Bl)
            # contiguous: a transposed stack would send matmul down its slow loop
            object.__setattr__(self, "_BdVt", np.ascontiguousarray(
                np.swapaxes(BdV.reshape(ne, nq * live.size, -1), 1, 2)))

    @property
    def n_pressure(self) -> int:
        return self.q.shape[-1] * len(self.element_dofs)

    def deformation(self, u) -> np.ndarray:
        """F at the quadrature points, (ne, nq, 3, 3), read-only; the last state's is kept
        (the line search's admissibility check and the evaluation that follows ask for the
        same one: 87 of 194 on the Table 1 stadium curve)."""
        u = np.asarray(u)
        last = self.__dict__.get("_last")
        if last is not None and np.array_equal(last[0], u):
            return last[1]
        F = self._deformation(u)
        F.flags.writeable = False
        object.__setattr__(self, "_last", (u.copy(), F))
        return F

    def _deformation(self, u) -> np.ndarray:
        ue = u[self.element_dofs]  # (ne, nd)
        ne, nq = self.dV.shape
        F = np.zeros((ne, nq, 9))
        F[:, :, self._live] = (self._Bl.reshape(ne, -1, ue.shape[1]) @ ue[:, :, None]).reshape(
            ne, nq, -1)
        F = F.reshape(ne, nq, 3, 3)
        F += np.eye(3)
        return F

    def _forces(self, P) -> np.ndarray:
        """r_e = ∫ Bᵀ P dV, (ne, nd), from P (ne, nq, 3, 3)."""
        ne, nq = P.shape[:2]
        Pl = P.reshape(ne, nq, 9)[:, :, self._live].reshape(ne, -1, 1)
        return (self._BdVt @ Pl)[:, :, 0]

    def zero_pressure(self) -> np.ndarray:
        """Pressure coefficients (ne, 3) of the undeformed state (MPa)."""
        return np.zeros((len(self.element_dofs), self.q.shape[-1]))

    def _fields(self, u, pc):
        F = self.deformation(u)
        J = determinant(F)
        if np.any(J <= 0):
            raise InvertedSection("det F <= 0 in the wall section")
        p = np.einsum("eqk,ek->eq", self.q, pc)
        rp = (np.einsum("eqk,eq,eq->ek", self.q, J - 1.0, self.dV)
              - np.einsum("ekl,el->ek", self.M, pc) / self.law.kappa)
        return F, J, p, rp

    def energy(self, u, pc) -> float:
        """The stored energy Σ ∫ Ψ(F, p) dV (mJ); at pressures settled on u (r_p = 0) it is
        the reduced potential whose gradient is r_u."""
        F, _, p, _ = self._fields(u, pc)
        return float(np.sum(self.law.energy(F, p) * self.dV))

    def pressure_error(self, rp) -> float:
        """max |M⁻¹ r_p|: the element-mean error of J − 1 − p/κ (dimensionless)."""
        return float(np.max(np.abs(np.einsum("ekl,el->ek", self.Minv, rp)), initial=0.0))

    def assemble(self, values) -> np.ndarray:
        """The element arrays ``values`` (ne, nd) summed onto the unknowns, in order (as
        ``np.add.at``, several times faster)."""
        return np.bincount(self.element_dofs.ravel(), weights=np.asarray(values).ravel(),
                           minlength=self.n_dofs)

    def residual(self, u, pc):
        """(r_u, r_p): nodal forces (N), shape (2n,), and the pressure residual (ne, 3)."""
        F, _, p, rp = self._fields(u, pc)
        return self.assemble(self._forces(self.law.stress(F, p))), rp

    def residual_tangent(self, u, pc):
        """(r_u, r_p, K, G): the residuals, the condensed tangent K + κ Gᵀ M⁻¹ G (N/mm, CSR)
        and the element blocks G (ne, k, nd) for :meth:`condensed_rhs` and :meth:`recover`."""
        r, rp, Ke, G = self.element_tangent(u, pc)
        K = sp.csr_matrix((Ke.ravel(), (self.rows, self.cols)), shape=(self.n_dofs,) * 2)
        return r, rp, K, G

    def element_tangent(self, u, pc):
        """(r_u, r_p, K_e, G): as :meth:`residual_tangent` with the condensed tangent as its
        element blocks K_e (ne, nd, nd) on :attr:`element_dofs`."""
        F, J, p, rp = self._fields(u, pc)
        P, A = self.law.stress_tangent(F, p)
        ne, nq = p.shape
        live, nd = self._live, self.B.shape[-1]
        Al = A.reshape(ne, nq, 9, 9)[:, :, live][:, :, :, live]
        # batched matmul over elements: (nd, nq·5) @ (nq·5, nd); einsum is 10x slower here
        Ke = self._BdVt @ (Al @ self._Bl).reshape(ne, -1, nd)
        # G[k, d] = Σ_(q c) q_k (J F⁻ᵀ)_c B_cd dV
        JG = cofactor(F)[1].reshape(ne, nq, 9)[:, :, live]
        Y = (JG[:, :, :, None] * self.q[:, :, None, :]).reshape(ne, -1, self.q.shape[-1])
        G = np.ascontiguousarray(np.swapaxes(self._BdVt @ Y, 1, 2))  # (ne, k, nd)
        Ke += self.law.kappa * (np.ascontiguousarray(np.swapaxes(G, 1, 2)) @ (self.Minv @ G))
        return self.assemble(self._forces(P)), rp, Ke, G

    def condensed_rhs(self, G, rp) -> np.ndarray:
        """κ Gᵀ M⁻¹ r_p as nodal forces (N), to add to r_u in the condensed solve."""
        fe = self.law.kappa * np.einsum("ekd,ek->ed", G, np.einsum("ekl,el->ek", self.Minv, rp))
        return self.assemble(fe)

    def recover(self, G, rp, du) -> np.ndarray:
        """Δp = κ M⁻¹ (r_p + G Δu), shape (ne, 3)."""
        Gdu = np.einsum("ekd,ed->ek", G, np.asarray(du)[self.element_dofs])
        return self.law.kappa * np.einsum("ekl,el->ek", self.Minv, rp + Gdu)


def section_solid(section: Section, law: NearlyIncompressible) -> MixedSolid:
    """The solid of the axisymmetric dome (F_θθ = 1 + u_R/R)."""
    B = _strain_operator(section)
    q = _pressure_basis(section.dV, section.Xq, section.measure)
    return MixedSolid(law, B, section.dV, q, section.element_dofs, section.n_dofs)
