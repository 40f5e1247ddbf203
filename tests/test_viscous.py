"""The Prony-series viscoelastic law at material points: its tangent is the derivative of its
stress with the history of a step; a held step relaxes as 1 + Σ β_i e^{−t/τ_i} (the closed
form, at the midpoint of the step that applied it); a ramp converges to the convolution
integral with the second order of the midpoint rule."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import quad

from spsc.core.errors import ParameterError
from spsc.fem.material import NearlyIncompressible
from spsc.fem.viscous import Prony, ViscousLaw
from spsc.materials import material

BASE = NearlyIncompressible(material("tpu60a"))
PRONY = Prony(((0.5, 1.0), (0.3, 0.1)))


def uniaxial(lam):
    """The isochoric uniaxial stretch λ (arrays: (..., 3, 3))."""
    lam = np.atleast_1d(np.asarray(lam, float))
    F = np.zeros(lam.shape + (3, 3))
    F[..., 0, 0], F[..., 1, 1], F[..., 2, 2] = lam, lam ** -0.5, lam ** -0.5
    return F


def iso(F):
    """S_iso of the relaxed law."""
    return np.linalg.solve(F, BASE.stress(F, np.zeros(F.shape[:-2])))


def test_tangent_is_the_derivative_of_the_stress_with_history():
    law = ViscousLaw(BASE, PRONY)
    rng = np.random.default_rng(0)
    F = np.eye(3) + 0.1 * rng.standard_normal((5, 3, 3))
    p = 0.01 * rng.standard_normal(5)
    law.set_time(None)
    law.commit(F)
    law.set_time(0.2)
    law.commit(F + 0.05 * rng.standard_normal((5, 3, 3)))  # some history
    F2 = F + 0.08 * rng.standard_normal((5, 3, 3))
    law.set_time(0.5)
    P, A = law.stress_tangent(F2, p)
    assert_allclose(law.stress(F2, p), P, rtol=1e-14)
    h, num = 1e-6, np.zeros_like(A)
    for k in range(3):
        for L in range(3):
            d = np.zeros_like(F2)
            d[:, k, L] = h
            num[..., k, L] = (law.stress(F2 + d, p) - law.stress(F2 - d, p)) / (2 * h)
    # central differences of a smooth stress: truncation ~h² ≈ 1e-12 of the tangent's scale
    assert_allclose(A, num, atol=1e-8 * np.abs(A).max())


@pytest.mark.parametrize("dt", [0.01, 0.05])
def test_a_held_step_relaxes_as_the_prony_series(dt):
    law = ViscousLaw(BASE, PRONY)
    F0, F = uniaxial(1.0), uniaxial(1.3)
    law.set_time(None)
    law.commit(F0)
    s_iso = iso(F)[0, 0, 0]
    for n in range(1, 200):
        t = n * dt
        law.set_time(t)
        # the stress of the step, p = 0: F S with S = S_iso (1 + Σ Q/S_iso)
        S = np.linalg.solve(F, law.stress(F, np.zeros(1)))[0, 0, 0]
        # the step applied somewhere in (0, dt]: the midpoint rule puts it at dt/2
        assert_allclose(S / s_iso, PRONY.relaxation(t - dt / 2), rtol=1e-12)
        law.commit(F)


def _ramp(law_dt, t_ramp=0.3, t_end=0.6, lam1=1.4):
    """S_11 at t_end of a ramp λ: 1 → lam1 over t_ramp, then held, with steps of law_dt."""
    law = ViscousLaw(BASE, PRONY)
    law.set_time(None)
    law.commit(uniaxial(1.0))
    n = round(t_end / law_dt)
    for k in range(1, n + 1):
        t = k * law_dt
        F = uniaxial(1.0 + (lam1 - 1.0) * min(t / t_ramp, 1.0))
        law.set_time(t)
        S = np.linalg.solve(F, law.stress(F, np.zeros(1)))[0, 0, 0]
        law.commit(F)
    return S


def _ramp_exact(t_ramp=0.3, t_end=0.6, lam1=1.4):
    """S_iso(t_end) + Σ β_i ∫₀^t_ramp e^{−(t−s)/τ_i} dS_iso/ds ds (adaptive quadrature; the
    rate by a central difference in λ, smooth through the ramp's ends)."""
    def s_of(lam):
        return iso(uniaxial(lam))[0, 0, 0]

    speed = (lam1 - 1.0) / t_ramp

    def rate(s, h=1e-5):
        lam = 1.0 + speed * s
        return (s_of(lam + h) - s_of(lam - h)) / (2 * h) * speed

    out = s_of(lam1)
    for b, tau in PRONY.terms:
        out += b * quad(lambda s: np.exp(-(t_end - s) / tau) * rate(s), 0.0, t_ramp,
                        epsabs=1e-14, epsrel=1e-12, limit=200)[0]
    return out


def test_a_ramp_converges_to_the_convolution_at_second_order():
    exact = _ramp_exact()
    errors = [abs(_ramp(dt) - exact) for dt in (0.02, 0.01, 0.005)]
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert errors[-1] < 1e-4 * abs(exact)
    assert np.all(rates > 1.8), rates


def test_bad_prony_terms_are_errors_naming_them():
    with pytest.raises(ParameterError, match="prony tau_1"):
        Prony(((0.5, 0.0),))
    with pytest.raises(ParameterError, match="prony beta_2"):
        Prony(((0.5, 1.0), (-0.1, 1.0)))
    with pytest.raises(ParameterError, match="prony"):
        Prony(())
