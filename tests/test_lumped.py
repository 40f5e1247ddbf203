"""Lumped air-spring model (eqs. 1–9), JND, mean metrics, and the simplified intersection model."""

import math

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.cad.geometry import preset
from spsc.core.curve import Curve
from spsc.core.constants import P_AMB
from spsc.membrane.lumped import (Setup, jnd_depth, lumped_curve, mean_sensitivity,
                                  mean_stiffness, pressure_abs, sensitivity_eq8, stiffness_eq9)
from spsc.membrane.simplified import cut_area, cut_volume, simplified_curve

VB = 5000.0


def _geom_curves(y):
    return 40.0 * y + 8.0 * y**2, 20.0 * y**2 + 1.5 * y**3  # A (mm²), ΔV (mm³)


@pytest.mark.parametrize("vr, n", [(0.0, 1.0), (40000.0, 1.0), (0.0, 1.4)])
def test_pressure_follows_the_polytropic_law(vr, n):
    y = np.linspace(0, 6, 61)
    a, dv = _geom_curves(y)
    s = Setup(30.0, VB, vr, n)
    c = lumped_curve(y, a, dv, s)
    P = c.pressure_kPa + (1e3 * P_AMB)
    # P V^n constant over bladder + reservoir (eq. 2, 5): exact up to round-off
    np.testing.assert_allclose(P * (VB + vr - dv) ** n, (30 + (1e3 * P_AMB)) * (VB + vr) ** n, rtol=1e-13)
    np.testing.assert_allclose(c.force_N, 1e-3 * c.pressure_kPa * a, rtol=1e-13)
    assert c.pressure_kPa[0] == pytest.approx(30.0, abs=1e-12)


@pytest.mark.parametrize("n", [1.0, 1.4])
def test_eq8_and_eq9_match_the_derivative_of_eqs6_7(n):
    y = np.linspace(0, 6, 2001)
    a, dv = _geom_curves(y)
    f_el = 0.5 * y**2
    s = Setup(20.0, VB, 0.0, n)
    c = lumped_curve(y, a, dv, s, elastic_force_N=f_el)
    # analytic derivatives of the closed forms; the finite differences inside are O(h²) with
    # h = 3e-3 mm: the cubic term of ΔV leaves 1.5 h² ≈ 1.4e-5 mm³/mm, i.e. < 1e-6 in dP/dy and
    # dF/dy near y = 0; 1e-5 relative + 2e-6 absolute is met, a wrong formula misses by > 1 %
    dvdy = 40.0 * y + 4.5 * y**2
    dpdy = n * (20.0 + (1e3 * P_AMB)) * VB**n / (VB - dv) ** (n + 1) * dvdy
    np.testing.assert_allclose(sensitivity_eq8(y, a, dv, s), dpdy, rtol=1e-5, atol=2e-6)
    dfdy = y + 1e-3 * ((c.pressure_kPa) * (40.0 + 16.0 * y) + dpdy * a)
    np.testing.assert_allclose(stiffness_eq9(y, a, dv, s, f_el), dfdy, rtol=1e-5, atol=2e-6)
    np.testing.assert_allclose(c.stiffness(), dfdy, rtol=1e-5, atol=2e-6)


def test_reservoir_softens_the_air_spring():
    y = np.linspace(0, 6, 31)
    a, dv = _geom_curves(y)
    high = lumped_curve(y, a, dv, Setup(10.0, VB, 0.0))
    low = lumped_curve(y, a, dv, Setup(10.0, VB, 40000.0))
    assert mean_sensitivity(high) > 5 * mean_sensitivity(low) > 0
    assert mean_stiffness(high) > mean_stiffness(low) > 0
    assert Setup(10.0, VB, 40000.0).xi == pytest.approx(9.0)
    assert Setup.from_xi(10.0, VB, 6.0).reservoir_mm3 == pytest.approx(25000.0)
    with pytest.raises(ParameterError, match="^xi"):
        Setup.from_xi(10.0, VB, 0.5)


def test_jnd_depth_interpolates_the_first_crossing():
    y = np.linspace(0, 6, 13)
    z = np.zeros_like(y)
    low = Curve(y, 3.0 * y, z, z, z, model="lumped")
    high = Curve(y, 5.0 * y, z, z, z, model="lumped")
    # |ΔF| = 2y ≥ max(0.3 y, 5 N) first at y = 2.5 mm (a sample): exact
    assert jnd_depth(high, low) == pytest.approx(2.5, abs=1e-12)
    # a 40 % relative threshold (0.4·3y = 1.2 y < 2y) keeps the 5 N rule: still 2.5
    assert jnd_depth(high, low, relative=0.4) == pytest.approx(2.5, abs=1e-12)
    # the relative rule is taken on F_low: 0.5·3y = 1.5 y < 2y → 2.5 (on F_high it would never be)
    assert jnd_depth(high, low, relative=0.5) == pytest.approx(2.5, abs=1e-12)
    # relative rule dominant: 0.8·3y = 2.4 y > 2y never → NaN
    assert math.isnan(jnd_depth(high, low, relative=0.8))
    # threshold between samples: 2y ≥ 5.25 at y = 2.625, linear data so interpolation is exact
    assert jnd_depth(high, low, absolute_N=5.25) == pytest.approx(2.625, abs=1e-12)


def test_mean_metrics_of_linear_curves():
    y = np.linspace(0, 6, 41)
    z = np.zeros_like(y)
    c1 = Curve(y, 4.0 * y, 10 + 2.0 * y, z, z)
    c2 = Curve(y, 6.0 * y, 10 + 4.0 * y, z, z)
    assert mean_stiffness([c1, c2]) == pytest.approx(5.0, rel=1e-12)
    assert mean_sensitivity([c1, c2]) == pytest.approx(3.0, rel=1e-12)


@pytest.mark.parametrize("kw, name", [(dict(p_i_kPa=-5.0), "pressure"),
                                      (dict(reservoir_mm3=-1.0), "reservoir"),
                                      (dict(bladder_volume_mm3=0.0), "bladder_volume")])
def test_setup_errors_are_one_line(kw, name):
    args = dict(p_i_kPa=10.0, bladder_volume_mm3=VB) | kw
    with pytest.raises(ParameterError) as e:
        Setup(**args)
    assert str(e.value).startswith(name) and "\n" not in str(e.value)


def test_volume_beyond_the_gas_is_an_error():
    with pytest.raises(ParameterError, match="volume_change"):
        pressure_abs([VB + 1.0], Setup(10.0, VB))


@pytest.mark.parametrize("t", "ABCD")
def test_simplified_model_is_the_cut_of_the_nominal_chamber(t):
    g = preset(t)
    y = np.linspace(0, 6, 241)
    a, dv = cut_area(g, y), cut_volume(g, y)
    # dΔV/dy = A exactly for a cut (the section swept by the plate); O(h²) differences,
    # the apex power law r ~ (h−z)^(1/n2) limits the first few samples: compare from y = 0.5
    k = y >= 0.5
    np.testing.assert_allclose(np.gradient(dv, y)[k], a[k], rtol=2e-3)
    # cutting at the base (y = h) removes the whole cavity, Table 1's V_b,i
    np.testing.assert_allclose(cut_volume(g, [g.h])[0], g.cavity_volume(), rtol=1e-9)
    c = simplified_curve(g, pressure_kPa=40.0, points=13)
    assert c.model == "simplified" and c.all_converged and np.all(np.diff(c.force_N) > 0)
