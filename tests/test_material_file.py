"""Material files and the catalogue's provenance (spsc.materials.file, .materials): one
lookup resolves a catalogue name or a material file; every problem with a file is one line
naming ``material``; the catalogue's constants and their provenance are data."""

from __future__ import annotations

import json

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.core.jsonio import write_json
from spsc.materials.file import material_record, read_material_file
from spsc.materials import CATALOGUE, PROVENANCES, Material, material, neo_hookean


def _write(tmp_path, name="m.json", **changes):
    rec = material_record("fitted", "neo-hookean", {"C10": 5.0 / 6.0})
    rec.update(changes)
    path = tmp_path / name
    write_json(path, rec)
    return path


def test_a_material_file_is_the_same_law_as_the_catalogue_entry(tmp_path):
    """C10 = μ/2 of tpu60a written and read back: the same coefficients bit for bit, so every
    model computes the same numbers (the CLI test runs the membrane on both)."""
    m = material(str(_write(tmp_path)))
    assert m.coefficients == CATALOGUE["tpu60a"].coefficients
    assert (m.name, m.law, m.provenance) == ("fitted", "neo-hookean", "user-fit")
    assert m.energy(4.0, 5.0) == CATALOGUE["tpu60a"].energy(4.0, 5.0)


@pytest.mark.parametrize("law,constants,coefficients", [
    ("mooney-rivlin", {"C10": 0.3, "C01": 0.05}, ((1, 0, 0.3), (0, 1, 0.05))),
    ("yeoh", {"C10": 0.5, "C20": -0.01, "C30": 0.002}, ((1, 0, 0.5), (2, 0, -0.01),
                                                        (3, 0, 0.002))),
])
def test_invariant_laws_map_onto_the_polynomial(tmp_path, law, constants, coefficients):
    path = _write(tmp_path, law=law, constants=constants)
    assert material(f"  {path}  ").coefficients == coefficients  # spaces as typed


def _error(tmp_path, **changes):
    with pytest.raises(ParameterError) as exc:
        material(str(_write(tmp_path, **changes)))
    msg = str(exc.value)
    assert "\n" not in msg and "material" in msg
    return msg


@pytest.mark.parametrize("changes,says", [
    ({"schema": "spsc.curve"}, "schema"),
    ({"schema_version": 2}, "schema_version 1"),
    ({"law": "gent"}, "law"),
    ({"constants": {"C10": -0.5}}, "initial shear modulus"),
    ({"constants": {"C10": "soft"}}, "C10"),
    ({"constants": {"C10": float("nan")}}, "C10"),
    ({"constants": {"C10": 0.5, "C01": 0.1}}, "exactly C10"),
    ({"constants": {}}, "exactly C10"),
    ({"constants": [0.5]}, "constants"),
    ({"provenance": "rumour"}, "provenance"),
    ({"bulk_ratio": -3}, "bulk_ratio"),
    ({"bulk_ratio": 500}, "2000"),
    ({"law": "ogden", "constants": {"mu": [0.5], "alpha": [-2.0]}}, "initial shear modulus"),
    ({"law": "ogden", "constants": {"mu": [0.5], "alpha": [0.0]}}, "alpha[0]"),
    ({"law": "ogden", "constants": {"mu": [0.5, 1.0], "alpha": [2.0]}}, "equal length"),
])
def test_bad_material_files_are_one_line_errors(tmp_path, changes, says):
    assert says in _error(tmp_path, **changes)


def test_missing_unreadable_and_foreign_files(tmp_path):
    with pytest.raises(ParameterError, match="no such file"):
        material(str(tmp_path / "nope.json"))
    bad = tmp_path / "bad.json"
    bad.write_text("{not json", encoding="utf-8")
    with pytest.raises(ParameterError, match="a JSON material file"):
        material(str(bad))
    (tmp_path / "dir.json").mkdir()
    with pytest.raises(ParameterError, match="not a folder"):
        material(str(tmp_path / "dir.json"))
    curve = tmp_path / "curve.json"
    curve.write_text(json.dumps([1, 2]), encoding="utf-8")
    with pytest.raises(ParameterError, match="schema"):
        material(str(curve))


def test_an_ogden_file_is_the_ogden_law_the_models_solve(tmp_path):
    """The file reads as a record (its fit is kept) and loads as the Ogden law (issue 47)."""
    from spsc.materials import Ogden

    path = _write(tmp_path, law="ogden", constants={"mu": [0.5, -0.01], "alpha": [1.5, -2.0]})
    assert read_material_file(path)["constants"]["alpha"] == [1.5, -2.0]
    law = material(str(path))
    assert isinstance(law, Ogden) and law.alpha == (1.5, -2.0)
    assert law.shear_modulus == pytest.approx(0.5 * (0.5 * 1.5 + 0.01 * 2.0))


def test_unknown_names_list_the_catalogue_and_files():
    with pytest.raises(ParameterError, match="tpu60a, elastic50a, silicone40a, as40, or a "
                       "material file"):
        material("rubber")


def test_catalogue_constants_and_provenance():
    """The catalogue's constants are unchanged and say where they come from."""
    assert CATALOGUE["tpu60a"].coefficients == ((1, 0, 5.0 / 6.0),)
    assert CATALOGUE["elastic50a"].coefficients == ((1, 0, 0.5056), (2, 0, 0.0),
                                                    (3, 0, 0.002562))
    assert CATALOGUE["silicone40a"].shear_modulus == pytest.approx(
        CATALOGUE["as40"].shear_modulus)
    assert {k: m.provenance for k, m in CATALOGUE.items()} == {
        "tpu60a": "datasheet", "elastic50a": "literature", "silicone40a": "assumed",
        "as40": "assumed"}
    assert [k for k, m in CATALOGUE.items() if m.assumed] == ["silicone40a", "as40"]


def test_provenance_is_checked():
    assert set(PROVENANCES) == {"datasheet", "paper", "literature", "assumed", "user-fit"}
    with pytest.raises(ParameterError, match="provenance"):
        Material("x", "neo-hookean", ((1, 0, 0.5),), "", "hearsay")
    assert neo_hookean(1.0).assumed and not neo_hookean(1.0, provenance="paper").assumed


def test_polynomial_energy_is_shared():
    """Material's W, dW and d2W are the module functions the fit uses (one definition)."""
    from spsc.materials import polynomial_d2W, polynomial_dW, polynomial_energy

    m = CATALOGUE["elastic50a"]
    I1, I2 = np.array([3.5, 5.0]), np.array([3.2, 4.0])
    np.testing.assert_array_equal(m.energy(I1, I2), polynomial_energy(m.coefficients, I1, I2))
    np.testing.assert_array_equal(m.dW(I1, I2), polynomial_dW(m.coefficients, I1, I2))
    np.testing.assert_array_equal(m.d2W(I1, I2), polynomial_d2W(m.coefficients, I1, I2))


def test_the_docs_catalogue_table_is_the_catalogue():
    """The materials guide's table (name, law, C10, μ0, provenance) says what the code holds."""
    import re
    from pathlib import Path

    text = (Path(__file__).parents[1] / "docs" / "guides" / "materials.md").read_text(encoding="utf-8")
    for key, m in CATALOGUE.items():
        row = re.search(rf"^\| {key} \| ([^|]+) \| C10 = ([0-9.]+)[^|]* \| ([0-9.]+) \| (\S+) \|",
                        text, re.M)
        assert row, key
        law, c10, mu0, prov = row.groups()
        assert law.strip().lower() == m.law and prov == m.provenance
        assert float(c10) == pytest.approx(m.coefficients[0][2], rel=5e-4)
        assert float(mu0) == pytest.approx(m.shear_modulus, rel=5e-3)
