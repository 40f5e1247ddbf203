"""Nearly incompressible hyperelasticity for the FEM, built on the one law of membrane/materials.

The strain energy is split (mixed u–p form, Taylor–Hood P2/P1):

    Ψ(F, p) = W(Ī1, Ī2) + p (J − 1) − p² / (2κ),

with W the catalogue law of :mod:`spsc.membrane.materials` evaluated at the isochoric invariants
Ī1 = J^(−2/3) I1, Ī2 = J^(−4/3) I2 of C = FᵀF, p the hydrostatic pressure field (MPa, positive in
tension) and κ the bulk modulus. Stationarity in p gives p = κ (J − 1); κ → ∞ is the
incompressible limit the membrane model uses. Everything works on whole arrays of deformation
gradients (shape ``(..., 3, 3)``), never on one element at a time.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError, require
from spsc.membrane.materials import Material

__all__ = ["NearlyIncompressible", "invariants"]

_I3 = np.eye(3)


def invariants(F):
    """(I1, I2, J) of C = FᵀF for an array of deformation gradients ``F`` (..., 3, 3)."""
    C = np.einsum("...ki,...kj->...ij", F, F)
    I1 = np.einsum("...ii->...", C)
    I2 = 0.5 * (I1**2 - np.einsum("...ij,...ij->...", C, C))
    return I1, I2, np.linalg.det(F)


@dataclass(frozen=True)
class NearlyIncompressible:
    """The law ``material`` (W(Ī1, Ī2), MPa) plus a volumetric part of bulk modulus κ (MPa).

    Parameters
    ----------
    material : Material
        The one hyperelastic definition (membrane/materials.py).
    bulk_ratio : float
        κ / μ0, default 2000 (Poisson's ratio 0.49975 at small strain). The mixed P2/P1
        formulation does not lock, so κ can be this large; it only has to make J − 1 negligible
        against the strains of interest (|J − 1| ≈ p/κ ≲ 1e-5 at 40 kPa).

    Notes
    -----
    With G = F⁻ᵀ, the first Piola–Kirchhoff stress is

        P = W1 ∂Ī1/∂F + W2 ∂Ī2/∂F + p J G,
        ∂Ī1/∂F = J^(−2/3) (2F − ⅔ I1 G),
        ∂Ī2/∂F = J^(−4/3) (2H − ⁴⁄₃ I2 G),   H = I1 F − F C,

    and the tangent 𝔸 = ∂P/∂F follows by differentiating once more with ∂J/∂F = J G and
    ∂G_iJ/∂F_kL = −G_iL G_kJ (see :meth:`stress_tangent`).
    """

    material: Material
    bulk_ratio: float = 2000.0

    def __post_init__(self):
        if not isinstance(self.material, Material):
            raise ParameterError("material", self.material, "a spsc.membrane.materials.Material")
        object.__setattr__(self, "bulk_ratio", require("bulk_ratio", self.bulk_ratio, gt=0))

    @property
    def mu(self) -> float:
        """Initial shear modulus μ0 (MPa)."""
        return self.material.shear_modulus

    @property
    def kappa(self) -> float:
        """Bulk modulus κ = bulk_ratio · μ0 (MPa)."""
        return self.bulk_ratio * self.mu

    def energy(self, F, p):
        """Ψ(F, p) in MPa for arrays F (..., 3, 3) and p (...)."""
        I1, I2, J = invariants(F)
        W = self.material.energy(J ** (-2 / 3) * I1, J ** (-4 / 3) * I2)
        return W + p * (J - 1.0) - p**2 / (2.0 * self.kappa)

    def stress(self, F, p):
        """First Piola–Kirchhoff stress P = ∂Ψ/∂F (MPa), shape (..., 3, 3)."""
        return self._stress(F, p)[0]

    def _stress(self, F, p):
        C = np.einsum("...ki,...kj->...ij", F, F)
        I1 = np.einsum("...ii->...", C)
        I2 = 0.5 * (I1**2 - np.einsum("...ij,...ij->...", C, C))
        J = np.linalg.det(F)
        G = np.swapaxes(np.linalg.inv(F), -1, -2)
        j23, j43 = J ** (-2 / 3), J ** (-4 / 3)
        W1, W2 = self.material.dW(j23 * I1, j43 * I2)
        H = I1[..., None, None] * F - F @ C
        d1 = j23[..., None, None] * (2.0 * F - (2 / 3) * I1[..., None, None] * G)
        d2 = j43[..., None, None] * (2.0 * H - (4 / 3) * I2[..., None, None] * G)
        P = (W1[..., None, None] * d1 + W2[..., None, None] * d2
             + (np.asarray(p) * J)[..., None, None] * G)
        return P, (C, I1, I2, J, G, j23, j43, H, d1, d2, W1, W2)

    def stress_tangent(self, F, p):
        """P (..., 3, 3) and 𝔸 = ∂P/∂F (..., 3, 3, 3, 3) with index order [i, J, k, L]."""
        P, (C, I1, I2, J, G, j23, j43, H, d1, d2, W1, W2) = self._stress(F, p)
        W11, W12, W22 = self.material.d2W(j23 * I1, j43 * I2)
        x = lambda a: a[..., None, None, None, None]  # noqa: E731 (broadcast a scalar field)
        o = lambda a, b: np.einsum("...ij,...kl->...ijkl", a, b)  # noqa: E731
        GG = np.einsum("...il,...kj->...ijkl", G, G)  # G_iL G_kJ
        II = np.einsum("ik,jl->ijkl", _I3, _I3)  # δ_ik δ_JL
        b = F @ np.swapaxes(F, -1, -2)
        # ∂d1/∂F
        dd1 = (-(2 / 3) * o(d1, G)
               + x(j23) * (2.0 * II - (4 / 3) * o(G, F) + (2 / 3) * x(I1) * GG))
        # ∂H/∂F = 2 F⊗F + I1 δ_ik δ_JL − δ_ik C_LJ − F_iL F_kJ − b_ik δ_JL
        dH = (2.0 * o(F, F) + x(I1) * II
              - np.einsum("ik,...lj->...ijkl", _I3, C)
              - np.einsum("...il,...kj->...ijkl", F, F)
              - np.einsum("...ik,jl->...ijkl", b, _I3))
        dd2 = (-(4 / 3) * o(d2, G)
               + x(j43) * (2.0 * dH - (8 / 3) * o(G, H) + (4 / 3) * x(I2) * GG))
        A = (x(W11) * o(d1, d1) + x(W12) * (o(d1, d2) + o(d2, d1)) + x(W22) * o(d2, d2)
             + x(W1) * dd1 + x(W2) * dd2
             + x(np.asarray(p) * J) * (o(G, G) - GG))
        return P, A
