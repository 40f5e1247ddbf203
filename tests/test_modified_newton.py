"""Modified Newton in a load's tail (``Settings.modified_newton``): the residual alone is
evaluated and the last factorisation reused while it contracts. It must give the curve full
Newton gives, with fewer tangents; and a PARDISO factor must refuse to solve once a later
factorisation replaced it (one solver per process)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.fem.engine.linsolve import available_solvers, factorize
from spsc.fem.wall import wall_curve
from spsc.fem.wall.model import WallModel, WallSettings
from spsc.materials import material


def _counted(monkeypatch):
    calls = {"tangent": 0, "residual": 0}
    evaluate = WallModel.evaluate

    def counting(self, x, load, *, tangent=True):
        calls["tangent" if tangent else "residual"] += 1
        return evaluate(self, x, load, tangent=tangent)

    monkeypatch.setattr(WallModel, "evaluate", counting)
    return calls


@pytest.mark.parametrize("l", [0.0, 3.0])
def test_modified_newton_gives_the_full_newton_curve_with_fewer_tangents(monkeypatch, l):
    g = preset("B", l=l)
    kw = dict(pressure_kPa=40, stroke_mm=3, points=7 if l else 10)
    calls = _counted(monkeypatch)
    full = wall_curve(g, material("tpu60a"), settings=WallSettings(modified_newton=0.0), **kw)
    tangents_full, residuals_full = calls["tangent"], calls["residual"]
    calls.update(tangent=0, residual=0)
    mod = wall_curve(g, material("tpu60a"), settings=WallSettings(modified_newton=1e-3), **kw)
    assert full.solver.converged and mod.solver.converged
    # both converge every point to a residual of 1e-9 of the force scale: the curves agree far
    # below any figure the report prints (1e-7 leaves room for the conditioning of the wall)
    assert_allclose(mod.force_N, full.force_N, rtol=1e-7, atol=1e-9)
    assert_allclose(mod.pressure_kPa, full.pressure_kPa, rtol=1e-7, atol=1e-9)
    assert calls["residual"] > residuals_full + 5  # the start state is one residual alone
    assert calls["tangent"] < 0.8 * tangents_full


@pytest.mark.skipif("pardiso" not in available_solvers(), reason="pypardiso not installed")
def test_a_replaced_pardiso_factor_refuses_to_solve():
    A = sp.csr_matrix(np.diag([2.0, 3.0, 4.0]))
    first = factorize(A, "pardiso")
    assert_allclose(first(np.ones(3)), [0.5, 1 / 3, 0.25], rtol=1e-12)
    second = factorize(2 * A, "pardiso")
    assert_allclose(second(np.ones(3)), [0.25, 1 / 6, 0.125], rtol=1e-12)
    with pytest.raises(RuntimeError, match="later factorisation"):
        first(np.ones(3))


@pytest.mark.skipif("pardiso" not in available_solvers(), reason="pypardiso not installed")
def test_cholesky_first_pardiso_falls_back_to_ldlt_with_the_inertia():
    """``pardiso-spd``: a positive definite matrix by Cholesky (no negative eigenvalue); an
    indefinite one by LDLᵀ with its negative eigenvalues counted; the Cholesky factor held
    before a failed attempt refuses to solve (its factors were overwritten)."""
    rng = np.random.default_rng(0)
    Q, _ = np.linalg.qr(rng.standard_normal((6, 6)))
    spd = sp.csr_matrix(Q @ np.diag([1.0, 2, 3, 4, 5, 6]) @ Q.T)
    b = rng.standard_normal(6)
    first = factorize(spd, "pardiso-spd")
    assert first.negative == 0
    assert_allclose(spd @ first(b), b, rtol=0, atol=1e-12)
    indefinite = sp.csr_matrix(Q @ np.diag([-1.0, -2, 3, 4, 5, 6]) @ Q.T)
    second = factorize(indefinite, "pardiso-spd")
    assert second.negative == 2
    assert_allclose(indefinite @ second(b), b, rtol=0, atol=1e-12)
    with pytest.raises(RuntimeError, match="later factorisation"):
        first(b)
