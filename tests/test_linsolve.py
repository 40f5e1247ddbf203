"""The sparse solvers' fallbacks (:mod:`spsc.fem.engine.linsolve`): an install without
pypardiso probes to SuperLU, and SuperLU's symmetric mode falls back to pivoted LU (inertia
unknown) where a symmetric pivot vanishes. Both paths are taken on machines this one is not
(no MKL wheel), so they are forced here."""

from __future__ import annotations

import builtins

import numpy as np
import scipy.sparse as sp
from numpy.testing import assert_allclose

from spsc.fem.engine import linsolve
from spsc.fem.engine.linsolve import factorize


def test_without_pypardiso_the_probe_offers_superlu(monkeypatch):
    real_import = builtins.__import__

    def no_pardiso(name, *args, **kwargs):
        if name == "pypardiso":
            raise ImportError("No module named 'pypardiso'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_pardiso)
    assert linsolve._probe.__wrapped__() == ("superlu", "superlu-mmd")


def test_symmetric_superlu_gives_the_inertia_of_a_definite_and_an_indefinite_matrix():
    rng = np.random.default_rng(1)
    Q, _ = np.linalg.qr(rng.standard_normal((6, 6)))
    b = rng.standard_normal(6)
    for eigenvalues, negative in (([1.0, 2, 3, 4, 5, 6], 0), ([-1.0, -2, 3, 4, 5, 6], 2)):
        A = sp.csr_matrix(Q @ np.diag(eigenvalues) @ Q.T)
        f = factorize(A, "superlu-sym")
        assert f.negative == negative
        assert_allclose(A @ f(b), b, rtol=0, atol=1e-12)


def test_symmetric_superlu_falls_back_to_pivoted_lu_at_a_zero_pivot():
    """[[0, 1], [1, 0]] has a zero first pivot without off-diagonal pivoting: the pivoted LU
    solves it and the inertia is reported unknown (None), not guessed."""
    A = sp.csr_matrix(np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 2.0]]))
    f = factorize(A, "superlu-sym")
    assert f.negative is None
    assert_allclose(f(np.array([1.0, 2.0, 4.0])), [2.0, 1.0, 2.0], rtol=1e-14)
