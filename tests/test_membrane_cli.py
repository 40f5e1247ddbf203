"""``spsc membrane``: outputs (JSON of docs/design.md, CSV, PNG) and one-line errors."""

import json

import numpy as np
import pytest

from spsc.core.curve import CURVE_COLUMNS, Curve
from spsc.cli.main import main


def test_membrane_writes_json_csv_png(tmp_path, capsys):
    j, c, png = tmp_path / "r.json", tmp_path / "r.csv", tmp_path / "r.png"
    rc = main(["membrane", "--type", "D", "--pressure", "40", "--reservoir", "40000",
               "--points", "11", "--json", str(j), "--csv", str(c), "--png", str(png),
               "--meridians"])
    assert rc == 0
    d = json.loads(j.read_text(encoding="utf-8"))
    for key in ("model", "geometry", "material", "setup", "nominal_volume_mm3",
                "inflated_volume_mm3", "inflated_height_mm", "curve"):
        assert key in d
    # the setup complete: the load case and the contact (schema v3)
    assert d["setup"] == {"p_i_kPa": 40.0, "reservoir_mm3": 40000.0, "polytropic_n": 1.0,
                          "indenter": "plate", "friction": "0"}
    assert d["geometry"] == {"w": 11.0, "h": 13.0, "l": 3.0, "t0": 1.0, "n1": 2.0, "n2": 2.2, "cy": 0.6}
    assert set(CURVE_COLUMNS) <= set(d["curve"]) and len(d["curve"]["y_mm"]) == 11
    assert d["inflated_height_mm"] > 13.0 and d["inflated_volume_mm3"] > d["nominal_volume_mm3"]
    a, b = Curve.from_json(j), Curve.from_csv(c)
    for k in CURVE_COLUMNS:
        np.testing.assert_array_equal(getattr(a, k), getattr(b, k))
    assert png.stat().st_size > 10_000
    m = d["extra"]["meridians_mm"]
    assert len(m) == 11 and m[0]["rho"][0] == 0.0 and m[-1]["x"][0] == 0.0
    assert m[-1]["rho"][-1] == pytest.approx(11.0) and m[-1]["eta"][-1] == pytest.approx(0.0, abs=1e-9)
    assert "mean stiffness" in capsys.readouterr().out
    assert d["solver"]["converged"] and d["solver"]["iterations"] > 0
    assert d["solver"]["seconds"] > 0 and d["solver"]["details"]["inflation_intervals"] > 0


def test_seven_parameters_and_a_pure_dome(tmp_path):
    j = tmp_path / "dome.json"
    rc = main(["membrane", "--w", "10", "--h", "10", "--l", "0", "--t0", "1", "--n1", "2",
               "--n2", "2", "--cy", "0", "--pressure", "20", "--points", "7", "--stroke", "3",
               "--json", str(j)])
    d = json.loads(j.read_text(encoding="utf-8"))
    assert rc == 0 and d["geometry"]["l"] == 0.0
    f, p, a = (np.array(d["curve"][k]) for k in ("force_N", "pressure_kPa", "contact_area_mm2"))
    np.testing.assert_allclose(f, 1e-3 * p * a, rtol=1e-12)


def test_simplified_model_option(tmp_path):
    j = tmp_path / "s.json"
    assert main(["membrane", "--type", "B", "--model", "simplified", "--json", str(j)]) == 0
    d = json.loads(j.read_text(encoding="utf-8"))
    assert d["model"] == "simplified"
    assert d["solver"]["converged"] and d["solver"]["seconds"] >= 0


@pytest.mark.parametrize("argv, needle", [
    (["--type", "B", "--pressure", "-5"], "pressure = -5.0"),
    (["--type", "B", "--material", "rubber"], "material = 'rubber'"),
    (["--type", "B", "--stroke", "14"], "stroke = 14.0"),
    (["--type", "E"], "type = 'E'"),
    (["--w", "10", "--h", "10"], "geometry"),
])
def test_bad_input_is_one_line_and_exit_2(capsys, argv, needle):
    assert main(["membrane", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err and err.startswith("spsc membrane: error:")
