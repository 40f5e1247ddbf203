"""Prony terms from a cyclic test (issue 52): the uniaxial form of the wall's viscous law
against its relaxed stress, and the fit recovering the terms a test was generated with —
exactly from the same rule, within the noise from a noisy one — through spsc fit-material."""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cli.main import main
from spsc.core.errors import ParameterError
from spsc.materials import material
from spsc.materials.prony import Prony
from spsc.materials.prony_cyclic import cyclic_stress, fit_cyclic

MAT = material("tpu60a")


def _test(rates=(0.5, 0.05), amp=0.5, dt=0.02):
    """Triangle cycles to λ = 1 + amp at each strain rate (1/s), 10 s at rest between."""
    ts, ls, t0 = [], [], 0.0
    for r in rates:
        t = np.arange(0.0, 2 * amp / r + 1e-12, dt * max(1.0, 0.05 / r))
        ts.append(t0 + t)
        ls.append(1.0 + amp - np.abs(amp - r * t))
        t0 += t[-1] + 10.0
    return np.concatenate(ts), np.concatenate(ls)


def test_the_relaxed_law_and_a_held_stretch():
    t, lam = _test()
    assert_allclose(cyclic_stress(MAT, None, t, lam), MAT.nominal_stress("uniaxial", lam),
                    rtol=1e-12, atol=1e-14)
    # a stretch held after a fast step relaxes as the Prony series says: 1 + Σβ e^(−t/τ)
    t = np.r_[0.0, np.linspace(1e-3, 8.0, 400)]
    lam = np.r_[1.0, np.full(400, 1.3)]
    p = cyclic_stress(MAT, Prony(((0.5, 2.0),)), t, lam)
    relaxed = MAT.nominal_stress("uniaxial", 1.3)
    # one step of 1 ms: the midpoint rule's e^(−Δt/2τ) at the step
    g = 1 + 0.5 * np.exp(-1e-3 / 4.0) * np.exp(-(t[1:] - 1e-3) / 2.0)
    assert_allclose(p[1:], relaxed * g, rtol=1e-12)


@pytest.mark.parametrize("terms", [((0.646, 1.0),), ((0.3, 0.2), (0.2, 5.0))])
def test_the_fit_recovers_the_terms_it_was_generated_with(terms):
    t, lam = _test()
    fit = fit_cyclic(MAT, t, lam, cyclic_stress(MAT, Prony(terms), t, lam))
    assert_allclose(np.array(fit.prony.terms), np.array(terms), rtol=1e-3)
    assert fit.rms_relative < 1e-6


def test_a_noisy_test_recovers_the_relaxation():
    """0.2 % noise: the series g(t) at the test's time scales within 1 %."""
    t, lam = _test()
    truth = Prony(((0.646, 1.0),))
    y = cyclic_stress(MAT, truth, t, lam)
    y = y + np.random.default_rng(0).normal(0.0, 0.002 * np.abs(y).max(), y.size)
    fit = fit_cyclic(MAT, t, lam, y)
    s = np.geomspace(0.1, 10.0, 30)

    def g(p):
        return 1 + sum(b * np.exp(-s / tau) for b, tau in p.terms)

    assert_allclose(g(fit.prony), g(truth), rtol=0.01)


def test_bad_cyclic_data_is_refused():
    t, lam = _test()
    with pytest.raises(ParameterError, match="cyclic stretch"):
        fit_cyclic(MAT, t, np.ones_like(t), np.zeros_like(t))
    with pytest.raises(ParameterError, match="cyclic time"):
        fit_cyclic(MAT, t[::-1], lam, lam)


def test_spsc_fit_material_writes_the_cyclic_terms(tmp_path, capsys):
    lam = np.linspace(1.0, 2.0, 21)
    (tmp_path / "tension.csv").write_text(
        "stretch,stress_MPa\n" + "".join(f"{a},{b}\n" for a, b in
                                         zip(lam, MAT.nominal_stress("uniaxial", lam))))
    t, l2 = _test()
    y = cyclic_stress(MAT, Prony(((0.646, 1.0),)), t, l2)
    (tmp_path / "cycle.csv").write_text(
        "t_s,stretch,stress_MPa\n" + "".join(f"{a},{b},{c}\n" for a, b, c in zip(t, l2, y)))
    out = tmp_path / "m.json"
    assert main(["fit-material", str(tmp_path / "tension.csv"), "--law", "neo-hookean",
                 "--cyclic", str(tmp_path / "cycle.csv"), "--out", str(out)]) == 0
    terms = json.loads(out.read_text())["prony"]["terms"]
    assert_allclose(np.array(terms), [[0.646, 1.0]], rtol=1e-3)
    assert "prony (cycle.csv" in capsys.readouterr().out
    assert main(["fit-material", str(tmp_path / "tension.csv"), "--cyclic",
                 str(tmp_path / "cycle.csv"), "--relaxation", str(tmp_path / "cycle.csv"),
                 "--out", str(out)]) == 2
