"""The masked restriction (constrained unknowns as unit rows, the pattern fixed) against the
reduced one (constrained unknowns removed): the same step, the same inertia, one pattern."""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.fem.engine.constraints import Constraints, Masked, Reduction
from spsc.fem.engine.linsolve import available_solvers, factorize
from spsc.fem.engine.steps import Load
from spsc.fem.wall.model import WallModel
from spsc.materials import material


@pytest.fixture(scope="module")
def dome_tangent():
    m = WallModel(preset("B", l=0.0), material("tpu60a"))
    x = m.zero_state()
    ev = m.evaluate(x, Load(pressure=0.04))  # 40 kPa on the undeformed dome: indefinite-free
    return m, ev


def _presc(m, k, seed):
    top = np.flatnonzero(~m.fixed[: m.n_u])
    return np.sort(np.random.default_rng(seed).choice(top, k, replace=False))


@pytest.mark.parametrize("solver", ["superlu"] + available_solvers()[:1])
def test_masked_solves_as_the_reduced_system(dome_tangent, solver):
    m, ev = dome_tangent
    rhs = np.random.default_rng(1).standard_normal(len(m.fixed))
    for seed, k in ((0, 0), (1, 3), (2, 11)):
        presc = _presc(m, k, seed)
        con = Constraints(len(m.fixed), presc, np.zeros(k), np.zeros(0, int), np.zeros(0), -1)
        free = con.free(m.fixed)
        red, mask = Reduction(ev.K, free), Masked(ev.K, free, presc)
        a, b = np.zeros(len(free)), np.zeros(len(free))
        red.put(a, factorize(red.matrix(ev.K), solver, upper=True)(red.take(rhs)))
        mask.put(b, factorize(mask.matrix(ev.K), solver, upper=True)(mask.take(rhs)))
        # two factorisations of the same well-conditioned system (cond ~1e6 here): 1e-9
        assert_allclose(b, a, rtol=1e-9, atol=1e-9 * np.abs(a).max())
        assert np.all(b[presc] == 0.0) and np.all(b[m.fixed] == 0.0)


@pytest.mark.skipif("pardiso" not in available_solvers(), reason="needs pypardiso")
def test_masked_keeps_the_pattern_and_the_inertia(dome_tangent):
    m, ev = dome_tangent
    shifted = ev.K - 0.5 * abs(ev.K.diagonal()).max() * _identity(ev.K)  # indefinite
    patterns, negatives = set(), set()
    for seed, k in ((0, 0), (1, 3), (2, 11)):
        presc = _presc(m, k, seed)
        con = Constraints(len(m.fixed), presc, np.zeros(k), np.zeros(0, int), np.zeros(0), -1)
        free = con.free(m.fixed)
        A = Masked(shifted, free, presc).matrix(shifted)
        patterns.add((A.indptr.tobytes(), A.indices.tobytes()))
        dense = Reduction(shifted, free).matrix(shifted).toarray()
        dense = dense + np.triu(dense, 1).T
        expected = int(np.sum(np.linalg.eigvalsh(dense) < 0))
        got = factorize(A, "pardiso", upper=True).negative
        negatives.add(got == expected and expected > 0)
    assert len(patterns) == 1  # one pattern whatever is prescribed: one symbolic analysis
    assert negatives == {True}


def _identity(K):
    import scipy.sparse as sp

    return sp.identity(K.shape[0], format="csr")
