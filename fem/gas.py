"""The closed gas cavity: after inflation to p_i the valve closes and P·(V + V_r)ⁿ = const.

P is the absolute pressure, V the (full) cavity volume and V_r the rigid reservoir (paper eqs.
6–7 with ξ = 1 + V_r/V). The gauge pressure as a function of the cavity volume is

    p(V) = (p_i + P_amb) ((V_i + V_r)/(V + V_r))ⁿ − P_amb,
    dp/dV = −n (p + P_amb) / (V + V_r),

which makes the load p(V) g with g = ∂V/∂u; its tangent adds the rank-one term −(dp/dV) g gᵀ
(positive: the trapped gas stiffens the chamber), solved by a Sherman–Morrison update.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.cad.errors import require

__all__ = ["GasCavity", "P_AMB", "solve_rank_one"]

#: Ambient pressure (MPa).
P_AMB = 0.101325


@dataclass(frozen=True)
class GasCavity:
    """Closed cavity: gauge pressure ``p_closed`` (MPa) at volume ``v_closed`` (mm³, full
    cavity) when the valve closes, reservoir ``reservoir`` (mm³), polytropic index ``n``."""

    p_closed: float
    v_closed: float
    reservoir: float = 0.0
    n: float = 1.0
    p_amb: float = P_AMB

    def __post_init__(self):
        require("p_closed", self.p_closed, gt=-self.p_amb, unit="MPa")
        require("v_closed", self.v_closed, gt=0, unit="mm³")
        require("reservoir", self.reservoir, ge=0, unit="mm³")
        require("polytropic_index", self.n, ge=1)

    def pressure(self, volume: float) -> float:
        """Gauge pressure (MPa) at cavity volume ``volume`` (mm³)."""
        ratio = (self.v_closed + self.reservoir) / (volume + self.reservoir)
        return (self.p_closed + self.p_amb) * ratio**self.n - self.p_amb

    def dpressure(self, volume: float) -> float:
        """dp/dV (MPa/mm³)."""
        return -self.n * (self.pressure(volume) + self.p_amb) / (volume + self.reservoir)

    def invariant(self, pressure: float, volume: float) -> float:
        """P (V + V_r)ⁿ (N·mm^(3n−2)), constant along a closed-valve path."""
        return (pressure + self.p_amb) * (volume + self.reservoir) ** self.n


def solve_rank_one(factor_solve, c: float, g: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Solve (K + c g gᵀ) x = r given ``factor_solve`` = K⁻¹ applied to an (n, k) array
    (Sherman–Morrison, one factorisation, two right-hand sides)."""
    sol = factor_solve(np.column_stack([r, g]))
    y, z = sol[:, 0], sol[:, 1]
    return y - z * (c * (g @ y) / (1.0 + c * (g @ z)))
