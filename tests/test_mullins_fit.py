"""Ogden–Roxburgh constants from a loading–unloading test (issue 52): eq. M2 is the wall's law
(the material point of :class:`~spsc.fem.mullins.MullinsLaw` in uniaxial tension gives the
same stress), the fit recovers the constants a test was generated with, within the noise from
a noisy one, and through ``spsc fit-material --mullins`` into a material file
``[chamber] mullins = true`` reads."""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cli.main import main
from spsc.core.errors import ParameterError
from spsc.fem.material import NearlyIncompressible
from spsc.fem.mullins import MullinsLaw
from spsc.materials import material
from spsc.materials.mullins import MullinsParams
from spsc.materials.mullins_fit import fit_mullins, mullins_stress

MAT = material("tpu60a")
TRUTH = MullinsParams(1.8, 0.05, 0.1)


def _history():
    """Load to 1.4, unload to 1.05, reload to 1.7, unload to 1.0 (the test's order)."""
    legs = [(1.0, 1.4), (1.4, 1.05), (1.05, 1.7), (1.7, 1.0)]
    return np.concatenate([np.linspace(a, b, 30, endpoint=False) for a, b in legs] + [[1.0]])


def test_eq_m2_is_the_walls_law_in_uniaxial_tension():
    lam = _history()
    law = MullinsLaw(NearlyIncompressible(MAT), TRUTH)
    got = []
    for x in lam:
        F = np.diag([x, x ** -0.5, x ** -0.5])[None]
        P = law.stress(F, np.zeros(1))
        p = -P[0, 1, 1] / x ** 0.5  # the lateral faces free (J G22 = λ^(1/2))
        got.append(law.stress(F, np.array([p]))[0, 0, 0])
        law.commit(F)
    assert_allclose(got, mullins_stress(MAT, TRUTH, lam), rtol=1e-10, atol=1e-12)


def test_the_fit_recovers_the_constants():
    lam = _history()
    fit = fit_mullins(MAT, lam, mullins_stress(MAT, TRUTH, lam))
    assert_allclose([fit.params.r, fit.params.m, fit.params.beta], [1.8, 0.05, 0.1], rtol=1e-4)
    assert fit.rms_relative < 1e-8 and fit.softened_points > 60


def test_a_noisy_test_recovers_the_softening():
    """0.5 % noise: the softened curve within 1 % of the stress (the constants trade off)."""
    lam = _history()
    y = mullins_stress(MAT, TRUTH, lam)
    noisy = y + np.random.default_rng(0).normal(0.0, 0.005 * np.abs(y).max(), y.size)
    fit = fit_mullins(MAT, lam, noisy)
    assert_allclose(mullins_stress(MAT, fit.params, lam), y, rtol=0, atol=0.01 * y.max())


def test_a_test_that_never_unloads_is_refused():
    lam = np.linspace(1.0, 1.6, 30)
    with pytest.raises(ParameterError, match="--mullins"):
        fit_mullins(MAT, lam, mullins_stress(MAT, TRUTH, lam))


def test_spsc_fit_material_writes_the_softening(tmp_path, capsys):
    from spsc.materials.catalogue import softening

    lam = np.linspace(1.0, 2.0, 21)
    (tmp_path / "tension.csv").write_text(
        "stretch,stress_MPa\n" + "".join(f"{a},{b}\n" for a, b in
                                         zip(lam, MAT.nominal_stress("uniaxial", lam))))
    h = _history()
    (tmp_path / "soften.csv").write_text("stretch,stress_MPa\n" + "".join(
        f"{a},{b}\n" for a, b in zip(h, mullins_stress(MAT, TRUTH, h))))
    out = tmp_path / "m.json"
    assert main(["fit-material", str(tmp_path / "tension.csv"), "--law", "neo-hookean",
                 "--mullins", str(tmp_path / "soften.csv"), "--out", str(out)]) == 0
    entry = json.loads(out.read_text())["mullins"]
    assert_allclose([entry["r"], entry["m"], entry["beta"]], [1.8, 0.05, 0.1], rtol=1e-3)
    assert "mullins (soften.csv" in capsys.readouterr().out
    prm, source = softening(str(out))
    assert prm.r == pytest.approx(1.8, rel=1e-3) and "soften.csv" in source
    (tmp_path / "bad.csv").write_text("stretch,force\n1,2\n")
    assert main(["fit-material", str(tmp_path / "tension.csv"), "--mullins",
                 str(tmp_path / "bad.csv"), "--out", str(out)]) == 2
