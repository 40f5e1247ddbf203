"""Follower pressure on the deformed cavity surface and the enclosed cavity volume.

On a 6-node cavity facet with current position x(ξ, η), the solid's outward normal times the
area element is x,ξ × x,η dξ dη (facets are ordered outward from the solid, i.e. into the
cavity). A gauge pressure p pushes the wall away from the cavity, so the external nodal force is
f = p g with

    g_a = −∫ N_a (x,ξ × x,η) dξ dη = ∂V/∂x_a,

the derivative of the enclosed volume V with respect to the node a; its derivative
H = ∂g/∂x (from Δ(x,ξ × x,η) = Δx,ξ × x,η + x,ξ × Δx,η) gives the load stiffness p H, the
consistent tangent of the follower load.

The volume of the part's cavity is V = ∫ z n_z da over the cavity facets (n out of the cavity):
the closing planes contribute nothing, the base z = 0 because z = 0 and the symmetry planes
x = 0, y = 0 because n_z = 0 there, and they stay planes since nodes on them move in-plane.
The full cavity is ``symmetry`` × V.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .element import tri_p2, tri_rule

__all__ = ["CavitySurface"]

_EPS = np.zeros((3, 3, 3))
_EPS[0, 1, 2] = _EPS[1, 2, 0] = _EPS[2, 0, 1] = 1.0
_EPS[0, 2, 1] = _EPS[2, 1, 0] = _EPS[1, 0, 2] = -1.0


@dataclass(frozen=True, eq=False)
class CavitySurface:
    """The cavity facets (nf, 6) of a mesh and their quadrature; ``symmetry`` copies of the part
    make the full cavity."""

    facets: np.ndarray
    symmetry: int = 1
    order: int = 4

    def _tangents(self, X, u):
        xq, w = tri_rule(self.order)
        N, dN = tri_p2(xq)
        x = (X + u)[self.facets]  # (nf, 6, 3)
        xs = np.einsum("fai,qa->fqi", x, dN[:, :, 0])
        xt = np.einsum("fai,qa->fqi", x, dN[:, :, 1])
        return x, N, dN, w, xs, xt

    @property
    def dofs(self) -> np.ndarray:
        """(nf, 18) displacement unknowns of the facets, node-major."""
        return (3 * self.facets[:, :, None] + np.arange(3)).reshape(len(self.facets), 18)

    def volume(self, X, u) -> float:
        """Enclosed volume of the full cavity (mm³) for nodes X and displacements u (N, 3)."""
        x, N, _, w, xs, xt = self._tangents(X, u)
        z = np.einsum("fai,qa->fqi", x, N)[..., 2]
        nz = xs[..., 0] * xt[..., 1] - xs[..., 1] * xt[..., 0]
        return -self.symmetry * float(np.einsum("fq,fq,q->", z, nz, w))

    def area(self, X, u) -> float:
        """Deformed area of the part's cavity facets (mm²)."""
        _, _, _, w, xs, xt = self._tangents(X, u)
        return float(np.einsum("fq,q->", np.linalg.norm(np.cross(xs, xt), axis=-1), w))

    def gradient(self, X, u, *, tangent: bool = True):
        """g = ∂V_part/∂u as a nodal array (N, 3) (mm²) and, if ``tangent``, the facet blocks of
        H = ∂g/∂u, shape (nf, 18, 18) (mm), to be scattered on :attr:`dofs`."""
        _, N, dN, w, xs, xt = self._tangents(X, u)
        n = np.cross(xs, xt)
        ge = -np.einsum("qa,fqi,q->fai", N, n, w)
        g = np.zeros_like(X)
        np.add.at(g, self.facets, ge)
        if not tangent:
            return g
        # ∂(x,ξ × x,η)_i/∂x_bm = ε_imk N_b,ξ x,η_k + ε_ijm x,ξ_j N_b,η, so
        # H_aibm = −Σ_q w N_a (N_b,ξ T_im + N_b,η S_im) with T = ε·x,η and S = x,ξ·ε: two
        # matrix products over the quadrature points (the 5-index einsum was 3 ms a call)
        T = np.einsum("imk,fqk->fqim", _EPS, xt).reshape(*xt.shape[:2], 9)
        S = np.einsum("ijm,fqj->fqim", _EPS, xs).reshape(*xs.shape[:2], 9)
        nq = len(w)
        Cs = (w[:, None, None] * N[:, :, None] * dN[:, None, :, 0]).reshape(nq, 36)
        Ct = (w[:, None, None] * N[:, :, None] * dN[:, None, :, 1]).reshape(nq, 36)
        H = -(Cs.T @ T + Ct.T @ S)  # (nf, (a b), (i m))
        H = H.reshape(len(self.facets), 6, 6, 3, 3).transpose(0, 1, 3, 2, 4)
        return g, H.reshape(len(self.facets), 18, 18)
