"""Hyperelastic laws, written once as W(I1, I2), used by the membrane solver, the wall model
and the FEM — and, through :meth:`Material.nominal_stress` and :meth:`Material.log_hessian`, by
the fitting of laws to tension tests and their Drucker check (:mod:`.fit_laws` evaluates a
trial law with these same functions), so a fitted law is the law the models solve with.

A law is a polynomial in the invariants, W = Σ C_ij (I1 − 3)^i (I2 − 3)^j (MPa), which covers
neo-Hookean (C10), Mooney–Rivlin (C10, C01) and Yeoh 3rd order (C10, C20, C30). For the
incompressible membrane the invariants are those of eq. 24; the nearly incompressible FEM uses
the isochoric invariants Ī1, Ī2 in the same functions plus its own volumetric term.

Each material records where its numbers come from (``provenance``: datasheet, paper,
literature, assumed or user-fit) beside the ``source`` text. The catalogue and the resolver of
a name or a material file are in :mod:`.catalogue`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from spsc.core.errors import ParameterError
from .kinematics import invariants, log_strain_derivatives, stretches

__all__ = ["Material", "PROVENANCES", "neo_hookean", "mooney_rivlin", "yeoh",
           "polynomial_energy", "polynomial_dW", "polynomial_d2W", "nominal_stress",
           "stretch_energy", "log_hessian", "uniaxial_isochoric_stress"]

#: Where a material's constants come from, from most to least trusted for a printed part:
#: ``user-fit`` (fitted to the user's own tests), ``literature`` (a published fit of the
#: material), ``paper`` (a value the SPSC paper states), ``datasheet`` (a manufacturer's
#: figure, linearised), ``assumed`` (no measurement of this material: an estimate).
PROVENANCES = ("user-fit", "literature", "paper", "datasheet", "assumed")


def _shifted(I1, I2):
    return np.asarray(I1, float) - 3.0, np.asarray(I2, float) - 3.0


def polynomial_energy(coefficients, I1, I2):
    """W = Σ C_ij (I1 − 3)^i (I2 − 3)^j in MPa for ``coefficients`` ((i, j, C_ij), ...)."""
    a, b = _shifted(I1, I2)
    return sum(c * a**i * b**j for i, j, c in coefficients)


def polynomial_dW(coefficients, I1, I2):
    """(∂W/∂I1, ∂W/∂I2) in MPa of the polynomial ``coefficients``."""
    a, b = _shifted(I1, I2)
    W1 = sum(c * i * a ** (i - 1) * b**j for i, j, c in coefficients if i > 0)
    W2 = sum(c * j * a**i * b ** (j - 1) for i, j, c in coefficients if j > 0)
    return W1 + 0.0 * a, W2 + 0.0 * b


def polynomial_d2W(coefficients, I1, I2):
    """(∂²W/∂I1², ∂²W/∂I1∂I2, ∂²W/∂I2²) in MPa of the polynomial ``coefficients``."""
    a, b = _shifted(I1, I2)
    z = 0.0 * a * b
    W11 = sum(c * i * (i - 1) * a ** (i - 2) * b**j for i, j, c in coefficients if i > 1)
    W12 = sum(c * i * j * a ** (i - 1) * b ** (j - 1) for i, j, c in coefficients
              if i > 0 and j > 0)
    W22 = sum(c * j * (j - 1) * a**i * b ** (j - 2) for i, j, c in coefficients if j > 1)
    return W11 + z, W12 + z, W22 + z


def nominal_stress(coefficients, test: str, lam):
    """Nominal stress P (MPa) along 1 of the homogeneous ``test`` at stretch ``lam``
    (:mod:`.kinematics`): P = (σ1 − σ3)/λ1 = 2 (λ1 − λ3²/λ1)(W1 + λ2² W2)."""
    l1, l2, l3 = stretches(test, lam)
    W1, W2 = polynomial_dW(coefficients, *invariants(l1, l2, l3))
    return 2.0 * (l1 - l3**2 / l1) * (W1 + l2**2 * W2)


def uniaxial_isochoric_stress(material, lam) -> np.ndarray:
    """(S_iso,11, S_iso,22) (n, 2), MPa: the isochoric second Piola–Kirchhoff stress of
    ``material`` (its ``dW``) in incompressible uniaxial tension at the stretches ``lam``, the
    deviatoric part the wall's rate and softening laws act on (:mod:`spsc.fem.viscous`,
    :mod:`spsc.fem.mullins`)."""
    lam = np.asarray(lam, float)
    c1, c2 = lam * lam, 1.0 / lam
    i1 = c1 + 2.0 * c2
    i2 = 2.0 * lam + c2 * c2  # C₂₂C₃₃ + 2 C₁₁C₂₂ = 1/λ² + 2λ
    w1, w2 = (np.asarray(v, float) for v in material.dW(i1, i2))
    k = 2.0 / 3.0 * (i1 * w1 + 2.0 * i2 * w2)
    s11 = 2.0 * (w1 + i1 * w2) - 2.0 * w2 * c1 - k / c1
    s22 = 2.0 * (w1 + i1 * w2) - 2.0 * w2 * c2 - k / c2
    return np.column_stack([s11, s22])


def stretch_energy(coefficients, l1, l2, l3):
    """W (MPa) at the principal stretches of an incompressible state."""
    return polynomial_energy(coefficients, *invariants(l1, l2, l3))


def log_hessian(coefficients, l1, l2, l3):
    """(H11, H12, H22): the Hessian of W in the log strains (e1, e2), the tangent dσ_a/dε_b of
    the stress differences σa − σ3 (Drucker's matrix), MPa."""
    I1, I2 = invariants(l1, l2, l3)
    W1, W2 = polynomial_dW(coefficients, I1, I2)
    W11, W12, W22 = polynomial_d2W(coefficients, I1, I2)
    (g1, H1), (g2, H2) = log_strain_derivatives(l1, l2, l3)
    out = []
    for (a, b), k in (((0, 0), 0), ((0, 1), 1), ((1, 1), 2)):
        out.append(W1 * H1[k] + W2 * H2[k] + W11 * g1[a] * g1[b]
                   + W12 * (g1[a] * g2[b] + g2[a] * g1[b]) + W22 * g2[a] * g2[b])
    return tuple(out)


@dataclass(frozen=True)
class Material:
    """W(I1, I2) = Σ C_ij (I1 − 3)^i (I2 − 3)^j, coefficients in MPa.

    Parameters
    ----------
    name : str
        Catalogue key, or the name a material file gives.
    law : str
        ``neo-hookean``, ``mooney-rivlin`` or ``yeoh`` (for reports).
    coefficients : tuple of (i, j, C_ij)
        Exponents and coefficient (MPa). Initial shear modulus μ0 = 2(C10 + C01) must be > 0.
    source : str
        Where the numbers come from, in words (a datasheet, a paper, the files of a fit).
    provenance : str
        The kind of source, one of :data:`PROVENANCES`; ``assumed`` (the default) marks values
        not taken from a measurement of the material.
    """

    name: str
    law: str
    coefficients: tuple[tuple[int, int, float], ...]
    source: str = ""
    provenance: str = "assumed"
    #: how the solvers read it: W(I1, I2) and its derivatives (:mod:`.ogden`: "stretches")
    kind: ClassVar[str] = "invariants"

    def __post_init__(self):
        if self.provenance not in PROVENANCES:
            raise ParameterError(f"{self.name}: provenance", self.provenance,
                                 "one of " + ", ".join(PROVENANCES))
        if self.shear_modulus <= 0:
            raise ParameterError(f"{self.name}: initial shear modulus 2(C10 + C01)",
                                 self.shear_modulus, "> 0 (MPa)")

    @property
    def assumed(self) -> bool:
        """True when the constants are an estimate, not from a measurement of the material."""
        return self.provenance == "assumed"

    @property
    def neo_hookean(self) -> bool:
        """W = C10 (I1 − 3) alone."""
        return [(i, j) for i, j, c in self.coefficients if c != 0] == [(1, 0)]

    def identity(self) -> dict:
        """What the law is, for cache keys and records: its name and coefficients."""
        return {"law": self.law, "coefficients": [list(c) for c in self.coefficients]}

    def scaled(self, s: float) -> "Material":
        """The law with W → s W (every coefficient × s)."""
        from dataclasses import replace

        return replace(self, coefficients=tuple((i, j, c * s) for i, j, c in self.coefficients))

    def _c(self, i: int, j: int) -> float:
        return sum(c for a, b, c in self.coefficients if (a, b) == (i, j))

    @property
    def shear_modulus(self) -> float:
        """Initial shear modulus μ0 = 2(C10 + C01) in MPa."""
        return 2.0 * (self._c(1, 0) + self._c(0, 1))

    def energy(self, I1, I2):
        """Strain energy density W in MPa (= mJ/mm³)."""
        return polynomial_energy(self.coefficients, I1, I2)

    def dW(self, I1, I2):
        """(∂W/∂I1, ∂W/∂I2) in MPa, the factors of eqs. 22–23."""
        return polynomial_dW(self.coefficients, I1, I2)

    def d2W(self, I1, I2):
        """(∂²W/∂I1², ∂²W/∂I1∂I2, ∂²W/∂I2²) in MPa, for consistent tangents."""
        return polynomial_d2W(self.coefficients, I1, I2)

    # the same law in the tests it is fitted to (spsc fit-material, Drucker's check)
    def nominal_stress(self, test: str, lam):
        """Nominal stress P (MPa) of the homogeneous ``test`` at stretch ``lam``."""
        return nominal_stress(self.coefficients, test, lam)

    def log_hessian(self, l1, l2, l3):
        """Drucker's matrix (H11, H12, H22) at the principal stretches, MPa."""
        return log_hessian(self.coefficients, l1, l2, l3)


def neo_hookean(mu: float, *, name: str = "neo-hookean", source: str = "",
                provenance: str = "assumed") -> Material:
    """Neo-Hookean W = (μ/2)(I1 − 3), μ in MPa."""
    return Material(name, "neo-hookean", ((1, 0, mu / 2.0),), source, provenance)


def mooney_rivlin(c10: float, c01: float, *, name: str = "mooney-rivlin", source: str = "",
                  provenance: str = "assumed") -> Material:
    """Mooney–Rivlin W = C10(I1 − 3) + C01(I2 − 3), MPa."""
    return Material(name, "mooney-rivlin", ((1, 0, c10), (0, 1, c01)), source, provenance)


def yeoh(c10: float, c20: float, c30: float, *, name: str = "yeoh", source: str = "",
         provenance: str = "assumed") -> Material:
    """Yeoh 3rd order W = C10(I1 − 3) + C20(I1 − 3)² + C30(I1 − 3)³, MPa."""
    return Material(name, "yeoh", ((1, 0, c10), (2, 0, c20), (3, 0, c30)), source, provenance)
