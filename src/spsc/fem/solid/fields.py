"""The 3D FEM's strain and energy where the wall carries them: the same fields as the wall
model's (:mod:`spsc.fem.wall.fields`), on the P2 tetrahedra, for the independent check of the
squeeze cycle's hot spot (issue 51).

At each of a tetrahedron's 4 quadrature points (degree 2) the largest principal stretch and
the strain-energy density W(Ī1, Ī2); the four values define one linear field in the element,
read at its 4 vertices (R = N₁⁻¹, N₁ the P1 shape values at the quadrature points) and
averaged over the elements that share a vertex. The P2 mid-edge nodes carry no value (NaN).
"""

from __future__ import annotations

import numpy as np

from ..fields import CycleFields, over_cycle, principal_stretch
from .assembly import deformation_gradient

__all__ = ["solid_fields", "vertex_values", "node_places", "cycle_fields"]


def solid_fields(model, x) -> tuple[np.ndarray, np.ndarray]:
    """(λ₁, W MPa) at the quadrature points (nel, nq) of the state ``x``."""
    d = model.disc
    u, _ = d.split(x)
    F = deformation_gradient(d, u)
    W = model.law.energy(F, np.zeros(F.shape[:-2]))
    return principal_stretch(F), np.asarray(W)


def vertex_values(model, values: np.ndarray) -> np.ndarray:
    """The quadrature values (nel, 4) as a continuous field on the vertices (N nodes; NaN on
    the mid-edge nodes)."""
    d = model.disc
    R = np.linalg.inv(d.Np)  # (4 vertices, 4 points)
    at = np.einsum("vq,eq->ev", R, values)
    corners = d.tets[:, :4]
    n = d.n_nodes
    total = np.bincount(corners.ravel(), at.ravel(), minlength=n)
    count = np.bincount(corners.ravel(), minlength=n)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, total / count, np.nan)


def node_places(model, geometry) -> dict:
    """Per node: ``height`` (mm above the base), ``radius`` (mm from the axis; on a stadium
    from its middle line), ``face`` and ``base`` (within t0 of the base, or of an element
    that touches it) as :func:`spsc.fem.wall.fields.node_places` names them."""
    mesh, d = model.mesh, model.disc
    X = d.X
    a = 0.5 * geometry.l
    radius = np.hypot(X[:, 0], np.maximum(np.abs(X[:, 1]) - a, 0.0))
    height = X[:, 2]
    base = height < geometry.t0
    on_base = mesh.nodes_on("base") if "base" in mesh.facets else np.zeros(0, int)
    touching = np.isin(d.tets, on_base).any(axis=1)
    base[d.tets[touching].ravel()] = True
    face = np.full(len(X), "inside", dtype=object)
    if "cavity" in mesh.facets:
        face[mesh.nodes_on("cavity")] = "inner"
    if "outer" in mesh.facets:
        face[mesh.nodes_on("outer")] = "outer"
    return {"height": height, "radius": radius, "face": face, "base": base}


def cycle_fields(model, states, geometry) -> CycleFields:
    """The cycle's fields over the states ``states`` (the rest first)."""
    pairs = [solid_fields(model, x) for x in states]
    return over_cycle([vertex_values(model, s) for s, _ in pairs],
                      [vertex_values(model, w) for _, w in pairs], node_places(model, geometry))
