"""Frictionless contact with a rigid plate z = z_plate moving down onto the chamber.

Primal–dual active set on the outer-surface nodes: an active node's height is prescribed at the
plate (its vertical displacement is eliminated like a support), and its contact force is the
reaction λ_a = −r_z,a ≥ 0 (N). A node is released when its reaction pulls (λ_a < −tol) and
activated when it penetrates the plate. With exact enforcement there is no penalty parameter to
tune, which is what makes the thin walls robust; the plate force is Σ λ_a over the active nodes
(× symmetry), the integral of the discrete contact pressure.
"""

from __future__ import annotations

import numpy as np

from .element import tri_p2, tri_rule

__all__ = ["plate_force", "group_forces", "contact_forces", "contact_area", "update_active_set"]


def contact_forces(r, active) -> np.ndarray:
    """Nodal contact forces λ_a (N, part) of the active nodes from the residual."""
    return -r[3 * np.asarray(active) + 2]


def plate_force(model, r, active) -> float:
    """Plate force (N) on the full part: the sum of the nodal contact forces × symmetry."""
    return float(contact_forces(r, active).sum()) * model.symmetry


def group_forces(model, r, active) -> dict:
    """Force (N, full part) through each named contact surface of the model: the nodal
    contact forces of its active nodes, summed (× symmetry)."""
    active = np.asarray(active)
    lam = contact_forces(r, active)
    return {name: float(lam[np.isin(active, nodes)].sum()) * model.symmetry
            for name, nodes in model.groups.items()}


def update_active_set(model, x, r, plate, active, force_tol, gap_tol):
    """The new active set, or None if it is unchanged (the PDAS fixed point)."""
    X = model.disc.X
    keep = contact_forces(r, active) >= -force_tol
    inactive = np.setdiff1d(model.contact_nodes, active)
    z = X[inactive, 2] + x[3 * inactive + 2] + model.gap[inactive]
    new = inactive[z > plate + gap_tol]
    if new.size == 0 and np.all(keep):
        return None
    return np.union1d(np.asarray(active)[keep], new)


def contact_area(model, x, plate: float, tol: float | None = None) -> float:
    """Outer-surface area (mm², full part) touching the plate: the quadrature weights of the
    outer facets whose points lie within ``tol`` (mm, default 1e-3) of the plate. Facets with
    all six nodes active lie exactly on it; partly touching facets count in part."""
    xq, w = tri_rule(4)
    N, dN = tri_p2(xq)
    pos = model.disc.X + model.displacement(x)
    f = pos[model.mesh.facets["outer"]]
    z = np.einsum("fai,qa->fqi", f, N)[..., 2]
    xs = np.einsum("fai,qa->fqi", f, dN[:, :, 0])
    xt = np.einsum("fai,qa->fqi", f, dN[:, :, 1])
    da = np.linalg.norm(np.cross(xs, xt), axis=-1) * w
    if tol is None:
        tol = 1e-3
    return float(np.sum(da[z >= plate - tol])) * model.symmetry
