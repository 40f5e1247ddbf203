"""The chamber's response to a small sinusoidal press about an operating point: the circuit of
:mod:`.circuit` linearised, as a Bode plot of the dynamic stiffness F̂/ŷ (N/mm) and sensitivity
P̂/ŷ (kPa/mm).

The operating point is the chamber at rest at travel y₀, its gas at ambient temperature: with
the valve open, chamber and reservoir at the one pressure of their pooled gas (the low mode's
state); closed, the chamber alone with the gas it held at the setup (the high mode's). About it

    δẋ = A δx + b_y δy + b_v δẏ,    δP = c δx + d δy,    δF = F_y δy + F_P δP

(x the four gas states; the Jacobians by central differences of the circuit's own rates), so
for y = ŷ e^{iωt}

    P̂/ŷ = c (iω − A)⁻¹ (b_y + iω b_v) + d,    F̂/ŷ = F_y + F_P P̂/ŷ.

At ω → 0 with the valve open this is the low mode's static stiffness and sensitivity at y₀
(isothermal); as ω grows the valve cannot move the gas in time and the chamber stiffens toward
the high mode, adiabatic above the thermal time constant's frequency.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .chamber import Chamber
from .circuit import _MG, _PA, _rates, initial_state
from .stiffness import pooled_pressure

__all__ = ["operating_point", "linearise", "bode"]



def operating_point(chamber_map, circuit, y0: float, valve_open: bool) -> np.ndarray:
    """The gas state at rest at travel ``y0``: the setup's gas pressed isothermally, pooled
    with the reservoir's when the valve is open (Newton on the pooled pressure)."""
    ch = Chamber(chamber_map, circuit.gas)
    x = initial_state(ch, circuit, 0.0 if chamber_map.y_range[0] <= 0 else chamber_map.y_range[0])
    t = circuit.gas.ambient_K
    if not valve_open or circuit.reservoir_mm3 <= 0:
        return np.array([x[0], t, x[2], t])
    total = (x[0] + x[2]) * _MG
    p = pooled_pressure(ch, y0, x[0] + x[2], t, circuit.reservoir_mm3)
    v = float(ch.slice(y0).volume(p)) * 1e-9
    mc = (p * 1e3 + _PA) * v / (circuit.gas.R * t)
    return np.array([mc / _MG, t, total / _MG - mc / _MG, t])


def _d_dy(fun, y0: float, lo: float, hi: float, h: float = 1e-5):
    """d fun/dy at y0 by second-order differences, one-sided at the map's ends."""
    if y0 + h > hi:
        return (3 * np.asarray(fun(y0)) - 4 * np.asarray(fun(y0 - h)) + fun(y0 - 2 * h)) \
            / (2 * h)
    if y0 - h < lo:
        return (-3 * np.asarray(fun(y0)) + 4 * np.asarray(fun(y0 + h)) - fun(y0 + 2 * h)) \
            / (2 * h)
    return (np.asarray(fun(y0 + h)) - fun(y0 - h)) / (2 * h)


def linearise(chamber_map, circuit, y0: float, valve_open: bool) -> dict:
    """The Jacobians about the operating point at ``y0`` (see the module's equations)."""
    ch = Chamber(chamber_map, circuit.gas)
    x0 = operating_point(chamber_map, circuit, y0, valve_open)

    def f(x, y, v):
        return _rates(ch, circuit, x, y, v, valve_open)

    def pressure(x, y):
        return ch.pressure(x[0] * _MG, x[1], y)

    hx = np.maximum(np.abs(x0) * 1e-7, 1e-9)
    hv = 1e-3
    lo, hi = chamber_map.y_range
    A = np.column_stack([(f(x0 + e, y0, 0.0) - f(x0 - e, y0, 0.0)) / (2 * h)
                         for e, h in ((np.eye(4)[i] * hx[i], hx[i]) for i in range(4))])
    b_y = _d_dy(lambda y: f(x0, y, 0.0), y0, lo, hi)
    b_v = (f(x0, y0, hv) - f(x0, y0, -hv)) / (2 * hv)
    c = np.array([(pressure(x0 + np.eye(4)[i] * hx[i], y0)
                   - pressure(x0 - np.eye(4)[i] * hx[i], y0)) / (2 * hx[i]) for i in range(4)])
    d = _d_dy(lambda y: pressure(x0, y), y0, lo, hi)
    p0 = pressure(x0, y0)
    s = ch.slice(y0)
    f_p = float(s.force(p0, 1))
    f_y = _d_dy(lambda y: float(ch.map.at(y).force(p0)), y0, lo, hi)
    return {"A": A, "b_y": b_y, "b_v": b_v, "c": c, "d": d, "F_y": f_y, "F_P": f_p,
            "x0": x0, "pressure_kPa": p0, "force_N": float(s.force(p0)), "y_mm": y0}


def bode(chamber_map, circuit, y0: float, valve_open: bool, freqs_Hz) -> pd.DataFrame:
    """Dynamic stiffness and sensitivity at ``freqs_Hz`` (magnitude and phase, degrees)."""
    lin = linearise(chamber_map, circuit, y0, valve_open)
    A, c = lin["A"], lin["c"]
    rows = []
    for fr in np.asarray(freqs_Hz, float):
        w = 2 * np.pi * fr
        dx = np.linalg.solve(1j * w * np.eye(4) - A, lin["b_y"] + 1j * w * lin["b_v"])
        p_hat = c @ dx + lin["d"]
        k_hat = lin["F_y"] + lin["F_P"] * p_hat
        rows.append((fr, abs(k_hat), np.degrees(np.angle(k_hat)), abs(p_hat),
                     np.degrees(np.angle(p_hat))))
    return pd.DataFrame(rows, columns=["f_Hz", "stiffness_N_per_mm", "stiffness_phase_deg",
                                       "sensitivity_kPa_per_mm", "sensitivity_phase_deg"])
