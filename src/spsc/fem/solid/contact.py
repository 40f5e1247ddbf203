"""What the 3D solid measures of its contact with the rigid plate: the nodal contact forces of
the active nodes (N), the force through each named contact surface and the contact area on the
outer surface. The active set itself is the engine's (:mod:`spsc.fem.engine.active_set`); here
``active`` are node indices.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve

from .element import tri_p2, tri_rule

__all__ = ["group_forces", "contact_forces", "contact_area", "surface_mass",
           "contact_tractions"]


def contact_forces(r, active) -> np.ndarray:
    """Nodal contact forces λ_a (N, part) of the active nodes from the residual."""
    return -r[3 * np.asarray(active) + 2]


def group_forces(model, r, active) -> dict:
    """Force (N, full part) through each named contact surface of the model: the nodal
    contact forces of its active nodes, summed (× symmetry)."""
    active = np.asarray(active)
    lam = contact_forces(r, active)
    return {name: float(lam[np.isin(active, nodes)].sum()) * model.symmetry
            for name, nodes in model.groups.items()}


def _outer_quadrature(model, x):
    """The deformed outer facets' quadrature: (facets (nf, 6), points (nf, nq, 3) in mm,
    weights × area (nf, nq) in mm², the P2 shape functions at the points (nq, 6))."""
    xq, w = tri_rule(4)
    N, dN = tri_p2(xq)
    facets = model.mesh.facets["outer"]
    f = (model.disc.X + model.displacement(x))[facets]
    xyz = np.einsum("fai,qa->fqi", f, N)
    xs = np.einsum("fai,qa->fqi", f, dN[:, :, 0])
    xt = np.einsum("fai,qa->fqi", f, dN[:, :, 1])
    return facets, xyz, np.linalg.norm(np.cross(xs, xt), axis=-1) * w, N


def contact_area(model, x, plate: float, tol: float | None = None, indenter=None) -> float:
    """Outer-surface area (mm², full part) touching the plate (or the curved ``indenter``
    whose tip is at ``plate``): the quadrature weights of the outer facets whose points lie
    within ``tol`` (mm, default 1e-3) of it. Facets with all six nodes active lie exactly on a
    plate; partly touching facets count in part."""
    _, xyz, da, _ = _outer_quadrature(model, x)
    z = xyz[..., 2]
    if indenter is not None and indenter.curved:
        z = z - indenter.surface(xyz[..., :2].reshape(-1, 2).T)[0].reshape(z.shape)
    if tol is None:
        tol = 1e-3
    return float(np.sum(da[z >= plate - tol])) * model.symmetry


def surface_mass(model, x) -> sp.csr_matrix:
    """The P2 mass matrix of the deformed outer surface, M_ab = ∫ N_a N_b dA (mm², nodes of
    the modelled part; zero rows off the surface)."""
    facets, _, da, N = _outer_quadrature(model, x)
    Me = np.einsum("fq,qa,qb->fab", da, N, N)
    rows = np.repeat(facets, 6, axis=1).ravel()
    cols = np.tile(facets, (1, 6)).ravel()
    n = model.disc.n_nodes
    return sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(n, n))


def contact_tractions(model, x, forces, indenter=None):
    """The contact traction on the outer surface, recovered from the nodal contact forces
    ``forces`` (n_nodes, 3; N, as :func:`spsc.fem.solid.chamber.contact_forces`: the part
    on the body) by L2 projection onto the P2 surface, M t = f: (contact pressure (n_nodes,)
    in MPa along the body's normal, compressive > 0; tangential traction (n_nodes, 3) in
    MPa, what a sticking plate carries). Over the whole outer surface, whose shape functions sum to 1: ∫ p dA under a
    plate is its force; the P2 projection rings a little past the contact's edge."""
    forces = np.asarray(forces, float)
    pressure, shear = np.zeros(len(forces)), np.zeros_like(forces)
    touched = np.flatnonzero(np.any(forces != 0.0, axis=1))
    if touched.size == 0:
        return pressure, shear
    near = np.unique(model.mesh.facets["outer"])
    M = surface_mass(model, x)[near][:, near].tocsc()
    t = np.zeros_like(forces)
    t[near] = spsolve(M, forces[near])
    normal = np.zeros_like(forces)
    normal[:, 2] = 1.0  # the plate's, out of the part into the body (the forces' sense)
    if indenter is not None and indenter.curved:
        pos = model.disc.X[near] + model.displacement(x)[near]
        grad = indenter.surface(pos[:, :2].T)[1].T
        ok = np.all(np.isfinite(grad), axis=1)
        n = np.column_stack([-grad, np.ones(len(near))])
        normal[near[ok]] = n[ok] / np.linalg.norm(n[ok], axis=1)[:, None]
    pressure = np.einsum("ni,ni->n", t, normal)
    shear = t - pressure[:, None] * normal
    return pressure, shear
