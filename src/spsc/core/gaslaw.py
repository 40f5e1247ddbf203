"""The trapped gas: after the valve closes, P (V + V_r)ⁿ = const (paper eqs. 2, 6–7).

P is the absolute pressure, V the cavity volume (bladder only) and V_r the rigid reservoir,
ξ = 1 + V_r/V (eq. 4). With p the gauge pressure and (p_c, V_c) the state when the valve closes,

    p(V) = (p_c + P_amb) ((V_c + V_r)/(V + V_r))ⁿ − P_amb,
    dp/dV = −n (p + P_amb) / (V + V_r),

the second being the consistent tangent every model adds (−dp/dV g gᵀ with g = ∂V/∂u, positive:
the gas stiffens the chamber). Units: MPa, mm³. Written once; membrane, lumped, wall and 3D
models all evaluate it here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constants import P_AMB
from .errors import require

__all__ = ["GasLaw"]


@dataclass(frozen=True)
class GasLaw:
    """Closed gas: gauge pressure ``p_closed`` (MPa) at cavity volume ``v_closed`` (mm³) when the
    valve closes, reservoir ``reservoir`` (mm³), polytropic index ``n`` (1: isothermal,
    1.4: adiabatic air)."""

    p_closed: float
    v_closed: float
    reservoir: float = 0.0
    n: float = 1.0
    p_amb: float = P_AMB

    def __post_init__(self):
        require("p_closed", self.p_closed, gt=-self.p_amb, unit="MPa gauge")
        require("v_closed", self.v_closed, gt=0, unit="mm³")
        require("reservoir", self.reservoir, ge=0, unit="mm³")
        require("polytropic_n", self.n, ge=1, le=1.4)

    @property
    def constant(self) -> float:
        """P (V + V_r)ⁿ of this gas (MPa·mm³ⁿ)."""
        return (self.p_closed + self.p_amb) * (self.v_closed + self.reservoir) ** self.n

    def pressure(self, volume):
        """Gauge pressure (MPa) at cavity volume ``volume`` (mm³, scalar or array)."""
        ratio = (self.v_closed + self.reservoir) / (np.asarray(volume, float) + self.reservoir)
        return (self.p_closed + self.p_amb) * ratio**self.n - self.p_amb

    def dpressure(self, volume):
        """dp/dV (MPa/mm³) at cavity volume ``volume`` (mm³)."""
        v = np.asarray(volume, float)
        return -self.n * (self.pressure(v) + self.p_amb) / (v + self.reservoir)

    def volume(self, pressure):
        """The cavity volume (mm³) at gauge pressure ``pressure`` (MPa): the inverse of
        :meth:`pressure` (eq. 40's ΔV = ξ V_b,i (1 − (P_i/P)^(1/n)))."""
        ratio = (self.p_closed + self.p_amb) / (np.asarray(pressure, float) + self.p_amb)
        return (self.v_closed + self.reservoir) * ratio ** (1.0 / self.n) - self.reservoir

    def work(self, v_from, v_to) -> float:
        """∫ p dV (MPa·mm³ = mJ) of the gauge pressure from cavity volume ``v_from`` to
        ``v_to`` (mm³): the work the gas does on the wall, the closed form of :meth:`pressure`
        integrated (ln for n = 1)."""
        a, b = float(v_from) + self.reservoir, float(v_to) + self.reservoir
        if self.n == 1.0:
            absolute = self.constant * np.log(b / a)
        else:
            absolute = self.constant * (b ** (1 - self.n) - a ** (1 - self.n)) / (1 - self.n)
        return float(absolute - self.p_amb * (b - a))

    def invariant(self, pressure, volume):
        """P (V + V_r)ⁿ at gauge ``pressure`` (MPa) and cavity ``volume`` (mm³): constant along
        a closed-valve path, equal to :attr:`constant`."""
        return (np.asarray(pressure, float) + self.p_amb) * (
            np.asarray(volume, float) + self.reservoir) ** self.n
