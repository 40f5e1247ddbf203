"""Hyperelastic laws for fitting: closed-form incompressible nominal stress of the three
homogeneous tests, energy and Drucker tangent, for the invariant laws of :mod:`.law`
(neo-Hookean, Mooney–Rivlin, Yeoh: the same W(I1, I2)) and Ogden's law in principal stretches.

The tests (stretch λ ≥ 1 along direction 1, direction 3 traction-free, incompressible):

- ``uniaxial``: λ1, λ2, λ3 = λ, λ^-1/2, λ^-1/2
- ``equibiaxial``: λ, λ, λ^-2
- ``planar`` (pure shear): λ, 1, λ^-1

The nominal (engineering) stress along 1 is P = (σ1 − σ3)/λ1 with σi − σ3 = λi ∂W/∂λi −
λ3 ∂W/∂λ3. For W(I1, I2): P = 2 (λ1 − λ3²/λ1)(W1 + λ2² W2), i.e. 2(λ − λ^-2)(W1 + W2/λ)
uniaxial, 2(λ − λ^-5)(W1 + λ² W2) equibiaxial, 2(λ − λ^-3)(W1 + W2) planar. Ogden,
W = Σ μk/αk (λ1^αk + λ2^αk + λ3^αk − 3): P = Σ μk (λ1^αk − λ3^αk)/λ1; initial shear modulus
μ0 = ½ Σ μk αk. Stresses in MPa (the constants' unit).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..file import LAW_CONSTANTS
from ..kinematics import TESTS, WORK_DIRECTIONS, stretches
from ..law import Material, log_hessian, nominal_stress, stretch_energy
from ..ogden import Ogden, ogden_energy, ogden_log_hessian, ogden_nominal_stress

__all__ = ["TESTS", "WORK_DIRECTIONS", "LAW_NAMES", "stretches", "PolynomialLaw", "OgdenLaw",
           "law"]

LAW_NAMES = ("neo-hookean", "mooney-rivlin", "yeoh", "ogden")


@dataclass(frozen=True)
class PolynomialLaw:
    """A law W = Σ C_ij (I1 − 3)^i (I2 − 3)^j with named constants (MPa), linear in them."""

    name: str

    @property
    def exponents(self) -> tuple[tuple[int, int], ...]:
        return tuple(LAW_CONSTANTS[self.name].values())

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(LAW_CONSTANTS[self.name])

    @property
    def lower(self) -> np.ndarray:
        """Bounds of the fit: C10 ≥ 0 for neo-Hookean and Yeoh (their μ0 = 2 C10); free else."""
        lo = np.full(len(self.names), -np.inf)
        if self.name in ("neo-hookean", "yeoh"):
            lo[0] = 0.0
        return lo

    @property
    def upper(self) -> np.ndarray:
        return np.full(len(self.names), np.inf)

    def coefficients(self, params) -> tuple[tuple[int, int, float], ...]:
        return tuple((i, j, float(c)) for (i, j), c in zip(self.exponents, params))

    def stress(self, test: str, lam, params) -> np.ndarray:
        """Nominal stress P (MPa) of ``test`` at stretch ``lam``: the solving law's own
        (:meth:`Material.nominal_stress`), for the constants ``params``."""
        return nominal_stress(self.coefficients(params), test, lam)

    def jacobian(self, test: str, lam, params) -> np.ndarray:
        """∂P/∂C (n, p): the stress is linear in the constants, each column the stress of a
        unit constant."""
        eye = np.eye(len(self.names))
        return np.column_stack([self.stress(test, lam, e) for e in eye])

    def energy(self, l1, l2, l3, params):
        """W (MPa) at the principal stretches (incompressible)."""
        return stretch_energy(self.coefficients(params), l1, l2, l3)

    def log_hessian(self, l1, l2, l3, params):
        """(H11, H12, H22): Drucker's matrix, MPa (:meth:`Material.log_hessian`)."""
        return log_hessian(self.coefficients(params), l1, l2, l3)

    def material(self, params, *, name: str, source: str = "",
                 provenance: str = "user-fit") -> Material:
        """The solving law of the constants ``params``: the :class:`Material` every model
        takes (checked: μ0 > 0)."""
        return Material(name, self.name, self.coefficients(params), source, provenance)

    def shear_modulus(self, params) -> float:
        """μ0 = 2 (C10 + C01), MPa."""
        d = dict(zip(self.names, params))
        return 2.0 * (d["C10"] + d.get("C01", 0.0))

    def constants(self, params) -> dict:
        return {n: float(v) for n, v in zip(self.names, params)}

    def starts(self, fit_linear) -> list[np.ndarray]:
        """Initial guesses: the linear least-squares solution (``fit_linear(jacobian_of)``)."""
        return [fit_linear(lambda test, lam: self.jacobian(test, lam, None))]


@dataclass(frozen=True)
class OgdenLaw:
    """Ogden's law with ``terms`` pairs (μk MPa, αk -), W = Σ μk/αk (Σi λi^αk − 3)."""

    terms: int = 2
    name: str = "ogden"
    #: |αk| bound of the fit (keeps λ^α finite over the checked stretches).
    alpha_max: float = 25.0

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(n for k in range(1, self.terms + 1) for n in (f"mu{k}", f"alpha{k}"))

    @property
    def lower(self) -> np.ndarray:
        return np.tile([-np.inf, -self.alpha_max], self.terms)

    @property
    def upper(self) -> np.ndarray:
        return np.tile([np.inf, self.alpha_max], self.terms)

    def split(self, params):
        p = np.asarray(params, float)
        return p[0::2], p[1::2]

    def stress(self, test: str, lam, params) -> np.ndarray:
        return ogden_nominal_stress(*self.split(params), test, lam)

    def jacobian(self, test: str, lam, params) -> np.ndarray:
        l1, _, l3 = stretches(test, lam)
        mu, alpha = self.split(params)
        cols = []
        for m, a in zip(mu, alpha):
            cols.append((l1**a - l3**a) / l1)
            cols.append(m * (l1**a * np.log(l1) - l3**a * np.log(l3)) / l1)
        return np.column_stack(cols)

    def energy(self, l1, l2, l3, params):
        return ogden_energy(*self.split(params), l1, l2, l3)

    def log_hessian(self, l1, l2, l3, params):
        return ogden_log_hessian(*self.split(params), l1, l2, l3)

    def material(self, params, *, name: str, source: str = "",
                 provenance: str = "user-fit") -> Ogden:
        """The solving law of the constants ``params`` (:class:`~..ogden.Ogden`: the wall
        model, the 3D FEM and the membranes take it; checked: μ0 > 0)."""
        mu, alpha = self.split(params)
        return Ogden(name, tuple(mu), tuple(alpha), source, provenance)

    def shear_modulus(self, params) -> float:
        mu, alpha = self.split(params)
        return 0.5 * float(np.dot(mu, alpha))

    def constants(self, params) -> dict:
        mu, alpha = self.split(params)
        return {"mu": [float(v) for v in mu], "alpha": [float(v) for v in alpha]}

    def starts(self, fit_linear) -> list[np.ndarray]:
        """Initial guesses: for each exponent set of :data:`_OGDEN_ALPHAS`, the moduli μk by
        linear least squares (the stress is linear in μ at fixed α)."""
        out = []
        for alphas in _OGDEN_ALPHAS[self.terms]:
            def jac(test, lam, alphas=alphas):
                full = np.column_stack([np.ones(len(alphas)), alphas]).ravel()
                return self.jacobian(test, lam, full)[:, 0::2]
            mu = fit_linear(jac)
            out.append(np.column_stack([mu, alphas]).ravel())
        return out


#: Deterministic starting exponents of Ogden fits (a few sign and size patterns, including
#: Ogden's 1972 Treloar exponents 1.3, 5, −2).
_OGDEN_ALPHAS = {
    1: [(2.0,), (-2.0,), (1.3,), (4.0,)],
    2: [(1.3, 5.0), (2.0, -2.0), (1.0, 4.0), (3.0, -1.0), (0.5, 8.0)],
    3: [(1.3, 5.0, -2.0), (2.0, 6.0, -2.0), (1.0, 3.0, -1.0), (0.5, 4.0, -3.0),
        (1.5, 8.0, -1.0)],
}


def law(name: str, *, ogden_terms: int = 2):
    """The fitting law ``name`` (one of :data:`LAW_NAMES`)."""
    if name == "ogden":
        return OgdenLaw(ogden_terms)
    if name in LAW_CONSTANTS:
        return PolynomialLaw(name)
    raise ValueError(f"unknown law {name!r}")
