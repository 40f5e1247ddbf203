"""The kinematics of the three homogeneous tests a material is fitted to (incompressible;
stretch λ ≥ 1 along direction 1, direction 3 traction-free):

- ``uniaxial``: λ1, λ2, λ3 = λ, λ^-1/2, λ^-1/2
- ``equibiaxial``: λ, λ, λ^-2
- ``planar`` (pure shear): λ, 1, λ^-1

and the invariants and log-strain derivatives the laws' stresses and Drucker tangents need.
"""

from __future__ import annotations

import numpy as np

__all__ = ["TESTS", "WORK_DIRECTIONS", "stretches", "invariants", "log_strain_derivatives"]

TESTS = ("uniaxial", "equibiaxial", "planar")
#: How many loaded directions do work in each test: dW/dλ = WORK_DIRECTIONS · P.
WORK_DIRECTIONS = {"uniaxial": 1, "equibiaxial": 2, "planar": 1}


def stretches(test: str, lam):
    """Principal stretches (λ1, λ2, λ3) of ``test`` at stretch ``lam`` (incompressible)."""
    lam = np.asarray(lam, float)
    if test == "uniaxial":
        return lam, lam**-0.5, lam**-0.5
    if test == "equibiaxial":
        return lam, lam, lam**-2.0
    if test == "planar":
        return lam, np.ones_like(lam), 1.0 / lam
    raise ValueError(f"unknown test {test!r}")


def invariants(l1, l2, l3):
    """I1 = Σ λi², I2 = Σ λi^-2 (= Σ λi²λj² when λ1λ2λ3 = 1)."""
    return l1**2 + l2**2 + l3**2, l1**-2.0 + l2**-2.0 + l3**-2.0


def log_strain_derivatives(l1, l2, l3):
    """Gradient and Hessian of I1 and I2 in the log strains (e1, e2), e3 = −e1 − e2:
    ((g1, H1), (g2, H2)) with g = (∂/∂e1, ∂/∂e2) and H = (∂11, ∂12, ∂22)."""
    a, b, c = l1**2, l2**2, l3**2
    g1 = (2 * (a - c), 2 * (b - c))
    H1 = (4 * (a + c), 4 * c, 4 * (b + c))
    g2 = (2 * (1 / c - 1 / a), 2 * (1 / c - 1 / b))
    H2 = (4 * (1 / a + 1 / c), 4 / c, 4 * (1 / b + 1 / c))
    return (g1, H1), (g2, H2)
