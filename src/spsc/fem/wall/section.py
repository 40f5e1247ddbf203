"""The meridional section of the chamber wall as a 2D solid of revolution: mesh, basis and
boundary sets.

The wall model (:mod:`spsc.fem.wall`) solves a dome (l = 0) as the axisymmetric body of
revolution of this section about the z axis, and sweeps the same section along a stadium
(l > 0, :mod:`spsc.fem.wall.swept`). It is the section of
:func:`spsc.fem.solid.mesh.wall_section` (the 3D model's structured section: cavity profile to
outer profile, clamped on z = 0; docs/design.md),
meshed with 9-node biquadratic quadrilaterals (isoparametric, scikit-fem's
``MeshQuad2``/``ElementQuad2``). Reference gradients, quadrature points and weights come from
scikit-fem's ``CellBasis``; the weights carry the measure 2πR, so nodal forces are whole-ring
forces (N).

Coordinates: (R, Z) in mm, R ≥ 0 the distance from the axis, Z the height above the cavity base
plane.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np

from spsc.cad.geometry import SPSCGeometry
from spsc.core.errors import require, require_integer

from ..solid.mesh import graded_fractions, wall_section

__all__ = ["Section", "section_mesh"]

# 3-point Gauss rule on [0, 1] for the quadratic boundary edges (exact for r² z', degree 5)
_GAUSS_T = 0.5 + 0.5 * np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])
_GAUSS_W = 0.5 * np.array([5.0, 8.0, 5.0]) / 9.0


def _edge_shape(t):
    """Quadratic Lagrange shape functions on [0, 1] (nodes 0, ½, 1) and their derivatives."""
    N = np.stack([(1 - t) * (1 - 2 * t), 4 * t * (1 - t), t * (2 * t - 1)], axis=-1)
    dN = np.stack([4 * t - 3, 4 - 8 * t, 4 * t - 1], axis=-1)
    return N, dN


# the cavity edges' shape values at the Gauss points, and the products the Hessian sums
# (q, a·b): made once (the volume and its gradient run at every Newton iteration)
_N, _DN = _edge_shape(_GAUSS_T)
_NN = (_N[:, :, None] * _N[:, None, :]).reshape(3, 9)
_NDN = (_N[:, :, None] * _DN[:, None, :]).reshape(3, 9)


@dataclass(frozen=True, eq=False)
class Section:
    """A meshed wall section with everything the assembly needs, precomputed.

    Attributes (n nodes, ne elements, nq quadrature points per element)
    ----------
    nodes : (n, 2) reference (R, Z), mm
    elements : (ne, 9) node indices
    dNdX : (ne, nq, 9, 2) reference gradients; N : (ne, nq, 9) shape values
    Xq : (ne, nq, 2) reference quadrature points; dV : (ne, nq) weights × measure (mm³)
    cavity : (m,) nodes of the cavity boundary from the apex (axis) to the base, m odd
    outer : (k,) nodes of the outer surface from the apex to the base
    fixed : (2n,) bool, prescribed displacement components (clamped base, axis/mid-plane)
    """

    nodes: np.ndarray = field(repr=False)
    elements: np.ndarray = field(repr=False)
    N: np.ndarray = field(repr=False)
    dNdX: np.ndarray = field(repr=False)
    Xq: np.ndarray = field(repr=False)
    dV: np.ndarray = field(repr=False)
    cavity: np.ndarray = field(repr=False)
    outer: np.ndarray = field(repr=False)
    fixed: np.ndarray = field(repr=False)
    grid_shape: tuple = (0, 0)

    @property
    def n_dofs(self) -> int:
        return 2 * len(self.nodes)

    @property
    def element_dofs(self) -> np.ndarray:
        """(ne, 18) unknowns of each element, node-major (u_R, u_Z)."""
        return (2 * self.elements[:, :, None] + np.arange(2)).reshape(len(self.elements), 18)

    def measure(self, r):
        """Measure of a boundary or volume element at radius ``r``: 2πr (mm)."""
        return 2.0 * math.pi * np.asarray(r)

    def positions(self, u) -> np.ndarray:
        """Deformed (r, z) of the nodes (mm) for displacements ``u`` (2n,)."""
        return self.nodes + np.asarray(u).reshape(-1, 2)

    # -- the enclosed cavity ------------------------------------------------------------------
    def _cavity_edges(self, u):
        x = self.positions(u)[self.cavity]
        return np.stack([x[0:-2:2], x[1:-1:2], x[2::2]], axis=1)  # (ne, 3, 2)

    def volume(self, u) -> float:
        """Volume of the cavity this section encloses (mm³): dome −π∮ r² z' (the body of
        revolution closed by the axis and the base plane)."""
        e = self._cavity_edges(u)
        r, dz = e[..., 0] @ _N.T, e[..., 1] @ _DN.T  # (ne, q)
        return -float(np.sum((math.pi * r * r * dz) @ _GAUSS_W))

    def volume_gradient(self, u, *, hessian: bool = True):
        """g = ∂V/∂u (2n,) in mm² and, if ``hessian``, the edge blocks of ∂²V/∂u², shape
        (ne, 6, 6), on the unknowns :meth:`cavity_edge_dofs`. The follower pressure p is the
        load p g; its consistent stiffness is p ∂²V/∂u² (the pressure does work p dV)."""
        e = self._cavity_edges(u)
        ne = len(e)
        r, dz = e[..., 0] @ _N.T, e[..., 1] @ _DN.T  # (ne, q)
        wdf = 2.0 * math.pi * r * _GAUSS_W  # ∂f/∂r w, f = π r²
        ge = np.empty((ne, 3, 2))
        ge[:, :, 0] = -(wdf * dz) @ _N  # ∂V/∂r_a
        ge[:, :, 1] = -(math.pi * r * r * _GAUSS_W) @ _DN  # ∂V/∂z_b
        g = np.bincount(self.cavity_edge_dofs.ravel(), weights=ge.ravel(),
                        minlength=self.n_dofs)
        if not hessian:
            return g
        H = np.zeros((ne, 3, 2, 3, 2))
        H[:, :, 0, :, 0] = -((2.0 * math.pi * _GAUSS_W * dz) @ _NN).reshape(ne, 3, 3)
        H[:, :, 0, :, 1] = -(wdf @ _NDN).reshape(ne, 3, 3)
        H[:, :, 1, :, 0] = np.swapaxes(H[:, :, 0, :, 1], 1, 2)
        return g, H.reshape(ne, 6, 6)

    @functools.cached_property
    def cavity_edge_dofs(self) -> np.ndarray:
        """(ne, 6) unknowns of the quadratic cavity edges."""
        c = self.cavity
        nodes = np.stack([c[0:-2:2], c[1:-1:2], c[2::2]], axis=1)
        return (2 * nodes[:, :, None] + np.arange(2)).reshape(len(nodes), 6)

    # -- the outer surface --------------------------------------------------------------------
    def contact_area(self, u, plate: float, tol: float = 1e-3, indenter=None) -> float:
        """Area (mm²) of the outer surface within ``tol`` (mm) of the plate at height
        ``plate`` (or of the sphere ``indenter`` with its tip there): the outer edges'
        quadrature points on it, weighted by their deformed length × measure (the 3D model's
        definition, :func:`spsc.fem.solid.contact.contact_area`)."""
        x = self.positions(u)[self.outer]
        e = np.stack([x[0:-2:2], x[1:-1:2], x[2::2]], axis=1)
        N, dN = _edge_shape(np.linspace(0.125, 0.875, 4))  # midpoints of 4 sub-intervals
        xq = np.einsum("qa,eai->eqi", N, e)
        ds = np.linalg.norm(np.einsum("qa,eai->eqi", dN, e), axis=-1) * 0.25
        z = xq[..., 1]
        if indenter is not None and indenter.curved:
            z = z - indenter.surface(xq[..., 0].reshape(1, -1))[0].reshape(z.shape)
        on = z >= plate - tol
        return float(np.sum((self.measure(xq[..., 0]) * ds)[on]))


def _coarse_cells(shape):
    """Corner indices (ne, 4) and the fine-grid index of each element's (0, 0) corner."""
    m, k = shape
    idx = np.arange(m * k).reshape(m, k)
    i, j = np.meshgrid(np.arange(0, m - 1, 2), np.arange(0, k - 1, 2), indexing="ij")
    i, j = i.ravel(), j.ravel()
    return idx, i, j


def _grid(g: SPSCGeometry, size: float, layers: int, apex: float | None) -> np.ndarray:
    """The section's fine grid (:func:`~spsc.fem.solid.mesh.wall_section`): about ``size``
    mm elements along the profile, graded from ``apex`` mm at the apex if given."""
    outer = g.outer_profile_points(2001)
    length = float(np.sum(np.hypot(*np.diff(outer, axis=0).T)))
    if apex is None:
        return wall_section(g, max(4, math.ceil(length / size)), layers)
    apex = require("apex_size", apex, gt=0, le=size, unit=f"mm, at most the mesh size "
                   f"{size:g} mm")
    fractions = graded_fractions(length, size, apex)
    return wall_section(g, (len(fractions) - 1) // 2, layers, fractions)


def section_mesh(g: SPSCGeometry, *, size: float = 0.5,
                 layers: int = 2, base: str = "clamped", apex: float | None = None) -> Section:
    """The meshed wall section of ``g``: about ``size`` mm elements along the profile,
    ``layers`` quadratic elements through the thickness (defaults: the mesh-convergence study
    of :mod:`spsc.fem.wall`). ``base``: ``"clamped"`` on z = 0 (the chamber, docs/design.md) or
    ``"sliding"`` (u_z = 0 only: with n1 = n2 = 2, c_y = 0, w = h the dome is half of a thick
    sphere, for the exact solution). ``apex``: the elements' length at the apex (mm), graded
    up to ``size`` (:func:`~spsc.fem.solid.mesh.graded_fractions`: a sharp probe's contact on
    the axis, resolved); None: ``size`` throughout."""
    from skfem import CellBasis, ElementQuad2, MeshQuad1, MeshQuad2

    size = require("mesh_size", size, gt=0, unit="mm")
    layers = require_integer("layers", layers, ge=1)
    if base not in ("clamped", "sliding"):
        raise ValueError(f"base = {base!r}: 'clamped' or 'sliding'")
    grid = _grid(g, size, layers, apex)  # (2n+1, 2L+1, 2): apex → base, cavity → outer
    shape = grid.shape[:2]
    fine = grid.reshape(-1, 2)
    idx, i, j = _coarse_cells(shape)
    corners = np.stack([idx[i, j], idx[i + 2, j], idx[i + 2, j + 2], idx[i, j + 2]], axis=1)
    # coarse vertex numbering for scikit-fem; its Quad2 mesh adds edge and centre nodes
    used = np.unique(corners)
    renum = -np.ones(len(fine), int)
    renum[used] = np.arange(len(used))
    m1 = MeshQuad1(fine[used].T.copy(), renum[corners].T.copy(), sort_t=False)
    m2 = MeshQuad2.from_mesh(m1)
    basis = CellBasis(m2, ElementQuad2(), intorder=4)
    ref = np.rint(2 * ElementQuad2().doflocs).astype(int)  # (9, 2) in half-cells
    fine_of = idx[i[None, :] + ref[:, 0, None], j[None, :] + ref[:, 1, None]]  # (9, ne)
    dofs = basis.element_dofs  # (9, ne) global Quad2 node of each local dof
    doflocs = m2.doflocs.copy()
    doflocs[:, dofs] = fine[fine_of].transpose(2, 0, 1)
    m2 = replace(m2, doflocs=doflocs)
    basis = CellBasis(m2, ElementQuad2(), intorder=4)
    nodes = m2.doflocs.T.copy()
    elements = basis.element_dofs.T.copy()
    global_of_fine = np.full(len(fine), -1)
    global_of_fine[fine_of.ravel()] = dofs.ravel()
    N = np.stack([np.asarray(basis.basis[a][0]) for a in range(9)], axis=-1)
    dNdX = np.stack([basis.basis[a][0].grad for a in range(9)], axis=-1)  # (2, ne, nq, 9)
    dNdX = np.moveaxis(dNdX, 0, -1)  # (ne, nq, 9, 2)
    Xq = np.moveaxis(basis.mapping.F(basis.X), 0, -1)  # (ne, nq, 2)
    dV = basis.dx * 2.0 * math.pi * Xq[..., 0]
    cavity = global_of_fine[idx[:, 0]]
    outer_nodes = global_of_fine[idx[:, -1]]
    tol = 1e-9 * max(g.w, g.h)
    fixed = np.zeros(2 * len(nodes), bool)
    on_base = np.nonzero(np.abs(nodes[:, 1]) < tol)[0]
    fixed[2 * on_base + 1] = True
    if base == "clamped":
        fixed[2 * on_base] = True  # clamped on z = 0 (docs/design.md)
    axis = np.nonzero(np.abs(nodes[:, 0]) < tol)[0]
    fixed[2 * axis] = True  # u_R = 0 on the axis
    if np.any(basis.dx <= 0):
        raise ValueError("inverted element in the wall section")
    return Section(nodes, elements, N, dNdX, Xq, dV, cavity, outer_nodes,
                   fixed, shape)
