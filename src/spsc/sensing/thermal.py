"""The gas's heat in the sensing estimate: a press of air is not isothermal.

A fast press compresses the chamber's air nearly adiabatically (its temperature rises, and its
pressure with it, beyond the isothermal map's), a hold lets it cool toward the wall's
temperature (the pressure falls at a constant travel), and a release expands it below ambient
(the pressure undershoots the rest, then recovers). An estimator that reads the pressure
through the isothermal content c = P_abs V (the paper's static tests, eq. 2 with n = 1) takes
the first for a deeper press, the second for the plate backing off and the third for a
release followed by a new contact. The gas model is :mod:`spsc.dynamics.gas`'s, the one
``spsc simulate`` integrates.

Lumped over the volume V_s that shares the gas (the chamber, with the reservoir when the valve
is open and the pressures equal), with c = m R T_a (kPa·mm³: the content at the ambient
temperature, conserved while no gas is added) and W = P_abs V_s = m R T (its energy,
W/(n − 1) = U), the energy balance of :mod:`spsc.dynamics.gas` summed over the volumes
(the valve's enthalpy flow is internal to them, both walls relax with the same τ) is

    dW/dt = −(n − 1) P_abs dV_s/dt + (c − W)/τ.                                      (T1)

Over a sample (Δt, the measured P_abs from P₀ to P₁, the mean P̄), by the variation of
constants with the work done at the step's middle, E = exp(−Δt/τ), and V_s = W/P_abs at both
ends, W₁ is the root of a linear equation:

    W₁ = c + (W₀ − c) E − (n − 1) P̄ (V₁ − V₀) E^½,   V₁ = W₁/P₁,                      (T2)

second order in Δt (tests/test_sensing_thermal.py).

The estimator reads the chamber's travel where the map's cavity holds V_s = W/P_abs at the
measured P, and its force there, F(y, P). Its detectors read the pressure the same gas would
have at the ambient temperature at the same travel, P_iso: the root of
(P_iso + P_a)(V(y, P_iso) + V_e) = c, to first order in the temperature's excess (the chamber
inflates with its pressure: ∂V/∂P = V_P),

    P_iso = P − (W − c)/(V_s + P_abs V_P),                                            (T3)

which passes the sensor's noise through with a gain of one (the isothermal table's frame: at
rest P_iso is its rest pressure). The isothermal gas (n = 1 or τ = 0) keeps W = c and
P_iso = P.
"""

from __future__ import annotations

import math

__all__ = ["compress", "compress_by", "relax", "iso_pressure"]


def relax(value: float, target: float, dt: float, tau: float) -> float:
    """``value`` relaxed toward ``target`` over ``dt`` s with the time constant ``tau`` s
    (inf: not at all; 0: at once)."""
    if tau == 0.0:
        return target
    if tau == math.inf:
        return value
    return target + (value - target) * math.exp(-dt / tau)


def compress(w: float, c: float, dt: float, p0_abs: float, p1_abs: float, n: float,
             tau: float) -> float:
    """W₁ (kPa·mm³) of eq. T2 after ``dt`` s in which the absolute pressure went from
    ``p0_abs`` to ``p1_abs`` (kPa), from W₀ = ``w`` and the ambient content ``c``; ``n`` the
    gas's ratio of heat capacities, ``tau`` its thermal time (s)."""
    if n == 1.0 or tau == 0.0:
        return c
    e = 1.0 if tau == math.inf else math.exp(-dt / tau)
    k = (n - 1.0) * 0.5 * (p0_abs + p1_abs) * math.sqrt(e)
    v0 = w / p0_abs
    v1 = (c + (w - c) * e + k * v0) / (p1_abs + k)
    return p1_abs * v1


def compress_by(w: float, c: float, dt: float, p_abs: float, dv: float, n: float,
                tau: float) -> float:
    """W₁ (kPa·mm³) of eq. T2 with the volume change ``dv`` (mm³) known (the chamber at a
    held travel while the valve equalises, its pressure not the pooled gas's) at the mean
    absolute pressure ``p_abs`` (kPa)."""
    if n == 1.0 or tau == 0.0:
        return c
    e = 1.0 if tau == math.inf else math.exp(-dt / tau)
    return c + (w - c) * e - (n - 1.0) * p_abs * dv * math.sqrt(e)


def iso_pressure(p_kPa: float, w: float, c: float, pa_kPa: float,
                 compliance: float = 0.0) -> float:
    """The gauge pressure (kPa) of the gas at the ambient temperature at the same travel
    (eq. T3), the chamber's ``compliance`` ∂V/∂P in mm³/kPa (0: at the same volume,
    (P + P_a) c/W − P_a)."""
    pabs = p_kPa + pa_kPa
    return p_kPa - (w - c) / (w / pabs + pabs * compliance)
