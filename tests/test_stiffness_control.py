"""Continuous stiffness: eq. (1) against the closed form on the analytic map, eq. (2) its
inverse, the controlled piston settling on the target with the gas mass conserved."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.dynamics import Gas, Valve, sonic_conductance
from spsc.dynamics.chamber import Chamber
from spsc.dynamics.circuit import Circuit
from spsc.dynamics.profile import PressProfile
from spsc.dynamics.stiffness import (StiffnessControl, integrate_controlled, reservoir_for,
                                     step_metrics, stiffness)
from test_dynamics import PA_KPA, linear_map


def test_stiffness_is_the_pooled_gas_closed_form_and_its_inverse():
    # V = 3000 − 400 y, F = 400 P y / 1000: dP/dy = (P + Pa) 400 / (V + V_r), so
    # k = 0.4 P + 0.4 y (P + Pa) 400 / (V + V_r)
    ch = Chamber(linear_map(), Gas(n=1.0))
    y, p = 2.0, 55.0
    for v_r in (0.0, 1000.0, 40000.0):
        want = 0.4 * p + 0.4 * y * (p + PA_KPA) * 400.0 / (3000.0 - 800.0 + v_r)
        assert_allclose(stiffness(ch, y, p, v_r), want, rtol=1e-10)
        assert_allclose(reservoir_for(ch, y, p, want), v_r, rtol=1e-9, atol=1e-7)
    assert reservoir_for(ch, y, p, 0.4 * p) == math.inf  # no volume is that soft
    assert math.isnan(reservoir_for(ch, -0.5, p, 30.0))  # not touching


def _run(target, gas=Gas(n=1.0), tau=0.02, stroke=(12000.0, 60000.0)):
    m = linear_map(compliance_kPa=300.0, top=400.0)
    circ = Circuit(40.0, 20000.0, Valve(sonic_conductance(0.3)), gas)
    ctl = StiffnessControl(tuple(target), stroke, tau)
    prof = PressProfile.of([[0, 0], [0.1, 2.5], [0.6, 2.5]])
    trace, stopped = integrate_controlled(m, circ, prof, ctl, dt=5e-4)
    assert stopped is None
    return trace


@pytest.mark.parametrize("gas", [Gas(n=1.0), Gas(n=1.4, thermal_time_s=0.02)],
                         ids=["isothermal", "air"])
def test_the_piston_settles_on_the_target_and_the_gas_is_conserved(gas):
    tr = _run([(0.0, 30.0), (0.3, 36.0)], gas)
    total = tr.chamber_mg + tr.reservoir_mg
    assert_allclose(total, total.iloc[0], rtol=1e-9)
    # at rest after 15 lags and 15 thermal times: the stiffness on target, the piston at eq. 2
    end = tr.iloc[-1]
    assert_allclose(end.stiffness_N_per_mm, 36.0, rtol=1e-4)
    assert_allclose(end.pressure_kPa, end.reservoir_kPa, atol=1e-4)
    before = tr[tr.t_s <= 0.3].iloc[-1]
    assert_allclose(before.stiffness_N_per_mm, 30.0, rtol=1e-3)
    assert end.reservoir_volume_mm3 < before.reservoir_volume_mm3  # stiffer: smaller
    m = step_metrics(tr.t_s, tr.stiffness_N_per_mm, 0.3)
    # a first-order lag of 20 ms: 10–90 % in about 2.2 τ, settling (2 %) in about 3.9 τ
    assert 0.02 < m["rise_s"] < 0.08 and 0.04 < m["settle_s"] < 0.15
    assert m["overshoot"] < 0.01


def test_a_target_beyond_the_stroke_holds_the_piston_at_its_end():
    tr = _run([(0.0, 30.0), (0.3, 500.0)])
    assert_allclose(tr.reservoir_volume_mm3.iloc[-1], 12000.0, rtol=1e-6)
    assert tr.stiffness_N_per_mm.iloc[-1] < 500.0


def test_step_metrics_of_a_first_order_lag():
    t = np.linspace(0, 1, 100001)
    k = np.where(t < 0.2, 1.0, 1.0 + 2.0 * (1 - np.exp(-(t - 0.2) / 0.05)))
    m = step_metrics(t, k, 0.2)
    # 10–90 %: τ ln 9; within 2 % of the change of its end value (1 − e^{−16} ≈ 1): τ ln 50
    assert_allclose(m["rise_s"], 0.05 * math.log(9), atol=2e-5)
    assert_allclose(m["settle_s"], 0.05 * math.log(50), atol=2e-5)
    assert m["overshoot"] == 0.0


@pytest.mark.parametrize("kw, name", [
    (dict(target=((-0.5, 3.0),)), "stiffness.target t_s"),
    (dict(target=((0.0, -3.0),)), "stiffness.target"),
    (dict(target=((0.0, 3.0),), reservoir_mm3=(0.0, 100.0)), "stiffness.reservoir_mm3"),
    (dict(target=((0.0, 3.0),), actuator_time_s=0.0), "stiffness.actuator_time_s"),
])
def test_bad_control_is_one_error_naming_it(kw, name):
    with pytest.raises(ParameterError, match=name):
        StiffnessControl(**kw)


def test_the_piston_work_is_the_gas_energy_change():
    """Adiabatic gas, the plate held, a rigid chamber: the valve's flow keeps the energy, so
    the gas's internal energy changes by the piston's work −∫ P_r dV_r only."""
    m = linear_map(top=400.0)
    gas = Gas(n=1.4)
    circ = Circuit(40.0, 20000.0, Valve(sonic_conductance(0.3)), gas)
    ctl = StiffnessControl(((0.0, 32.0), (0.1, 38.0)), (12000.0, 60000.0), 0.02)
    tr, stopped = integrate_controlled(m, circ, PressProfile.of([[0, 2.5], [0.3, 2.5]]), ctl,
                                       dt=1e-4)
    assert stopped is None
    u = gas.cv * (tr.chamber_mg * tr.chamber_K + tr.reservoir_mg * tr.reservoir_K) * 1e-6
    p_r = (tr.reservoir_kPa + PA_KPA) * 1e3
    work = -np.trapezoid(p_r, tr.reservoir_volume_mm3 * 1e-9)
    assert abs(work) > 1e-3  # J: the piston moved
    # the trapezoid rule on 0.1 ms samples of smooth P_r, V_r: error well below 1e-4
    assert_allclose(u.iloc[-1] - u.iloc[0], work, rtol=1e-4)
