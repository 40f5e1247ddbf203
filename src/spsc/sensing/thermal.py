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

Written in the adiabatic invariant S = ln W + (n − 1) ln V_s = n ln W − (n − 1) ln P_abs, the
compression drops out and only the wall's heat is left,

    dS/dt = (c/W − 1)/τ,   W = P_abs^(1 − 1/n) exp(S/n),                            (T2)

so W follows the measured pressure through a function of state, and the sensor's noise moves
it and takes it back (over 30 s of noise at a constant pressure the volume W/P it gives stays
within 5e-6 of the true one: tests/test_sensing_thermal.py). At a constant pressure T2 is
linear in W: W − c decays with n τ exactly. Over a sample (P₀ → P₁) the step is Strang's:
half the relaxation at P₀, the adiabatic change (S kept), half at P₁; second order in Δt,
exact for τ = ∞ (P Vⁿ kept to round-off) and at a constant pressure.

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

__all__ = ["invariant", "energy", "relax_invariant", "compress_by", "relax", "iso_pressure"]


def relax(value: float, target: float, dt: float, tau: float) -> float:
    """``value`` relaxed toward ``target`` over ``dt`` s with the time constant ``tau`` s
    (inf: not at all; 0: at once)."""
    if tau == 0.0:
        return target
    if tau == math.inf:
        return value
    return target + (value - target) * math.exp(-dt / tau)


def invariant(w: float, p_abs: float, n: float) -> float:
    """S = n ln W − (n − 1) ln P_abs of the gas's energy ``w`` (kPa·mm³) at the absolute
    pressure ``p_abs`` (kPa): constant under an adiabatic change."""
    return n * math.log(w) - (n - 1.0) * math.log(p_abs)


def energy(s: float, p_abs: float, n: float) -> float:
    """W (kPa·mm³) of the invariant ``s`` at the absolute pressure ``p_abs`` (kPa), eq. T2."""
    return math.exp((s + (n - 1.0) * math.log(p_abs)) / n)


def relax_invariant(s: float, c: float, dt: float, p0_abs: float, p1_abs: float, n: float,
                    tau: float) -> float:
    """S after ``dt`` s in which the absolute pressure went from ``p0_abs`` to ``p1_abs``
    (kPa): half the wall's heat at P₀, the adiabatic change, half at P₁ (each half exact at
    its constant pressure: W − c decays with n τ)."""
    if tau == math.inf:
        return s
    for p in (p0_abs, p1_abs):
        w = energy(s, p, n)
        w = relax(w, c, 0.5 * dt, n * tau)
        s = invariant(w, p, n)
    return s


def compress_by(w: float, c: float, dt: float, p_abs: float, dv: float, n: float,
                tau: float) -> float:
    """W₁ (kPa·mm³) of eq. T1 over ``dt`` s with the volume change ``dv`` (mm³) known (the
    chamber at a held travel while the valve equalises, its pressure not the pooled gas's,
    so no invariant of one gas holds) at the mean absolute pressure ``p_abs`` (kPa): the work
    at the step's middle, the heat exact over the step."""
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
