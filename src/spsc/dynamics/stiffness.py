"""Continuous stiffness (the paper's future work, sec. 5): the reservoir's volume as the control
input, a piston driven to track a target stiffness, the valve open.

Between the paper's two modes — the reservoir shut off (high) and open to 40 cm³ (low) — every
stiffness is a reservoir of some volume V_r. With the valve open and the gas pooled and at
ambient temperature (slow control), the chamber's quasi-static stiffness at travel y is

    k(V_r) = ∂F/∂y + ∂F/∂P dP/dy,   dP/dy = −(P + Pₐ) ∂V/∂y / (V + V_r + (P + Pₐ) ∂V/∂P)   (1)

(the chamber's map, :mod:`.chamber_map`; the pooled gas's law (P + Pₐ)(V + V_r) = m R T
differentiated). It falls monotonically with V_r, so a target k* has one volume

    V_r* = −∂F/∂P (P + Pₐ) ∂V/∂y / (k* − ∂F/∂y) − V − (P + Pₐ) ∂V/∂P                     (2)

at a given pressure. The controller's set point is the volume at which the pooled gas *at rest*
has k* — eq. (1) = k* with P the pooled gas's pressure at that volume, (P + Pₐ)(V + V_r) =
m R Tₐ, by Brent's method from eq. (2)'s monotonicity — so it does not move while the piston
compresses the gas (eq. (2) at the instantaneous pressure would, and overshoots); it is clipped
to the piston's stroke. The piston follows it with a first-order
lag ``actuator_time_s`` and at most ``rate_mm3_s``; the reservoir's gas is compressed by it
(the work −P dV_r/dt in its energy balance), and flows through the valve as in :mod:`.circuit`.
Where the plate does not touch, k does not depend on V_r and the piston holds.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from spsc.core.constants import P_AMB_KPA
from spsc.core.errors import ParameterError, require

from .chamber import Chamber
from .circuit import _MG, _rates, initial_state

__all__ = ["StiffnessControl", "parse_stiffness", "stiffness", "reservoir_for", "pooled_pressure", "set_point",
           "integrate_controlled", "step_metrics"]

_PA_KPA = P_AMB_KPA


@dataclass(frozen=True)
class StiffnessControl:
    """``target`` ((t_s, k N/mm), ...): the target stiffness, held from each instant on (before
    the first, the piston holds: a target makes sense once the plate presses); ``reservoir_mm3``
    (min, max) the piston's stroke; ``actuator_time_s`` its lag; ``rate_mm3_s`` its top
    speed."""

    target: tuple
    reservoir_mm3: tuple = (1000.0, 40000.0)
    actuator_time_s: float = 0.05
    rate_mm3_s: float = math.inf

    def __post_init__(self):
        lo, hi = self.reservoir_mm3
        if not (0 < lo < hi <= 1e7):
            raise ParameterError("stiffness.reservoir_mm3", list(self.reservoir_mm3),
                                 "[min, max] with 0 < min < max <= 1e7 mm³")
        require("stiffness.actuator_time_s", self.actuator_time_s, gt=0, le=100, unit="s")
        if not self.rate_mm3_s > 0:
            raise ParameterError("stiffness.rate_mm3_s", self.rate_mm3_s, "> 0 mm³/s (inf: "
                                 "no limit)")
        t = [float(a) for a, _ in self.target]
        if not t or t[0] < 0.0 or any(b <= a for a, b in zip(t, t[1:])):
            raise ParameterError("stiffness.target t_s", t, ">= 0 and strictly increasing "
                                 "(s)")
        for _, k in self.target:
            require("stiffness.target", k, gt=0, le=1e4, unit="N/mm")

    def at(self, t: float) -> float:
        """The target (N/mm) at ``t``: the last one set (nan before the first)."""
        k = math.nan
        for ts, kk in self.target:
            if ts <= t + 1e-12:
                k = kk
        return float(k)


def _slopes(chamber, y, p):
    s = chamber.slice(y)
    return (float(s.volume(p)), float(s.volume(p, 1)), float(s.dvolume_dy(p)),
            float(s.force(p, 1)), float(s.dforce_dy(p)))


def stiffness(chamber, y: float, p: float, v_r: float) -> float:
    """Eq. (1): the quasi-static stiffness (N/mm) at travel ``y`` (mm), gauge pressure ``p``
    (kPa), the valve open to ``v_r`` (mm³; 0: the chamber alone, the high mode)."""
    v, vp, vy, fp, fy = _slopes(chamber, y, p)
    pa = p + _PA_KPA
    return fy - fp * pa * vy / (v + v_r + pa * vp)


def reservoir_for(chamber, y: float, p: float, k: float) -> float:
    """Eq. (2): the reservoir volume (mm³) that gives the stiffness ``k`` (N/mm); inf where no
    volume is soft enough (k ≤ ∂F/∂y), nan where the plate does not touch."""
    v, vp, vy, fp, fy = _slopes(chamber, y, p)
    pa = p + _PA_KPA
    if fp * vy >= -1e-12:
        return math.nan
    if k <= fy:
        return math.inf
    return -fp * pa * vy / (k - fy) - v - pa * vp


def pooled_pressure(chamber, y: float, mass_mg: float, t_K: float, v_r: float) -> float:
    """The gauge pressure (kPa) of the gas ``mass_mg`` at ``t_K`` pooled in the chamber at
    travel ``y`` and a reservoir of ``v_r`` mm³: (P + Pₐ)(V(y, P) + V_r) = m R T (Newton)."""
    s, target = chamber.slice(y), mass_mg * _MG * chamber.gas.R * t_K / 1e-6  # kPa·mm³
    p = chamber.map.setup_kPa
    for _ in range(50):
        v = float(s.volume(p)) + v_r
        step = ((p + _PA_KPA) * v - target) / (v + (p + _PA_KPA) * float(s.volume(p, 1)))
        p -= step
        if abs(step) < 1e-12 * (abs(p) + 1.0):
            return p
    raise ValueError(f"no pooled pressure at y = {y:.4g} mm, V_r = {v_r:.4g} mm³")


def _within_map(chamber, y, mass_mg, t_K, stroke) -> tuple[float, float]:
    """The piston's stroke cut to the volumes whose pooled pressure stays within the map's
    pressures, with 2 % of them to spare for the gas's transients."""
    p_lo, p_hi = chamber.p_lo, chamber.p_hi
    spare = 0.02 * (p_hi - p_lo)
    s, mrt = chamber.slice(y), mass_mg * _MG * chamber.gas.R * t_K / 1e-6  # kPa·mm³

    def volume_at(p):
        return mrt / (p + _PA_KPA) - float(s.volume(p))

    return max(stroke[0], volume_at(p_hi - spare)), min(stroke[1], volume_at(p_lo + spare))


def set_point(chamber, y: float, mass_mg: float, t_K: float, k: float, stroke) -> float:
    """The reservoir volume (mm³, within ``stroke`` and the map's pressures) at which the
    pooled gas at rest gives the stiffness ``k`` (N/mm): eq. (1) = k with P the pooled
    pressure of that volume (so the set point does not move as the piston compresses the
    gas); the nearest end where no volume does; nan where the plate does not touch or there
    is no target."""
    def gap(v_r):
        return stiffness(chamber, y, pooled_pressure(chamber, y, mass_mg, t_K, v_r), v_r) - k

    if math.isnan(k):
        return math.nan
    lo, hi = _within_map(chamber, y, mass_mg, t_K, stroke)
    _, _, vy, fp, _ = _slopes(chamber, y, pooled_pressure(chamber, y, mass_mg, t_K, hi))
    if fp * vy >= -1e-12:
        return math.nan
    if gap(lo) <= 0:  # even the smallest volume is softer than k
        return lo
    if gap(hi) >= 0:  # even the largest is stiffer
        return hi
    return brentq(gap, lo, hi, xtol=1e-9 * hi, rtol=1e-12)


def _rates_controlled(chamber, circuit, control, memo, x, t, y, ydot):
    """d/dt of (m_c mg, T_c K, m_r mg, T_r K, V_r mm³); ``memo`` holds the last set point (it
    depends on the travel and the target only: the gas mass is conserved)."""
    v_r = x[4]
    c = dataclasses.replace(circuit, reservoir_mm3=v_r)
    d = _rates(chamber, c, x[:4], y, ydot, True)
    key = (y, control.at(t))
    if key != memo.get("key"):
        memo.update(key=key, want=set_point(chamber, y, x[0] + x[2], circuit.gas.ambient_K,
                                            key[1], control.reservoir_mm3))
    want = memo["want"]
    want = v_r if math.isnan(want) else want
    dv = max(-control.rate_mm3_s, min(control.rate_mm3_s, (want - v_r) / control.actuator_time_s))
    gas = circuit.gas
    if not gas.isothermal:  # the piston's work on the reservoir's gas
        p_r = gas.pressure(x[2] * _MG, v_r * 1e-9, x[3])
        d[3] -= p_r * dv * 1e-9 / (x[2] * _MG * gas.cv)
    return np.append(d, dv)


def integrate_controlled(chamber_map, circuit, profile, control, *, dt=1e-3,
                         progress=None) -> pd.DataFrame:
    """The trace of a travel ``profile`` with the valve open and the reservoir's volume driven
    by ``control`` (:class:`StiffnessControl`), from ``circuit.reservoir_mm3``: the columns
    of :func:`~.circuit.integrate`'s trace and reservoir_volume_mm3, stiffness_N_per_mm (eq. 1
    at the state), target_N_per_mm; and None, or why it stopped early (the gas leaving the
    map): the trace is then kept to the start of the piece it failed in."""
    chamber = Chamber(chamber_map, circuit.gas)
    t_end = profile.duration
    x = np.append(initial_state(chamber, circuit, float(profile.y(0.0))), circuit.reservoir_mm3)
    cuts = sorted({float(t) for t in profile.t_s} | {float(t) for t, _ in control.target
                                                     if t < t_end})
    out_t = np.arange(0.0, t_end + 0.5 * dt, dt)
    out_t = out_t[out_t <= t_end + 1e-12]
    ts, xs, memo, stopped = [], [], {}, None
    scale = np.array([x[0] + x[2], 1.0, x[0] + x[2], 1.0, control.reservoir_mm3[1]])
    for t0, t1 in zip(cuts, cuts[1:]):
        rate, y0 = profile.rate(t0, t1), float(profile.y(t0))
        want = np.clip(out_t[(out_t >= t0 - 1e-12) & ((out_t < t1 - 1e-12) | (t1 >= t_end))],
                       t0, t1)
        try:
            sol = solve_ivp(lambda t, s: _rates_controlled(chamber, circuit, control, memo, s, t,
                                                           y0 + rate * (t - t0), rate),
                            (t0, t1), x, method="LSODA", t_eval=np.append(want, t1)
                            if not want.size or want[-1] < t1 else want,
                            rtol=1e-9, atol=1e-12 * scale)
            failed = None if sol.success else sol.message
        except (ValueError, np.linalg.LinAlgError) as exc:
            failed = str(exc)
        if failed is not None:  # what was computed is kept; the piece it failed in is not
            stopped = f"stopped in t = {t0:.4g} … {t1:.4g} s: {failed}"
            break
        ts.append(sol.t[:len(want)])
        xs.append(sol.y[:, :len(want)])
        x = sol.y[:, -1]
        if progress is not None:
            progress(t1, t_end)
    if not ts:
        ts, xs = [np.zeros(0)], [np.zeros((5, 0))]
    return _frame(chamber, circuit, profile, control, np.concatenate(ts),
                  np.concatenate(xs, axis=1)), stopped


def _frame(chamber, circuit, profile, control, t, x) -> pd.DataFrame:
    gas, rows = circuit.gas, []
    for i, ti in enumerate(t):
        y = float(profile.y(ti))
        p = chamber.pressure(x[0, i] * _MG, x[1, i], y)
        s = chamber.slice(y)
        p_r = gas.pressure(x[2, i] * _MG, x[4, i] * 1e-9, x[3, i]) / 1e3 - _PA_KPA
        rows.append((ti, y, max(float(s.force(p)), 0.0), p, p_r, 1, max(float(s.area(p)), 0.0),
                     float(s.volume(p)), x[1, i], x[3, i], x[0, i], x[2, i], x[4, i],
                     stiffness(chamber, y, p, x[4, i]), control.at(ti)))
    return pd.DataFrame(rows, columns=[
        "t_s", "y_mm", "force_N", "pressure_kPa", "reservoir_kPa", "valve_open", "contact_mm2",
        "volume_mm3", "chamber_K", "reservoir_K", "chamber_mg", "reservoir_mg",
        "reservoir_volume_mm3", "stiffness_N_per_mm", "target_N_per_mm"])


def step_metrics(t, k, t_step: float, band: float = 0.02) -> dict:
    """The response of ``k`` (at times ``t``) to the target step at ``t_step``: its values
    before and at the end, the 10–90 % rise time, the time after which it stays within
    ``band`` of the change from its end value, the overshoot (fraction of the change)."""
    t, k = np.asarray(t, float), np.asarray(k, float)
    before = float(np.interp(t_step - 1e-9, t, k))
    after = t >= t_step
    tt, kk = t[after], k[after]
    final = float(kk[-1])
    change = final - before
    if abs(change) < 1e-12:
        return {"before": before, "final": final, "rise_s": 0.0, "settle_s": 0.0,
                "overshoot": 0.0}
    frac = (kk - before) / change
    rise = float(tt[np.argmax(frac >= 0.9)] - tt[np.argmax(frac >= 0.1)])
    outside = np.flatnonzero(np.abs(kk - final) > band * abs(change))
    settle = float(tt[outside[-1] + 1] - t_step) if outside.size and outside[-1] + 1 < tt.size \
        else (0.0 if not outside.size else math.nan)
    return {"before": before, "final": final, "rise_s": rise, "settle_s": settle,
            "overshoot": float(max(frac.max() - 1.0, 0.0))}


def parse_stiffness(st, press, reservoir: float, events):
    """The scenario's ``[stiffness]`` table ``st`` (None: no control) as a
    :class:`StiffnessControl`, checked against the ``press`` (a travel profile), the
    ``reservoir`` it starts at (mm³) and the valve ``events`` (none allowed)."""
    from .profile import PressProfile

    if st is None:
        return None
    if not isinstance(st, dict):
        raise ParameterError("[stiffness]", st, "a table")
    extra = sorted(set(st) - {"target", "reservoir_mm3", "actuator_time_s", "rate_mm3_s"})
    if extra:
        raise ParameterError(f"stiffness.{extra[0]}", st[extra[0]], "one of the keys "
                             "actuator_time_s, rate_mm3_s, reservoir_mm3, target")
    if not isinstance(press, PressProfile):
        raise ParameterError("[stiffness]", "with a force press", "a travel profile (press."
                             "profile): the controller is for a press of known travel")
    if events:
        raise ParameterError("[[events]]", "with [stiffness]", "none: the valve stays open "
                             "while the piston controls the stiffness")
    try:
        target = tuple((float(t), float(k)) for t, k in st.get("target", []))
    except (TypeError, ValueError):
        raise ParameterError("stiffness.target", st.get("target"),
                             "a list of [t_s, N_per_mm] pairs") from None
    stroke = st.get("reservoir_mm3", [1000.0, 40000.0])
    if not (isinstance(stroke, list) and len(stroke) == 2):
        raise ParameterError("stiffness.reservoir_mm3", stroke, "[min, max] (mm³)")
    ctl = StiffnessControl(target, (float(stroke[0]), float(stroke[1])),
                           float(st.get("actuator_time_s", 0.05)),
                           float(st.get("rate_mm3_s", float("inf"))))
    if not (stroke[0] <= reservoir <= stroke[1]):
        raise ParameterError("circuit.reservoir_mm3", reservoir, f"within the piston's stroke "
                             f"[{stroke[0]:g}, {stroke[1]:g}] mm³ (where it starts)")
    return ctl
