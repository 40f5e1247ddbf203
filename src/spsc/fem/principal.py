"""A law in the principal stretches (Ogden's, :class:`spsc.materials.ogden.Ogden`) in the
nearly incompressible solids: the same split as :mod:`.material`,

    Ψ(F, p) = W(λ̄1, λ̄2, λ̄3) + p (J − 1) − p² / (2κ),   λ̄a = J^(−1/3) λa,

with the isochoric part's Kirchhoff stress τ = Σa τa na ⊗ na from the eigenvectors na of
b = F Fᵀ (a function of b, so well defined where stretches coincide, as in the undeformed
state) and the law's principal stresses τa (:meth:`~spsc.materials.ogden.Ogden.kirchhoff`);
P = (τ + p J I) F⁻ᵀ. The tangent ∂P/∂F is the stress's central difference (step
:data:`STEP` in each component of F: round-off and truncation both below 1e-9 of it), which
keeps Newton's convergence quadratic to the solvers' tolerances at 18 stress evaluations a
point.
"""

from __future__ import annotations

import numpy as np

__all__ = ["energy", "stress", "stress_tangent", "STEP"]

#: the step of the tangent's central differences, in F's components (dimensionless)
STEP = 1e-6


def _isochoric_stretches(F):
    """(λ̄ (…, 3), the eigenvectors of b (…, 3, 3), J)."""
    J = np.linalg.det(F)
    lam2, n = np.linalg.eigh(F @ np.swapaxes(F, -1, -2))
    return np.sqrt(np.maximum(lam2, 0.0)) * (J ** (-1.0 / 3.0))[..., None], n, J


def energy(material, F, p, kappa: float):
    """Ψ(F, p) in MPa for arrays F (…, 3, 3) and p (…)."""
    lb, _, J = _isochoric_stretches(F)
    W = material.stretch_energy(lb[..., 0], lb[..., 1], lb[..., 2])
    return W + p * (J - 1.0) - p**2 / (2.0 * kappa)


def stress(material, F, p):
    """The first Piola–Kirchhoff stress P (MPa), (…, 3, 3)."""
    lb, n, J = _isochoric_stretches(F)
    tau = material.kirchhoff(lb)
    T = (n * tau[..., None, :]) @ np.swapaxes(n, -1, -2)  # Σa τa na ⊗ na
    T = T + (np.asarray(p) * J)[..., None, None] * np.eye(3)
    return T @ np.swapaxes(np.linalg.inv(F), -1, -2)


def stress_tangent(material, F, p, step: float = STEP):
    """P and 𝔸 = ∂P/∂F (…, 3, 3, 3, 3), index order [i, J, k, L] (as the invariant laws')."""
    F = np.asarray(F, float)
    A = np.empty(F.shape + (3, 3))
    for k in range(3):
        for L in range(3):
            dF = np.zeros((3, 3))
            dF[k, L] = step
            A[..., k, L] = (stress(material, F + dF, p) - stress(material, F - dF, p)) / (2 * step)
    return stress(material, F, p), A
