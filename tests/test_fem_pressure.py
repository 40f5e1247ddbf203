"""Follower pressure and cavity volume: derivatives checked by differences (the gas law: test_gaslaw.py)."""

import numpy as np
import scipy.sparse as sp

from spsc.cad.geometry import preset
from spsc.fem.engine.linsolve import solve_rank_one
from spsc.fem.solid.mesh import spsc_wall
from spsc.fem.solid.pressure import CavitySurface


def _admissible(m, v):
    v = v.copy()
    X = m.nodes
    v[X[:, 0] == 0.0, 0] = 0.0
    v[X[:, 1] == 0.0, 1] = 0.0
    v[X[:, 2] == 0.0, :] = 0.0
    return v


def test_volume_gradient_and_load_stiffness_by_differences():
    m = spsc_wall(preset("D"), 2.0, layers=1)
    cs = CavitySurface(m.facets["cavity"], 4)
    rng = np.random.default_rng(3)
    X = m.nodes
    u = _admissible(m, 0.05 * rng.standard_normal(X.shape))
    v = _admissible(m, rng.standard_normal(X.shape))
    g, H = cs.gradient(X, u)
    h = 1e-6
    dV = (cs.volume(X, u + h * v) - cs.volume(X, u - h * v)) / (2 * h)
    # V is a cubic polynomial in u: central differences are exact up to round-off (~1e-9 rel)
    np.testing.assert_allclose(dV, 4 * np.sum(g * v), rtol=1e-7, atol=0)
    rows = np.repeat(cs.dofs, 18, axis=1).ravel()
    cols = np.tile(cs.dofs, (1, 18)).ravel()
    Hm = sp.coo_matrix((H.ravel(), (rows, cols)), shape=(X.size, X.size)).tocsr()
    dg = (cs.gradient(X, u + h * v, tangent=False) - cs.gradient(X, u - h * v, tangent=False))
    np.testing.assert_allclose(Hm @ v.ravel(), dg.ravel() / (2 * h), rtol=0,
                               atol=1e-7 * np.abs(Hm @ v.ravel()).max())


def test_uniform_dilation_scales_volume():
    m = spsc_wall(preset("A"), 2.0, layers=1)
    cs = CavitySurface(m.facets["cavity"], 4)
    s = 1.1
    np.testing.assert_allclose(cs.volume(m.nodes, (s - 1) * m.nodes),
                               s**3 * cs.volume(m.nodes, 0 * m.nodes), rtol=1e-12)


def test_sherman_morrison_solve():
    rng = np.random.default_rng(0)
    K = sp.random(30, 30, density=0.3, random_state=1) + 10 * sp.eye(30)
    g, r = rng.standard_normal(30), rng.standard_normal(30)
    x = solve_rank_one(lambda b: np.linalg.solve(K.toarray(), b), 2.5, g, r)
    np.testing.assert_allclose((K.toarray() + 2.5 * np.outer(g, g)) @ x, r, rtol=0, atol=1e-11)
