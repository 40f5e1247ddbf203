"""The report's metrics on synthetic curves with closed-form answers.

Tolerances: the finite differences of :meth:`Curve.stiffness` (second order, ``edge_order=2``)
are exact for quadratics, so closed forms hold to rounding (rel 1e-12); linear interpolation is
exact for linear data likewise.
"""

import math
import warnings

import numpy as np
import pytest

from spsc.core.curve import Curve
from spsc.study.metrics import (DesignMetrics, design_metrics, headline, headline_row, interp,
                                   jnd, model_errors, type_mean, with_f_el)

Y = np.linspace(0.0, 6.0, 13)


def _curve(y, F, P, A=None, dV=None, model="membrane", p_i=None, volume=math.nan):
    y = np.asarray(y, float)
    z = np.zeros_like(y)
    setup = {} if p_i is None else {"p_i_kPa": p_i}
    return Curve(y, F, P, z if A is None else A, z if dV is None else dV, model=model,
                 setup=setup, nominal_volume_mm3=volume)


def test_interp_is_linear_inside_the_finite_samples_and_nan_outside():
    v = np.where(Y > 5, np.nan, 2 * Y + 1)  # last two points not converged
    f = interp(Y, v)
    np.testing.assert_allclose(f([0.25, 4.9]), [1.5, 10.8], rtol=1e-12)
    assert np.isnan(f([5.2, -0.1])).all()
    assert np.isnan(interp([0, 1], [1, np.nan])([0.5])).all()  # one sample: no line


def test_f_el_is_added_on_the_curve_grid():
    yf = np.linspace(0, 6, 4)
    mem = _curve(Y, 2 * Y, 40 + Y)
    comb = with_f_el(mem, _curve(yf, yf, 0 * yf, model="fem"))
    np.testing.assert_allclose(comb.force_N, 3 * Y, rtol=1e-12)
    assert comb.model == "membrane+F_el"
    np.testing.assert_array_equal(comb.pressure_kPa, mem.pressure_kPa)
    assert with_f_el(mem, None) is mem


def test_model_errors_at_the_fem_points_leave_non_converged_points_out():
    yf = np.linspace(0, 6, 4)
    fem = _curve(yf, 3 * yf, 40 + yf, model="fem")
    ref = _curve(Y, 3 * Y, 40 + Y + 0.5 * (Y == 6))  # pressure off by 0.5 kPa at y = 6 only
    e = model_errors(fem, ref)
    assert e["force_N"]["max"] == pytest.approx(0.0, abs=1e-12)
    assert e["pressure_kPa"]["max"] == pytest.approx(0.5, rel=1e-12)
    assert e["pressure_kPa"]["rms"] == pytest.approx(math.sqrt(0.25 / 4), rel=1e-12)
    assert e["pressure_kPa"]["rms_pct"] == pytest.approx(100 * math.sqrt(0.25 / 4) / 46,
                                                         rel=1e-12)
    assert e["pressure_kPa"]["n"] == 4
    fem_nan = fem.replace(pressure_kPa=np.where(yf == 6, np.nan, fem.pressure_kPa))
    assert errors_at(fem_nan, ref) == (0.0, 3)
    assert model_errors(fem.replace(force_N=np.full(4, np.nan)), ref)["force_N"]["n"] == 0


def errors_at(fem, ref):
    e = model_errors(fem, ref)["pressure_kPa"]
    return e["max"], e["n"]


def test_type_mean_is_the_stroke_mean_then_the_pressure_mean():
    # F = a y + b y²: dF/dy = a + 2 b y, whose mean over the stroke [0, 6] is a + 6 b
    c1 = _curve(Y, 2 * Y + 0.5 * Y**2, 1 * Y)  # mean slope 5, sensitivity 1
    c2 = _curve(Y, 4 * Y, 3 * Y + 0.25 * Y**2)  # mean slope 4, sensitivity 4.5
    assert type_mean([c1, c2], "stiffness") == pytest.approx(4.5, rel=1e-12)
    assert type_mean([c1, c2], "sensitivity") == pytest.approx(2.75, rel=1e-12)
    # a non-converged tail drops out of the stroke mean: the mean of the slope 2 + y over the
    # stroke reached, [0, 3], is 2 + 1.5
    part = c1.replace(force_N=np.where(Y > 3, np.nan, c1.force_N))
    assert type_mean([part], "stiffness") == pytest.approx(3.5, rel=1e-12)
    # a curve with no finite slope makes the mean over the pressures undefined (said by NaN,
    # not by numpy's empty-slice warning)
    dead = c1.replace(force_N=np.full(Y.size, np.nan))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert math.isnan(type_mean([c1, dead], "stiffness"))
    assert math.isnan(type_mean([], "sensitivity"))


def test_headline_is_the_mean_over_stroke_pressures_then_types():
    # type X: slopes 2 and 4 N/mm at two pressures; type Y: 6 N/mm; sensitivities 1, 3, 5
    cs = {"X": [_curve(Y, 2 * Y, 1 * Y), _curve(Y, 4 * Y, 3 * Y)],
          "Y": [_curve(Y, 6 * Y, 5 * Y), None]}  # None: a failed run, left out
    h = headline(cs)
    assert h["types"]["X"] == {"stiffness": pytest.approx(3.0, rel=1e-12),
                               "sensitivity": pytest.approx(2.0, rel=1e-12), "n": 2}
    assert h["types"]["Y"]["n"] == 1
    assert h["stiffness"] == pytest.approx(4.5, rel=1e-12)  # (3 + 6) / 2: types weigh equally
    assert h["sensitivity"] == pytest.approx(3.5, rel=1e-12)
    assert math.isnan(headline({"Z": [None]})["stiffness"])


def test_headline_row_ratios_are_high_over_low():
    h = {"high": {"stiffness": 8.0, "sensitivity": 6.0},
         "low": {"stiffness": 5.0, "sensitivity": 0.5}}
    r = headline_row("membrane", h)
    assert (r.stiffness_low, r.stiffness_high) == (5.0, 8.0)
    assert r.stiffness_ratio == pytest.approx(1.6, rel=1e-12)
    assert r.sensitivity_ratio == pytest.approx(12.0, rel=1e-12)
    only_high = headline_row("fem", {"high": h["high"]})
    assert math.isnan(only_high.stiffness_low) and math.isnan(only_high.stiffness_ratio)


def test_jnd_depth_and_reach():
    # |F_high − F_low| = 2y against max(0.1 y, 5): first reached at y = 2.5
    hi, lo = _curve(Y, 3 * Y, Y), _curve(Y, Y, Y)
    assert jnd(hi, lo).depth_mm == pytest.approx(2.5, rel=1e-12)
    assert jnd(hi, lo).reach_mm == 6.0
    # the relative threshold governs when F_low is large: 0.1·F_low = 0.1(y + 100) > 5,
    # so 2y >= 0.1 y + 10 at y = 10/1.9
    lo_big = _curve(Y, Y + 100, Y)
    hi_big = lo_big.replace(force_N=3 * Y + 100)
    assert jnd(hi_big, lo_big).depth_mm == pytest.approx(10 / 1.9, rel=1e-12)
    # never reached: NaN, and how far both curves were known
    near = hi.replace(force_N=np.where(Y > 2, np.nan, Y + 1))
    j = jnd(near, lo)
    assert math.isnan(j.depth_mm) and j.reach_mm == 2.0


def test_design_metrics_of_one_design():
    def pair(p, k_hi, k_lo, s_hi, s_lo):
        return (_curve(Y, k_hi * Y, p + s_hi * Y, p_i=p, volume=6505.0),
                _curve(Y, k_lo * Y, p + s_lo * Y, p_i=p, volume=6505.0))

    h10, l10 = pair(10, 8.0, 4.0, 6.0, 0.5)  # JND: 4y >= max(0.4y, 5) at y = 1.25
    h40, l40 = pair(40, 10.0, 6.0, 8.0, 0.7)  # JND: 4y >= max(0.6y, 5) at y = 1.25 too ...
    h40 = h40.replace(force_N=20.0 * Y)  # ... unless F_high is steeper: 14y >= 5 at 5/14
    m = design_metrics([h40, h10], [l10, l40])
    assert isinstance(m, DesignMetrics)
    assert m.stiffness_high == pytest.approx(14.0, rel=1e-12)  # (8 + 20) / 2
    assert m.stiffness_low == pytest.approx(5.0, rel=1e-12)
    assert m.sensitivity_high == pytest.approx(7.0, rel=1e-12)
    assert m.sensitivity_low == pytest.approx(0.6, rel=1e-12)
    assert m.jnd_mm == pytest.approx(1.25, rel=1e-12)  # the lowest setup pressure's pair
    assert m.cavity_mm3 == 6505.0
    assert math.isnan(design_metrics([h10], [l40]).jnd_mm)  # no pair at one pressure
