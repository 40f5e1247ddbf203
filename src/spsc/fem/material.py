"""Nearly incompressible hyperelasticity for the FEM, built on the one law of spsc.materials.

The strain energy is split (mixed u–p form, Taylor–Hood P2/P1):

    Ψ(F, p) = W(Ī1, Ī2) + p (J − 1) − p² / (2κ),

with W the catalogue law of :mod:`spsc.materials` evaluated at the isochoric invariants
Ī1 = J^(−2/3) I1, Ī2 = J^(−4/3) I2 of C = FᵀF, p the hydrostatic pressure field (MPa, positive in
tension) and κ the bulk modulus. Stationarity in p gives p = κ (J − 1); κ → ∞ is the
incompressible limit the membrane model uses. Everything works on whole arrays of deformation
gradients (shape ``(..., 3, 3)``), never on one element at a time.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError, require
from spsc.materials import Material

from .principal import energy as principal_energy, stress as principal_stress, \
    stress_tangent as principal_stress_tangent
from .material_kernel import AVAILABLE as COMPILED, invariants as compiled_invariants, \
    stress as compiled_stress, stress_tangent as compiled_stress_tangent

__all__ = ["NearlyIncompressible", "invariants"]

_I3 = np.eye(3)


def invariants(F):
    """(I1, I2, J) of C = FᵀF for an array of deformation gradients ``F`` (..., 3, 3)."""
    C = np.einsum("...ki,...kj->...ij", F, F)
    I1 = np.einsum("...ii->...", C)
    I2 = 0.5 * (I1**2 - np.einsum("...ij,...ij->...", C, C))
    return I1, I2, np.linalg.det(F)


def _isochoric_invariants(F):
    """(Ī1, Ī2) = (J^(−2/3) I1, J^(−4/3) I2) of ``F`` by the compiled kernel."""
    I1, I2, J = compiled_invariants(F)
    return J ** (-2 / 3) * I1, J ** (-4 / 3) * I2


@dataclass(frozen=True)
class NearlyIncompressible:
    """The law ``material`` (W(Ī1, Ī2), MPa) plus a volumetric part of bulk modulus κ (MPa).

    Parameters
    ----------
    material : Material
        The one hyperelastic definition (spsc/materials/law.py).
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
        if getattr(self.material, "kind", None) not in ("invariants", "stretches"):
            raise ParameterError("material", self.material, "a law of spsc.materials (W(I1, "
                                 "I2) or in the principal stretches)")
        object.__setattr__(self, "bulk_ratio", require("bulk_ratio", self.bulk_ratio, gt=0))

    @property
    def mu(self) -> float:
        """Initial shear modulus μ0 (MPa)."""
        return self.material.shear_modulus

    @property
    def kappa(self) -> float:
        """Bulk modulus κ = bulk_ratio · μ0 (MPa)."""
        return self.bulk_ratio * self.mu

    @property
    def _stretches(self) -> bool:
        """The law is written in the principal stretches (:mod:`.principal`)."""
        return self.material.kind == "stretches"

    def energy(self, F, p):
        """Ψ(F, p) in MPa for arrays F (..., 3, 3) and p (...)."""
        if self._stretches:
            return principal_energy(self.material, F, p, self.kappa)
        I1, I2, J = invariants(F)
        W = self.material.energy(J ** (-2 / 3) * I1, J ** (-4 / 3) * I2)
        return W + p * (J - 1.0) - p**2 / (2.0 * self.kappa)

    def stress(self, F, p):
        """First Piola–Kirchhoff stress P = ∂Ψ/∂F (MPa), shape (..., 3, 3): compiled
        (:mod:`.material_kernel`) where Numba is installed, else :meth:`stress_numpy`; a law
        in the principal stretches by :mod:`.principal`."""
        if self._stretches:
            return principal_stress(self.material, F, p)
        if not COMPILED:
            return self.stress_numpy(F, p)
        return compiled_stress(F, p, *self.material.dW(*_isochoric_invariants(F)))

    def stress_numpy(self, F, p):
        """:meth:`stress` in NumPy (the fallback, and the compiled kernel's reference)."""
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
        """P (..., 3, 3) and 𝔸 = ∂P/∂F (..., 3, 3, 3, 3) with index order [i, J, k, L]:
        compiled (:mod:`.material_kernel`) where Numba is installed, else
        :meth:`stress_tangent_numpy`; a law in the principal stretches by :mod:`.principal`."""
        if self._stretches:
            return principal_stress_tangent(self.material, F, p)
        if not COMPILED:
            return self.stress_tangent_numpy(F, p)
        Ib1, Ib2 = _isochoric_invariants(F)
        return compiled_stress_tangent(F, p, *self.material.dW(Ib1, Ib2),
                                       *self.material.d2W(Ib1, Ib2))

    def stress_tangent_numpy(self, F, p):
        """P and 𝔸 in NumPy (the fallback, and the compiled kernel's reference).

        Built on flattened components (iJ, kL) = (3i + J, 3k + L): the outer-product terms
        as one small matrix product Uᵀ M U over U = (d1, d2, G, F, H), the δ-terms as 3×3
        blocks and the two swapped products X_iL Y_kJ by broadcasting."""
        P, (C, I1, I2, J, G, j23, j43, H, d1, d2, W1, W2) = self._stress(F, p)
        W11, W12, W22 = self.material.d2W(j23 * I1, j43 * I2)
        shape = F.shape[:-2]
        pJ = np.asarray(p) * J
        a1, a2 = W1 * j23, W2 * j43
        U = np.stack([d1, d2, G, F, H], axis=-3).reshape(shape + (5, 9))
        M = np.zeros(shape + (5, 5))
        M[..., 0, 0], M[..., 1, 1] = W11, W22
        M[..., 0, 1] = M[..., 1, 0] = W12
        M[..., 0, 2] = -(2 / 3) * W1  # ∂d1/∂F ∋ −⅔ d1⊗G
        M[..., 1, 2] = -(4 / 3) * W2  # ∂d2/∂F ∋ −⁴⁄₃ d2⊗G
        M[..., 2, 3] = -(4 / 3) * a1  # −⁴⁄₃ j23 G⊗F
        M[..., 3, 3] = 4.0 * a2  # 2 j43 · 2 F⊗F
        M[..., 2, 4] = -(8 / 3) * a2  # −⁸⁄₃ j43 G⊗H
        M[..., 2, 2] = pJ  # p J G⊗G
        A = np.swapaxes(U, -1, -2) @ (M @ U)
        # δ_ik δ_JL (the diagonal), δ_ik C_LJ and b_ik δ_JL (C, b symmetric): 3×3 blocks
        A.reshape(shape + (81,))[..., ::10] += (2.0 * a1 + 2.0 * a2 * I1)[..., None]
        A4 = A.reshape(shape + (3, 3, 3, 3))
        two_a2 = (2.0 * a2)[..., None, None]
        C2, b2 = two_a2 * C, two_a2 * (F @ np.swapaxes(F, -1, -2))
        for i in range(3):
            A4[..., i, :, i, :] -= C2
            A4[..., :, i, :, i] -= b2
        # swapped products G_iL G_kJ and F_iL F_kJ
        cG = ((2 / 3) * a1 * I1 + (4 / 3) * a2 * I2 - pJ)[..., None, None]
        Gt, Ft = np.swapaxes(cG * G, -1, -2), np.swapaxes(two_a2 * F, -1, -2)
        A4 += (G[..., :, None, None, :] * Gt[..., None, :, :, None]
               - F[..., :, None, None, :] * Ft[..., None, :, :, None])
        return P, A4

