"""A press load started from the last load's factorisation (``Settings.warm_start``): the
linearised response to the plate's advance picks the first contact set, where the secant
prediction alone took every node past the plate. Same curve, fewer factorisations; a
factorisation replaced since is not used."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from numpy.testing import assert_allclose

from spsc.fem.engine.bodies import Sets
from spsc.fem.engine.linsolve import available_solvers, factorize
from spsc.fem.engine.newton import Warm
from spsc.fem.engine.settings import SEMISMOOTH_CONTACT, Settings


def test_warm_start_gives_the_same_curve_with_fewer_factorisations(counted_chamber):
    cold, n_cold = counted_chamber(Settings(warm_start=False, **SEMISMOOTH_CONTACT))
    warm, n_warm = counted_chamber(Settings(warm_start=True, **SEMISMOOTH_CONTACT))
    # both converge each point to 1e-8 of its force scale: the curves agree far below any
    # figure a report prints (1e-7 leaves room for the wall's conditioning)
    assert_allclose(warm.force_N, cold.force_N, rtol=1e-7, atol=1e-9)
    assert_allclose(warm.pressure_kPa, cold.pressure_kPa, rtol=1e-7, atol=1e-9)
    assert n_warm < n_cold, (n_warm, n_cold)


@pytest.mark.skipif("pardiso" not in available_solvers(), reason="pypardiso not installed")
def test_a_replaced_factorisation_is_no_warm_start():
    A = sp.csr_matrix(np.diag([2.0, 3.0, 4.0]))
    warm = Warm(factorize(A, "pardiso"), None, None,
                Sets({"active": np.array([1, 2]), "engaged": np.zeros(0, int)}))
    assert warm.fits(Sets({"active": np.array([1, 2])}))  # no tie: no engaged nodes
    assert not warm.fits(Sets({"active": np.array([1])}))  # another contact set
    assert not warm.fits(Sets({"active": np.array([1, 2]), "engaged": np.array([4])}))
    factorize(2 * A, "pardiso")
    assert not warm.fits(Sets({"active": np.array([1, 2])}))
