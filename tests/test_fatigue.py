"""The fatigue life (issue 51): the power law through its calibration point, and spsc fatigue
end to end (the Type B dome against the calibration on Table 1's Type B)."""

from __future__ import annotations

import json
import math

import pytest
from numpy.testing import assert_allclose

from spsc.cli.main import main
from spsc.core.errors import ParameterError
from spsc.materials.catalogue import CATALOGUE, FATIGUE_TESTS
from spsc.materials.fatigue import FatigueLaw


def test_the_law_passes_through_its_point_with_its_slope():
    law = FatigueLaw(4.0, 0.09, 4100.0)
    assert law.life(0.09) == pytest.approx(4100.0, rel=1e-12)
    assert law.life(0.18) == pytest.approx(4100.0 / 16.0, rel=1e-12)  # W_a doubled: 2^-F
    assert law.life(0.0) == math.inf
    assert law.energy_MPa == pytest.approx(0.09 * 4100.0 ** 0.25, rel=1e-12)
    assert law.life(law.energy_MPa) == pytest.approx(1.0, rel=1e-12)  # W_c: one cycle
    assert law.amplitude_for(law.life(0.05)) == pytest.approx(0.05, rel=1e-12)
    two = law.with_exponent(2.0)
    assert two.life(0.09) == pytest.approx(4100.0, rel=1e-12)
    assert two.life(0.18) == pytest.approx(4100.0 / 4.0, rel=1e-12)
    for bad in (-1.0, math.nan, math.inf):
        with pytest.raises(ParameterError, match="energy amplitude"):
            law.life(bad)
    with pytest.raises(ParameterError, match="fatigue exponent"):
        FatigueLaw(1.0, 0.09, 4100.0)


def test_every_catalogue_material_has_its_table_2_test():
    assert set(FATIGUE_TESTS) == set(CATALOGUE)
    cycles = {k: v["cycles"] for k, v in FATIGUE_TESTS.items()}
    assert cycles == {"tpu60a": 4100.0, "elastic50a": 1330.0, "silicone40a": 2075.0,
                      "as40": 5000.0}
    assert [k for k, v in FATIGUE_TESTS.items() if v["runout"]] == ["as40"]


def test_spsc_fatigue_predicts_a_dome_from_the_type_b_calibration(tmp_path, capsys):
    out, png = tmp_path / "f.json", tmp_path / "f.png"
    assert main(["fatigue", "--type", "B", "--l", "0", "--json", str(out), "--png", str(png),
                 "--quiet"]) == 0
    doc = json.loads(out.read_text(encoding="utf-8"))
    law = doc["law"]
    assert law["calibration_cycles"] == 4100.0 and law["exponent"] == 4.0
    w = doc["energy_amplitude_MPa"]
    # eq. L1 through the calibration point, recomputed here
    expect = 4100.0 * (w / law["calibration_amplitude_MPa"]) ** -4.0
    assert_allclose(doc["life_cycles"], expect, rtol=1e-12)
    assert_allclose(doc["life_other_exponent"]["cycles"],
                    4100.0 * (w / law["calibration_amplitude_MPa"]) ** -2.0, rtol=1e-12)
    hot = doc["peaks"]["energy_amplitude"]
    assert hot["value"] == w and not hot["base"] and hot["face"] in ("inner", "outer")
    assert doc["converged"] and doc["setup"]["pressure_kPa"] == 50.0
    assert doc["provenance"]["commit"] is None or len(doc["provenance"]["commit"]) == 40
    assert png.stat().st_size > 10_000
    text = capsys.readouterr().out
    assert "hot spot" in text and "life" in text and "CALIBRATED" in text


def test_a_run_out_gives_a_lower_bound(tmp_path, capsys):
    out = tmp_path / "f.json"
    assert main(["fatigue", "--type", "B", "--l", "0", "--material", "as40", "--json",
                 str(out), "--quiet"]) == 0
    doc = json.loads(out.read_text(encoding="utf-8"))
    assert doc["life_is_lower_bound"] and "life at least" in capsys.readouterr().out


def _material_file(path, fatigue):
    record = {"schema": "spsc.material", "schema_version": 1, "name": "my-tpu",
              "law": "neo-hookean", "constants": {"C10": 5.0 / 6.0}, "fatigue": fatigue}
    path.write_text(json.dumps(record))
    return str(path)


@pytest.mark.slow  # 7-10 s: make test-slow (make test stays under 3 min)
def test_a_material_file_carries_its_own_fatigue_law(tmp_path):
    """A file's ``fatigue`` entry: its own law (no calibration), or its own Type B test
    (calibrated as Table 2 calibrates the catalogue's: with the catalogue's TPU 60A constants
    and its 4100 cycles, the same law)."""
    from spsc.fem.wall.durability import paper_fatigue_law

    own = _material_file(tmp_path / "own.json", {"exponent": 3.0, "amplitude_MPa": 0.05,
                                                 "cycles": 1e4, "source": "my test"})
    law = paper_fatigue_law(own)
    assert (law.exponent, law.amplitude_MPa, law.cycles, law.source) == (3.0, 0.05, 1e4,
                                                                       "my test")
    test = _material_file(tmp_path / "test.json", {"exponent": 4.0, "cycles": 4100})
    assert_allclose(paper_fatigue_law(test).amplitude_MPa,
                    paper_fatigue_law("tpu60a").amplitude_MPa, rtol=1e-9)
    for bad, key in (({"exponent": 1, "cycles": 10}, "fatigue.exponent"),
                     ({"exponent": 4}, "fatigue.cycles"),
                     ({"exponent": 4, "cycles": 10, "slope": 2}, "fatigue.slope")):
        with pytest.raises(ParameterError, match=key):
            paper_fatigue_law(_material_file(tmp_path / f"bad{len(key)}.json", bad))
    out = tmp_path / "f.json"
    assert main(["fatigue", "--type", "B", "--l", "0", "--material", own, "--json", str(out),
                 "--quiet"]) == 0
    assert json.loads(out.read_text())["law"]["source"] == "my test"
