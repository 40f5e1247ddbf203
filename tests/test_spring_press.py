"""A compliant object: the plate on a spring of k whose far end follows x(t)
(:class:`~spsc.dynamics.profile.SpringProfile`), on the analytic map of test_dynamics
(V = v0 (1 + P/K) − a y, F = a P y / 1000):

* the closed isothermal chamber: F(y, P) = k (x − y) and (P + Pa) V = const at every sample;
* the adiabatic gas keeps P Vⁿ through the third row F_P Ṗ + (F_y + k) ẏ = k ẋ (a wrong ẏ
  breaks it);
* a stiff spring is the travel press (y within F/k of x), off the chamber y = x;
* a bad stiffness is a one-line error naming it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.dynamics import Gas, Valve, sonic_conductance
from spsc.dynamics.circuit import Circuit, integrate
from spsc.dynamics.profile import PressProfile, SpringProfile
from test_dynamics import PA_KPA, linear_map, volume

PAIRS = [[0.0, -0.5], [0.2, 0.5], [1.0, 3.0], [1.2, 3.0]]


def test_closed_isothermal_chamber_on_a_spring_balances_it():
    k = 16.0  # N/mm: the chamber's own a P/1000 at 40 kPa, so both take a share
    tr = integrate(linear_map(), Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.0)),
                   SpringProfile.of(PAIRS, k), dt=0.01)
    x = np.interp(tr.t_s, *zip(*PAIRS))
    on = tr.y_mm > 0.3  # the analytic map is exact from y = 0.25 mm
    assert_allclose(tr.force_N[on], k * (x - tr.y_mm)[on], rtol=1e-9)
    pv = (tr.pressure_kPa + PA_KPA) * volume(tr)
    assert_allclose(pv, pv[0], rtol=1e-9)
    assert 0.5 < tr.y_mm[-1] < 2.5  # the chamber took part of the 3 mm, the spring the rest
    off = x <= 0.0
    assert_allclose(tr.y_mm[off], x[off], atol=1e-12)


@pytest.mark.parametrize("compliance", [math.inf, 300.0])
def test_adiabatic_chamber_on_a_spring_keeps_p_v_to_the_n(compliance):
    m = linear_map(compliance_kPa=compliance)
    pairs = [[0.0, 0.5], [0.05, 3.0]]
    tr = integrate(m, Circuit(40.0, 0.0, Valve(0.06), Gas(n=1.4)),
                   SpringProfile.of(pairs, 5.0), dt=1e-3)
    V = volume(tr, compliance_kPa=compliance)
    pv = (tr.pressure_kPa + PA_KPA) * V ** 1.4
    assert_allclose(pv, pv[0], rtol=1e-6)  # the integrator's rtol is 1e-9 per step
    x = np.interp(tr.t_s, *zip(*pairs))
    assert_allclose(tr.force_N, 5.0 * (x - tr.y_mm), rtol=1e-8)


def test_a_stiff_spring_is_the_travel_press():
    m = linear_map(compliance_kPa=300.0)
    circ = Circuit(40.0, 40000.0, Valve(sonic_conductance(0.3)), Gas(n=1.4, thermal_time_s=0.2))
    press = integrate(m, circ, PressProfile.of(PAIRS), valve_open=True, dt=1e-3)
    spring = integrate(m, circ, SpringProfile.of(PAIRS, 1e5), valve_open=True, dt=1e-3)
    assert_allclose(spring.y_mm, press.y_mm, atol=press.force_N.max() / 1e5 * 1.01)
    assert_allclose(spring.force_N, press.force_N, rtol=1e-3, atol=1e-6)


@pytest.mark.parametrize("k", [0.0, -1.0, math.inf])
def test_a_bad_stiffness_is_one_error_naming_it(k):
    with pytest.raises(ParameterError, match="object stiffness"):
        SpringProfile.of(PAIRS, k)


def test_a_scenario_takes_an_object_spring_with_a_travel_profile_only():
    from spsc.dynamics.scenario import parse_scenario

    def doc(press):
        return {"chamber": {"type": "B"}, "circuit": {"setup_kPa": 40}, "press": press}

    sc = parse_scenario(doc({"profile": [[0, -0.3], [1, 3]], "object_N_per_mm": 1.5}))
    assert isinstance(sc.press, SpringProfile) and sc.press.stiffness_N_per_mm == 1.5
    with pytest.raises(ParameterError, match="press.object_N_per_mm"):
        parse_scenario(doc({"force": [[0, 0], [1, 5]], "object_N_per_mm": 1.5}))
    with pytest.raises(ParameterError, match="press.object_N_per_mm"):
        parse_scenario(doc({"profile": [[0, 0], [1, 3]], "object_N_per_mm": -2}))
