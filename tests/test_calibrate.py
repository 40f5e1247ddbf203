"""Calibration of the material's stiffness on a bench test through the wall model (issue 12)."""

import json
import re

import numpy as np
import pytest

from spsc.cad.geometry import preset
from spsc.core.errors import ParameterError
from spsc.fem.wall.calibrate import calibrate, scaled
from spsc.fem.wall import WallSettings, wall_curve
from spsc.core.bench import BenchData
from spsc.materials import material
from spsc.cli.main import main

G = preset("B", l=0.0)
MAT = material("tpu60a")
#: a coarse dome: the identities below hold on any mesh
FAST = WallSettings(mesh_size_mm=1.0, layers=1)


def test_vented_forces_scale_with_the_stiffness():
    # no pressure load: the equilibrium under prescribed plate travel does not depend on the
    # stiffness, every force scales with it (the closed form the open-chamber calibration uses)
    a = wall_curve(G, MAT, pressure_kPa=0.0, stroke_mm=2.0, points=5, settings=FAST)
    b = wall_curve(G, scaled(MAT, 2.5), pressure_kPa=0.0, stroke_mm=2.0, points=5, settings=FAST)
    np.testing.assert_allclose(b.force_N[1:], 2.5 * a.force_N[1:], rtol=1e-7)
    np.testing.assert_allclose(b.contact_area_mm2, a.contact_area_mm2, rtol=1e-7, atol=1e-9)


def _bench(s_true, pressure_kPa, reservoir=0.0, points=21, stroke=2.5):
    c = wall_curve(G, scaled(MAT, s_true), pressure_kPa=pressure_kPa, reservoir_mm3=reservoir,
                   stroke_mm=stroke, points=points, settings=FAST)
    return BenchData(c.y_mm, c.force_N, c.pressure_kPa if pressure_kPa > 0 else None,
                     source="synthetic")


@pytest.mark.parametrize("pressure, reservoir", [(0.0, 0.0), (40.0, 0.0), (10.0, 40000.0)])
def test_recovers_the_stiffness_of_a_synthetic_bench(pressure, reservoir):
    # bench on a 21-point grid, the model on 13 points interpolated onto it: the recovered
    # factor and the residual carry only the interpolation error (measured: factor within
    # 2e-4..1.2e-3, relative RMS 2.4e-3 on the vented dome, whose flat top inverts)
    cal = calibrate(_bench(1.6, pressure, reservoir), G, MAT, pressure_kPa=pressure,
                    reservoir_mm3=reservoir, settings=FAST, points=13)
    assert cal.scale == pytest.approx(1.6, rel=2e-3)
    assert cal.relative_rms < 5e-3
    assert cal.material.shear_modulus == pytest.approx(1.6 * MAT.shear_modulus, rel=2e-3)


def test_noise_moves_the_factor_by_about_the_noise_over_root_n():
    bench = _bench(0.8, 0.0, points=41)
    rng = np.random.default_rng(3)
    noisy = BenchData(bench.y_mm, bench.force_N * (1 + 0.03 * rng.standard_normal(41)), None)
    cal = calibrate(noisy, G, MAT, pressure_kPa=0.0, settings=FAST, points=13)
    # 3 % noise on 40 points: the factor's standard error is ~0.5 %; allow 4 sigma
    assert cal.scale == pytest.approx(0.8, rel=0.02)
    assert 0.01 < cal.relative_rms < 0.05


def test_bad_bench_is_a_one_line_error():
    b = _bench(1.0, 40.0, points=5, stroke=1.0)
    with pytest.raises(ParameterError, match="setup pressure"):  # absolute pressure, not gauge
        calibrate(BenchData(b.y_mm, b.force_N, b.pressure_kPa + 101.3), G, MAT,
                  pressure_kPa=40.0, settings=FAST)
    with pytest.raises(ParameterError, match="non-zero force"):
        calibrate(BenchData(b.y_mm, 0 * b.force_N, None), G, MAT, pressure_kPa=0.0,
                  settings=FAST)


def test_cli_writes_the_calibrated_material_and_predictions(tmp_path, capsys):
    b = _bench(1.3, 0.0, points=11, stroke=2.0)
    csv = tmp_path / "open.csv"
    csv.write_text("# open chamber\ny_mm,force_N\n"
                   + "".join(f"{y},{f}\n" for y, f in zip(b.y_mm, b.force_N)))
    out = tmp_path / "cal.json"
    rc = main(["calibrate", str(csv), "--type", "B", "--l", "0", "--pressure", "0",
               "--mesh-size", "1", "--layers", "1", "--predict-pressures", "40",
               "--predict-reservoirs", "0", "--predict-stroke", "1", "--json", str(out),
               "--out", str(tmp_path / "mine.json"), "--quiet"])
    assert rc == 0
    data = json.loads(out.read_text())
    assert data["scale"] == pytest.approx(1.3, rel=2e-3)
    # the calibrated law as a material file every model takes as --material
    mine = material(str(tmp_path / "mine.json"))
    assert mine.provenance == "user-fit"
    assert mine.shear_modulus == pytest.approx(data["scale"] * MAT.shear_modulus, rel=1e-12)
    assert data["material"]["shear_modulus_MPa"] == pytest.approx(1.3 * 5 / 3, rel=2e-3)
    (pred,) = data["predictions"]
    assert pred["setup"]["p_i_kPa"] == 40 and pred["solver"]["converged"]
    assert re.search(r"stiffness x 1\.(29|30)", capsys.readouterr().out)


@pytest.mark.parametrize("argv, message", [
    (["--pressure", "0", "BENCH_P"], "bench pressure_kPa"),      # pressures on a vented test
    (["--pressure", "40", "BENCH_Y"], "stroke"),                 # bench y beyond the chamber
    (["--pressure", "-1", "BENCH_P"], "pressure"),
    (["--pressure", "40", "--predict-pressures", "x", "BENCH_P"], "predict-pressures"),
    (["--pressure", "40", "--material", "unobtainium", "BENCH_P"], "material"),
    (["--pressure", "40", "NOFILE"], "no such file"),
])
def test_cli_bad_input_is_one_line_exit_2(tmp_path, capsys, argv, message):
    (tmp_path / "p.csv").write_text("y_mm,force_N,pressure_kPa\n0,0,40\n1,1,41\n2,3,42\n")
    (tmp_path / "y.csv").write_text("y_mm,force_N\n0,0\n10,1\n20,3\n")
    files = {"BENCH_P": str(tmp_path / "p.csv"), "BENCH_Y": str(tmp_path / "y.csv"),
             "NOFILE": str(tmp_path / "missing.csv")}
    rc = main(["calibrate", "--type", "B", "--quiet"] + [files.get(a, a) for a in argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and message in err[0], err


def test_identification_is_compared_and_agrees_at_the_tests_own_setup(tmp_path, capsys):
    # the paper's identification reproduces its own bench test by construction (eqs. 39-40 then
    # 6-7 at the same setup), as does the calibrated wall model: the two predictions meet there
    b = _bench(1.2, 40.0, points=9, stroke=2.0)
    csv = tmp_path / "p40.csv"
    csv.write_text("y_mm,force_N,pressure_kPa\n" + "".join(
        f"{y},{f},{p}\n" for y, f, p in zip(b.y_mm, b.force_N, b.pressure_kPa)))
    out = tmp_path / "cal.json"
    rc = main(["calibrate", str(csv), "--type", "B", "--l", "0", "--pressure", "40",
               "--mesh-size", "1", "--layers", "1", "--predict-pressures", "10,40",
               "--predict-reservoirs", "0", "--predict-stroke", "2", "--json", str(out),
               "--quiet"])
    assert rc == 0
    data = json.loads(out.read_text())
    wall = {c["setup"]["p_i_kPa"]: c for c in data["predictions"]}
    ident = {c["setup"]["p_i_kPa"]: c for c in data["identification_predictions"]}
    assert set(wall) == set(ident) == {10, 40}
    # at 40 kPa both end at the bench's force and pressure: the identification exactly, the
    # calibrated wall model to its fit (a 13-point model interpolated onto 9 bench points:
    # measured 0.3 % in force at the end, 1e-5 in pressure)
    for c, rel in ((ident[40], 1e-9), (wall[40], 1e-2)):
        assert c["curve"]["force_N"][-1] == pytest.approx(b.force_N[-1], rel=rel)
        assert c["curve"]["pressure_kPa"][-1] == pytest.approx(b.pressure_kPa[-1], rel=rel / 10)
    assert "paper's identification" in capsys.readouterr().out


@pytest.mark.parametrize("text,says", [
    ("10,,40", "item 2 is empty"), ("10,", "item 2 is empty"), (",10", "item 1 is empty"),
    ("", "one or more"), ("10,x", "item 2, 'x', is not a number"),
    ("10,-1", ">= 0 and <= 100 (kPa) in every item (item 2 is -1)"), ("nan", "item 1 is nan"),
    ("10,10", "each value once"), ("1e5", "<= 100"),
])
def test_a_list_of_numbers_is_refused_whole_naming_the_item(text, says):
    """calibrate's and identify's --predict-* lists (and fem's vectors) go through one parser:
    an empty item is an error, not skipped ('10,,40' was read as 10, 40)."""
    from spsc.cli.options import number_list

    with pytest.raises(ParameterError, match=re.escape(says)) as exc:
        number_list("predict-pressures", text, ge=0, le=100, unit="kPa", distinct=True)
    assert str(exc.value).startswith(f"predict-pressures = {text!r} is invalid")


def test_a_list_of_numbers_reads_as_typed():
    from spsc.cli.options import number_list

    assert number_list("x", " 10, 20.5 ,40 ", ge=0) == (10.0, 20.5, 40.0)
    assert number_list("x", "0,0,-1", count=3) == (0.0, 0.0, -1.0)
    with pytest.raises(ParameterError, match="3 comma-separated numbers"):
        number_list("x", "0,1", count=3)
