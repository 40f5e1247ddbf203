"""The Prony fit of a relaxation test: on data made from a known series (with and without
noise) the fitted curve g(t) is the true one; a term on the fit's own grid of relaxation times
comes back exactly; bad data are one error naming what is wrong."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.materials.prony import Prony, fit_relaxation

T = np.logspace(-2, 3, 80)  # 10 ms … 1000 s


def test_a_term_on_the_grid_comes_back_exactly():
    true = Prony(((0.8, 1.0),))  # τ = 1 s is on the grid (two a decade from 10^-3)
    fit = fit_relaxation(T, 2.5 * true.relaxation(T))
    assert_allclose(fit.relaxed, 2.5, rtol=1e-10)
    assert len(fit.prony.terms) == 1
    assert_allclose(fit.prony.terms[0], (0.8, 1.0), rtol=1e-8)


def test_the_relaxation_curve_of_a_series_off_the_grid_is_recovered():
    true = Prony(((0.4, 0.37), (0.25, 12.0), (0.1, 200.0)))
    fit = fit_relaxation(T, 3.0 * true.relaxation(T))
    # off-grid times are shared between neighbouring terms: the curve, not the terms, is
    # determined; with two terms a decade it is within 0.2 % of the relaxed level
    assert_allclose(fit.prony.relaxation(T), true.relaxation(T), atol=2e-3)
    assert_allclose(fit.relaxed, 3.0, rtol=5e-3)
    assert fit.rms_relative < 1e-3


def test_noisy_data_give_the_curve_to_the_noise():
    true = Prony(((0.6, 2.0), (0.2, 50.0)))
    rng = np.random.default_rng(3)
    y = 1.7 * true.relaxation(T) * (1 + 0.002 * rng.standard_normal(T.size))
    fit = fit_relaxation(T, y)
    assert_allclose(fit.prony.relaxation(T), true.relaxation(T), atol=6e-3)  # 3σ of 0.2 %
    assert all(b >= 0 for b, _ in fit.prony.terms)  # every term dissipates


@pytest.mark.parametrize("t, y, name", [
    (T[:3], np.ones(3), "relaxation data"),
    (T[::-1], np.ones(T.size), "relaxation time"),
    (T, -np.ones(T.size), "relaxation value"),
])
def test_bad_relaxation_data_are_one_error(t, y, name):
    with pytest.raises(ParameterError, match=name):
        fit_relaxation(t, y)


def test_a_test_from_t0_a_creep_test_and_a_logger_s_million_rows():
    """Issue 53: a relaxation test starting at t = 0 (the step's instant) was refused though
    valid; creep data (a rising value) was fitted as "beta 0" with an RMS of 19.5 %; a
    million-row log made the least squares diverge and blamed the data."""
    import numpy as np
    import pytest
    from numpy.testing import assert_allclose

    from spsc.core.errors import ParameterError
    from spsc.materials.prony import fit_relaxation

    t = np.linspace(0.0, 100.0, 1001)
    y = 1.0 + 0.6 * np.exp(-t / 1.0) + 0.3 * np.exp(-t / 10.0)
    fit = fit_relaxation(t, y)
    # the two terms on the grid's own times: exact to round-off
    assert_allclose([b for b, _ in fit.prony.terms], [0.6, 0.3], rtol=1e-9)
    with pytest.raises(ParameterError, match="falls with time"):
        fit_relaxation(t, 2.0 - np.exp(-t))
    big = np.linspace(1e-3, 100.0, 200_000)
    fit = fit_relaxation(big, 1.0 + 0.6 * np.exp(-big) + 0.3 * np.exp(-big / 10.0))
    assert fit.rms_relative < 1e-4 and abs(fit.relaxed - 1.0) < 1e-3
