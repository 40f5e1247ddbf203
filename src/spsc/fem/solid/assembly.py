"""Vectorised assembly of the mixed P2/P1 (Taylor–Hood) hyperelastic system on a fixed pattern.

The unknowns are x = [u (3 per P2 node, node-major), p (1 per tetrahedron vertex)]. Kinematics
are computed once per call for all elements and quadrature points, the material returns stress
and tangent over whole arrays, and the element matrices are batched matrix products; the CSR
pattern and the scatter map from element entries to CSR slots are built once per mesh.

Weak form (reference configuration Ω0, G = F⁻ᵀ):

    r_u = ∫ P(F, p) : ∇δu dV,      r_p = ∫ (J − 1 − p/κ) δp dV,
    K_uu = ∫ ∇δu : 𝔸 : ∇Δu dV,     K_up = ∫ J G : ∇δu Δp dV,     K_pp = −∫ δp Δp / κ dV.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..material import NearlyIncompressible
from ..material_kernel import cofactor
from .assembly_kernel import AVAILABLE as COMPILED, deformation_gradient as compiled_F, \
    residual as compiled_residual, residual_tangent as compiled_residual_tangent
from .element import tet_p1, tet_p2, tet_rule

__all__ = ["Pattern", "Discretisation", "discretise", "assemble", "InvertedElement"]


class InvertedElement(ValueError):
    """det F ≤ 0 at a quadrature point: the trial state is not admissible."""


@dataclass(frozen=True, eq=False)
class Pattern:
    """A CSR sparsity pattern and where each entry of a batch of element matrices lands in it."""

    n: int
    indptr: np.ndarray
    indices: np.ndarray
    keys: np.ndarray  # sorted row * n + col of the stored entries
    slots: np.ndarray  # (nel, m, m) CSR positions of the element matrix entries
    order: np.ndarray  # the elements by their lowest unknown (the compiled loop's order)

    @classmethod
    def from_element_dofs(cls, dofs: np.ndarray, n: int, nodes: np.ndarray,
                          local: np.ndarray) -> "Pattern":
        """The pattern of the element unknowns ``dofs`` (nel, m) among ``n``, found on the
        elements' ``nodes`` (nel, k): column j of ``dofs`` is an unknown of node
        ``local[j]``, and an element lists every unknown of each of its nodes (a P2 node's
        three displacements, a vertex's pressure too). Two unknowns couple where their nodes
        share an element, so the node pairs (nel k², 9× fewer than the unknown pairs) are
        sorted instead of the unknown pairs: 1.3 → 0.2 s a Type B quarter (issue 26)."""
        nel, m = dofs.shape
        n_nodes = int(nodes.max()) + 1
        node_of = np.zeros(n, np.int64)
        node_of[dofs.ravel()] = nodes[:, local].ravel()
        # each node's unknowns in ascending order, and each unknown's rank among them
        by_node = np.argsort(node_of * n + np.arange(n), kind="stable")
        first = np.searchsorted(node_of[by_node], np.arange(n_nodes + 1))
        rank = np.empty(n, np.int64)
        rank[by_node] = np.arange(n) - first[node_of[by_node]]
        count = np.diff(first)
        # the node pairs: row node a, column node b, sorted; each element's pairs among them
        k = nodes.shape[1]
        pair_keys = (nodes[:, :, None].astype(np.int64) * n_nodes + nodes[:, None, :]).ravel()
        pairs, inverse = np.unique(pair_keys, return_inverse=True)
        a, b = pairs // n_nodes, pairs % n_nodes
        # the columns of row node a: every unknown of every b, sorted (one list per node)
        per = count[b]
        start = np.concatenate([[0], np.cumsum(per)])
        col = by_node[np.repeat(first[b] - start[:-1], per) + np.arange(start[-1])]
        row_node = np.repeat(a, per)
        order = np.argsort(row_node * n + col, kind="stable")
        row_first = np.searchsorted(row_node[order], np.arange(n_nodes + 1))
        where = np.empty(order.size, np.int64)  # position of each (pair, unknown) in its row
        where[order] = np.arange(order.size) - row_first[row_node[order]]
        sorted_cols = col[order]
        length = np.diff(row_first)
        indptr = np.concatenate([[0], np.cumsum(length[node_of])])
        entry_row_node = np.repeat(node_of, length[node_of])
        offset = np.arange(indptr[-1]) - np.repeat(indptr[:-1], length[node_of])
        indices = sorted_cols[row_first[entry_row_node] + offset]
        keys = np.repeat(np.arange(n, dtype=np.int64), length[node_of]) * n + indices
        # element entry (i, j): row dofs[i]'s start + where of (pair (local i, local j),
        # the rank of dofs[j] within its node)
        pair = inverse.reshape(nel, k, k)[:, local[:, None], local[None, :]]
        slots = indptr[dofs][:, :, None] + where[start[pair] + rank[dofs][:, None, :]]
        return cls(n, indptr, indices.astype(np.int32), keys, slots,
                   np.argsort(dofs.min(axis=1), kind="stable"))

    def slots_of(self, dofs: np.ndarray) -> np.ndarray:
        """CSR positions of the (k, m, m) blocks of another batch (e.g. surface facets) whose
        couplings are already in the pattern."""
        m = dofs.shape[1]
        key = dofs[:, :, None].astype(np.int64) * self.n + dofs[:, None, :]
        pos = np.searchsorted(self.keys, key)
        if np.any(self.keys[np.minimum(pos, self.keys.size - 1)] != key):
            raise ValueError("coupling outside the element pattern")
        return pos.reshape(-1, m, m)

    def matrix(self, values: np.ndarray, slots: np.ndarray | None = None,
               extra=()) -> sp.csr_matrix:
        """Sum the element matrices ``values`` (k, m, m) (plus any ``(values, slots)`` pairs in
        ``extra``) into a CSR matrix holding the whole pattern, explicit zeros included, so
        its structure never changes between Newton iterations."""
        slots = self.slots if slots is None else slots
        data = np.bincount(slots.ravel(), weights=values.ravel(), minlength=self.keys.size)
        return self.csr(data, extra)

    def csr(self, data: np.ndarray, extra=()) -> sp.csr_matrix:
        """The CSR matrix of the pattern's values ``data`` with the ``extra`` blocks added."""
        for v, s in extra:
            data += np.bincount(s.ravel(), weights=v.ravel(), minlength=self.keys.size)
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))


@dataclass(frozen=True, eq=False)
class Discretisation:
    """Everything about a mesh the assembly needs, computed once.

    ``X`` (N, 3) reference node coordinates (mm); ``tets`` (nel, 10) P2 connectivity;
    ``pressure_dof`` maps a node to its pressure unknown (−1 on edge nodes); ``dNdX`` (nel, nq,
    10, 3) reference gradients; ``dV`` (nel, nq) quadrature weights × reference volume (mm³);
    ``Np`` (nq, 4) P1 pressure shape functions; ``dofs`` (nel, 34) element unknowns.
    """

    X: np.ndarray
    tets: np.ndarray
    pressure_dof: np.ndarray
    dNdX: np.ndarray
    dV: np.ndarray
    Np: np.ndarray
    dofs: np.ndarray
    pattern: Pattern = field(repr=False)

    @property
    def n_nodes(self) -> int:
        return self.X.shape[0]

    @property
    def n_u(self) -> int:
        return 3 * self.X.shape[0]

    @property
    def n_p(self) -> int:
        return int(self.pressure_dof.max()) + 1

    @property
    def n(self) -> int:
        return self.n_u + self.n_p

    def split(self, x):
        """(u (N, 3), p (n_p,)) views of the unknown vector x."""
        return x[: self.n_u].reshape(-1, 3), x[self.n_u:]

    def volume(self) -> float:
        """Reference volume of the mesh (mm³)."""
        return float(self.dV.sum())


def discretise(X, tets, *, order: int = 2) -> Discretisation:
    """Precompute geometry and the sparsity pattern for P2 nodes ``X`` (N, 3) and 10-node
    tetrahedra ``tets`` (nel, 10); ``order`` is the quadrature degree.

    The default degree 2 (4 points, all weights positive) integrates ∇N·det J exactly on
    straight-sided tetrahedra, so they pass the patch test; curved (isoparametric) ones need
    degree 5 (14 points) for that, while at degree 2 their consistency error vanishes with h
    (tests: patch test both ways, thick-sphere convergence).
    """
    X = np.asarray(X, dtype=float)
    tets = np.asarray(tets, dtype=np.int64)
    xq, wq = tet_rule(order)
    _, dN = tet_p2(xq)  # (nq, 10, 3)
    Jac = np.einsum("eai,qaj->eqij", X[tets], dN)  # ∂X/∂ξ
    det = np.linalg.det(Jac)
    if np.any(det <= 0):
        raise ValueError(f"{int(np.sum(np.any(det <= 0, axis=1)))} inverted or degenerate tets")
    dNdX = np.einsum("qaj,eqji->eqai", dN, np.linalg.inv(Jac))
    dV = det * wq
    corner = np.unique(tets[:, :4])
    pressure_dof = -np.ones(X.shape[0], dtype=np.int64)
    pressure_dof[corner] = np.arange(corner.size)
    udofs = (3 * tets[:, :, None] + np.arange(3)).reshape(len(tets), 30)
    dofs = np.hstack([udofs, 3 * X.shape[0] + pressure_dof[tets[:, :4]]])
    local = np.concatenate([np.repeat(np.arange(10), 3), np.arange(4)])
    pattern = Pattern.from_element_dofs(dofs, 3 * X.shape[0] + corner.size, tets, local)
    return Discretisation(X, tets, pressure_dof, dNdX, dV, tet_p1(xq), dofs, pattern)


def deformation_gradient(d: Discretisation, u):
    """F = I + ∇u at every quadrature point, (nel, nq, 3, 3), for nodal displacements u (N, 3)."""
    if COMPILED:
        return compiled_F(u, d.tets, d.dNdX)
    return np.eye(3) + np.einsum("eai,eqaj->eqij", u[d.tets], d.dNdX)


def assemble(d: Discretisation, law: NearlyIncompressible, x, *, tangent: bool = True,
             extra=()):
    """Internal residual r(x) (n,) and, if ``tangent``, the consistent tangent K (CSR, n×n),
    with the ``(values, slots)`` blocks of ``extra`` (e.g. load stiffness) added in.

    Units: u in mm, p in MPa; r_u in N, r_p in mm³.
    """
    u, p = d.split(x)
    F = deformation_gradient(d, u)
    pq = np.einsum("qb,eb->eq", d.Np, p[d.pressure_dof[d.tets[:, :4]]])
    J, JG = cofactor(F)
    if not np.all(J > 0):
        bad = np.any(~(J > 0), axis=1)
        c = d.X[d.tets[np.argmax(bad), :4]].mean(axis=0)
        raise InvertedElement(f"{int(np.sum(bad))} elements inverted (the first near "
                              f"{c[0]:.2f}, {c[1]:.2f}, {c[2]:.2f} mm in the model frame)")
    if tangent:
        P, A = law.stress_tangent(F, pq)
    else:
        P = law.stress(F, pq)
    if COMPILED:
        if not tangent:
            return compiled_residual(P, J, pq, d.dNdX, d.dV, d.Np, law.kappa, d.dofs, d.n)
        r, data = compiled_residual_tangent(P, A, JG, J, pq, d.dNdX, d.dV, d.Np, law.kappa,
                                            d.dofs, d.pattern.slots, d.pattern.order, d.n,
                                            d.pattern.keys.size)
        return r, d.pattern.csr(data, extra)
    nel, nq = d.dV.shape
    ru = np.einsum("eqij,eqaj,eq->eai", P, d.dNdX, d.dV).reshape(nel, 30)
    rp = np.einsum("eq,qb,eq->eb", J - 1.0 - pq / law.kappa, d.Np, d.dV)
    r = np.bincount(d.dofs.ravel(), weights=np.hstack([ru, rp]).ravel(), minlength=d.n)
    if not tangent:
        return r
    # B maps element displacements (a, k) to ∇u entries (i, J): B[(iJ), (a k)] = δ_ik ∂N_a/∂X_J
    B = np.zeros((nel, nq, 3, 3, 10, 3))
    for i in range(3):
        B[:, :, i, :, :, i] = np.swapaxes(d.dNdX, 2, 3)
    B = B.reshape(nel, nq, 9, 30)
    BdV = B * d.dV[..., None, None]
    Kuu = np.einsum("eqmi,eqmn,eqnj->eij", BdV, A.reshape(nel, nq, 9, 9), B, optimize=True)
    Kup = np.einsum("eqm,eqmi,qb->eib", JG.reshape(nel, nq, 9), BdV,
                    d.Np, optimize=True)
    Kpp = -np.einsum("qa,qb,eq->eab", d.Np, d.Np, d.dV) / law.kappa
    Ke = np.empty((nel, 34, 34))
    Ke[:, :30, :30] = Kuu
    Ke[:, :30, 30:] = Kup
    Ke[:, 30:, :30] = np.swapaxes(Kup, 1, 2)
    Ke[:, 30:, 30:] = Kpp
    return r, d.pattern.matrix(Ke, extra=extra)
