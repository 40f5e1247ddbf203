"""A factorisation updated for a few changed contact constraints (:mod:`spsc.fem.engine.lowrank`)
solves the new masked system as a fresh factorisation of it does; it declines a change larger
than its rank, and a factorisation replaced since."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from numpy.testing import assert_allclose

from spsc.fem.engine.constraints import Masked
from spsc.fem.engine.linsolve import available_solvers, factorize
from spsc.fem.engine.lowrank import updated

SOLVERS = [s for s in ("pardiso", "superlu") if s in available_solvers()]


def _system(n=60, seed=0):
    """A sparse symmetric positive definite K (a 1D chain with some long links) and a free
    mask with two supported unknowns."""
    rng = np.random.default_rng(seed)
    main = 4.0 + rng.random(n)
    K = sp.diags([main, -np.ones(n - 1), -np.ones(n - 1)], [0, 1, -1], format="lil")
    for i, j in rng.integers(0, n, size=(15, 2)):
        if i != j:
            K[i, j] = K[j, i] = -0.3
    K = sp.csr_matrix(K)
    K.setdiag(np.abs(K).sum(axis=1).A1 + 1.0)  # diagonally dominant: definite
    free = np.ones(n, bool)
    free[[0, n - 1]] = False
    return K.tocsr(), free


def _masked(K, free, presc):
    f = free.copy()
    f[presc] = False
    return Masked(K, f, np.asarray(presc, int))


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("before, after", [([5, 9, 20], [5, 9, 20, 31]),   # one added
                                           ([5, 9, 20], [9, 20]),          # one released
                                           ([5, 9, 20], [5, 21, 22, 40]),  # both, rank 4
                                           ([], [10, 11])])
def test_updated_factor_solves_the_new_system(solver, before, after):
    K, free = _system()
    old, new = _masked(K, free, before), _masked(K, free, after)
    factor = factorize(old.matrix(K), solver, upper=True)
    up = updated(factor, old, new, K, max_rank=6)
    assert up is not None
    A1 = new.matrix(K)
    A1 = A1 + sp.triu(A1, k=1).T
    b = np.random.default_rng(1).standard_normal((new.n, 2))
    x = up(b)
    # Woodbury on a well-conditioned system: round-off only
    assert_allclose(A1 @ x, b, rtol=0, atol=1e-11)
    assert_allclose(x, factorize(new.matrix(K), solver, upper=True)(b), rtol=1e-10, atol=1e-12)


def test_updated_factor_declines_large_changes_and_other_unknowns():
    K, free = _system()
    old = _masked(K, free, [5, 9, 20])
    factor = factorize(old.matrix(K), "superlu", upper=True)
    assert updated(factor, old, _masked(K, free, [5, 9, 20, 30, 31, 32]), K, 2) is None
    assert updated(factor, old, old, K, 4) is None  # nothing changed
    other = free.copy()
    other[3] = False  # another supported unknown: another system
    assert updated(factor, old, _masked(K, other, [5, 9, 20]), K, 4) is None


@pytest.mark.skipif("pardiso" not in available_solvers(), reason="pypardiso not installed")
def test_updated_factor_of_a_replaced_factorisation_is_refused():
    K, free = _system()
    old, new = _masked(K, free, [5]), _masked(K, free, [5, 6])
    factor = factorize(old.matrix(K), "pardiso", upper=True)
    up = updated(factor, old, new, K, 4)
    factorize(2 * old.matrix(K), "pardiso", upper=True)
    assert not up.current()
    assert updated(factor, old, new, K, 4) is None


def test_chamber_curve_with_updated_factorisations(counted_chamber):
    """A 3D chamber curve whose small active-set changes update the last factorisation
    (``Settings.low_rank``) is the curve of fresh factorisations, with fewer of them."""
    from spsc.fem.engine.settings import SEMISMOOTH_CONTACT, Settings

    out = {rank: counted_chamber(Settings(warm_start=True, low_rank=rank, **SEMISMOOTH_CONTACT))
           for rank in (0, 16)}
    (fresh, n_fresh), (upd, n_upd) = out[0], out[16]
    # both converge each point to 1e-8 of its force scale (1e-7: room for the conditioning)
    assert_allclose(upd.force_N, fresh.force_N, rtol=1e-7, atol=1e-9)
    assert_allclose(upd.pressure_kPa, fresh.pressure_kPa, rtol=1e-7, atol=1e-9)
    assert n_upd < n_fresh, (n_upd, n_fresh)


@pytest.mark.skipif("pardiso" not in available_solvers(), reason="pypardiso not installed")
@pytest.mark.parametrize("before, after", [([5, 9, 20], [5, 9, 20, 31]), ([5, 9, 20], [9]),
                                           ([5, 9], [9, 21, 22, 40])])
def test_updated_factor_counts_the_negative_eigenvalues(before, after):
    """On an indefinite K (a quarter of its diagonal made negative) the updated factor's
    inertia, by Haynsworth's additivity, is the fresh LDLᵀ's."""
    K, free = _system(seed=3)
    K = K.tolil()
    for i in range(0, K.shape[0], 4):
        K[i, i] = -K[i, i]
    K = K.tocsr()
    old, new = _masked(K, free, before), _masked(K, free, after)
    factor = factorize(old.matrix(K), "pardiso", upper=True)
    up = updated(factor, old, new, K, max_rank=8)
    fresh = factorize(new.matrix(K), "pardiso", upper=True)
    assert fresh.negative > 0
    assert up.negative == fresh.negative
