"""The mixed u–p solid of the swept wall with Cartesian displacements: its deformation
gradient, residual and condensed element tangent from the shape gradients alone
(:class:`CartesianSolid`, used by :class:`~spsc.fem.wall.swept.SweptWall`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..material_kernel import cofactor
from .section_solid import MixedSolid

__all__ = ["CartesianSolid"]

#: hexahedra per batch of the tangent's products (measured: 8 keeps them in cache, 5.1 ms
#: against 8.1 ms all at once on the Table 1 stadium's 126)
_CHUNK = 8


@dataclass(frozen=True, eq=False)
class CartesianSolid(MixedSolid):
    """A :class:`~spsc.fem.wall.section_solid.MixedSolid` whose displacement is Cartesian,
    F = I + Σ_b u_b ⊗ ∇N_b, given by the shape gradients ``grad`` (ne, nq, nb, 3) instead of
    the full ∂F/∂u (9× smaller, and its tangent 3× cheaper):

        r_bi = ∫ P_ij ∂_j N_b dV,   K_bi,ck = ∫ ∂_j N_b 𝔸_ijkl ∂_l N_c dV.
    """

    grad: np.ndarray = field(default=None, repr=False)

    def __post_init__(self):
        super().__post_init__()
        ne, nq, nb, _ = self.grad.shape
        GdV = self.grad * self.dV[..., None, None]
        # constant operands in the layouts the products need (contiguous: no copy per call)
        object.__setattr__(self, "_Gt", np.ascontiguousarray(  # [e, b, (q j)]
            np.transpose(GdV, (0, 2, 1, 3))).reshape(ne, nb, nq * 3))
        object.__setattr__(self, "_Gl", np.ascontiguousarray(  # [e, q, l, c]
            np.swapaxes(self.grad, 2, 3)))

    def _deformation(self, u) -> np.ndarray:
        ue = u[self.element_dofs].reshape(len(self.element_dofs), 1, -1, 3)
        return np.eye(3) + np.swapaxes(self._Gl @ ue, -1, -2)

    def _forces(self, P) -> np.ndarray:
        """r_e[b, i] = ∫ P_ij ∂_j N_b dV, (ne, 3 nb)."""
        ne, nq = P.shape[:2]
        Pt = np.ascontiguousarray(np.swapaxes(P, -1, -2)).reshape(ne, nq * 3, 3)  # [(q j), i]
        return (self._Gt @ Pt).reshape(ne, -1)

    def residual(self, u, pc):
        F, _, p, rp = self._fields(u, pc)
        return self.assemble(self._forces(self.law.stress(F, p))), rp

    def element_tangent(self, u, pc):
        F, J, p, rp = self._fields(u, pc)
        P, A = self.law.stress_tangent(F, p)  # A[i, j, k, l]
        ne, nq, nb, _ = self.grad.shape
        # U[e, q, j, (i k c)] = Σ_l A_ijkl ∂_l N_c, then K[b, (i k c)] = Σ_(q j) ∂_j N_b dV U,
        # a few elements at a time: U of all of them at once is 60 MB, fresh pages every call
        Aj = np.ascontiguousarray(np.transpose(A, (0, 1, 3, 2, 4, 5))).reshape(ne, nq, 27, 3)
        Ke = np.empty((ne, nb, 3, nb, 3))
        for e in range(0, ne, _CHUNK):
            at = slice(e, e + _CHUNK)
            U = (Aj[at] @ self._Gl[at]).reshape(-1, nq * 3, 9 * nb)
            Ke[at] = np.transpose((self._Gt[at] @ U).reshape(-1, nb, 3, 3, nb), (0, 1, 2, 4, 3))
        Ke = Ke.reshape(ne, 3 * nb, 3 * nb)
        # G[k, (b i)] = ∫ q_k J F⁻ᵀ_ij ∂_j N_b dV
        nk = self.q.shape[-1]
        JFinv = np.swapaxes(cofactor(F)[1], -1, -2)  # J F⁻¹
        Y = self.q[:, :, None, :, None] * JFinv[:, :, :, None, :]
        G = (self._Gt @ Y.reshape(ne, nq * 3, nk * 3)).reshape(ne, nb, nk, 3)
        G = np.ascontiguousarray(np.transpose(G, (0, 2, 1, 3))).reshape(ne, nk, 3 * nb)
        Ke += self.law.kappa * (np.ascontiguousarray(np.swapaxes(G, 1, 2)) @ (self.Minv @ G))
        return self.assemble(self._forces(P)), rp, Ke, G
