"""The one gas law (core/gaslaw.py) against identities it does not use to compute itself:
Boyle's and Poisson's laws written out here with the ambient pressure, the inverse map, the
derivative by differences (with its second-order error), and one-line errors."""

import numpy as np
import pytest

from spsc.core import P_AMB, GasLaw, ParameterError

V_C = 4000.0  # mm³


def test_isothermal_halving_doubles_the_absolute_pressure():
    """Boyle, by hand, with the standard atmosphere (101.325 kPa): 40 kPa gauge = 141.325 kPa
    absolute; at half the volume 282.65 kPa absolute = 181.325 kPa gauge; with a reservoir of
    3 V_c, half the cavity leaves 3.5 of the 4 V_c of gas: P = 141.325 · 4/3.5 kPa."""
    gas = GasLaw(0.04, V_C)
    np.testing.assert_allclose(gas.pressure(V_C / 2), 0.181325, rtol=1e-14)
    with_reservoir = GasLaw(0.04, V_C, reservoir=3 * V_C)
    np.testing.assert_allclose(with_reservoir.pressure(V_C / 2), 0.141325 * 4 / 3.5 - 0.101325,
                               rtol=1e-14)
    np.testing.assert_allclose(gas.pressure(V_C), 0.04, rtol=1e-15)


def test_adiabatic_compression_follows_poisson():
    """n = 1.4: halving the gas volume raises the absolute pressure by 2^1.4 = 2.6390..."""
    gas = GasLaw(0.0, V_C, n=1.4)
    np.testing.assert_allclose((gas.pressure(V_C / 2) + P_AMB) / P_AMB, 2.6390158215457884,
                               rtol=1e-14)


@pytest.mark.parametrize("reservoir, n", [(0.0, 1.0), (40000.0, 1.0), (0.0, 1.4),
                                          (40000.0, 1.4)])
def test_invariant_and_inverse_along_a_compression(reservoir, n):
    gas = GasLaw(0.03, V_C, reservoir=reservoir, n=n)
    v = np.linspace(0.5 * V_C, 1.2 * V_C, 29)
    p = gas.pressure(v)
    # P (V + V_r)ⁿ written out, not through GasLaw: exact up to round-off (a few ulp)
    const = (0.03 + P_AMB) * (V_C + reservoir) ** n
    np.testing.assert_allclose((p + P_AMB) * (v + reservoir) ** n, const, rtol=1e-13, atol=0)
    np.testing.assert_allclose(gas.invariant(p, v), const, rtol=1e-13, atol=0)
    np.testing.assert_allclose(gas.constant, const, rtol=1e-15, atol=0)
    # volume() is the inverse of pressure(), both ways
    np.testing.assert_allclose(gas.volume(p), v, rtol=1e-12, atol=0)
    q = np.linspace(-0.05, 0.5, 23)
    np.testing.assert_allclose(gas.pressure(gas.volume(q)), q, rtol=0, atol=1e-15)
    assert np.all(np.diff(p) < 0)  # compression raises the pressure


@pytest.mark.parametrize("reservoir, n", [(0.0, 1.0), (40000.0, 1.0), (0.0, 1.4)])
def test_dpressure_by_central_differences_at_second_order(reservoir, n):
    """The derivative against central differences of pressure(). For p + P_amb = C (V + V_r)⁻ⁿ
    the central difference's leading error is p‴h²/6 = p′ (n+1)(n+2) h² / (6 (V + V_r)²): with
    that term added the match is to round-off (≈ eps P/(h p′) ≈ 5e-13 at h = 1 mm³; the next
    term is O(h⁴/V⁴) ≈ 1e-14), and without it the error falls fourfold when h halves (h = 200,
    100 mm³)."""
    gas = GasLaw(0.04, V_C, reservoir=reservoir, n=n)
    v = np.array([3500.0, 4000.0, 4500.0])

    def central(h):
        return (gas.pressure(v + h) - gas.pressure(v - h)) / (2 * h)

    exact = gas.dpressure(v)
    h = 1.0
    leading = (n + 1) * (n + 2) * h**2 / (6 * (v + reservoir) ** 2)
    np.testing.assert_allclose(central(h), exact * (1 + leading), rtol=1e-11, atol=0)
    e1, e2 = np.abs(central(200.0) / exact - 1), np.abs(central(100.0) / exact - 1)
    np.testing.assert_allclose(np.log2(e1 / e2), 2.0, atol=0.05)
    # the isothermal tangent is −P/(V + V_r) (the gas's bulk modulus is its pressure)
    if n == 1.0:
        np.testing.assert_allclose(exact, -(gas.pressure(v) + P_AMB) / (v + reservoir),
                                   rtol=1e-14)


@pytest.mark.parametrize("kw, name", [(dict(p_closed=-0.2), "p_closed"),
                                      (dict(v_closed=0.0), "v_closed"),
                                      (dict(reservoir=-1.0), "reservoir"),
                                      (dict(n=1.5), "polytropic_n"),
                                      (dict(n=0.9), "polytropic_n")])
def test_bad_gas_is_a_one_line_error_naming_the_parameter(kw, name):
    args = dict(p_closed=0.04, v_closed=V_C) | kw
    with pytest.raises(ParameterError) as e:
        GasLaw(**args)
    assert str(e.value).startswith(name) and "\n" not in str(e.value)
