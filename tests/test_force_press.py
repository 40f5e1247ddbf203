"""The force-controlled press: the plate goes where the chamber carries the prescribed force.

On the analytic map of test_dynamics (V = v0 (1 + P/K) − a y, F = a P y / 1000, exact under
the map's interpolation for y ≥ 0.25 mm) the closed chamber's travel has a closed form; the
adiabatic gas keeps P Vⁿ; a force press replaying a travel press's force gives its travel back.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.dynamics import Gas, Valve, sonic_conductance
from spsc.dynamics.circuit import Circuit, CircuitFailure, integrate
from spsc.dynamics.gas import T_AMBIENT
from spsc.dynamics.profile import ForceProfile, PressProfile
from spsc.dynamics.scenario import parse_scenario
from test_dynamics import PA_KPA, linear_map, volume


def closed_isothermal_travel(force, setup=40.0, v0=3000.0, a=400.0, y0=None):
    """y with a P y / 1000 = F and (P + Pa)(v0 − a y) = (setup + Pa)(v0 − a y0)."""
    c = (setup + PA_KPA) * (v0 - a * y0)
    # P = 1000 F / (a y): (1000 F/(a y) + Pa)(v0 − a y) = c, times y: a quadratic in y
    k = 1000.0 * force / a
    # (k + Pa y)(v0 − a y) = c y  ->  −Pa a y² + (Pa v0 − k a − c) y + k v0 = 0
    return np.array([max(np.roots([-PA_KPA * a, PA_KPA * v0 - kk * a - c, kk * v0]))
                     for kk in np.atleast_1d(k)])


def test_closed_isothermal_force_press_has_the_closed_form_travel():
    f0, f1 = 8.0, 20.0  # N: from y = 0.5 mm at 40 kPa
    tr = integrate(linear_map(), Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.0)),
                   ForceProfile.of([[0, f0], [1, f1]]), dt=0.01)
    want_f = f0 + (f1 - f0) * tr.t_s
    # the travel is Newton's root to 1e-10 of the force; the mass is the integrator's (fixed)
    assert_allclose(tr.force_N, want_f, rtol=1e-9)
    y0 = 1000.0 * f0 / (400.0 * 40.0)
    assert_allclose(tr.y_mm, closed_isothermal_travel(want_f, y0=y0), rtol=1e-9)
    pv = (tr.pressure_kPa + PA_KPA) * volume(tr)
    assert_allclose(pv, pv[0], rtol=1e-9)
    assert tr.y_mm[-1] > tr.y_mm[0] + 0.4


@pytest.mark.parametrize("compliance", [math.inf, 300.0])
def test_closed_adiabatic_force_press_keeps_p_v_to_the_n(compliance):
    """The third row F_P Ṗ + F_y ẏ = Ḟ of the energy balance: a wrong ẏ breaks P Vⁿ."""
    m = linear_map(compliance_kPa=compliance)
    tr = integrate(m, Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.4)),
                   ForceProfile.of([[0, 8.0], [0.05, 30.0]]), dt=1e-3)
    V = volume(tr, compliance_kPa=compliance)
    pv = (tr.pressure_kPa + PA_KPA) * V ** 1.4
    assert_allclose(pv, pv[0], rtol=1e-6)  # the integrator's rtol is 1e-9 per step
    assert_allclose(tr.chamber_K * V ** 0.4, T_AMBIENT * V[0] ** 0.4, rtol=1e-6)
    assert_allclose(tr.force_N, 8.0 + 22.0 * tr.t_s / 0.05, rtol=1e-9)


def test_force_press_replays_a_travel_press_through_the_valve():
    """The valve open, air with heat exchange: the force of a travel press, replayed as a
    force press, gives the travel back."""
    m = linear_map(compliance_kPa=300.0)
    circ = Circuit(40.0, 40000.0, Valve(sonic_conductance(0.3)), Gas(n=1.4, thermal_time_s=0.2))
    travel = integrate(m, circ, PressProfile.of([[0, 0.5], [0.05, 3.0], [0.15, 3.0]]),
                       valve_open=True, dt=5e-4)
    force = integrate(m, circ, ForceProfile.of(np.column_stack([travel.t_s, travel.force_N])),
                      valve_open=True, dt=5e-4)
    # the replayed force is piecewise linear between samples of a smooth force: measured
    # max |Δy| 2.5e-6, 1.0e-5, 6.3e-5, 2.8e-4 mm at dt 0.1, 0.2, 0.5, 1 ms (second order)
    assert_allclose(force.y_mm, travel.y_mm, atol=1e-4)
    assert_allclose(force.pressure_kPa, travel.pressure_kPa, rtol=4e-5)


def test_force_beyond_the_map_stops_with_the_trace_so_far():
    p5 = (40.0 + PA_KPA) * (3000.0 - 400.0 * 0.5) / (3000.0 - 400.0 * 5.0) - PA_KPA
    f_max = 400.0 * p5 * 5.0 / 1000.0  # what the closed chamber carries at the map's 5 mm
    with pytest.raises(CircuitFailure, match="max_travel_mm") as err:
        integrate(linear_map(top=1000.0), Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.0)),
                  ForceProfile.of([[0, 8.0], [1, 800.0]]), dt=0.01)
    tr = err.value.trace
    # kept to where it failed (the last output before 586 N), to 1 µs
    assert tr.force_N[-2] <= f_max < tr.force_N[-2] + 7.92
    assert_allclose(8.0 + 792.0 * err.value.time_s, f_max, atol=792.0 * 2e-6)
    assert tr.y_mm.max() <= 5.0


@pytest.mark.parametrize("bad, name", [
    ([[0, 1.0], [1, -2.0]], "press force force_N"),
    ([[0.5, 1.0], [1, 2.0]], "press force t_s"),
    ([[0, 1.0]], "press force"),
    ("hard", "press force"),
])
def test_bad_force_profile_is_one_error_naming_it(bad, name):
    with pytest.raises(ParameterError, match=name):
        ForceProfile.of(bad)


def _doc(press):
    return {"chamber": {"type": "B"}, "circuit": {"setup_kPa": 40}, "press": press}


def test_scenario_takes_a_force_press_or_a_travel_press_not_both():
    sc = parse_scenario(_doc({"force": [[0, 0], [1, 5]], "max_travel_mm": 3.5}))
    assert isinstance(sc.press, ForceProfile) and sc.press.extent == (0.0, 3.5)
    with pytest.raises(ParameterError, match="press"):
        parse_scenario(_doc({"force": [[0, 0], [1, 5]], "profile": [[0, 0], [1, 3]]}))
    with pytest.raises(ParameterError, match="press.max_travel_mm"):
        parse_scenario(_doc({"profile": [[0, 0], [1, 3]], "max_travel_mm": 3}))
    with pytest.raises(ParameterError, match="press.max_travel_mm"):
        parse_scenario(_doc({"force": [[0, 0], [1, 5]], "max_travel_mm": -1}))


@pytest.mark.parametrize("path", sorted((Path(__file__).parents[1] / "examples").glob("*.toml")),
                         ids=lambda p: p.name)
def test_every_example_scenario_is_valid(path):
    from spsc.dynamics.scenario import read_scenario

    sc = read_scenario(path)
    assert sc.press.duration > 0 and sc.chamber.geometry() is not None
