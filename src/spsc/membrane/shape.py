"""A solved meridian: positions, stretches and tensions at the nodes of the box scheme."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.constants import to_kPa

from .bvp import BoxScheme
from .tension import relaxed_tensions, tensions

__all__ = ["Shape", "make_shape"]


@dataclass(frozen=True, eq=False)
class Shape:
    """A deformed meridian: nodes in undeformed arc length s (mm), their undeformed position
    x, y (mm), deformed ρ, η (mm), φ (rad), λ1, λ2,
    T1, T2 (N/mm); gauge pressure p (kPa); contact boundary s_Γ (mm, 0 without contact) and its
    node index; cavity volume (mm³); edge s_0 of the slack (wrinkled, stress-free) core on the
    plate (mm, 0 if none — the nodes then start at s_0)."""

    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    rho: np.ndarray
    eta: np.ndarray
    phi: np.ndarray
    lambda1: np.ndarray
    lambda2: np.ndarray
    T1: np.ndarray
    T2: np.ndarray
    pressure_kPa: float
    s_gamma: float
    gamma_index: int
    volume_mm3: float
    s_slack: float = 0.0

    def meridian(self):
        """(x, ρ, η) in mm from the apex to the clamped edge, for output and plots. A slack
        core (s < s_0) lies wrinkled on the plate; it is drawn flat, ρ scaled from x."""
        if self.s_slack <= 0.0:
            return self.x, self.rho, self.eta
        k = max(2, int(np.ceil(self.s_slack / (self.s[1] - self.s[0]))))
        xc = np.linspace(0.0, self.x[0], k, endpoint=False)
        rc = xc * self.rho[0] / self.x[0]
        ec = np.full(k, self.eta[0])
        return (np.concatenate([xc, self.x]), np.concatenate([rc, self.rho]),
                np.concatenate([ec, self.eta]))

    @property
    def contact_radius(self) -> float:
        """Deformed contact radius ρ(s_Γ) = λ2 x_Γ (mm)."""
        return float(self.rho[self.gamma_index])



def make_shape(bs: BoxScheme, v, p_mpa: float, sg: float = 0.0, s0: float = 0.0) -> Shape:
    """The :class:`Shape` of the unknown vector ``v`` of ``bs`` at gauge pressure p (MPa),
    contact boundary s_Γ and slack-core edge s_0 (mm)."""
    Z = bs.split(v)[0]
    s = bs.nodes(sg, s0)
    x = bs.mer.x(s)
    rho, eta, phi, l1 = (Z[:, k].copy() for k in range(4))
    l2 = np.where(x > 0, rho / np.where(x > 0, x, 1.0), l1)
    T1, T2 = relaxed_tensions(bs.mat, bs.t0, l1, l2)  # free membrane: tension field
    k = bs.nc + 1 if bs.contact else 0
    T1[:k], T2[:k] = tensions(bs.mat, bs.t0, l1[:k], l2[:k])  # on the plate: taut law
    return Shape(s, x, bs.mer.y(s), rho, eta, phi, l1, l2, T1, T2, to_kPa(p_mpa), sg, bs.nc,
                 bs.volume(Z), s0)
