"""Finite-strain viscoelasticity: a Prony series on the isochoric stress (Simo 1987; Holzapfel,
*Nonlinear Solid Mechanics*, sec. 6.10), over the nearly incompressible law of :mod:`.material`.

The hyperelastic law is the material's *long-term* (relaxed) response. Each Prony term i adds a
stress-like internal variable Q_i (second Piola–Kirchhoff, MPa) driven by the isochoric stress
S_iso = F⁻¹ ∂W(Ī1, Ī2)/∂F:

    Q̇_i + Q_i/τ_i = β_i Ṡ_iso,      S = S_vol + S_iso + Σ_i Q_i,

so a strain held from t = 0 relaxes as S_iso (1 + Σ β_i e^{−t/τ_i}): instantaneously 1 + Σβ_i
times stiffer, the relaxed law at t ≫ τ. Over a step Δt (the midpoint rule of the convolution,
exact for S_iso constant or linear in t):

    Q_i^{n+1} = a_i Q_i^n + b_i (S_iso^{n+1} − S_iso^n),   a_i = e^{−Δt/τ_i}, b_i = β_i e^{−Δt/2τ_i}.

In the first Piola stress the step is P = P_hyper(F, p) + g P_iso(F) + F H with g = Σ b_i and
H = Σ (a_i Q_i^n − b_i S_iso^n) fixed during the step; its tangent adds g 𝔸_iso and
δ_ik H_LJ. A step of Δt = ∞ (a load without time: the chamber at rest for long) is the relaxed
law; Δt = 0 the instantaneous one.
"""

from __future__ import annotations

import numpy as np

from spsc.materials.prony import Prony

__all__ = ["Prony", "ViscousLaw"]


class ViscousLaw:
    """``base`` (:class:`~spsc.fem.material.NearlyIncompressible`) with the ``prony`` terms and
    their history at every quadrature point (allocated at the first call, by the shape of F).

    :meth:`set_time` before solving a step at time t (s; None: at rest, relaxed);
    :meth:`commit` with the converged deformation gradients to close it."""

    def __init__(self, base, prony: Prony):
        self.base, self.prony = base, prony
        self.kappa, self.mu, self.material = base.kappa, base.mu, base.material
        self.t_committed = self._t = None
        self.Q = self.S_prev = None
        self._step(None)

    def _step(self, dt) -> None:
        a, b = self.prony.factors(dt)
        self.g = float(b.sum())
        self.H = None if self.Q is None or not (a.any() or b.any()) else \
            np.einsum("i,i...->...", a, self.Q) - self.g * self.S_prev

    def set_time(self, t: float | None) -> None:
        """The step ends at time ``t`` (s): Δt from the last committed state."""
        if t is None:
            self._step(None)
        else:
            self._step(t - (self.t_committed or 0.0))
        self._t = t

    def _iso(self, F):
        return self.base.stress(F, np.zeros(F.shape[:-2]))

    def commit(self, F) -> None:
        """Close the step at the converged ``F`` (..., 3, 3): the internal variables updated."""
        S = np.linalg.solve(F, self._iso(F))
        n = len(self.prony.terms)
        if self.Q is None:  # from the undeformed, stress-free reference
            self.Q = np.zeros((n,) + F.shape)
            self.S_prev = np.zeros_like(S)
        a, b = self.prony.factors(None if self._t is None else
                                  self._t - (self.t_committed or 0.0))
        shape = (-1,) + (1,) * F.ndim
        self.Q = a.reshape(shape) * self.Q + b.reshape(shape) * (S - self.S_prev)[None]
        self.S_prev = S
        if self._t is not None:
            self.t_committed = self._t
        self._step(None if self._t is None else 0.0)

    def stress(self, F, p):
        P = self.base.stress(F, p)
        if self.g:
            P = P + self.g * self._iso(F)
        if self.H is not None:
            P = P + F @ self.H
        return P

    def stress_tangent(self, F, p):
        P, A = self.base.stress_tangent(F, p)
        if self.g:
            P0, A0 = self.base.stress_tangent(F, np.zeros(F.shape[:-2]))
            P, A = P + self.g * P0, A + self.g * A0
        if self.H is not None:
            P = P + F @ self.H
            A = A.copy()
            for i in range(3):
                A[..., i, :, i, :] += np.swapaxes(self.H, -1, -2)  # δ_ik H_LJ
        return P, A

    def energy(self, F, p):
        """The relaxed law's energy (a viscous step has no potential)."""
        return self.base.energy(F, p)
