"""Hyperelastic laws, written once as W(I1, I2), used by the membrane solver and the FEM.

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

import numpy as np

from spsc.core.errors import ParameterError

__all__ = ["Material", "PROVENANCES", "neo_hookean", "mooney_rivlin", "yeoh",
           "polynomial_energy", "polynomial_dW", "polynomial_d2W"]

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
