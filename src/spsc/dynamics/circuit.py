"""The pneumatic circuit in time (the paper's Fig. 1): the chamber on its quasi-static map, a
valve to a rigid reservoir, the gas in each volume with its energy balance, the press.

State: the gas mass and temperature in the chamber and in the reservoir. At each instant the
chamber's pressure P is the root of P V(y, P) = m R T (:mod:`.chamber_map`, the wall's
equilibrium at that pressure), and the energy balance of :mod:`.gas` holds with
dV/dt = ∂V/∂y ẏ + ∂V/∂P Ṗ; with the ideal-gas law differentiated this is, per instant, the
linear system in (Ṗ, Ṫ)

    (V + P ∂V/∂P) Ṗ − m R Ṫ = R T q − P ∂V/∂y ẏ
    P ∂V/∂P Ṗ + m c_v Ṫ = E + Q − P ∂V/∂y ẏ

(q the mass flow in, E its enthalpy term, Q the heat from the wall). The isothermal gas keeps
T = T_a and needs only dm/dt = q. The valve's flow is ISO 6358 (:mod:`.valve`). The ODE is
integrated by LSODA between the profile's knots and the valve events (so ẏ and the valve state
are constant on each piece), and the state is output every ``dt``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from spsc.core.constants import P_AMB

__all__ = ["Circuit", "Chamber", "integrate", "TraceArrays", "CircuitFailure"]

_PA = P_AMB * 1e6  # ambient pressure (Pa)
_MM3 = 1e-9  # m³ per mm³
_KPA = 1e3  # Pa per kPa
_MG = 1e-6  # kg per mg: the state's mass unit (tolerances)


class CircuitFailure(RuntimeError):
    """The integration stopped (the gas left the map's pressures or travels, or the
    integrator failed); ``time_s`` where, the trace up to there is kept."""

    def __init__(self, message: str, time_s: float):
        super().__init__(message)
        self.time_s = time_s


@dataclass(frozen=True)
class Circuit:
    """``reservoir_mm3`` (0: none), the ``valve`` (:class:`~.valve.Valve`), the ``gas``
    (:class:`~.gas.Gas`), ``setup_kPa`` the gauge pressure both were filled to at rest."""

    setup_kPa: float
    reservoir_mm3: float
    valve: object
    gas: object


class Chamber:
    """The chamber's gas on ``chamber_map``: its pressure from mass, temperature and travel."""

    def __init__(self, chamber_map, gas):
        self.map, self.gas = chamber_map, gas
        self.p_lo, self.p_hi = chamber_map.pressure_range
        self.y_lo, self.y_hi = chamber_map.y_range
        self._y, self._slice, self._p = None, None, chamber_map.setup_kPa

    def slice(self, y: float):
        if y != self._y:
            if not (self.y_lo - 1e-9 <= y <= self.y_hi + 1e-9):
                raise ValueError(f"plate travel {y:.4g} mm outside the map's "
                                 f"[{self.y_lo:.3g}, {self.y_hi:.3g}] mm")
            self._y, self._slice = y, self.map.at(min(max(y, self.y_lo), self.y_hi))
        return self._slice

    def pressure(self, m: float, t: float, y: float) -> float:
        """The gauge pressure (kPa) with P V(y, P) = m R T, by Newton from the last one."""
        s, target = self.slice(y), m * self.gas.R * t
        p = self._p
        for _ in range(50):
            v = float(s.volume(p)) * _MM3
            f = (p * _KPA + _PA) * v - target
            df = v * _KPA + (p * _KPA + _PA) * float(s.volume(p, 1)) * _MM3
            step = f / df
            p -= step
            if abs(step) < 1e-12 * (abs(p) + 1.0):
                break
        if not (self.p_lo - 1e-6 <= p <= self.p_hi + 1e-6):
            raise ValueError(f"chamber pressure {p:.4g} kPa outside the map's "
                             f"[{self.p_lo:.3g}, {self.p_hi:.3g}] kPa")
        self._p = p
        return p


def _rates(chamber, circuit, state, y, ydot, open_):
    """d(state)/dt for state (m_c mg, T_c K, m_r mg, T_r K)."""
    gas, valve = circuit.gas, circuit.valve
    mc, tc, mr, tr = state[0] * _MG, state[1], state[2] * _MG, state[3]
    p = chamber.pressure(mc, tc, y)
    s = chamber.slice(y)
    pa = p * _KPA + _PA
    v = float(s.volume(p)) * _MM3
    vp = float(s.volume(p, 1)) * _MM3 / _KPA  # m³/Pa
    vy = float(s.dvolume_dy(p)) * _MM3 * 1e3 * ydot * 1e-3  # ∂V/∂y ẏ (m³/s)
    vr = circuit.reservoir_mm3 * _MM3
    q = 0.0
    if open_ and vr > 0:
        q = valve.mass_flow(gas.pressure(mr, vr, tr), pa, tr, tc)  # reservoir -> chamber
    if gas.isothermal:
        return np.array([q / _MG, 0.0, -q / _MG, 0.0])
    A = np.array([[v + pa * vp, -mc * gas.R], [pa * vp, mc * gas.cv]])
    b = np.array([gas.R * tc * q - pa * vy,
                  gas.enthalpy_in(q, tc, tr) + gas.heat(mc, tc) - pa * vy])
    _, tc_dot = np.linalg.solve(A, b)
    tr_dot = 0.0
    if vr > 0:
        tr_dot = (gas.enthalpy_in(-q, tr, tc) + gas.heat(mr, tr)) / (mr * gas.cv)
    return np.array([q / _MG, tc_dot, -q / _MG, tr_dot])


@dataclass
class TraceArrays:
    """The trace at the output instants (s, mm, N, kPa gauge, mm², mm³, K, mg)."""

    t_s: np.ndarray
    y_mm: np.ndarray
    force_N: np.ndarray
    pressure_kPa: np.ndarray
    reservoir_kPa: np.ndarray
    valve_open: np.ndarray
    chamber_K: np.ndarray
    reservoir_K: np.ndarray
    contact_mm2: np.ndarray
    volume_mm3: np.ndarray
    chamber_mg: np.ndarray
    reservoir_mg: np.ndarray


def initial_state(chamber, circuit, y0: float) -> np.ndarray:
    """Chamber and reservoir at rest at the setup pressure and ambient temperature, the
    plate at ``y0``."""
    gas = circuit.gas
    t = gas.ambient_K
    pa = circuit.setup_kPa * _KPA + _PA
    vc = float(chamber.slice(y0).volume(circuit.setup_kPa)) * _MM3
    mr = gas.mass(pa, circuit.reservoir_mm3 * _MM3, t)
    return np.array([gas.mass(pa, vc, t) / _MG, t, mr / _MG, t])


def _segments(profile, events, t_end):
    """The pieces [t0, t1] between the profile's knots and the valve events."""
    cuts = set(float(t) for t in profile.t_s if t <= t_end) | {0.0, float(t_end)}
    cuts |= {float(e[0]) for e in events if 0.0 < e[0] < t_end}
    cuts = sorted(cuts)
    return list(zip(cuts[:-1], cuts[1:]))


def _valve_state(open0: bool, events, t: float) -> bool:
    state = open0
    for te, opened in sorted(events):
        if te <= t:
            state = opened
    return state


def _outputs(chamber, circuit, times, states):
    """The trace's columns at ``times`` from the states (4, n)."""
    gas, vr = circuit.gas, circuit.reservoir_mm3 * _MM3
    n = len(times)
    y = np.empty(n)
    cols = {k: np.empty(n) for k in ("force", "p", "pr", "area", "volume")}
    for i, t in enumerate(times):
        y[i] = chamber.profile_y(t)
        mc, tc, mr, tr = states[0, i] * _MG, states[1, i], states[2, i] * _MG, states[3, i]
        p = chamber.pressure(mc, tc, y[i])
        s = chamber.slice(y[i])
        # F ≥ 0, A ≥ 0: the spline along P rings where some levels touch the plate and
        # others not yet (a few mN, mm²); the plate only pushes
        cols["p"][i], cols["force"][i], cols["area"][i] = p, max(float(s.force(p)), 0.0), \
            max(float(s.area(p)), 0.0)
        cols["volume"][i] = float(s.volume(p))
        cols["pr"][i] = (gas.pressure(mr, vr, tr) - _PA) / _KPA if vr > 0 else math.nan
    return y, cols


def integrate(chamber_map, circuit, profile, events=(), *, valve_open: bool = False,
              dt: float = 1e-3, progress=None) -> TraceArrays:
    """The trace of ``profile`` (:class:`~.profile.PressProfile`) on the chamber of
    ``chamber_map`` in ``circuit``, the valve ``valve_open`` at t = 0 and switched by
    ``events`` ((t_s, opened) pairs), output every ``dt`` (s). ``progress(t, t_end)`` after
    each piece. Raises :class:`CircuitFailure` with the trace so far (``.trace``)."""
    chamber = Chamber(chamber_map, circuit.gas)
    chamber.profile_y = profile.y
    t_end = profile.duration
    out_t = np.arange(0.0, t_end + 0.5 * dt, dt)
    out_t = out_t[out_t <= t_end + 1e-12]
    state = initial_state(chamber, circuit, float(profile.y(0.0)))
    done_t, done_s, done_v = [], [], []
    scale = np.array([state[0] + state[2], 1.0, state[0] + state[2], 1.0])
    for t0, t1 in _segments(profile, events, t_end):
        open_ = _valve_state(valve_open, events, t0)
        ydot = profile.rate(t0, t1)
        last = t1 >= t_end
        want = np.clip(out_t[(out_t >= t0 - 1e-12) & ((out_t < t1 - 1e-12) | last)], t0, t1)

        def rhs(t, s, _y0=float(profile.y(t0)), _t0=t0):
            return _rates(chamber, circuit, s, _y0 + ydot * (t - _t0), ydot, open_)

        t_eval = np.append(want, t1) if not want.size or want[-1] < t1 else want
        try:
            sol = solve_ivp(rhs, (t0, t1), state, method="LSODA", t_eval=t_eval,
                            rtol=1e-9, atol=1e-12 * scale)
            failed = None if sol.success else sol.message
        except (ValueError, np.linalg.LinAlgError) as exc:
            failed = str(exc)
        if failed is not None:  # the trace up to here, with the state it stopped at
            done_t.append(np.array([t0]))
            done_s.append(state[:, None])
            done_v.append(np.array([open_]))
            trace = _trace(chamber, circuit, done_t, done_s, done_v)
            err = CircuitFailure(f"stopped at t = {t0:.4g} s: {failed}", t0)
            err.trace = trace
            raise err
        keep = len(want)
        done_t.append(sol.t[:keep])
        done_s.append(sol.y[:, :keep])
        done_v.append(np.full(keep, open_))
        state = sol.y[:, -1]
        if progress is not None:
            progress(t1, t_end)
    return _trace(chamber, circuit, done_t, done_s, done_v)


def _trace(chamber, circuit, done_t, done_s, done_v) -> TraceArrays:
    if not done_t:
        z = np.zeros(0)
        return TraceArrays(*(z for _ in range(12)))
    t = np.concatenate(done_t)
    s = np.concatenate(done_s, axis=1)
    y, c = _outputs(chamber, circuit, t, s)
    return TraceArrays(t, y, c["force"], c["p"], c["pr"], np.concatenate(done_v),
                       s[1], s[3], c["area"], c["volume"], s[0], s[2])
