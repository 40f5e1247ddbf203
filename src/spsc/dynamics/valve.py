"""A pneumatic valve's mass flow by ISO 6358 (ISO 6358-1:2013): sonic conductance C, critical
pressure ratio b, subsonic index m, and the laminar end of the 2013 edition.

    q_m = C ρ₀ p₁ √(T₀/T₁) · φ(p₂/p₁),
    φ = 1                                    for r = p₂/p₁ ≤ b      (choked)
    φ = [1 − ((r − b)/(1 − b))²]^m           for b < r ≤ r_l         (subsonic)
    φ = φ(r_l) (1 − r)/(1 − r_l)             for r_l < r ≤ 1         (laminar, r_l = 0.999)

with p₁ ≥ p₂ the absolute pressures up- and downstream (the flow goes from the higher), T₁ the
upstream temperature and ρ₀ = 1.185 kg/m³, T₀ = 293.15 K the standard reference atmosphere
(ISO 8778). The laminar end makes the flow linear in the pressure difference as the two sides
equalise (the square-root law alone has an infinite slope there: no time constant).

The paper's directional valve is given by an effective orifice area (≥ 0.3 mm², sec. 4):
:func:`sonic_conductance` converts it for an ideal nozzle, C = S · c*/(ρ₀ √T₀) with the choked
flow function of air c* = √(γ/R) (2/(γ+1))^((γ+1)/(2(γ−1))) = 0.0404 s·√K/m, i.e.
C ≈ 0.199 dm³/(s·bar) per mm², the rule of thumb S ≈ 5 C.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import require

from .gas import GAMMA_AIR, R_AIR

__all__ = ["Valve", "sonic_conductance", "RHO0", "T0", "LAMINAR_RATIO"]

#: the ISO 8778 standard reference atmosphere: density (kg/m³) and temperature (K)
RHO0, T0 = 1.185, 293.15
#: pressure ratio above which the flow is laminar (linear in the difference), ISO 6358-1:2013
LAMINAR_RATIO = 0.999
#: dm³/(s·bar) in m³/(s·Pa)
_C_SI = 1e-3 / 1e5


def _choked_flow_function(gamma: float = GAMMA_AIR, r: float = R_AIR) -> float:
    """c* (s·√K/m): the choked mass flux of an ideal nozzle is c* p₁/√T₁."""
    return math.sqrt(gamma / r) * (2 / (gamma + 1)) ** ((gamma + 1) / (2 * (gamma - 1)))


def sonic_conductance(area_mm2: float) -> float:
    """The sonic conductance C (dm³/(s·bar)) of an ideal nozzle of effective area
    ``area_mm2`` (mm²), with b = 0.528 its critical ratio."""
    require("orifice area", area_mm2, gt=0, unit="mm²")
    c_si = area_mm2 * 1e-6 * _choked_flow_function() / (RHO0 * math.sqrt(T0))
    return c_si / _C_SI


@dataclass(frozen=True)
class Valve:
    """ISO 6358 flow: sonic conductance ``C`` (dm³/(s·bar)), critical pressure ratio ``b``
    (0 ≤ b < 1) and subsonic index ``m`` (0.5: the classic elliptic law)."""

    C: float
    b: float = 0.528
    m: float = 0.5

    def __post_init__(self):
        require("valve C", self.C, gt=0, le=1e3, unit="dm³/(s·bar)")
        require("valve b", self.b, ge=0, lt=LAMINAR_RATIO)
        require("valve m", self.m, gt=0, le=1)

    def phi(self, r: float) -> float:
        """The flow function φ of the pressure ratio r = p₂/p₁ ∈ [0, 1]."""
        if r <= self.b:
            return 1.0
        if r <= LAMINAR_RATIO:
            return (1.0 - ((r - self.b) / (1.0 - self.b)) ** 2) ** self.m
        return self._phi_l * (1.0 - r) / (1.0 - LAMINAR_RATIO)

    @property
    def _phi_l(self) -> float:
        return (1.0 - ((LAMINAR_RATIO - self.b) / (1.0 - self.b)) ** 2) ** self.m

    def mass_flow(self, p_a: float, p_b: float, t_a: float, t_b: float) -> float:
        """Mass flow (kg/s) from side a to side b (negative: from b to a) for absolute
        pressures ``p_a``, ``p_b`` (Pa) and temperatures ``t_a``, ``t_b`` (K)."""
        if p_a >= p_b:
            return self._flow(p_a, p_b, t_a)
        return -self._flow(p_b, p_a, t_b)

    def _flow(self, p1: float, p2: float, t1: float) -> float:
        if p1 <= 0.0:
            return 0.0
        return self.C * _C_SI * RHO0 * p1 * math.sqrt(T0 / t1) * self.phi(p2 / p1)

    def mass_flows(self, p_a, p_b, t_a, t_b):
        """:meth:`mass_flow` for arrays (many valves at once: :mod:`spsc.virtual`)."""
        p_a, p_b = np.asarray(p_a, float), np.asarray(p_b, float)
        forward = p_a >= p_b
        up, down = np.where(forward, p_a, p_b), np.where(forward, p_b, p_a)
        t_up = np.where(forward, t_a, t_b)
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(up > 0, down / np.where(up > 0, up, 1.0), 1.0)
        sub = np.abs(1.0 - ((np.clip(r, self.b, LAMINAR_RATIO) - self.b) / (1.0 - self.b))
                     ** 2) ** self.m
        phi = np.where(r <= self.b, 1.0, np.where(
            r <= LAMINAR_RATIO, sub, self._phi_l * (1.0 - r) / (1.0 - LAMINAR_RATIO)))
        q = self.C * _C_SI * RHO0 * np.maximum(up, 0.0) * np.sqrt(T0 / t_up) * phi
        return np.where(forward, q, -q)

    def conductance(self, p: float, t: float) -> float:
        """d q_m / d(p₁ − p₂) (kg/(s·Pa)) as the two sides equalise at pressure ``p`` (Pa)
        and temperature ``t`` (K): the laminar end's slope, for the linearised circuit."""
        return self.C * _C_SI * RHO0 * math.sqrt(T0 / t) * self._phi_l / (1.0 - LAMINAR_RATIO)
