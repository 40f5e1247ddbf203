"""The wall's strain and energy where it carries them: the fields a fatigue or a failure
criterion reads (issue 51; the paper's sec. 3.2 fatigue test cycles a Type B chamber at
50 kPa between rest and full squeeze).

At each quadrature point of the wall model (:class:`~spsc.fem.wall.model.WallModel`, the
dome's section or the swept wall) and a state x:

* the largest principal stretch λ₁ = √(largest eigenvalue of C = FᵀF), and the largest
  principal Green strain E₁ = (λ₁² − 1)/2;
* the strain-energy density W = W(Ī1, Ī2) of the material (MPa = mJ/mm³; the isochoric
  part: the wall is nearly incompressible, |J − 1| ≲ 1e-5), the predictor of the classical
  energy approach to rubber fatigue (Mars & Fatemi, Int. J. Fatigue 24, 2002, 949–961).

Over a cycle (the records of a walk) :func:`cycle_fields` keeps, per point, the largest
value and the amplitude (largest − smallest: the inflation's share is static, only the
squeeze's is cycled), on the nodes: each element's quadrature values extrapolated to its
nodes and averaged where elements meet (:func:`nodal`: a crack starts at the surface, and the
surface's values converge under refinement where the largest quadrature value lags them).
A node is named by its place on the wall: its height, its distance from the axis, whether it
lies on the inner (cavity) or the outer face or between, and whether its element touches the
clamped base or lies within a wall thickness of it (where the wall meets the rigid base plate:
a re-entrant corner, its peak a singularity that grows under refinement; :meth:`CycleFields.peak` reports the peak away from
it unless asked).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fields import CycleFields, over_cycle, principal_stretch

__all__ = ["WallFields", "CycleFields", "wall_fields", "cycle_fields", "nodal", "node_places"]


@dataclass(frozen=True)
class WallFields:
    """λ₁ ``stretch`` and W ``energy`` (MPa) at the quadrature points (ne, nq)."""

    stretch: np.ndarray
    energy: np.ndarray


def wall_fields(model, x) -> WallFields:
    """The fields of the wall model ``model`` at the state ``x``."""
    F = np.asarray(model.solid.deformation(model.displacements(x)))
    W = model.solid.law.energy(F, np.zeros(F.shape[:-2]))  # isochoric: p = 0
    return WallFields(principal_stretch(F), np.asarray(W))


def _recovery(model) -> tuple[np.ndarray, np.ndarray]:
    """(R (nn, nq): an element's quadrature values to its nodes, nodes (ne, nn)): the
    quadrature rule has as many points as the element has nodes (Q2 section 3 × 3, swept
    3 × 3 × 3) and the shape values at them are the same in every element, so the element's
    own interpolant through its quadrature values is read at its nodes (R = N⁻¹)."""
    section = model.part.section
    N = np.asarray(section.N[0])  # (nq, 9): the same for every element
    if model.stadium:
        from .swept import _ZG, _phi

        phi = _phi(_ZG)[0]  # (g, k)
        N = np.einsum("ia,gk->giak", N, phi).reshape(N.shape[0] * 3, -1)
    per = 3 if model.stadium else 2
    nodes = np.asarray(model.solid.element_dofs)[:, ::per] // per
    return np.linalg.inv(N), nodes


def nodal(model, values: np.ndarray, recovery=None) -> np.ndarray:
    """The quadrature values (ne, nq) of a field as a continuous nodal field (n nodes): each
    element's values extrapolated to its nodes (:func:`_recovery`), averaged over the
    elements that share a node (the surface's values, where a crack starts, converge under
    refinement; the largest quadrature value lags them by the distance to the face)."""
    R, nodes = recovery or _recovery(model)
    at_nodes = np.einsum("nq,eq->en", R, values)
    n = int(nodes.max()) + 1
    total = np.bincount(nodes.ravel(), at_nodes.ravel(), minlength=n)
    count = np.bincount(nodes.ravel(), minlength=n)
    return total / np.maximum(count, 1)


def node_places(model) -> dict:
    """Per node: ``position`` (n, d) reference (mm; (R, Z) on the dome, (x, y, z) on the
    swept wall), ``height`` (mm above the base), ``radius`` (mm from the axis; on the swept
    wall from the stadium's middle line), ``face`` ("inner" on the cavity, "outer", or
    "inside" the wall) and ``base``: the node lies within one wall thickness t0 of the
    clamped base or belongs to an element that touches it (the re-entrant corner's peak is
    singular: it grows under refinement, and the next rows of elements feel it)."""
    per = 3 if model.stadium else 2
    ref = np.asarray(model.reference).reshape(-1, per)
    height = ref[:, -1]
    if model.stadium:
        a = 0.5 * model.geometry.l
        radius = np.hypot(ref[:, 0], np.maximum(ref[:, 1] - a, 0.0))
    else:
        radius = ref[:, 0]
    _, nodes = _recovery(model)
    fixed = np.asarray(model.fixed[: model.n_u], bool).reshape(-1, per).all(axis=1)
    near = fixed[nodes].any(axis=1)
    base = height < model.geometry.t0
    base[nodes[near].ravel()] = True
    cavity, outer = _face_nodes(model)
    face = np.full(len(ref), "inside", dtype=object)
    face[cavity], face[outer] = "inner", "outer"
    return {"position": ref, "height": height, "radius": radius, "face": face, "base": base}


def _face_nodes(model) -> tuple[np.ndarray, np.ndarray]:
    """(cavity nodes, outer nodes) of the model's node numbering."""
    part = model.part
    section = part.section
    if model.stadium:
        st = part.node_of  # (station, section node) -> node
        return np.unique(st[:, section.cavity]), np.unique(st[:, section.outer])
    return np.asarray(section.cavity).ravel(), np.asarray(section.outer).ravel()


def cycle_fields(model, states) -> CycleFields:
    """The cycle's fields over the states ``states`` (the records' x, the rest first)."""
    rec = _recovery(model)
    fields = [wall_fields(model, x) for x in states]
    return over_cycle([nodal(model, f.stretch, rec) for f in fields],
                      [nodal(model, f.energy, rec) for f in fields], node_places(model))
