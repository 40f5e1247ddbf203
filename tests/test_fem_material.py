"""The FEM's nearly incompressible law: built on spsc.materials, consistent stress and
tangent, Hooke's law at small strain."""

import numpy as np
import pytest

from spsc.fem.material import NearlyIncompressible, compiled_invariants, invariants
from spsc.materials import material, mooney_rivlin, yeoh

LAWS = [material("tpu60a"), mooney_rivlin(0.3, 0.1), yeoh(0.5056, 0.01, 0.002562)]


def _random_F(n, seed=0, scale=0.3):
    rng = np.random.default_rng(seed)
    F = np.eye(3) + scale * rng.standard_normal((n, 3, 3))
    F[np.linalg.det(F) < 0] *= -1  # keep det F > 0
    return F, rng.standard_normal(n)


@pytest.mark.parametrize("mat", LAWS, ids=lambda m: m.name)
def test_stress_and_tangent_are_derivatives(mat):
    law = NearlyIncompressible(mat, bulk_ratio=10.0)
    F, p = _random_F(5)
    P, A = law.stress_tangent(F, p)
    h = 1e-6
    Pn, An = np.zeros_like(P), np.zeros_like(A)
    for k in range(3):
        for l in range(3):
            E = np.zeros((3, 3))
            E[k, l] = h
            Pn[..., k, l] = (law.energy(F + E, p) - law.energy(F - E, p)) / (2 * h)
            An[..., k, l] = (law.stress(F + E, p) - law.stress(F - E, p)) / (2 * h)
    # central differences with h = 1e-6 on O(1) values: truncation ~1e-12, round-off ~1e-10
    np.testing.assert_allclose(P, Pn, rtol=0, atol=1e-7 * np.abs(P).max())
    np.testing.assert_allclose(A, An, rtol=0, atol=1e-7 * np.abs(A).max())
    # major symmetry of a hyperelastic tangent
    np.testing.assert_allclose(A, np.einsum("...ijkl->...klij", A), rtol=0, atol=1e-10)


@pytest.mark.parametrize("mat", LAWS, ids=lambda m: m.name)
def test_compiled_kernel_is_the_numpy_law(mat):
    """The Numba kernel (spsc.fem.material_kernel) against the NumPy formulas: the same sums in
    another order, so equal to round-off (1e-13 of the largest entry: 100 ulp)."""
    from spsc.fem.material import COMPILED

    if not COMPILED:
        pytest.skip("Numba is not installed: the NumPy formulas are the law")
    law = NearlyIncompressible(mat, bulk_ratio=10.0)
    F, p = _random_F(60, seed=3)
    F, p = F.reshape(3, 20, 3, 3), p.reshape(3, 20)  # any leading shape
    for pressure in (p, 0.0):
        P, A = law.stress_tangent(F, pressure)
        P0, A0 = law.stress_tangent_numpy(F, pressure)
        assert P.shape == P0.shape and A.shape == A0.shape
        np.testing.assert_allclose(P, P0, rtol=0, atol=1e-13 * np.abs(P0).max())
        np.testing.assert_allclose(A, A0, rtol=0, atol=1e-13 * np.abs(A0).max())
        np.testing.assert_allclose(law.stress(F, pressure), law.stress_numpy(F, pressure),
                                   rtol=0, atol=1e-13 * np.abs(P0).max())
    I1, I2, J = invariants(F)
    np.testing.assert_allclose(np.stack(compiled_invariants(F)), np.stack([I1, I2, J]),
                               rtol=1e-14, atol=0)


def test_compiled_cofactor_and_determinant():
    """J and J F⁻ᵀ of the compiled kernel against NumPy's LU-based det and inv (1e-13)."""
    from spsc.fem.material_kernel import cofactor, determinant

    F, _ = _random_F(40, seed=5)
    F = F.reshape(2, 20, 3, 3)
    J, cof = cofactor(F)
    J0 = np.linalg.det(F)
    np.testing.assert_allclose(determinant(F), J0, rtol=1e-13, atol=0)
    np.testing.assert_allclose(J, J0, rtol=1e-13, atol=0)
    np.testing.assert_allclose(cof, J0[..., None, None] * np.swapaxes(np.linalg.inv(F), -1, -2),
                               rtol=0, atol=1e-13 * np.abs(cof).max())


def test_isochoric_part_is_the_membrane_law():
    """On isochoric F (J = 1, p = 0) the energy is exactly W(I1, I2) of spsc.materials."""
    mat = yeoh(0.5056, 0.01, 0.002562)
    law = NearlyIncompressible(mat)
    lam = np.array([0.7, 1.3, 2.0])
    F = np.zeros((3, 3, 3))
    F[:, 0, 0], F[:, 1, 1], F[:, 2, 2] = lam, lam, 1 / lam**2
    I1, I2, J = invariants(F)
    np.testing.assert_allclose(J, 1.0, rtol=0, atol=1e-14)
    np.testing.assert_allclose(law.energy(F, 0.0), mat.energy(I1, I2), rtol=1e-13, atol=0)


def test_small_strain_is_hooke():
    """Linearised at F = I the tangent is isotropic Hooke with μ = μ0 and K = κ (p = κ ε_v)."""
    mat = material("tpu60a")
    law = NearlyIncompressible(mat, bulk_ratio=50.0)
    _, A = law.stress_tangent(np.eye(3)[None], np.zeros(1))
    mu = mat.shear_modulus
    # at p = 0 the volumetric stiffness enters through the pressure field (mixed form), so the
    # displacement block alone is the deviatoric Hooke tensor 2μ(𝕀_sym − ⅓ I⊗I)
    I = np.eye(3)
    sym = 0.5 * (np.einsum("ik,jl->ijkl", I, I) + np.einsum("il,jk->ijkl", I, I))
    dev = 2 * mu * (sym - np.einsum("ij,kl->ijkl", I, I) / 3)
    # the skew part of A at F = I is the initial-stress term, zero at zero stress
    A_sym = 0.5 * (A[0] + np.einsum("ijkl->jikl", A[0]))
    np.testing.assert_allclose(A_sym, dev, rtol=0, atol=1e-12)
