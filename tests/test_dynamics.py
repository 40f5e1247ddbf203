"""The circuit in time against closed forms, on chamber maps whose V(y, P) is known exactly:
a rigid piston (V = V0 − a y) and a compliant one (V = V0 (1 + P/K) − a y), both linear, so
the map's interpolation is exact and only the circuit is tested.

* a closed adiabatic chamber follows P Vⁿ = const and T V^(n−1) = const; an isothermal one
  P V = const;
* the gas mass is conserved through the valve (chamber + reservoir);
* the valve equalises the two to the pressure of their pooled gas, and at its laminar end with
  the time constant of the linearised circuit, τ = 1/(k R T (1/C_c + 1/V_r)), C_c = V + P ∂V/∂P;
* ISO 6358's flow function is continuous, 1 when choked, and the orifice's conductance is the
  ideal nozzle's.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.dynamics import Gas, Valve, sonic_conductance
from spsc.dynamics.chamber_map import ChamberMap
from spsc.dynamics.circuit import Circuit, CircuitFailure, integrate
from spsc.dynamics.gas import R_AIR, T_AMBIENT
from spsc.dynamics.profile import PressProfile
from spsc.dynamics.valve import LAMINAR_RATIO, RHO0, T0

PA_KPA = 101.325


def linear_map(v0=3000.0, a=400.0, compliance_kPa=math.inf, setup=40.0, top=200.0):
    """V = v0 (1 + P/K) − a y (mm³), F = a P y/1000 (N): exact under the map's interpolation."""
    y = np.linspace(-1.0, 5.0, 25)
    p = np.linspace(0.0, top, 9)
    Y, P = np.meshgrid(y, p, indexing="ij")
    V = v0 * (1.0 + P / compliance_kPa) - a * Y
    F = a * P * np.clip(Y, 0, None) / 1000.0
    return ChamberMap(y, p, V, F, np.zeros_like(V), setup)


def volume(trace, v0=3000.0, a=400.0, compliance_kPa=math.inf):
    return v0 * (1.0 + trace.pressure_kPa / compliance_kPa) - a * trace.y_mm


@pytest.mark.parametrize("compliance", [math.inf, 300.0])
def test_closed_adiabatic_chamber_follows_p_v_to_the_n(compliance):
    m = linear_map(compliance_kPa=compliance)
    circ = Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.4))
    tr = integrate(m, circ, PressProfile.of([[0, 0], [0.05, 3]]), dt=1e-3)
    V = volume(tr, compliance_kPa=compliance)
    assert_allclose(V, tr.volume_mm3, rtol=1e-12)
    pv = (tr.pressure_kPa + PA_KPA) * V ** 1.4
    # the integrator's rtol is 1e-9 per step: the invariant holds to well below 1e-6
    assert_allclose(pv, pv[0], rtol=1e-6)
    assert_allclose(tr.chamber_K * V ** 0.4, T_AMBIENT * V[0] ** 0.4, rtol=1e-6)
    assert tr.pressure_kPa[-1] > 40.0 and tr.chamber_K[-1] > T_AMBIENT + 10


def test_closed_isothermal_chamber_keeps_p_v():
    m = linear_map(compliance_kPa=300.0)
    tr = integrate(m, Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.0)),
                   PressProfile.of([[0, 0], [1, 4]]), dt=1e-2)
    pv = (tr.pressure_kPa + PA_KPA) * volume(tr, compliance_kPa=300.0)
    assert_allclose(pv, pv[0], rtol=1e-9)
    assert_allclose(tr.chamber_K, T_AMBIENT, rtol=0)


def test_heat_exchange_relaxes_the_gas_to_ambient():
    m = linear_map()
    tr = integrate(m, Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.4, thermal_time_s=0.1)),
                   PressProfile.of([[0, 0], [0.01, 3], [1.5, 3]]), dt=1e-3)
    # after 15 time constants at rest the gas is at ambient: the isothermal pressure
    v0, v1 = 3000.0, 3000.0 - 400.0 * 3
    assert_allclose(tr.chamber_K[-1], T_AMBIENT, atol=1e-3)
    assert_allclose(tr.pressure_kPa[-1] + PA_KPA, (40 + PA_KPA) * v0 / v1, rtol=1e-6)


def _equalise(gas, compliance=math.inf, reservoir=40000.0, t_open=0.05, t_end=2.0, dt=1e-4):
    m = linear_map(compliance_kPa=compliance)
    circ = Circuit(40.0, reservoir, Valve(sonic_conductance(0.3)), gas)
    prof = PressProfile.of([[0, 0], [0.02, 3], [t_end, 3]])
    return integrate(m, circ, prof, [(t_open, True)], dt=dt)


def test_gas_mass_is_conserved_through_the_valve():
    tr = _equalise(Gas(n=1.4, thermal_time_s=0.2))
    total = tr.chamber_mg + tr.reservoir_mg
    assert_allclose(total, total[0], rtol=1e-9)
    assert tr.chamber_mg[-1] < tr.chamber_mg[0]  # gas went to the reservoir


@pytest.mark.parametrize("compliance", [math.inf, 300.0])
def test_valve_equalises_to_the_pooled_gas_with_the_linearised_time_constant(compliance):
    tr = _equalise(Gas(n=1.0), compliance=compliance)
    # the final state: one pressure, P (V_c(P) + V_r) = m R T of the pooled gas
    mass = (tr.chamber_mg[0] + tr.reservoir_mg[0]) * 1e-6
    p = tr.pressure_kPa[-1]
    vc = 3000.0 * (1 + p / compliance) - 400.0 * 3
    assert_allclose((p * 1e3 + PA_KPA * 1e3) * (vc + 40000.0) * 1e-9, mass * R_AIR * T_AMBIENT,
                    rtol=1e-8)
    assert_allclose(tr.reservoir_kPa[-1], p, atol=1e-7)
    # the laminar end: Δ(t) = Δ0 exp(−t/τ) once Δ < (1 − r_l) P
    valve, T = Valve(sonic_conductance(0.3)), T_AMBIENT
    pa = (p + PA_KPA) * 1e3
    k = valve.conductance(pa, T)
    cc = (vc + (pa * 3000.0 / compliance / 1e3 if math.isfinite(compliance) else 0.0)) * 1e-9
    tau = 1.0 / (k * R_AIR * T * (1.0 / cc + 1.0 / 40000e-9))
    d = (tr.pressure_kPa - tr.reservoir_kPa) * 1e3
    window = (d < 0.5 * (1 - LAMINAR_RATIO) * pa) & (d > 1e-4 * (1 - LAMINAR_RATIO) * pa) \
        & (tr.t_s > 0.05)
    slope = np.polyfit(tr.t_s[window], np.log(d[window]), 1)[0]
    assert window.sum() > 20
    assert_allclose(-1.0 / slope, tau, rtol=0.02)


def test_iso6358_flow_function_and_the_orifice_conversion():
    v = Valve(0.06, b=0.4, m=0.5)
    assert v.phi(0.1) == 1.0 == v.phi(0.4)
    r = np.linspace(0.0, 1.0, 20001)
    phi = np.array([v.phi(x) for x in r])
    assert np.all(np.diff(phi) <= 1e-12) and phi[-1] == 0.0
    assert np.max(np.abs(np.diff(phi))) < 1e-2  # continuous at b and at the laminar end
    # choked: q = C ρ0 p1 sqrt(T0/T1)
    assert_allclose(v.mass_flow(5e5, 1e5, T0, T0), 0.06e-8 * RHO0 * 5e5, rtol=1e-12)
    assert v.mass_flow(1e5, 5e5, T0, T0) == -v.mass_flow(5e5, 1e5, T0, T0)
    # an ideal nozzle: the choked flux c* p/√T with c* = 0.0404 s·√K/m for air
    c = sonic_conductance(0.3)
    assert_allclose(Valve(c).mass_flow(3e5, 1e5, 300.0, 300.0), 0.3e-6 * 0.040418 * 3e5
                    / math.sqrt(300.0), rtol=1e-4)
    assert 4.9 < 0.3 / c < 5.1  # the rule of thumb S ≈ 5 C


def test_leaving_the_map_stops_with_the_trace_so_far():
    m = linear_map(top=50.0)  # the press drives the closed chamber past 50 kPa
    with pytest.raises(CircuitFailure, match="left the map") as err:
        integrate(m, Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.0)),
                  PressProfile.of([[0, 0], [0.5, 0.1], [1, 4]]), dt=1e-2)
    # 50 kPa at (40 + Pa) 3000 / (3000 − 400 y) = 50 + Pa: y = 0.4956 mm, t = 0.5507 s; the
    # trace is kept to there (outputs every 10 ms and where it stopped, to 1 µs)
    y = 3000.0 * (1.0 - (40.0 + PA_KPA) / (50.0 + PA_KPA)) / 400.0
    t = 0.5 + (y - 0.1) / (3.9 / 0.5)
    assert_allclose(err.value.time_s, t, atol=2e-6)
    tr = err.value.trace
    assert len(tr.t_s) == 57 and tr.pressure_kPa.max() <= 50.0 + 1e-6


@pytest.mark.parametrize("bad, name", [
    (dict(C=0.0), "valve C"), (dict(C=0.06, b=1.0), "valve b"), (dict(C=0.06, m=0), "valve m")])
def test_bad_valve_is_one_error_naming_it(bad, name):
    with pytest.raises(ParameterError, match=name):
        Valve(**bad)


def test_bad_gas_and_profile_are_errors_naming_them():
    with pytest.raises(ParameterError, match="gas n"):
        Gas(n=0.9)
    with pytest.raises(ParameterError, match="thermal_time_s"):
        Gas(n=1.4, thermal_time_s=-1)
    with pytest.raises(ParameterError, match="press profile t_s"):
        PressProfile.of([[0, 0], [1, 2], [1, 3]])
    with pytest.raises(ParameterError, match="press profile"):
        PressProfile.of([[0, 0]])


def _pooled_sensitivity(p_kPa, y, n, v_r, compliance=300.0, v0=3000.0, a=400.0):
    """dP/dy (kPa/mm) of the linear chamber at rest: isothermal with the reservoir pooled
    (n = 1, v_r > 0), or closed and adiabatic (n, v_r = 0): d(P (V + V_r)ⁿ) = 0."""
    pa = p_kPa + PA_KPA
    v = v0 * (1 + p_kPa / compliance) - a * y
    return n * pa * a / (v + v_r + n * pa * v0 / compliance)


def test_bode_limits_are_the_pooled_and_the_closed_adiabatic_chamber():
    from spsc.dynamics.frequency import bode

    m = linear_map(compliance_kPa=300.0)
    circ = Circuit(40.0, 40000.0, Valve(sonic_conductance(0.3)), Gas(n=1.4, thermal_time_s=0.2))
    table = bode(m, circ, 3.0, True, [1e-5, 1e5])
    lo, hi = table.sensitivity_kPa_per_mm.to_numpy()
    from spsc.dynamics.frequency import linearise

    p = linearise(m, circ, 3.0, True)["pressure_kPa"]
    # slow: the pooled isothermal gas (the low mode); fast: the chamber closed, adiabatic
    assert_allclose(lo, _pooled_sensitivity(p, 3.0, 1.0, 40000.0), rtol=1e-4)
    assert_allclose(hi, _pooled_sensitivity(p, 3.0, 1.4, 0.0), rtol=1e-4)
    # F = a P y / 1000: F̂/ŷ = a P/1000 + a y/1000 · P̂/ŷ
    assert_allclose(table.stiffness_N_per_mm.iloc[0], 0.4 * p + 0.4 * 3.0 * lo, rtol=1e-4)


# 60 Hz takes 10 s of make test's 3 minutes: with the slow cases (CI runs both)
@pytest.mark.parametrize("f_Hz", [2.0, pytest.param(60.0, marks=pytest.mark.slow)])
def test_bode_is_the_time_domain_response_to_a_small_sinusoid(monkeypatch, f_Hz):
    """The linearisation against the nonlinear circuit pressed by ŷ = 5 µm at f, after the
    start-up transient (a lock-in on whole periods)."""
    import spsc.dynamics.circuit as cm
    from spsc.dynamics.frequency import bode, operating_point

    m = linear_map(compliance_kPa=300.0)
    circ = Circuit(40.0, 40000.0, Valve(sonic_conductance(0.3)),
                   Gas(n=1.4, thermal_time_s=0.02))
    x0 = operating_point(m, circ, 3.0, True)
    monkeypatch.setattr(cm, "initial_state", lambda ch, c, y: x0.copy())
    period, n = 1.0 / f_Hz, 80
    settle = max(3 * period, 0.3)  # the thermal transient (15 τ) and the valve's (ms)
    t = np.arange(0.0, settle + 4 * period + 0.5 * period / n, period / n)
    prof = PressProfile.of(list(zip(t, 3.0 + 0.005 * np.sin(2 * np.pi * f_Hz * t))))
    tr = integrate(m, circ, prof, valve_open=True, dt=period / n)
    sel = tr.t_s >= settle - 1e-9
    sel[np.flatnonzero(sel)[-1]] = False  # whole periods
    ph = np.exp(-2j * np.pi * f_Hz * tr.t_s[sel])
    y_hat = 2 * np.mean((tr.y_mm[sel] - 3.0) * ph)
    p_hat = 2 * np.mean((tr.pressure_kPa[sel] - tr.pressure_kPa[sel].mean()) * ph)
    ref = bode(m, circ, 3.0, True, [f_Hz]).iloc[0]
    # 5 µm on a 3 mm press: the nonlinearity is ~1e-3 of the response; the piecewise-linear
    # profile (80 knots a period) ~2e-3 at 2 Hz (0.8 % with 40, converging with more)
    assert_allclose(abs(p_hat / y_hat), ref.sensitivity_kPa_per_mm, rtol=5e-3)
    assert abs(np.degrees(np.angle(p_hat / y_hat)) - ref.sensitivity_phase_deg) < 0.5


def test_a_pressure_threshold_switches_the_valve_where_the_pressure_crosses_it():
    from spsc.dynamics.circuit import Trigger

    m = linear_map(compliance_kPa=300.0)
    circ = Circuit(40.0, 40000.0, Valve(sonic_conductance(0.3)), Gas(n=1.0))
    prof = PressProfile.of([[0, 0], [1, 3], [2, 3], [3, 0]])
    # closed while pressed: the pressure rises through 45 kPa, the valve opens there (once);
    # the release then drops the pooled pressure (about 42.5 kPa at 3 mm) back toward the
    # setup's 40: below 40.5 kPa, armed at 2 s, it closes again
    trig = (Trigger(45.0, True, True), Trigger(40.5, False, False, after_s=2.0))
    tr = integrate(m, circ, prof, valve_open=False, dt=1e-3, triggers=trig)
    (t1, o1, w1), (t2, o2, w2) = tr.switches
    assert o1 and not o2 and "above 45" in w1 and "below 40.5" in w2
    # the pressure a closed, isothermal chamber has at t1 (the profile's y): exactly 45 kPa
    y1 = 3.0 * t1
    v0, p = 3000.0 * (1 + 40 / 300.0), 45.0
    v1 = 3000.0 * (1 + p / 300.0) - 400.0 * y1
    assert_allclose((p + PA_KPA) * v1, (40 + PA_KPA) * v0, rtol=1e-7)
    assert tr.valve_open[np.searchsorted(tr.t_s, t1) - 1] == 0
    assert tr.valve_open[np.searchsorted(tr.t_s, t1) + 1] == 1
    assert 2.0 < t2 < 3.0 and tr.valve_open[-1] == 0
    # read off the 1 ms samples of a pressure falling 2.5 kPa/s (a few Pa between samples)
    assert_allclose(np.interp(t2, tr.t_s, tr.pressure_kPa), 40.5, atol=5e-3)


def test_a_threshold_met_when_armed_fires_at_once():
    from spsc.dynamics.circuit import Trigger

    m = linear_map()
    tr = integrate(m, Circuit(40.0, 40000.0, Valve(0.06), Gas(n=1.0)),
                   PressProfile.of([[0, 0], [1, 2]]), valve_open=True, dt=1e-2,
                   triggers=(Trigger(30.0, True, False, after_s=0.5),))
    assert [(t, o) for t, o, _ in tr.switches] == [(0.5, False)]
