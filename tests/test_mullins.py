"""The Ogden–Roxburgh Mullins law at material points (issue 52): its tangent is the derivative
of its stress on the softened path; in isochoric uniaxial tension the nominal stress is
η(W, W_m) times the virgin law's (the closed form of eq. M1, written out here apart from the
code); the primary path is the hyperelastic law; a wall reloaded after a first cycle retraces
its unloading (pseudo-elastic: the second cycle dissipates nothing)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.fem.material import NearlyIncompressible
from spsc.fem.mullins import MullinsLaw, MullinsParams
from spsc.materials import material

BASE = NearlyIncompressible(material("tpu60a"))  # neo-Hookean, C10 = 5/6 MPa
PRM = MullinsParams(r=1.5, m=0.05, beta=0.2)


def uniaxial(lam):
    lam = np.atleast_1d(np.asarray(lam, float))
    F = np.zeros(lam.shape + (3, 3))
    F[..., 0, 0], F[..., 1, 1], F[..., 2, 2] = lam, lam ** -0.5, lam ** -0.5
    return F


def test_the_tangent_is_the_derivative_of_the_softened_stress():
    law = MullinsLaw(BASE, PRM)
    rng = np.random.default_rng(1)
    F0 = np.eye(3) + 0.15 * rng.standard_normal((6, 3, 3))
    law.commit(F0)  # the largest energy so far
    F = np.eye(3) + 0.5 * (F0 - np.eye(3))  # unloaded halfway: softened
    p = 0.01 * rng.standard_normal(6)
    eta = law.damage(F)
    assert np.all(eta < 1.0)
    P, A = law.stress_tangent(F, p)
    assert_allclose(P, law.stress(F, p), rtol=1e-12, atol=1e-14)
    h = 1e-6
    for k in range(3):
        for L in range(3):
            dF = np.zeros((3, 3))
            dF[k, L] = h
            fd = (law.stress(F + dF, p) - law.stress(F - dF, p)) / (2 * h)
            assert_allclose(A[..., :, :, k, L], fd, rtol=1e-6, atol=1e-8)


def test_uniaxial_unloading_is_eta_times_the_virgin_stress():
    """Loaded to λ = 1.5, unloaded to λ: P11 (lateral stress zero) = η μ (λ − λ⁻²), with
    W = C10 (λ² + 2/λ − 3) and η = 1 − erf((W_m − W)/(m + β W_m))/r."""
    law = MullinsLaw(BASE, PRM)
    law.commit(uniaxial(np.full(5, 1.5)))  # five material points, each loaded to 1.5
    lam = np.array([1.05, 1.2, 1.35, 1.5, 1.6])
    F = uniaxial(lam)
    c10 = 5.0 / 6.0
    W = c10 * (lam**2 + 2 / lam - 3)
    Wm = np.maximum(c10 * (1.5**2 + 2 / 1.5 - 3), W)
    eta = 1 - np.array([math.erf(v) for v in (Wm - W) / (PRM.m + PRM.beta * Wm)]) / PRM.r
    P_iso = law.stress(F, np.zeros(5))
    p = -P_iso[:, 1, 1] / lam ** 0.5  # J G22 = λ^(1/2): the lateral stress zero
    P = law.stress(F, p)
    assert_allclose(P[:, 1, 1], 0.0, atol=1e-12)
    assert_allclose(P[:, 0, 0], eta * 2 * c10 * (lam - lam**-2), rtol=1e-10)
    assert eta[3] == 1.0 and eta[4] == 1.0  # at and beyond the largest: the primary path


def test_the_primary_path_is_the_hyperelastic_law():
    law = MullinsLaw(BASE, PRM)
    F = uniaxial(np.linspace(1.0, 1.6, 7))
    p = np.zeros(7)
    for k in range(1, 7):  # loading monotonically, committing each step
        law.commit(F[:k])
        Fk = np.broadcast_to(F[k], (k, 3, 3))
        assert_allclose(law.stress(Fk, p[:k]), BASE.stress(Fk, p[:k]), rtol=1e-14)


@pytest.mark.parametrize("kwargs, says", [({"r": 1.0, "m": 0.1}, "mullins r"),
                                          ({"r": 2, "m": 0}, "mullins m"),
                                          ({"r": 2, "m": 0.1, "beta": -1}, "mullins beta")])
def test_bad_constants_are_one_line(kwargs, says):
    with pytest.raises(ParameterError, match=says):
        MullinsParams(**kwargs)


@pytest.mark.slow
def test_a_wall_reloaded_retraces_its_first_unloading():
    """Type B vented, 4 mm: the first squeeze–release dissipates (the wall softened where it
    was strained), the second's loop is under 2 % of the first's (pseudo-elastic), and
    without the law the wall retraces itself."""
    from spsc.cad.geometry import preset
    from spsc.fem.wall.cycle import wall_cycle

    prm = MullinsParams(2.0, 0.02)
    first = wall_cycle(preset("B"), material("tpu60a"), None, stroke_mm=4.0, points=17,
                       mullins=prm)
    second = wall_cycle(preset("B"), material("tpu60a"), None, stroke_mm=4.0, points=17,
                        mullins=prm, cycles=2)
    assert first.complete and second.complete
    assert first.hysteresis_N > 0.3 and first.dissipated_mJ > 0.5
    assert second.dissipated_mJ < 0.02 * first.dissipated_mJ
    assert_allclose(second.force_load_N[1:], first.force_unload_N[1:], rtol=0.02, atol=0.02)


def test_a_material_file_carries_its_own_constants(tmp_path):
    import json

    from spsc.materials.catalogue import softening

    prm, source = softening("tpu60a")
    assert prm == MullinsParams(2.0, 0.02, 0.0) and "ASSUMED" in source
    f = tmp_path / "m.json"
    rec = {"schema": "spsc.material", "schema_version": 1, "name": "mine",
           "law": "neo-hookean", "constants": {"C10": 0.8},
           "mullins": {"r": 3.0, "m": 0.1, "source": "my cyclic test"}}
    f.write_text(json.dumps(rec))
    assert softening(str(f)) == (MullinsParams(3.0, 0.1, 0.0), "my cyclic test")
    rec["mullins"] = {"r": 3.0}
    f.write_text(json.dumps(rec))
    with pytest.raises(ParameterError, match="mullins"):
        softening(str(f))
