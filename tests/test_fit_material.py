"""Material fitting (spsc.materials.fit.laws, .fit, .drucker): the closed-form stresses against
an independent route, recovery of known constants with and without noise (the 95 % intervals
checked by their coverage over seeded repetitions), Treloar's classic data, Drucker stability.
"""

from __future__ import annotations

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.materials.drucker import drucker
from spsc.materials.fit.fitting import choose, fit_law, fit_laws
from spsc.materials.fit.laws import TESTS, WORK_DIRECTIONS, OgdenLaw, law, stretches
from spsc.materials.data import TestData, read_tests
from spsc.materials import mooney_rivlin, neo_hookean, yeoh

DATA = __import__("pathlib").Path(__file__).parent / "data"
TRELOAR = [DATA / f"treloar_{t}.csv" for t in ("uniaxial", "equibiaxial", "planar")]

#: Known constants (MPa, and - for Ogden's exponents) the synthetic data are made from: stable
#: laws with every term significant; the Ogden sets are not the starting exponents of the fit.
TRUE = {"neo-hookean": (law("neo-hookean"), [0.8]),
        "mooney-rivlin": (law("mooney-rivlin"), [0.4, 0.1]),
        "yeoh": (law("yeoh"), [0.5, -0.02, 0.002]),
        "ogden-2": (OgdenLaw(2), [0.6, 1.8, -0.05, -2.5]),
        "ogden-3": (OgdenLaw(3), [0.5, 1.6, 0.003, 4.5, -0.02, -1.5])}


def synthetic(fl, params, tests=TESTS, *, points=15, noise=0.0, seed=None):
    """Data of ``fl`` at ``params``: λ 1.05–3 (equibiaxial 1.05–2), optional relative noise."""
    rng = np.random.default_rng(seed)
    out = []
    for t in tests:
        lam = np.linspace(1.05, 2.0 if t == "equibiaxial" else 3.0, points)
        P = fl.stress(t, lam, params)
        if noise:
            P = P * (1.0 + noise * rng.standard_normal(P.shape))
        out.append(TestData(t, lam, P))
    return out


# -- the closed forms ----------------------------------------------------------------------
def _model_energy(name, params):
    """W(λ1, λ2, λ3) of the models' own Material (spsc.materials), or Ogden's."""
    if name.startswith("ogden"):
        fl = TRUE[name][0]
        return lambda l1, l2, l3: fl.energy(l1, l2, l3, params)
    mat = {"neo-hookean": lambda: neo_hookean(2 * params[0]),
           "mooney-rivlin": lambda: mooney_rivlin(*params), "yeoh": lambda: yeoh(*params)}[name]()
    return lambda l1, l2, l3: mat.energy(l1**2 + l2**2 + l3**2, l1**-2 + l2**-2 + l3**-2)


@pytest.mark.parametrize("test", TESTS)
@pytest.mark.parametrize("name", list(TRUE))
def test_closed_form_stress_is_the_derivative_of_the_energy(name, test):
    """P = (1/k) dW/dλ along the test's path (k loaded directions do work), W the models' own
    energy, by central differences with step 1e-4 λ: truncation ~h² W'''/W' ~ 1e-8, roundoff
    ~1e-16 W/h ~ 1e-12, so 1e-6 relative is a clean margin."""
    fl, params = TRUE[name]
    W = _model_energy(name, params)
    lam = np.linspace(1.02, 6.0, 25)
    h = 1e-4 * lam
    dW = (W(*stretches(test, lam + h)) - W(*stretches(test, lam - h))) / (2 * h)
    np.testing.assert_allclose(fl.stress(test, lam, params), dW / WORK_DIRECTIONS[test],
                               rtol=1e-6)


@pytest.mark.parametrize("name", list(TRUE))
def test_drucker_tangent_is_the_hessian_of_the_energy_in_log_strains(name):
    """D = ∂²Ŵ/∂e∂e of Ŵ(e1, e2) = W(e^e1, e^e2, e^(−e1−e2)), by second differences (h = 1e-3:
    truncation ~1e-7 relative)."""
    fl, params = TRUE[name]
    W = _model_energy(name, params)

    def What(e1, e2):
        return W(np.exp(e1), np.exp(e2), np.exp(-e1 - e2))

    for l1, l2 in ((1.7, 0.9), (0.6, 1.3), (2.5, 2.5)):
        e1, e2, h = np.log(l1), np.log(l2), 1e-3
        H11 = (What(e1 + h, e2) - 2 * What(e1, e2) + What(e1 - h, e2)) / h**2
        H22 = (What(e1, e2 + h) - 2 * What(e1, e2) + What(e1, e2 - h)) / h**2
        H12 = (What(e1 + h, e2 + h) - What(e1 + h, e2 - h) - What(e1 - h, e2 + h)
               + What(e1 - h, e2 - h)) / (4 * h * h)
        got = fl.log_hessian(l1, l2, 1 / (l1 * l2), params)
        np.testing.assert_allclose(got, (H11, H12, H22), rtol=2e-5, atol=1e-9)


# -- recovery --------------------------------------------------------------------------------
@pytest.mark.parametrize("name", list(TRUE))
def test_exact_data_give_back_the_constants(name):
    """Noise-free uniaxial + equibiaxial + planar data: the residual is zero at the truth; the
    optimiser stops at ftol = xtol = 1e-12 and the problem's condition number (up to 4e4 for
    3-term Ogden) amplifies that to at most ~1e-8 in the constants."""
    fl, params = TRUE[name]
    f = fit_law(fl, synthetic(fl, params))
    np.testing.assert_allclose(f.params, params, rtol=1e-8)
    assert f.converged and all(r > 1 - 1e-12 for r in f.r2.values())


def _coverage(name, seeds, points=15):
    fl, params = TRUE[name]
    p = np.asarray(params)
    inside = []
    for seed in range(seeds):
        f = fit_law(fl, synthetic(fl, params, noise=0.01, seed=seed, points=points))
        inside.append((f.ci95[:, 0] <= p) & (p <= f.ci95[:, 1]))
    return float(np.mean(inside))


@pytest.mark.parametrize("name,seeds", [("neo-hookean", 100), ("mooney-rivlin", 100),
                                        ("yeoh", 100), ("ogden-2", 25)])
def test_95_percent_intervals_hold_the_truth_95_percent_of_the_time(name, seeds):
    """1 % relative noise, seeded fits: the reported 95 % intervals contain the true constants
    in 88–99 % of the cases (binomial: with 100–300 intervals, 3 standard deviations around
    95 %; intervals half as wide cover ~68 %, twice as wide ~100 %, and fail)."""
    assert 0.88 <= _coverage(name, seeds) <= 0.99


@pytest.mark.parametrize("name", ["yeoh", "ogden-2", "ogden-3"])
def test_noisy_uniaxial_and_equibiaxial_fit_is_within_1_percent_of_the_truth(name):
    """The issue's synthetic check: Yeoh and Ogden (2 and 3 pairs) from uniaxial + equibiaxial
    data with 1 % noise: the fitted stress has an RMS error under 1 % of the true stress at the
    data in every seeded fit (measured worst 0.56 %), the median of the largest error is under
    1 % (measured about 0.7 %)."""
    fl, params = TRUE[name]
    worst = []
    for seed in range(12):
        tests = synthetic(fl, params, ("uniaxial", "equibiaxial"), points=20, noise=0.01,
                          seed=seed)
        f = fit_law(fl, tests)
        e = np.concatenate([f.stress(d.test, d.stretch) / fl.stress(d.test, d.stretch, params)
                            - 1 for d in tests])
        assert np.sqrt(np.mean(e**2)) < 0.01
        worst.append(np.max(np.abs(e)))
    assert np.median(worst) < 0.01


@pytest.mark.parametrize("name", ["mooney-rivlin", "ogden-2"])
def test_standard_errors_match_scipy_curve_fit(name):
    """Constants and standard errors against an independent implementation: scipy's
    curve_fit with the same weights (sigma = the relative scales, absolute_sigma=False, so
    its covariance is s² (JᵀJ)⁻¹ with s² on n − p degrees of freedom)."""
    from scipy.optimize import curve_fit

    fl, params = TRUE[name]
    tests = synthetic(fl, params, noise=0.01, seed=3)
    f = fit_law(fl, tests)
    x = np.concatenate([d.stretch for d in tests])
    kind = np.concatenate([[k] * d.points for k, d in enumerate(tests)])
    y = np.concatenate([d.stress_MPa for d in tests])
    sigma = np.concatenate([np.maximum(np.abs(d.stress_MPa), 0.01 * np.abs(d.stress_MPa).max())
                            for d in tests])

    def model(_, *p):
        return np.concatenate([fl.stress(d.test, x[kind == k], p) for k, d in enumerate(tests)])

    popt, pcov = curve_fit(model, x, y, p0=f.params, sigma=sigma, absolute_sigma=False)
    np.testing.assert_allclose(f.params, popt, rtol=1e-6)
    np.testing.assert_allclose(f.stderr, np.sqrt(np.diag(pcov)), rtol=1e-4)


def test_fewer_points_than_constants_is_refused():
    fl, params = TRUE["yeoh"]
    with pytest.raises(ParameterError, match="more than its 3 constants"):
        fit_law(fl, synthetic(fl, params, ("uniaxial",), points=3))


def test_a_fit_the_data_cannot_determine_says_so():
    """3-term Ogden on seven uniaxial points: six constants the data cannot pin down, said in
    the notes; 2-term Ogden on all three tests is determined: no note."""
    fl, params = TRUE["ogden-3"]
    f = fit_law(fl, synthetic(fl, params, ("uniaxial",), points=7, noise=0.01, seed=1))
    assert any("not determined by the data" in n for n in f.notes)
    fl, params = TRUE["ogden-2"]
    f = fit_law(fl, synthetic(fl, params, noise=0.01, seed=1))
    assert not f.notes


# -- Treloar (1944) ----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def treloar():
    tests, _ = read_tests(TRELOAR)
    return tests, fit_laws(("neo-hookean", "mooney-rivlin", "yeoh", "ogden"), tests,
                           ogden_terms=3)


#: Ogden (1972), Proc. R. Soc. Lond. A 326, 565, his fit of Treloar's data: μ (kgf/cm²) 6.3,
#: 0.012, −0.1 with α 1.3, 5.0, −2.0; μ0 = ½ Σ μk αk = 4.225 kgf/cm² = 0.4143 MPa.
OGDEN_1972 = np.array([6.3 * 0.0980665, 1.3, 0.012 * 0.0980665, 5.0, -0.1 * 0.0980665, -2.0])


def test_treloar_three_term_ogden_fits_every_test(treloar):
    """The classic result: a joint 3-term Ogden fit of the uniaxial, equibiaxial and pure shear
    data reaches R² > 0.99 on each (measured 0.993, 0.999, 0.997)."""
    _, fits = treloar
    assert all(r > 0.99 for r in fits["ogden"].r2.values()), fits["ogden"].r2


def test_treloar_ogden_agrees_with_the_published_fit(treloar):
    """Ogden's 1972 constants describe our typed-in data (R² > 0.96 on every test: measured
    0.969, 0.996, 0.996), our fit is at least as good under its own objective, and its initial
    shear modulus is within 10 % of his 0.414 MPa (measured 0.386: the transcriptions and the
    weighting differ), with a stable first term of the same size (μ1 0.50 vs 0.62 MPa)."""
    tests, fits = treloar
    ogden = fits["ogden"]
    fl = OgdenLaw(3)
    for d in tests:
        P, Q = d.stress_MPa, fl.stress(d.test, d.stretch, OGDEN_1972)
        assert 1 - np.sum((P - Q) ** 2) / np.sum((P - P.mean()) ** 2) > 0.96
    published = fit_law(fl, tests)  # same objective, evaluated at the published constants:
    scale = [np.maximum(np.abs(d.stress_MPa), 0.01 * d.stress_MPa.max()) for d in tests]
    cost = 0.5 * sum(np.sum(((fl.stress(d.test, d.stretch, OGDEN_1972) - d.stress_MPa) / s) ** 2)
                     for d, s in zip(tests, scale))
    assert published.cost <= cost
    assert ogden.shear_modulus == pytest.approx(fl.shear_modulus(OGDEN_1972), rel=0.10)


def test_treloar_neo_hookean_misses_the_uniaxial_upturn(treloar):
    """Neo-Hookean cannot follow the stiffening at large stretch: R² < 0.7 in uniaxial tension
    (measured 0.60) and at λ = 7.6 it predicts under half the measured 6.3 MPa."""
    tests, fits = treloar
    nh = fits["neo-hookean"]
    assert nh.r2["uniaxial"] < 0.7
    uni = next(d for d in tests if d.test == "uniaxial")
    assert nh.stress("uniaxial", uni.stretch[-1:])[0] < 0.5 * uni.stress_MPa[-1]


def test_treloar_material_file_law_is_the_best_stable_invariant_law(treloar):
    _, fits = treloar
    best, why = choose(fits)
    assert best.name == "yeoh" and best.drucker.stable
    assert "AICc" in why and "ogden is reported, not chosen (--law ogden writes it)" in why


# -- Drucker ---------------------------------------------------------------------------------
def test_mooney_rivlin_with_negative_C01_is_unstable_where_theory_says():
    """W = C10(I1 − 3) + C01(I2 − 3) in uniaxial tension: D22 = 8(C10/λ + C01 λ), which turns
    negative for λ > sqrt(C10/−C01) = sqrt(5) at C10 = 0.5, C01 = −0.1 MPa."""
    d = drucker(law("mooney-rivlin"), [0.5, -0.1])
    assert not d.stable
    (a, b), = [s for s in d.unstable["uniaxial"] if s[0] > 1]
    assert a == pytest.approx(np.sqrt(5.0), rel=1e-6) and b == 10.0
    assert "uniaxial stretch > 2.236" in d.describe()
    assert d.stable_range["uniaxial"][1] == pytest.approx(np.sqrt(5.0), rel=1e-6)
    assert d.stable_over({"uniaxial": (1.0, 2.2)}) and not d.stable_over({"uniaxial": (1, 2.3)})


def test_strongly_negative_C01_is_flagged_in_every_test():
    d = drucker(law("mooney-rivlin"), [0.5, -0.3])
    assert all(d.unstable[t] for t in TESTS)
    assert d.describe().startswith("Drucker-UNSTABLE")


@pytest.mark.parametrize("mu", [1e-3, 5.0 / 3.0, 50.0])
def test_neo_hookean_is_stable_everywhere(mu):
    d = drucker(law("neo-hookean"), [mu / 2])
    assert d.stable and d.stable_range == {t: (0.1, 10.0) for t in TESTS}


@pytest.mark.parametrize("name", ["tpu60a", "elastic50a"])
def test_a_fitted_law_is_the_law_the_models_solve_with(name):
    """One law object: the catalogue's Material answers the fit's questions (test stresses,
    Drucker's matrix) with the same numbers the fitting family computes for its constants,
    and the family's constants give back that Material."""
    from spsc.materials import material

    mat = material(name)
    family = law(mat.law)
    params = [c for _, _, c in mat.coefficients]
    lam = np.linspace(1.0, 3.0, 41)
    for test in TESTS:
        assert np.array_equal(mat.nominal_stress(test, lam), family.stress(test, lam, params))
        l1, l2, l3 = stretches(test, lam)
        assert all(np.array_equal(a, b) for a, b in zip(mat.log_hessian(l1, l2, l3),
                                                         family.log_hessian(l1, l2, l3, params)))
    back = family.material(params, name=mat.name, source=mat.source, provenance=mat.provenance)
    assert back == mat
    # small-strain uniaxial slope: Young's modulus 3 μ0 (incompressible), within the 0.1 %
    # strain step's curvature
    eps = 1e-3
    E = mat.nominal_stress("uniaxial", np.array([1.0 + eps]))[0] / eps
    np.testing.assert_allclose(E, 3 * mat.shear_modulus, rtol=2e-3)
