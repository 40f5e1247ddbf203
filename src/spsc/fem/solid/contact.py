"""What the 3D solid measures of its contact with the rigid plate: the nodal contact forces of
the active nodes (N), the force through each named contact surface and the contact area on the
outer surface. The active set itself is the engine's (:mod:`spsc.fem.engine.active_set`); here
``active`` are node indices.
"""

from __future__ import annotations

import numpy as np

from .element import tri_p2, tri_rule

__all__ = ["group_forces", "contact_forces", "contact_area", "contact_patch"]


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


def contact_area(model, x, plate: float, tol: float | None = None, indenter=None) -> float:
    """Outer-surface area (mm², full part) touching the plate (or the curved ``indenter``
    whose tip is at ``plate``): the quadrature weights of the outer facets whose points lie
    within ``tol`` (mm, default 1e-3) of it. Facets with all six nodes active lie exactly on a
    plate; partly touching facets count in part."""
    xq, w = tri_rule(4)
    N, dN = tri_p2(xq)
    pos = model.disc.X + model.displacement(x)
    f = pos[model.mesh.facets["outer"]]
    xyz = np.einsum("fai,qa->fqi", f, N)
    z = xyz[..., 2]
    if indenter is not None and indenter.curved:
        z = z - indenter.surface(xyz[..., :2].reshape(-1, 2).T)[0].reshape(z.shape)
    xs = np.einsum("fai,qa->fqi", f, dN[:, :, 0])
    xt = np.einsum("fai,qa->fqi", f, dN[:, :, 1])
    da = np.linalg.norm(np.cross(xs, xt), axis=-1) * w
    if tol is None:
        tol = 1e-3
    return float(np.sum(da[z >= plate - tol])) * model.symmetry


def contact_patch(model, x, plate: float, indenter=None, tol: float = 1e-3):
    """The contact patch as the outer facets in the deformed state x: (corners (nf, 3, 3) in
    mm, the part of each facet's area on the body (nf,), 0–1), for the facets that touch
    at all, in the modelled part (mirror it for the whole). The same quadrature as
    :func:`contact_area`, whose sum it is (÷ symmetry)."""
    xq, w = tri_rule(4)
    N, dN = tri_p2(xq)
    pos = model.disc.X + model.displacement(x)
    f = pos[model.mesh.facets["outer"]]
    xyz = np.einsum("fai,qa->fqi", f, N)
    z = xyz[..., 2]
    if indenter is not None and indenter.curved:
        z = z - indenter.surface(xyz[..., :2].reshape(-1, 2).T)[0].reshape(z.shape)
    xs = np.einsum("fai,qa->fqi", f, dN[:, :, 0])
    xt = np.einsum("fai,qa->fqi", f, dN[:, :, 1])
    da = np.linalg.norm(np.cross(xs, xt), axis=-1) * w
    on = (da * (z >= plate - tol)).sum(axis=1) / da.sum(axis=1)
    touch = on > 0
    return f[touch, :3], on[touch]
