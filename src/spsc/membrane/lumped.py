"""Lumped static model of an SPSC (sec. 2.1, eqs. 1–9), the JND metric and the mean metrics.

Given the geometric curves A(y), ΔV(y) (and optionally the structural force F_el(y)) and the
setup (P_i, V_r or ξ, n), the air spring gives P(y) and F(y) in both stiffness modes.
Inside: mm, N, MPa, mm³; the public functions take and return kPa gauge at the edge.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.loadcase import PRESSURE_MAX_KPA
from spsc.core.errors import ParameterError, require

from spsc.core.constants import P_AMB, P_AMB_KPA, to_kPa, to_MPa
from spsc.core.curve import Curve
from spsc.core.gaslaw import GasLaw

__all__ = [
    "LOW_STIFFNESS_RESERVOIR_MM3",
    "Setup",
    "xi_from_reservoir",
    "pressure_abs",
    "lumped_curve",
    "sensitivity_eq8",
    "stiffness_eq9",
    "jnd_depth",
    "mean_stiffness",
    "mean_sensitivity",
]

#: Reservoir of the paper's bench (low-stiffness mode), sec. 3.1: 40 cm³.
LOW_STIFFNESS_RESERVOIR_MM3 = 40_000.0


@dataclass(frozen=True)
class Setup:
    """Setup of the air spring.

    Parameters
    ----------
    p_i_kPa : float
        Setup (inflation) pressure, kPa gauge, >= 0.
    bladder_volume_mm3 : float
        V_b,i, the bladder volume at rest, mm³, > 0.
    reservoir_mm3 : float
        V_r, mm³, >= 0 (0: high-stiffness mode, closed valve).
    polytropic_n : float
        Polytropic index n (eq. 2), >= 1 (1: isothermal).
    """

    p_i_kPa: float
    bladder_volume_mm3: float
    reservoir_mm3: float = 0.0
    polytropic_n: float = 1.0

    def __post_init__(self):
        object.__setattr__(self, "p_i_kPa", require("pressure", self.p_i_kPa, ge=0, le=PRESSURE_MAX_KPA,
                                   unit="kPa gauge"))
        object.__setattr__(self, "bladder_volume_mm3",
                           require("bladder_volume", self.bladder_volume_mm3, gt=0, unit="mm³"))
        object.__setattr__(self, "reservoir_mm3",
                           require("reservoir", self.reservoir_mm3, ge=0, unit="mm³"))
        object.__setattr__(self, "polytropic_n",
                           require("polytropic_n", self.polytropic_n, ge=1, le=1.4))

    @classmethod
    def from_xi(cls, p_i_kPa: float, bladder_volume_mm3: float, xi: float,
                polytropic_n: float = 1.0) -> "Setup":
        """Setup from ξ = V_i/V_b,i >= 1 (eq. 4) instead of the reservoir: V_r = (ξ − 1) V_b,i."""
        xi = require("xi", xi, ge=1)
        return cls(p_i_kPa, bladder_volume_mm3, (xi - 1.0) * bladder_volume_mm3, polytropic_n)

    @property
    def xi(self) -> float:
        """ξ = V_i / V_b,i (eq. 4), >= 1."""
        return xi_from_reservoir(self.bladder_volume_mm3, self.reservoir_mm3)

    def gas(self) -> GasLaw:
        """The closed gas of this setup (eqs. 2, 6): p_i at V_b,i, reservoir V_r."""
        return GasLaw(to_MPa(self.p_i_kPa), self.bladder_volume_mm3, self.reservoir_mm3,
                      self.polytropic_n)

    def as_dict(self) -> dict:
        return {"p_i_kPa": self.p_i_kPa, "reservoir_mm3": self.reservoir_mm3,
                "polytropic_n": self.polytropic_n}


def xi_from_reservoir(bladder_volume_mm3: float, reservoir_mm3: float) -> float:
    """ξ = (V_b,i + V_r) / V_b,i (eqs. 3–4), dimensionless."""
    return (bladder_volume_mm3 + reservoir_mm3) / bladder_volume_mm3


def pressure_abs(volume_change_mm3, setup: Setup):
    """Absolute pressure P(y) in kPa, eq. 6: P_i (ξV_b,i / (ξV_b,i − ΔV))^n."""
    dv = np.asarray(volume_change_mm3, float)
    vi = setup.xi * setup.bladder_volume_mm3
    if np.any(dv >= vi):
        raise ParameterError("volume_change", float(np.max(dv)), f"< ξV_b,i = {vi:.6g} mm³")
    gauge_mpa = setup.gas().pressure(setup.bladder_volume_mm3 - dv)
    return to_kPa(gauge_mpa + P_AMB)


def sensitivity_eq8(y_mm, area_mm2, volume_change_mm3, setup: Setup) -> np.ndarray:
    """dP/dy in kPa/mm, eq. 8 by the chain rule of eq. 6: n P (dΔV/dy) / (ξV_b,i − ΔV).

    The printed eq. 8 carries an extra factor A(y) that fails its units (it would hold with
    dΔV/dy replaced by A, the piston limit); the derivative of eq. 6 has no such factor.
    """
    y, dv = np.asarray(y_mm, float), np.asarray(volume_change_mm3, float)
    vi = setup.xi * setup.bladder_volume_mm3
    P = pressure_abs(dv, setup)
    return setup.polytropic_n * P * _grad(dv, y) / (vi - dv)


def stiffness_eq9(y_mm, area_mm2, volume_change_mm3, setup: Setup, elastic_force_N=None):
    """dF/dy in N/mm, eq. 9: k_el + (P − P_amb) dA/dy + (dP/dy) A (kPa → MPa at this edge)."""
    y, a = np.asarray(y_mm, float), np.asarray(area_mm2, float)
    p_gauge = pressure_abs(volume_change_mm3, setup) - P_AMB_KPA
    k_el = 0.0 if elastic_force_N is None else _grad(np.asarray(elastic_force_N, float), y)
    dpdy = sensitivity_eq8(y, a, volume_change_mm3, setup)
    return k_el + 1e-3 * (p_gauge * _grad(a, y) + dpdy * a)


def lumped_curve(y_mm, area_mm2, volume_change_mm3, setup: Setup, *, elastic_force_N=None,
                 geometry: dict | None = None, material: str = "", model: str = "lumped",
                 inflated_height_mm: float = float("nan"),
                 nominal_volume_mm3: float | None = None) -> Curve:
    """P(y) and F(y) of eqs. 6–7 from the geometric curves, as a :class:`Curve`.

    ``y_mm`` (mm), ``area_mm2`` A(y) (mm²), ``volume_change_mm3`` ΔV(y) (mm³) and the optional
    ``elastic_force_N`` F_el(y) (N) share one grid. The setup's bladder volume is V_b,i.
    """
    y = np.asarray(y_mm, float)
    a = np.asarray(area_mm2, float)
    dv = np.asarray(volume_change_mm3, float)
    if not (y.shape == a.shape == dv.shape):
        raise ParameterError("shapes of y, A, ΔV", (y.shape, a.shape, dv.shape), "equal")
    if np.any(a < 0):
        raise ParameterError("contact_area", float(a.min()), ">= 0 (mm²)")
    p_gauge = pressure_abs(dv, setup) - P_AMB_KPA
    f_el = np.zeros_like(y) if elastic_force_N is None else np.asarray(elastic_force_N, float)
    force = f_el + 1e-3 * p_gauge * a  # kPa · mm² = 1e-3 N
    return Curve(y, force, p_gauge, a, dv, model=model, geometry=geometry or {},
                 material=material, setup=setup.as_dict(),
                 nominal_volume_mm3=(setup.bladder_volume_mm3 if nominal_volume_mm3 is None
                                     else nominal_volume_mm3),
                 inflated_volume_mm3=setup.bladder_volume_mm3,
                 inflated_height_mm=inflated_height_mm)


def jnd_depth(high: Curve, low: Curve, *, relative: float = 0.10, absolute_N: float = 5.0):
    """First plate travel y (mm) where the two modes are distinguishable (sec. 3.1):
    |F_high − F_low| ≥ max(relative·F_low, absolute_N), linearly interpolated between samples.

    The curves must share their y grid; returns NaN if the threshold is never reached.
    """
    if high.y_mm.shape != low.y_mm.shape or not np.allclose(high.y_mm, low.y_mm):
        raise ParameterError("y grids of the two curves", "different", "identical grids (mm)")
    margin = np.abs(high.force_N - low.force_N) - np.maximum(relative * low.force_N, absolute_N)
    hit = np.nonzero(margin >= 0)[0]
    if hit.size == 0:
        return float("nan")
    k = hit[0]
    if k == 0:
        return float(high.y_mm[0])
    m0, m1 = margin[k - 1], margin[k]
    y0, y1 = high.y_mm[k - 1], high.y_mm[k]
    return float(y0 + (y1 - y0) * (-m0) / (m1 - m0))


def mean_stiffness(curves) -> float:
    """Mean of dF/dy (N/mm) over the stroke each curve reached (:meth:`Curve.mean_stiffness`,
    the integral mean), then over the curves (docs/design.md: over the setup pressures of one type
    and mode; apply again over types)."""
    return float(np.mean([c.mean_stiffness(reached=True) for c in _as_list(curves)]))


def mean_sensitivity(curves) -> float:
    """Mean of dP/dy (kPa/mm) over the stroke reached, then over the curves."""
    return float(np.mean([c.mean_sensitivity(reached=True) for c in _as_list(curves)]))


def _as_list(curves):
    return [curves] if isinstance(curves, Curve) else list(curves)


def _grad(f, y):
    return np.gradient(f, y, edge_order=2) if y.size > 2 else np.gradient(f, y)
