"""Ogden's law solved by the models (issue 47): the identities that pin it to the invariant laws
(one term with α = 2 is neo-Hookean, the pair α = ±2 Mooney–Rivlin) in the 3D/wall solid's
stress and tangent, in the membrane's tensions and in a whole wall curve; a genuine Ogden law
against its closed-form homogeneous test; its material file through fit-material and the
models."""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.fem.material import NearlyIncompressible
from spsc.materials import Ogden, material, mooney_rivlin, neo_hookean
from spsc.membrane.tension import strain_energy_density, tensions

TRELOAR = Ogden("treloar", (0.63, 0.0012, -0.01), (1.3, 5.0, -2.0))  # Ogden 1972's fit


def _gradients(n=40, seed=0):
    """Random deformation gradients (J > 0), the identity and a uniaxial stretch: coincident
    principal stretches included."""
    rng = np.random.default_rng(seed)
    F = np.eye(3) + 0.3 * rng.standard_normal((n, 3, 3))
    F[np.linalg.det(F) < 0] *= -1
    uni = np.diag([1.4, 1 / np.sqrt(1.4), 1 / np.sqrt(1.4)])
    return np.concatenate([F, np.eye(3)[None], uni[None]]), 0.1 * rng.standard_normal(n + 2)


@pytest.mark.parametrize("invariant, ogden", [
    (neo_hookean(1.3), Ogden("nh", (1.3,), (2.0,))),
    (mooney_rivlin(0.4, 0.1), Ogden("mr", (0.8, -0.2), (2.0, -2.0)))])
def test_the_solid_law_in_stretches_is_the_invariant_law_it_equals(invariant, ogden):
    F, p = _gradients()
    a, b = NearlyIncompressible(invariant), NearlyIncompressible(ogden)
    Pa, Aa = a.stress_tangent_numpy(F, p)
    Pb, Ab = b.stress_tangent(F, p)
    # the stress is exact (eigenvectors of b, round-off only); the tangent a central
    # difference of it (1e-6 steps: truncation and round-off below 1e-8 of its largest entry)
    assert_allclose(Pb, Pa, rtol=0, atol=1e-9 * np.abs(Pa).max())
    assert_allclose(Ab, Aa, rtol=0, atol=1e-7 * np.abs(Aa).max())
    assert_allclose(b.energy(F, p), a.energy(F, p), rtol=0, atol=1e-10)
    assert b.material.neo_hookean == a.material.neo_hookean


def test_a_genuine_ogden_law_meets_its_homogeneous_tests():
    """Uniaxial: F = diag(λ, λ^-1/2, λ^-1/2), the pressure p making the lateral stress zero;
    P11 is the closed form Σ μk (λ^αk − λ^(−αk/2))/λ. And P is the derivative of the energy
    (an independent central difference of Ψ)."""
    law = NearlyIncompressible(TRELOAR)
    lam = np.linspace(1.05, 4.0, 12)
    F = np.zeros((lam.size, 3, 3))
    F[:, 0, 0], F[:, 1, 1], F[:, 2, 2] = lam, lam**-0.5, lam**-0.5
    p0 = np.zeros(lam.size)
    p = -law.stress(F, p0)[:, 1, 1] * lam**-0.5  # P22 = (τ2 + p)/λ2 = 0
    P = law.stress(F, p)
    assert_allclose(P[:, 1, 1], 0.0, atol=1e-12)
    assert_allclose(P[:, 0, 0], TRELOAR.nominal_stress("uniaxial", lam), rtol=1e-12)
    Fr, pr = _gradients(8, seed=1)
    h = 1e-6
    for k in range(3):
        for L in range(3):
            d = np.zeros((3, 3))
            d[k, L] = h
            dpsi = (law.energy(Fr + d, pr) - law.energy(Fr - d, pr)) / (2 * h)
            assert_allclose(dpsi, law.stress(Fr, pr)[:, k, L], rtol=0, atol=1e-7)


def test_membrane_tensions_in_stretches_are_the_invariant_ones():
    l1, l2 = np.linspace(0.8, 2.5, 9), np.linspace(1.0, 1.9, 9)
    for invariant, ogden in ((neo_hookean(1.3), Ogden("nh", (1.3,), (2.0,))),
                             (mooney_rivlin(0.4, 0.1), Ogden("mr", (0.8, -0.2), (2.0, -2.0)))):
        assert_allclose(tensions(ogden, 1.0, l1, l2), tensions(invariant, 1.0, l1, l2),
                        rtol=1e-13)
        assert_allclose(strain_energy_density(ogden, l1, l2),
                        strain_energy_density(invariant, l1, l2), rtol=1e-13)


def _ogden_file(path, mu, alpha):
    path.write_text(json.dumps({"schema": "spsc.material", "schema_version": 1,
                                "name": path.stem, "law": "ogden",
                                "constants": {"mu": list(mu), "alpha": list(alpha)},
                                "bulk_ratio": 2000, "provenance": "assumed",
                                "source": "a test"}))
    return path


def test_an_ogden_file_is_the_neo_hookean_wall_curve_when_it_is_one(tmp_path):
    """The catalogue's TPU 60A (neo-Hookean, μ0 = 5/3 MPa) and the one-term Ogden file with
    μ1 = 5/3, α = 2: the same wall curve to round-off, in as many Newton iterations."""
    from spsc.core.curve import Curve
    from spsc.cli.main import main

    f = _ogden_file(tmp_path / "og.json", [5 / 3], [2.0])
    assert isinstance(material(str(f)), Ogden)
    curves = []
    for mat in ("tpu60a", str(f)):
        out = tmp_path / f"{len(curves)}.json"
        assert main(["curve", "--model", "wall", "--type", "B", "--l", "0", "--pressure", "40",
                     "--points", "9", "--material", mat, "--json", str(out), "--quiet"]) == 0
        curves.append(Curve.from_json(out))
    a, b = curves
    assert_allclose(b.force_N, a.force_N, rtol=1e-9, atol=1e-12)
    assert_allclose(b.pressure_kPa, a.pressure_kPa, rtol=1e-12)
    assert b.solver.iterations == a.solver.iterations


def test_fit_material_writes_an_ogden_file_the_models_take(tmp_path, capsys):
    from pathlib import Path

    from spsc.cli.main import main

    data = Path(__file__).parent / "data"
    out = tmp_path / "ogden.json"
    assert main(["fit-material", *(str(data / f"treloar_{t}.csv") for t in
                                   ("uniaxial", "equibiaxial", "planar")),
                 "--law", "ogden", "--ogden-terms", "2", "--out", str(out)]) == 0
    assert f"use it as --material {out}" in capsys.readouterr().out
    law = material(str(out))
    assert isinstance(law, Ogden) and len(law.mu) == 2
    assert main(["curve", "--model", "membrane", "--type", "B", "--l", "0", "--pressure", "5",
                 "--points", "5", "--material", str(out), "--quiet"]) == 0
    # the surrogate answers only a neo-Hookean law (an exact stiffness scale of its own)
    assert main(["curve", "--model", "surrogate", "--type", "B", "--l", "0", "--material",
                 str(out), "--quiet"]) == 2
    assert "neo-Hookean" in capsys.readouterr().err


def test_bad_ogden_constants_are_one_line_errors():
    from spsc.core.errors import ParameterError

    for mu, alpha, name in (((1.0,), (0.0,), "alpha"), ((1.0, 2.0), (2.0,), "Ogden terms"),
                            ((-1.0,), (2.0,), "initial shear modulus")):
        with pytest.raises(ParameterError, match=name):
            Ogden("bad", mu, alpha)
    assert TRELOAR.scaled(2.0).shear_modulus == pytest.approx(2 * TRELOAR.shear_modulus)


def test_a_new_law_is_one_class_and_one_registry_line(tmp_path, monkeypatch):
    """Gent's law, W = −(μ Jm/2) ln(1 − (I1 − 3)/Jm), added here as a class and a
    register_law line (not shipped): a material file names it, and the wall model and the
    membrane solve it; with a very large Jm it is the neo-Hookean law."""
    from dataclasses import dataclass
    from typing import ClassVar

    from spsc.core.curve import Curve
    from spsc.cli.main import main
    from spsc.materials import file as material_file

    @dataclass(frozen=True)
    class Gent:
        name: str
        mu: float
        jm: float
        source: str = ""
        provenance: str = "assumed"
        law: str = "gent"
        kind: ClassVar[str] = "invariants"
        neo_hookean: ClassVar[bool] = False
        shear_modulus = property(lambda self: self.mu)

        def identity(self):
            return {"law": self.law, "mu": self.mu, "jm": self.jm}

        def energy(self, I1, I2):
            return -0.5 * self.mu * self.jm * np.log1p(-(I1 - 3.0) / self.jm)

        def dW(self, I1, I2):
            return 0.5 * self.mu / (1.0 - (I1 - 3.0) / self.jm), 0.0 * I2

        def d2W(self, I1, I2):
            w11 = 0.5 * self.mu / self.jm / (1.0 - (I1 - 3.0) / self.jm) ** 2
            return w11, 0.0 * I1, 0.0 * I2

    monkeypatch.setitem(material_file.LAWS, "gent", None)  # restored after the test
    material_file.register_law("gent", lambda name, c, source, prov: Gent(
        name, float(c["mu"]), float(c["jm"]), source, prov))
    base = {"schema": "spsc.material", "schema_version": 1, "law": "gent",
            "bulk_ratio": 2000, "provenance": "assumed", "source": "a test"}
    curves = {}
    for model in ("membrane", "wall"):
        for name, constants in (("gent", {"mu": 5 / 3, "jm": 1e9}), ("tpu60a", None)):
            mat = "tpu60a"
            if constants:
                mat = tmp_path / "gent.json"
                mat.write_text(json.dumps(dict(base, name=name, constants=constants)))
            out = tmp_path / f"{model}-{name}.json"
            assert main(["curve", "--model", model, "--type", "B", "--l", "0", "--points", "7",
                         "--material", str(mat), "--json", str(out), "--quiet"]) == 0
            curves[model, name] = Curve.from_json(out)
        a, b = curves[model, "tpu60a"], curves[model, "gent"]
        assert b.material == "gent"
        # Jm = 1e9: W differs from neo-Hookean by (I1 - 3)/Jm of itself
        assert_allclose(b.force_N, a.force_N, rtol=1e-6, atol=1e-9)
    # and the law is what the solver reads: Jm = 2 stiffens the wall where I1 − 3 nears it
    mat = tmp_path / "gent.json"
    mat.write_text(json.dumps(dict(base, name="gent2", constants={"mu": 5 / 3, "jm": 2.0})))
    out = tmp_path / "wall-gent2.json"
    assert main(["curve", "--model", "wall", "--type", "B", "--l", "0", "--points", "7",
                 "--material", str(mat), "--json", str(out), "--quiet"]) == 0
    stiff = Curve.from_json(out)
    assert stiff.force_N[-1] > 1.005 * curves["wall", "tpu60a"].force_N[-1]
