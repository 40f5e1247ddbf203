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
T = T_a and needs only dm/dt = q. Under a force-controlled press (:class:`~.profile.ForceProfile`)
the travel is where the gas carries the force (:meth:`~.chamber.Chamber.travel`) and ẏ joins
(Ṗ, Ṫ) as a third unknown with F_P Ṗ + F_y ẏ = Ḟ. The valve's flow is ISO 6358 (:mod:`.valve`). The ODE is
integrated by LSODA between the profile's knots and the valve events (so ẏ and the valve state
are constant on each piece), and the state is output every ``dt``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from spsc.core.constants import P_AMB

from .chamber import Chamber

__all__ = ["Circuit", "Trigger", "integrate", "TraceArrays", "CircuitFailure"]

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
    (:class:`~.gas.Gas`), ``setup_kPa`` the gauge pressure both were filled to at rest;
    ``leak`` an orifice from the chamber to the ambient air (a :class:`~.valve.Valve`,
    :mod:`.leak`; None: sealed)."""

    setup_kPa: float
    reservoir_mm3: float
    valve: object
    gas: object
    leak: object = None


def _rates(chamber, circuit, state, y, ydot, open_, fdot=None, spring=0.0):
    """d(state)/dt for state (m_c mg, T_c K, m_r mg, T_r K) at travel ``y`` (mm) moving at
    ``ydot`` (mm/s); under a force-controlled press (``fdot``: Ḟ N/s) ẏ is the third unknown
    of the energy balance, with F_P Ṗ + F_y ẏ = Ḟ; on a spring of k (``spring`` N/mm, and
    ``fdot`` = k ẋ) F_P Ṗ + (F_y + k) ẏ = k ẋ."""
    gas, valve = circuit.gas, circuit.valve
    mc, tc, mr, tr = state[0] * _MG, state[1], state[2] * _MG, state[3]
    p = chamber.pressure(mc, tc, y, check=False)
    s = chamber.slice(y)
    pa = p * _KPA + _PA
    v = float(s.volume(p)) * _MM3
    vp = float(s.volume(p, 1)) * _MM3 / _KPA  # m³/Pa
    vr = circuit.reservoir_mm3 * _MM3
    q = 0.0
    if open_ and vr > 0:
        q = valve.mass_flow(gas.pressure(mr, vr, tr), pa, tr, tc)  # reservoir -> chamber
    q_in = q  # into the chamber: the valve's, less the leak's to the ambient air
    if circuit.leak is not None:
        q_in = q + circuit.leak.mass_flow(_PA, pa, gas.ambient_K, tc)
    if gas.isothermal:
        return np.array([q_in / _MG, 0.0, -q / _MG, 0.0])
    tr_dot = 0.0
    if vr > 0:
        tr_dot = (gas.enthalpy_in(-q, tr, tc) + gas.heat(mr, tr)) / (mr * gas.cv)
    vy = float(s.dvolume_dy(p)) * _MM3 * 1e3  # ∂V/∂y (m³/m)
    enthalpy = gas.enthalpy_in(q, tc, tr) + gas.heat(mc, tc)
    if q_in != q:
        enthalpy += gas.enthalpy_in(q_in - q, tc, gas.ambient_K)
    rhs = [gas.R * tc * q_in, enthalpy]
    if fdot is None:
        A = np.array([[v + pa * vp, -mc * gas.R], [pa * vp, mc * gas.cv]])
        b = np.array(rhs) - pa * vy * ydot * 1e-3
    else:  # unknowns Ṗ (Pa/s), Ṫ (K/s), ẏ (m/s)
        f_p, f_y = float(s.force(p, 1)) / _KPA, float(s.dforce_dy(p)) * 1e3  # N/Pa, N/m
        if spring and float(s.force(p)) <= 0.0:  # off the chamber: the plate follows x
            f_p, f_y = 0.0, 0.0
        A = np.array([[v + pa * vp, -mc * gas.R, pa * vy], [pa * vp, mc * gas.cv, pa * vy],
                      [f_p, 0.0, f_y + spring * 1e3]])
        b = np.array(rhs + [fdot])
    tc_dot = np.linalg.solve(A, b)[1]
    return np.array([q_in / _MG, tc_dot, -q / _MG, tr_dot])


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
    #: the valve's switches: (t_s, opened, why)
    switches: list = field(default_factory=list)


def initial_state(chamber, circuit, y0: float) -> np.ndarray:
    """Chamber and reservoir at rest at the setup pressure and ambient temperature, the
    plate at ``y0`` (mm)."""
    gas = circuit.gas
    t = gas.ambient_K
    pa = circuit.setup_kPa * _KPA + _PA
    vc = float(chamber.slice(y0).volume(circuit.setup_kPa)) * _MM3
    mr = gas.mass(pa, circuit.reservoir_mm3 * _MM3, t)
    return np.array([gas.mass(pa, vc, t) / _MG, t, mr / _MG, t])


def _cuts(profile, events, triggers, t_end) -> list:
    """The piece boundaries: the profile's knots, the valve's timed events and the instants
    thresholds are armed."""
    cuts = set(float(t) for t in profile.t_s if t <= t_end) | {0.0, float(t_end)}
    cuts |= {float(e[0]) for e in events if 0.0 < e[0] < t_end}
    cuts |= {float(tr.after_s) for tr in triggers if 0.0 < tr.after_s < t_end}
    return sorted(cuts)


@dataclass(frozen=True)
class Trigger:
    """Switch the valve (``opened``) when the chamber's gauge pressure first rises above
    (``above``) or falls below ``level_kPa``, from ``after_s`` on; once."""

    level_kPa: float
    above: bool
    opened: bool
    after_s: float = 0.0

    def describe(self) -> str:
        return (f"chamber pressure {'above' if self.above else 'below'} {self.level_kPa:g} kPa:"
                f" valve {'open' if self.opened else 'closed'}")


def _outputs(chamber, circuit, profile, times, states):
    """The trace's columns at ``times`` from the states (4, n)."""
    gas, vr = circuit.gas, circuit.reservoir_mm3 * _MM3
    n = len(times)
    y = np.empty(n)
    cols = {k: np.empty(n) for k in ("force", "p", "pr", "area", "volume")}
    for i, t in enumerate(times):
        mc, tc, mr, tr = states[0, i] * _MG, states[1, i], states[2, i] * _MG, states[3, i]
        y[i] = profile.travel(t, chamber, mc, tc)
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
              dt: float = 1e-3, progress=None, triggers=()) -> TraceArrays:
    """The trace of ``profile`` (:class:`~.profile.PressProfile`, or
    :class:`~.profile.ForceProfile`: the plate goes where the chamber carries the force) on
    the chamber of ``chamber_map`` in ``circuit``, the valve ``valve_open`` at t = 0 and switched by
    ``events`` ((t_s, opened) pairs) and by pressure ``triggers`` (:class:`Trigger`, located by
    the integrator's root finding), output every ``dt`` (s). ``progress(t, t_end)`` after each
    piece. Raises :class:`CircuitFailure` with the trace so far (``.trace``)."""
    chamber = Chamber(chamber_map, circuit.gas)
    t_end = profile.duration
    out_t = np.arange(0.0, t_end + 0.5 * dt, dt)
    out_t = out_t[out_t <= t_end + 1e-12]
    if hasattr(profile, "y"):
        y0 = float(profile.y(0.0))
    elif hasattr(profile, "stiffness_N_per_mm"):
        y0 = chamber.spring_at_pressure(circuit.setup_kPa, float(profile.x(0.0)),
                                        profile.stiffness_N_per_mm)
    else:
        y0 = chamber.travel_at_pressure(circuit.setup_kPa, float(profile.force(0.0)))
    state = initial_state(chamber, circuit, y0)
    run = _Run(chamber, circuit, profile, state, valve_open, list(triggers))
    cuts = _cuts(profile, events, triggers, t_end)
    t0 = 0.0
    while t0 < t_end - 1e-12:
        t1 = next(c for c in cuts if c > t0 + 1e-12)
        for te, opened in events:
            if abs(te - t0) <= 1e-12:
                run.switch(te, opened, f"at t = {te:g} s: valve {'open' if opened else 'closed'}")
        want = np.clip(out_t[(out_t >= t0 - 1e-12) & ((out_t < t1 - 1e-12) | (t1 >= t_end))],
                       t0, t1)
        t0 = run.piece(t0, t1, want)
        if progress is not None:
            progress(t0, t_end)
    return run.trace()


class _Stopped(Exception):
    """A piece's integration failed (the message says why)."""


class _Run:
    """An integration under way: the state, the valve, the pending triggers, the trace."""

    def __init__(self, chamber, circuit, profile, state, valve_open, triggers):
        self.chamber, self.circuit, self.profile = chamber, circuit, profile
        self.state, self.open, self.pending = state, valve_open, triggers
        self.scale = np.array([state[0] + state[2], 1.0, state[0] + state[2], 1.0])
        self.done_t, self.done_s, self.done_v, self.switches = [], [], [], []

    def switch(self, t, opened, why) -> None:
        self.open = opened
        self.switches.append((float(t), bool(opened), why))

    def _pressure(self, t, s, check=True):
        y = self.profile.travel(t, self.chamber, s[0] * _MG, s[1])
        return self.chamber.pressure(s[0] * _MG, s[1], y, check)

    def _events(self, armed) -> list:
        """The integrator's terminal events: each armed trigger's crossing, then the chamber
        pressure leaving the map's pressures (last)."""
        def crossing(tr):
            def f(t, s):
                return self._pressure(t, s, False) - tr.level_kPa
            f.terminal, f.direction = True, 1.0 if tr.above else -1.0
            return f

        lo, hi = self.chamber.p_lo, self.chamber.p_hi

        def leaving(t, s):
            p = self._pressure(t, s, False)
            return min(p - lo, hi - p) + 1e-7
        leaving.terminal, leaving.direction = True, -1.0
        return [crossing(tr) for tr in armed] + [leaving]

    def piece(self, t0, t1, want) -> float:
        """Integrate from t0 toward t1 (outputs at ``want``); where it got to (a trigger
        fires before t1). Where the integration fails, the halves of the piece, down to 1 µs:
        the trace is kept up to where it fails, and :class:`CircuitFailure` says when."""
        try:
            return self._piece(t0, t1, want)
        except _Stopped as exc:
            if t1 - t0 <= 1e-6:
                self._keep(np.array([t0]), self.state[:, None], self.open)
                err = CircuitFailure(f"stopped at t = {t0:.6g} s: {exc}", t0)
                err.trace = self.trace()
                raise err from None
        mid = 0.5 * (t0 + t1)
        got = self.piece(t0, mid, want[want < mid])
        return got if got < mid else self.piece(mid, t1, want[want >= mid])

    def _piece(self, t0, t1, want) -> float:
        rate, open_ = self.profile.rate(t0, t1), self.open
        armed = [tr for tr in self.pending if tr.after_s <= t0 + 1e-12]
        for tr in armed:  # a condition already met when armed fires at once
            p = self._pressure(t0, self.state)
            if (p > tr.level_kPa) if tr.above else (p < tr.level_kPa):
                self.pending.remove(tr)
                self.switch(t0, tr.opened, f"at t = {t0:.6g} s: {tr.describe()}")
                return t0

        if hasattr(self.profile, "y"):
            y0 = float(self.profile.y(t0))

            def rhs(t, s):
                return _rates(self.chamber, self.circuit, s, y0 + rate * (t - t0), rate, open_)
        else:
            k = getattr(self.profile, "stiffness_N_per_mm", 0.0)
            fdot = k * rate if k else rate  # on a spring, rate is ẋ (mm/s): k ẋ in N/s

            def rhs(t, s):
                y = self.profile.travel(t, self.chamber, s[0] * _MG, s[1])
                return _rates(self.chamber, self.circuit, s, y, None, open_, fdot=fdot,
                              spring=k)

        t_eval = np.append(want, t1) if not want.size or want[-1] < t1 else want
        try:
            sol = solve_ivp(rhs, (t0, t1), self.state, method="LSODA", t_eval=t_eval,
                            rtol=1e-9, atol=1e-12 * self.scale,
                            events=self._events(armed))
            failed = None if sol.success else sol.message
        except (ValueError, np.linalg.LinAlgError) as exc:
            failed = str(exc)
        if failed is not None:
            raise _Stopped(failed)
        fired = [(k, ev[0]) for k, ev in enumerate(sol.t_events or []) if len(ev)]
        if fired:
            k, te = min(fired, key=lambda kv: kv[1])
            keep = sol.t < te
            self._keep(sol.t[keep], sol.y[:, keep], open_)
            self.state = sol.y_events[k][0]
            if k == len(armed):  # the gas left the map: the trace ends where it did
                self._keep(np.array([te]), self.state[:, None], open_)
                p = self._pressure(te, self.state, False)
                err = CircuitFailure(f"stopped at t = {te:.6g} s: the chamber pressure "
                                     f"({p:.4g} kPa) left the map's [{self.chamber.p_lo:.3g}, "
                                     f"{self.chamber.p_hi:.3g}] kPa", float(te))
                err.trace = self.trace()
                raise err
            tr = armed[k]
            self.pending.remove(tr)
            self.switch(te, tr.opened, f"at t = {te:.6g} s: {tr.describe()}")
            return float(te)
        keep = len(want)
        self._keep(sol.t[:keep], sol.y[:, :keep], open_)
        self.state = sol.y[:, -1]
        return t1

    def _keep(self, t, y, open_) -> None:
        self.done_t.append(t)
        self.done_s.append(y)
        self.done_v.append(np.full(len(t), open_))

    def trace(self) -> "TraceArrays":
        tr = _trace(self.chamber, self.circuit, self.profile, self.done_t, self.done_s, self.done_v)
        tr.switches = list(self.switches)
        return tr


def _trace(chamber, circuit, profile, done_t, done_s, done_v) -> TraceArrays:
    if not done_t:
        z = np.zeros(0)
        return TraceArrays(*(z for _ in range(12)))
    t = np.concatenate(done_t)
    s = np.concatenate(done_s, axis=1)
    y, c = _outputs(chamber, circuit, profile, t, s)
    return TraceArrays(t, y, c["force"], c["p"], c["pr"], np.concatenate(done_v),
                       s[1], s[3], c["area"], c["volume"], s[0], s[2])
