"""The air in a volume: ideal gas P V = m R T with an energy balance between adiabatic and
isothermal (the paper's polytropic law, eq. 2, as the limits of a thermal time constant).

For a volume V(t) with mass m and temperature T, exchanging mass at the rate q (kg/s, > 0 in)
with a neighbour at temperature T_in, and heat with the wall at ambient T_a,

    dm/dt = q
    m c_v dT/dt = q⁺ (c_p T_in − c_v T) − q⁻ R T − P dV/dt + m c_v (T_a − T)/τ

(q⁺ = max(q, 0), q⁻ = max(−q, 0); c_v = R/(n − 1), c_p = n c_v). ``n`` is the gas's ratio of
heat capacities: 1.4 for air; n = 1 is the isothermal gas (T = T_a throughout, the paper's
static tests). ``thermal_time_s`` τ: ∞ is adiabatic (a closed volume follows P Vⁿ = const),
τ → 0 isothermal; a chamber wall relaxes the gas toward T_a with τ = m c_v/(h A).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from spsc.core.errors import ParameterError, require

__all__ = ["Gas", "R_AIR", "GAMMA_AIR", "T_AMBIENT"]

#: specific gas constant of dry air (J/(kg·K)) and its ratio of heat capacities
R_AIR, GAMMA_AIR = 287.05, 1.4
#: ambient temperature (K), the ISO 8778 reference
T_AMBIENT = 293.15


@dataclass(frozen=True)
class Gas:
    """``n`` ratio of heat capacities (1: isothermal, 1.4: air), ``thermal_time_s`` τ (s; inf:
    adiabatic), ``ambient_K`` the wall's temperature, ``R`` J/(kg·K)."""

    n: float = 1.0
    thermal_time_s: float = math.inf
    ambient_K: float = T_AMBIENT
    R: float = R_AIR

    def __post_init__(self):
        require("gas n", self.n, ge=1.0, le=1.67)
        tau = self.thermal_time_s
        if not (isinstance(tau, (int, float)) and (tau == math.inf or math.isfinite(tau))
                and tau >= 0):
            raise ParameterError("gas thermal_time_s", tau, ">= 0 (s; inf: adiabatic)")
        require("gas ambient_K", self.ambient_K, gt=0, unit="K")

    @property
    def isothermal(self) -> bool:
        return self.n == 1.0 or self.thermal_time_s == 0.0

    @property
    def cv(self) -> float:
        """c_v (J/(kg·K)); infinite for the isothermal gas."""
        return math.inf if self.n == 1.0 else self.R / (self.n - 1.0)

    def mass(self, p_pa: float, volume_m3: float, t: float) -> float:
        """m = P V/(R T) (kg) for absolute P (Pa)."""
        return p_pa * volume_m3 / (self.R * t)

    def pressure(self, m: float, volume_m3: float, t: float) -> float:
        """P = m R T/V (Pa, absolute)."""
        return m * self.R * t / volume_m3

    def enthalpy_in(self, q: float, t: float, t_in: float) -> float:
        """q⁺ (c_p T_in − c_v T) − q⁻ R T (W): the energy the exchange brings (beyond the
        internal energy c_v T q it moves)."""
        cv = self.cv
        if q >= 0.0:
            return q * (self.n * cv * t_in - cv * t)
        return q * self.R * t

    def heat(self, m: float, t: float) -> float:
        """m c_v (T_a − T)/τ (W) from the wall."""
        if self.thermal_time_s == math.inf:
            return 0.0
        return m * self.cv * (self.ambient_K - t) / self.thermal_time_s
