"""Thick spherical shell (octant, structured P2 mesh): Lamé at small strain, no volumetric
locking, and the exact large-strain inflation of an incompressible neo-Hookean sphere."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from spsc.fem.solid.mesh import sphere_shell
from spsc.fem.solid.model import FEMModel, Load
from spsc.fem.engine import Inflate, Settings, newton, solve
from spsc.materials import material

A, B = 1.0, 1.5  # inner and outer radius (mm)
OCTANT = {"base": (2,), "sym_x": (0,), "sym_y": (1,)}  # z = 0 is a symmetry plane here
MAT = material("tpu60a")
MU = MAT.shear_modulus


def _model(bulk_ratio=2000.0, n_theta=4, layers=2):
    return FEMModel.build(sphere_shell(A, B, n_theta=n_theta, layers=layers), MAT,
                          bulk_ratio=bulk_ratio, supports=OCTANT)


def _radial(model, x, tag):
    nodes = model.mesh.nodes_on(tag)
    X = model.disc.X[nodes]
    radial = X / np.linalg.norm(X, axis=1)[:, None]
    return np.einsum("ij,ij->i", model.displacement(x)[nodes], radial)


def _lame(p, r, K):
    """Small-strain radial displacement of a pressurised thick sphere (compressible Lamé)."""
    a3, b3 = A**3, B**3
    return p * a3 / (3 * K * (b3 - a3)) * r + p * a3 * b3 / (4 * MU * (b3 - a3)) / r**2


def test_lame_small_strain():
    model = _model()
    p = 1e-5 * MU  # linear regime: geometric nonlinearity is O(p/μ) = 1e-5 relative
    x = newton(model, model.zero_state(), Load(pressure=p), Settings(rtol=1e-10)).x
    for tag, r in (("cavity", A), ("outer", B)):
        # P2 on 4 × 2 cells: nodal error measured 5.8e-3 at most (worst next to the pole),
        # 1e-3 on average, falling to 8e-4 / 1e-4 on 8 × 4 cells; a wrong modulus, load or
        # sign is off by O(1)
        u, exact = _radial(model, x, tag), _lame(p, r, model.law.kappa)
        np.testing.assert_allclose(u, exact, rtol=1e-2, atol=0)
        np.testing.assert_allclose(u.mean(), exact, rtol=2e-3, atol=0)


def test_no_volumetric_locking():
    """From κ/μ = 10³ to 10⁶ (ν = 0.4999995) the error against Lamé does not grow: a locking
    element's error would grow with κ until it is orders of magnitude too stiff."""
    p = 1e-5 * MU
    errors = []
    for ratio in (1e3, 1e6):
        model = _model(bulk_ratio=ratio)
        x = newton(model, model.zero_state(), Load(pressure=p), Settings(rtol=1e-10)).x
        u = _radial(model, x, "cavity")
        errors.append(u.mean() / _lame(p, A, model.law.kappa) - 1)
        np.testing.assert_allclose(u, _lame(p, A, model.law.kappa), rtol=1e-2, atol=0)
    # measured −1.1e-3 at both ratios
    np.testing.assert_allclose(errors[1], errors[0], rtol=0, atol=2e-4)


def _exact_pressure(lam_a):
    lam_b = (1 + (A / B) ** 3 * (lam_a**3 - 1)) ** (1 / 3)
    f = lambda lam: 2 / lam + 1 / (2 * lam**4)  # noqa: E731
    return MU * (f(lam_b) - f(lam_a))


def test_exact_thick_sphere_inflation():
    """p = μ[(2/λb + 1/(2λb⁴)) − (2/λa + 1/(2λa⁴))], λb³ = 1 + (A/B)³(λa³ − 1), up to λa ≈ 1.35
    (the pressure peak of this shell is at λa ≈ 1.60)."""
    model = _model()
    p = 0.45 * MU
    res = solve(model, [Inflate(p, increments=4)])
    assert res.converged, res.message
    for rec in res.of("inflate"):
        lam_a = (rec.volume / (4 / 3 * math.pi * A**3)) ** (1 / 3)
        lam_exact = brentq(lambda lam: _exact_pressure(lam) - rec.pressure, 1.0, 1.6)
        # the criterion is 2 %; we measure < 1e-3 on this mesh, so hold 0.5 %
        np.testing.assert_allclose(lam_a - 1, lam_exact - 1, rtol=5e-3, atol=0)
        # the deformed cavity stays spherical: the radius of every cavity node
        r = np.linalg.norm(model.disc.X + model.displacement(rec.x), axis=1)
        np.testing.assert_allclose(r[model.mesh.nodes_on("cavity")], lam_exact * A,
                                   rtol=5e-3, atol=0)


@pytest.mark.slow
def test_exact_sphere_converges_with_mesh():
    """Error in λa against the exact solution falls with the mesh (measured 3.9e-4 on 3 × 1
    cells, 1.7e-5 on 6 × 2). κ/μ = 10⁵ here: at the default 2000 the compressibility alone
    shifts λa by ~3e-4 (J − 1 ≈ p/κ), which hides the discretisation error."""
    errs = []
    for n, layers in ((3, 1), (6, 2)):
        model = _model(bulk_ratio=1e5, n_theta=n, layers=layers)
        res = solve(model, [Inflate(0.45 * MU, increments=4)])
        lam_a = (res.records[-1].volume / (4 / 3 * math.pi)) ** (1 / 3)
        lam_exact = brentq(lambda lam: _exact_pressure(lam) - 0.45 * MU, 1.0, 1.6)
        errs.append(abs(lam_a - lam_exact))
    assert errs[1] < errs[0] / 4, errs
