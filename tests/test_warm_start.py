"""A press load started from the last load's factorisation (``Settings.warm_start``): the
linearised response to the plate's advance picks the first contact set, where the secant
prediction alone took every node past the plate. Same curve, fewer factorisations; a
factorisation replaced since is not used."""

from __future__ import annotations

import sys

import numpy as np
import pytest
import scipy.sparse as sp
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.fem.engine.linsolve import available_solvers, factorize
from spsc.fem.engine.newton import Warm
from spsc.fem.engine.settings import SEMISMOOTH_CONTACT, Settings
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.materials import material

_linear = sys.modules["spsc.fem.engine.linear"]


def _curve(tmp_path, monkeypatch, warm: bool):
    count = [0]

    def counting(*args, **kwargs):
        count[0] += 1
        return factorize(*args, **kwargs)

    monkeypatch.setattr(_linear, "factorize", counting)
    run = chamber_run(preset("B"), material("tpu60a"), pressure_kPa=40.0, stroke_mm=3.0,
                      points=7, mesh_size_mm=3.0, layers=1)
    curve, result, _ = run_chamber(run, settings=Settings(warm_start=warm,
                                                          **SEMISMOOTH_CONTACT),
                                   cache_dir=tmp_path)
    assert result.converged, result.message
    return curve, count[0]


def test_warm_start_gives_the_same_curve_with_fewer_factorisations(tmp_path, monkeypatch):
    cold, n_cold = _curve(tmp_path, monkeypatch, False)
    warm, n_warm = _curve(tmp_path, monkeypatch, True)
    # both converge each point to 1e-8 of its force scale: the curves agree far below any
    # figure a report prints (1e-7 leaves room for the wall's conditioning)
    assert_allclose(warm.force_N, cold.force_N, rtol=1e-7, atol=1e-9)
    assert_allclose(warm.pressure_kPa, cold.pressure_kPa, rtol=1e-7, atol=1e-9)
    assert n_warm < n_cold, (n_warm, n_cold)


@pytest.mark.skipif("pardiso" not in available_solvers(), reason="pypardiso not installed")
def test_a_replaced_factorisation_is_no_warm_start():
    A = sp.csr_matrix(np.diag([2.0, 3.0, 4.0]))
    warm = Warm(factorize(A, "pardiso"), None, None, np.array([1, 2]), np.zeros(0, int))
    assert warm.fits([1, 2], None)
    assert not warm.fits([1], None)  # another contact set
    factorize(2 * A, "pardiso")
    assert not warm.fits([1, 2], None)
