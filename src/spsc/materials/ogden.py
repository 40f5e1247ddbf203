"""Ogden's law in the principal stretches, a solving law beside the polynomial family of
:mod:`.law` (issue 47).

W = Σk μk/αk (λ1^αk + λ2^αk + λ3^αk − 3) of the isochoric stretches (Ogden 1972, Proc. R.
Soc. A 326: 565), μk in MPa; the initial shear modulus is μ0 = ½ Σ μk αk. One term with
α = 2 is the neo-Hookean law (μ1 = μ0), and the pair (α = 2, α = −2) with μ1 = 2 C10,
μ2 = −2 C01 is Mooney–Rivlin (Σ λa^−2 = I2 when J = 1): the tests check both identities in
every model.

A law declares how the solvers read it (``kind``): ``"invariants"`` (W(I1, I2) with its
derivatives, :class:`~.law.Material`) or ``"stretches"`` (this one: the principal Kirchhoff
stresses of the isochoric stretches, :meth:`Ogden.kirchhoff`). The 3D FEM and the wall model
take either (:class:`~spsc.fem.material.NearlyIncompressible`), the membrane models too
(:mod:`spsc.membrane.tension`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from spsc.core.errors import ParameterError

from .kinematics import stretches

__all__ = ["Ogden", "ogden_energy", "ogden_nominal_stress", "ogden_log_hessian"]


def ogden_energy(mu, alpha, l1, l2, l3):
    """W (MPa) at the principal stretches (isochoric: λ1 λ2 λ3 = 1)."""
    return sum(m / a * (l1**a + l2**a + l3**a - 3.0) for m, a in zip(mu, alpha))


def ogden_nominal_stress(mu, alpha, test: str, lam):
    """Nominal stress P = Σ μk (λ1^αk − λ3^αk)/λ1 (MPa) of the homogeneous ``test``
    (:func:`~.kinematics.stretches`; direction 3 traction-free)."""
    l1, _, l3 = stretches(test, lam)
    return sum(m * (l1**a - l3**a) / l1 for m, a in zip(mu, alpha)) + 0.0 * l1


def ogden_log_hessian(mu, alpha, l1, l2, l3):
    """Drucker's matrix (H11, H12, H22) at the principal stretches, MPa: the derivatives of
    the stress differences σa − σ3 in the log strains."""
    H11 = sum(m * a * (l1**a + l3**a) for m, a in zip(mu, alpha))
    H12 = sum(m * a * l3**a for m, a in zip(mu, alpha))
    H22 = sum(m * a * (l2**a + l3**a) for m, a in zip(mu, alpha))
    return H11, H12, H22


@dataclass(frozen=True)
class Ogden:
    """Ogden's law: ``mu`` (MPa) and ``alpha`` (-), one pair per term.

    Parameters
    ----------
    name : catalogue key or the name a material file gives.
    mu, alpha : the terms' moduli and exponents (αk ≠ 0; μ0 = ½ Σ μk αk > 0).
    source, provenance : as :class:`~.law.Material`.
    """

    name: str
    mu: tuple[float, ...]
    alpha: tuple[float, ...]
    source: str = ""
    provenance: str = "assumed"
    law: str = "ogden"
    kind: ClassVar[str] = "stretches"

    def __post_init__(self):
        from .law import PROVENANCES

        object.__setattr__(self, "mu", tuple(float(v) for v in self.mu))
        object.__setattr__(self, "alpha", tuple(float(v) for v in self.alpha))
        if not self.mu or len(self.mu) != len(self.alpha):
            raise ParameterError(f"{self.name}: Ogden terms", f"{len(self.mu)} mu, "
                                 f"{len(self.alpha)} alpha", "as many mu as alpha, at least one")
        if any(a == 0.0 or not np.isfinite(a) for a in self.alpha) or \
                not all(np.isfinite(self.mu)):
            raise ParameterError(f"{self.name}: alpha", self.alpha, "finite, non-zero exponents")
        if self.provenance not in PROVENANCES:
            raise ParameterError(f"{self.name}: provenance", self.provenance,
                                 "one of " + ", ".join(PROVENANCES))
        if self.shear_modulus <= 0:
            raise ParameterError(f"{self.name}: initial shear modulus ½ Σ mu_k alpha_k",
                                 self.shear_modulus, "> 0 (MPa)")

    @property
    def assumed(self) -> bool:
        return self.provenance == "assumed"

    @property
    def shear_modulus(self) -> float:
        """μ0 = ½ Σ μk αk, MPa."""
        return 0.5 * float(np.dot(self.mu, self.alpha))

    @property
    def neo_hookean(self) -> bool:
        """One term with α = 2: exactly the neo-Hookean law."""
        return len(self.alpha) == 1 and self.alpha[0] == 2.0

    def identity(self) -> dict:
        """What the law is, for cache keys and records: its name and constants."""
        return {"law": self.law, "mu": list(self.mu), "alpha": list(self.alpha)}

    def scaled(self, s: float) -> "Ogden":
        """The law with W → s W (every μk × s)."""
        from dataclasses import replace

        return replace(self, mu=tuple(m * s for m in self.mu))

    def stretch_energy(self, l1, l2, l3):
        """W (MPa) at the principal stretches."""
        return ogden_energy(self.mu, self.alpha, l1, l2, l3)

    def kirchhoff(self, lb):
        """The isochoric part's principal Kirchhoff stresses (MPa), (…, 3), at the isochoric
        principal stretches ``lb`` (…, 3): τa = Σk μk (λ̄a^αk − ⅓ Σb λ̄b^αk), the deviatoric
        part of λa ∂W/∂λa."""
        tau = np.zeros_like(lb)
        for m, a in zip(self.mu, self.alpha):
            p = lb**a
            tau += m * (p - p.mean(axis=-1, keepdims=True))
        return tau

    def nominal_stress(self, test: str, lam):
        """Nominal stress P (MPa) of the homogeneous ``test`` at stretch ``lam``."""
        return ogden_nominal_stress(self.mu, self.alpha, test, lam)

    def log_hessian(self, l1, l2, l3):
        """Drucker's matrix (H11, H12, H22) at the principal stretches, MPa."""
        return ogden_log_hessian(self.mu, self.alpha, l1, l2, l3)
