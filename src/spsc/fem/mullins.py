"""The Mullins effect: stress softening after a first loading, as Ogden and Roxburgh's
pseudo-elastic model (R. W. Ogden, D. G. Roxburgh, "A pseudo-elastic model for the Mullins
effect in filled rubber", Proc. R. Soc. Lond. A 455 (1999) 2861-2877, eqs. 5.1-5.3, with the
β W_m term of Dorfmann & Ogden 2004) over the nearly incompressible law of :mod:`.material`.

A damage variable η scales the isochoric stress:

    S = S_vol + η S_iso,      η = 1 − (1/r) erf((W_m − W₀) / (m + β W_m)),          (M1)

with W₀ = W(Ī1, Ī2) the virgin material's isochoric energy at the current deformation and W_m
its largest value so far at that point. On the primary path (W₀ = W_m) η = 1, the law is the
hyperelastic one; unloading (W₀ < W_m) follows a softer curve, and reloading retraces it up to
W_m, where the primary path resumes: a first cycle dissipates, later ones to the same extent
do not. r > 1 sets how much softer (η at full unloading is 1 − erf(W_m/(m + βW_m))/r), m
(MPa) and β (-) how the softening spreads with the energy. The first Piola stress and its
tangent (P_iso = ∂W₀/∂F, 𝔸 = ∂P/∂F) are

    P = P_base + (η − 1) P_iso,
    𝔸 = 𝔸_base + (η − 1) 𝔸_iso + (∂η/∂W₀) P_iso ⊗ P_iso,
    ∂η/∂W₀ = 2 exp(−a²) / (r √π (m + β W_m)),   a = (W_m − W₀)/(m + β W_m),

with W_m held over a step and updated when the step is committed (:meth:`commit`).
"""

from __future__ import annotations

import numpy as np

from spsc.materials.mullins import MullinsParams

__all__ = ["MullinsParams", "MullinsLaw"]


class MullinsLaw:
    """``base`` (:class:`~spsc.fem.material.NearlyIncompressible`) softened by the Mullins
    effect (``params``), with its largest energy W_m at every quadrature point (allocated at
    the first call, by the shape of F, from the undeformed state: 0). :meth:`commit` with the
    converged deformation gradients closes a step."""

    def __init__(self, base, params: MullinsParams):
        self.base, self.params = base, params
        self.kappa, self.mu, self.material = base.kappa, base.mu, base.material
        self.w_max = None

    def _w0(self, F):
        return self.base.energy(F, np.zeros(F.shape[:-2]))

    def _eta(self, F):
        w0 = self._w0(F)
        w_max = np.zeros_like(w0) if self.w_max is None or self.w_max.shape != w0.shape \
            else self.w_max
        return self.params.eta(w0, w_max)

    def commit(self, F) -> None:
        """Close the step at the converged ``F`` (..., 3, 3): W_m ← max(W_m, W₀)."""
        w0 = self._w0(F)
        self.w_max = w0 if self.w_max is None or self.w_max.shape != w0.shape else \
            np.maximum(self.w_max, w0)

    def damage(self, F):
        """η at ``F`` with the committed W_m (1: virgin or on the primary path)."""
        return self._eta(F)[0]

    def stress(self, F, p):
        eta, _ = self._eta(F)
        P = self.base.stress(F, p)
        if np.all(eta == 1.0):
            return P
        return P + (eta - 1.0)[..., None, None] * self.base.stress(F, np.zeros(F.shape[:-2]))

    def stress_tangent(self, F, p):
        eta, d = self._eta(F)
        P, A = self.base.stress_tangent(F, p)
        if np.all(eta == 1.0):
            return P, A
        P0, A0 = self.base.stress_tangent(F, np.zeros(F.shape[:-2]))
        e = (eta - 1.0)[..., None, None]
        P = P + e * P0
        A = A + e[..., None, None] * A0 + d[..., None, None, None, None] * \
            np.einsum("...ij,...kl->...ijkl", P0, P0)
        return P, A

    def energy(self, F, p):
        """The virgin law's energy (a softened step has no potential of its own)."""
        return self.base.energy(F, p)
