"""``spsc fit-material`` end to end, the test data it reads (units and layouts from the column
names, one line saying what was assumed, one-line errors naming file, row and column), and a
fitted material file used by the models."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.materials.fit.laws import law
from spsc.materials.data import read_tests
from spsc.cli.main import main

DATA = Path(__file__).parent / "data"
TRELOAR = [str(DATA / f"treloar_{t}.csv") for t in ("uniaxial", "equibiaxial", "planar")]
LAM = np.array([1.0, 1.2, 1.5, 2.0, 2.5, 3.0])
NH = law("neo-hookean")


def _csv(tmp_path, name, text, encoding="utf-8"):
    path = tmp_path / name
    path.write_bytes(text.encode(encoding) if isinstance(text, str) else text)
    return str(path)


def _nh_rows(test="uniaxial", mu=5.0 / 3.0, fmt=lambda lam, P: f"{lam!r},{P!r}"):
    P = NH.stress(test, LAM, [mu / 2])
    return "\n".join(fmt(float(a), float(b)) for a, b in zip(LAM, P)) + "\n"


# -- reading ---------------------------------------------------------------------------------
@pytest.mark.parametrize("header,convert,unit_note", [
    ("stretch,stress_MPa", lambda lam, P: (lam, P), "in MPa"),
    ("strain,stress_kPa", lambda lam, P: (lam - 1, 1e3 * P), "strain in -"),
    ("strain_pct,nominal_stress_pa", lambda lam, P: (100 * (lam - 1), 1e6 * P), "in %"),
    ("Strain (%),Stress [N/mm2]", lambda lam, P: (100 * (lam - 1), P), "in %"),
    ("strain_%,stress_psi", lambda lam, P: (100 * (lam - 1), P / 6.894757293168361e-3),
     "psi"),
    ("lambda,engineering stress", lambda lam, P: (lam, P), "assumed: no unit"),
])
def test_columns_and_units_from_the_names(tmp_path, header, convert, unit_note):
    P = NH.stress("uniaxial", LAM, [0.8])
    rows = "\n".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(*convert(LAM, P)))
    path = _csv(tmp_path, "a.csv", f"{header}\n{rows}\n")
    (d,), (note,) = read_tests([path])
    np.testing.assert_allclose(d.stretch, LAM, rtol=1e-14)
    np.testing.assert_allclose(d.stress_MPa, P, rtol=1e-14)
    assert unit_note in note and "assumed: no --test" in note and "\n" not in note


def test_bom_latin1_comments_semicolons_and_decimal_commas(tmp_path):
    """A spreadsheet's export: byte-order mark, a Latin-1 comment (°, µ), semicolons with
    decimal commas, a '# test:' line naming the test."""
    text = ("# Prüfung bei 23 °C, µ-Probe\n# test: equibiaxial\nstretch;stress_MPa\n"
            + _nh_rows("equibiaxial", fmt=lambda a, b: f"{a!r};{b!r}".replace(".", ",")))
    path = _csv(tmp_path, "b.csv", b"\xef\xbb\xbf" + text.encode("latin-1"))
    (d,), (note,) = read_tests([path])
    assert d.test == "equibiaxial" and "'# test:' line" in note
    assert d.notes == ("Prüfung bei 23 °C, µ-Probe",)  # the source, kept; '# test:' is not
    np.testing.assert_allclose(d.stress_MPa, NH.stress("equibiaxial", LAM, [5 / 6]),
                               rtol=1e-14)


def test_a_test_column_holds_several_tests(tmp_path):
    rows = "".join(f"{t},{float(a)!r},{float(b)!r}\n" for t in ("pure shear", "uniaxial")
                   for a, b in zip(LAM, NH.stress("planar" if t == "pure shear" else t, LAM,
                                                  [0.5])))
    tests, (note,) = read_tests([_csv(tmp_path, "c.csv", "test,stretch,stress_MPa\n" + rows)])
    assert [d.test for d in tests] == ["uniaxial", "planar"] and "'test' column" in note


@pytest.mark.parametrize("text,says", [
    ("strain,force_N\n0,0\n1,2\n", "a stretch (or strain) column and a stress column"),
    ("stretch,stress_MPa\n1,0\n1.5,abc\n", "row 3, column 'stress_MPa'"),
    ("stretch,stress_MPa\n1,0\n1.5,nan\n", "NaN rows"),
    ("stretch,stress_MPa\n1,0\n1.5,\n", "row 3"),
    ("stretch,stress_MPa\n1,0\n0.8,0.1\n", "stretch >= 1"),
    ("strain,stress_MPa\n0,0\n-1.5,0.1\n", "stretch > 0"),
    ("stretch,stress_MPa\n1,0\n1.5,0.2\n1.4,0.3\n", "the stretch must increase"),
    ("stretch,stress_MPa\n1,0.5\n1.5,0.2\n", "increases with the stretch"),
    ("stretch,stress_MPa\n1,0\n1.25,-0.1\n1.5,0.5\n2,1.8\n", "row 3, column 'stress_MPa' = "
     "'-0.1 MPa' is invalid: allowed a nominal stress >= 0"),
    ("stretch,stress_MPa\n1,0\n1.5,1.06\n2,0.75\n3,2.9\n", "row 4, column 'stress_MPa' = "
     "'0.75 MPa' is invalid: allowed >= 1.06 MPa of a row before"),
    ("stretch,stress_bar\n1,0\n1.5,0.2\n", "a stress unit of"),
    ("stretch,true_stress_MPa\n1,0\n1.5,0.2\n", "nominal (engineering) stress"),
    ("stretch,stress_MPa,stress_kPa\n1,0,0\n1.5,0.2,200\n", "one stress column"),
    ("log_strain,stress_MPa\n0,0\n0.4,0.2\n", "not log strain"),
    ("stretch,stress_MPa\n", "data rows"),
    ("", "a header line"),
    ("# test: torsion\nstretch,stress_MPa\n1,0\n1.5,0.2\n", "uniaxial, equibiaxial or planar"),
    ("stretch,stress_MPa\n1,0,7\n", "2 fields"),
])
def test_bad_data_is_one_line_naming_file_row_column(tmp_path, text, says):
    with pytest.raises(ParameterError) as exc:
        read_tests([_csv(tmp_path, "bad.csv", text)])
    msg = str(exc.value)
    assert says in msg and "\n" not in msg and "bad.csv" in msg


def test_noise_within_one_percent_of_the_largest_stress_is_data():
    """A load cell's zero offset and a dip of its noise (0.9 % of the largest stress, under
    STRESS_NOISE = 1 %) are read; 1.1 % is refused."""
    from spsc.materials.data import read_file

    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        ok = _csv(Path(tmp), "ok.csv", "stretch,stress_MPa\n1,-0.009\n1.5,1\n1.6,0.991\n2,1\n")
        bad = _csv(Path(tmp), "bad.csv", "stretch,stress_MPa\n1,0\n1.5,1\n1.6,0.989\n2,1\n")
        assert read_file(ok)[0][0].points == 4
        with pytest.raises(ParameterError, match="must not fall"):
            read_file(bad)


def test_test_options_and_declarations_must_agree(tmp_path):
    a = _csv(tmp_path, "a.csv", "# test: planar\nstretch,stress_MPa\n" + _nh_rows("planar"))
    b = _csv(tmp_path, "b.csv", "stretch,stress_MPa\n" + _nh_rows())
    with pytest.raises(ParameterError, match="--test.*declares"):
        read_tests([a], tests=["uniaxial"])
    with pytest.raises(ParameterError, match="once per file"):
        read_tests([a, b, b], tests=["planar", "uniaxial"])
    with pytest.raises(ParameterError, match="given twice"):
        read_tests([b, b])
    tests, _ = read_tests([a, b], tests=["planar", "equibiaxial"])
    assert [d.test for d in tests] == ["planar", "equibiaxial"]


# -- the command -------------------------------------------------------------------------------
def _run(argv, capsys):
    rc = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


@pytest.fixture
def tpu_data(tmp_path):
    """Neo-Hookean data at tpu60a's μ = 5/3 MPa in the three tests, three units."""
    files = []
    for test, header, scale in (("uniaxial", "stretch,stress_MPa", 1.0),
                                ("equibiaxial", "stretch,stress_kPa", 1e3),
                                ("planar", "stretch,stress_Pa", 1e6)):
        rows = _nh_rows(test, fmt=lambda a, b: f"{a!r},{b * scale!r}")
        files.append(_csv(tmp_path, f"{test}.csv",
                          f"# {test} test, lab X\n# test: {test}\n{header}\n{rows}"))
    return files


def test_fit_writes_report_figure_and_material_file(tmp_path, tpu_data, capsys):
    out = tmp_path / "tpu.json"
    rc, stdout, err = _run(["fit-material", *tpu_data, "--out", out, "--json",
                            tmp_path / "fit.json", "--png", tmp_path / "fit.png"], capsys)
    assert rc == 0, err
    read = [ln for ln in err.splitlines() if ln.startswith("spsc fit-material: read ")]
    assert len(read) == 3 and "stress in kPa" in read[1]  # one line a file
    rec = json.loads(out.read_text(encoding="utf-8"))
    assert rec["schema"] == "spsc.material" and rec["name"] == "tpu"
    assert rec["law"] == "neo-hookean" and "lowest AICc" in rec["fit"]["choice"]
    assert rec["constants"]["C10"] == pytest.approx(5 / 6, rel=1e-12)
    assert [d["test"] for d in rec["data"]] == ["uniaxial", "equibiaxial", "planar"]
    assert all(len(d["sha256"]) == 64 for d in rec["data"])
    assert [d["notes"] for d in rec["data"]] == [[f"{t} test, lab X"] for t in
                                                 ("uniaxial", "equibiaxial", "planar")]
    assert rec["fit"]["drucker_stable"] and rec["provenance"] == "user-fit"
    report = json.loads((tmp_path / "fit.json").read_text(encoding="utf-8"))
    assert set(report["fits"]) == {"neo-hookean", "mooney-rivlin", "yeoh", "ogden"}
    assert report["material_file"]["law"] == "neo-hookean"
    assert (tmp_path / "fit.png").stat().st_size > 10_000
    assert "material file law: neo-hookean" in stdout


def _curve(argv, tmp_path, capsys, name):
    path = tmp_path / name
    rc, _, err = _run(["curve", "--model", "membrane", "--type", "B", "--points", "7",
                       "--quiet", "--json", path, *argv], capsys)
    assert rc == 0, err
    return json.loads(path.read_text(encoding="utf-8"))


def test_fitted_material_runs_the_membrane_like_the_catalogue_entry(tmp_path, tpu_data,
                                                                     capsys):
    """A material file of tpu60a's law gives tpu60a's curve: bit for bit when the file holds
    the catalogue constant (the same coefficients), and to 1e-9 when it was fitted to exact
    data at that μ (the fit reproduces C10 to ~1e-15)."""
    from spsc.core.jsonio import write_json
    from spsc.materials.file import material_record

    ref = _curve(["--material", "tpu60a"], tmp_path, capsys, "ref.json")
    same = tmp_path / "same.json"
    write_json(same, material_record("same", "neo-hookean", {"C10": 5.0 / 3.0 / 2.0}))
    exact = _curve(["--material", same], tmp_path, capsys, "exact.json")
    fitted = tmp_path / "fitted.json"
    assert _run(["fit-material", *tpu_data, "--law", "neo-hookean", "--out", fitted],
                capsys)[0] == 0
    fit = _curve(["--material", fitted], tmp_path, capsys, "fit.json")
    for key in ("force_N", "pressure_kPa", "contact_area_mm2", "volume_change_mm3"):
        assert exact["curve"][key] == ref["curve"][key]
        np.testing.assert_allclose(fit["curve"][key], ref["curve"][key], rtol=1e-9, atol=1e-12)
    assert fit["material"] == "fitted" and ref["material"] == "tpu60a"


def test_treloar_all_laws_take_yeoh_for_the_models(tmp_path, capsys):
    rc, stdout, _ = _run(["fit-material", *TRELOAR, "--ogden-terms", "3", "--out",
                          tmp_path / "nr.json"], capsys)
    assert rc == 0
    assert "material file law: yeoh" in stdout and "R²: uniaxial 0.9930" in stdout
    rec = json.loads((tmp_path / "nr.json").read_text(encoding="utf-8"))
    assert rec["law"] == "yeoh" and set(rec["fit"]["r2"]) == {"uniaxial", "equibiaxial",
                                                                "planar"}


def test_a_law_unstable_over_its_data_exits_1_and_still_writes(tmp_path, capsys):
    """Mooney–Rivlin data with C01 < 0 up to λ = 3: the fit recovers the law, which is
    Drucker-unstable above √5 in uniaxial tension, inside the data: exit 1, file written."""
    mr = law("mooney-rivlin")
    lam = np.linspace(1.0, 3.0, 12)
    rows = "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(lam, mr.stress("uniaxial", lam,
                                                                   [0.5, -0.1])))
    path = _csv(tmp_path, "mr.csv", "stretch,stress_MPa\n" + rows)
    rc, _, err = _run(["fit-material", path, "--law", "mooney-rivlin", "--out",
                       tmp_path / "mr.json"], capsys)
    assert rc == 1 and "unstable: mooney-rivlin" in err and "stretch > 2.236" in err
    assert (tmp_path / "mr.json").exists()


def test_list_catalogue_shows_law_constants_and_provenance(capsys):
    rc, out, _ = _run(["fit-material", "--list-catalogue"], capsys)
    assert rc == 0
    for name, prov in (("tpu60a", "datasheet"), ("elastic50a", "literature"),
                       ("silicone40a", "assumed"), ("as40", "assumed")):
        assert f"provenance: {prov}" in next(ln for ln in out.splitlines()
                                             if ln.startswith(name + ":"))
    assert "C10 = 0.833333" in out


@pytest.mark.parametrize("argv,names", [
    (["membrane", "--type", "B", "--material", "{missing}"], "material"),
    (["curve", "--model", "surrogate", "--type", "B", "--l", "0", "--material", "{ogden}"],
     "neo-Hookean"),
    (["bladder", "--type", "B", "--material", "{ogden}"], "material file carries no process"),
    (["fit-material", "{data}", "--range", "5:6"], "--range"),
    (["fit-material", "{data}", "--law", "ogden", "--ogden-terms", "3"], "data points"),
])
def test_one_line_errors(tmp_path, capsys, argv, names):
    from spsc.core.jsonio import write_json
    from spsc.materials.file import material_record

    ogden = tmp_path / "og.json"
    write_json(ogden, material_record("og", "ogden", {"mu": [0.5, 0.01], "alpha": [2.0, 4.0]}))
    data = _csv(tmp_path, "d.csv", "stretch,stress_MPa\n1,0\n1.5,0.2\n2,0.4\n")
    fill = {"{missing}": str(tmp_path / "missing.json"), "{ogden}": str(ogden),
            "{data}": data}
    rc, _, err = _run([fill.get(a, a) for a in argv], capsys)
    assert rc == 2 and len(err.strip().splitlines()) == 1 and names in err, err


def test_one_test_plots_predictions_and_an_ogden_file_is_a_model_law(tmp_path, capsys):
    """Uniaxial data only: the figure still has the equibiaxial and planar panels (the laws'
    predictions); --law ogden writes a material file the models solve."""
    rc, out, _ = _run(["fit-material", TRELOAR[0], "--range", ":5", "--png",
                       tmp_path / "u.png", "--law", "ogden", "--out", tmp_path / "og.json"],
                      capsys)
    assert rc == 0 and (tmp_path / "u.png").stat().st_size > 10_000
    assert f"use it as --material {tmp_path / 'og.json'}" in out
    rc, out, _ = _run(["membrane", "--type", "B", "--pressure", "5", "--points", "5",
                       "--material", tmp_path / "og.json"], capsys)
    assert rc == 0 and "material og" in out


# -- the law the material file takes --------------------------------------------------------
def _written(tmp_path, capsys, name, lam, P, fmt):
    rows = "".join(f"{a:{fmt[0]}},{b:{fmt[1]}}\n" for a, b in zip(lam, P))
    data = _csv(tmp_path, f"{name}.csv", "stretch,stress_MPa\n" + rows)
    out = tmp_path / f"{name}.material.json"
    rc, stdout, _ = _run(["fit-material", data, "--out", out], capsys)
    assert rc == 0
    return json.loads(out.read_text()), stdout


@pytest.mark.parametrize("fmt", [(".4f", ".6f"), (".2f", ".4f")])
def test_exact_neo_hookean_data_give_a_neo_hookean_file(tmp_path, capsys, fmt):
    """μ = 1 MPa at 41 stretches 1-3, written to 6 (or 4) decimals: Mooney-Rivlin fits the
    rounding better (C01 ~ 1e-6, lower AICc), within the data's resolution: the file is
    neo-Hookean."""
    lam = np.linspace(1.0, 3.0, 41)
    rec, stdout = _written(tmp_path, capsys, "nh", lam, NH.stress("uniaxial", lam, [0.5]), fmt)
    assert rec["law"] == "neo-hookean", stdout
    assert rec["constants"]["C10"] == pytest.approx(0.5, rel=1e-4)  # 4 decimals of ~1 MPa
    assert "within the data's resolution" in rec["fit"]["choice"]


def test_mooney_rivlin_data_with_a_real_C01_give_a_mooney_rivlin_file(tmp_path, capsys):
    """C10 = 0.4, C01 = 0.02 MPa (C01/C10 = 5 %), written to 6 decimals: neo-Hookean misses
    by ~1e-2 MPa, far above the resolution (~4e-5 MPa): the file is Mooney-Rivlin with C01
    recovered to 1 %."""
    lam = np.linspace(1.0, 3.0, 41)
    P = law("mooney-rivlin").stress("uniaxial", lam, [0.4, 0.02])
    rec, stdout = _written(tmp_path, capsys, "mr", lam, P, (".4f", ".6f"))
    assert rec["law"] == "mooney-rivlin", stdout
    assert rec["constants"]["C01"] == pytest.approx(0.02, rel=0.01)


def test_resolution_is_the_rounding_of_the_numbers_as_written(tmp_path):
    """P = λ - 1 MPa (slope 1) written to 0.01 MPa and 1e-4 in stretch: resolution
    sqrt((0.01² + 1e-4²)/12); trailing zeros count (1.5000 has 4 decimals); a kPa column's
    step is in kPa (1 kPa = 1e-3 MPa)."""
    from spsc.materials.fit.resolution import resolution_MPa

    mpa = _csv(tmp_path, "mpa.csv", "stretch,stress_MPa\n1.0000,0.00\n1.5000,0.50\n2.0000,"
               "1.00\n")
    kpa = _csv(tmp_path, "kpa.csv", "stretch,stress_kPa\n1.0000,0\n1.5000,500\n2.0000,1000\n")
    (d,), _ = read_tests([mpa])
    assert d.columns["deformation_decimals"] == 4 and d.columns["stress_decimals"] == 2
    assert resolution_MPa([d])["uniaxial"] == pytest.approx(np.sqrt((1e-4 + 1e-8) / 12),
                                                            rel=1e-9)
    (k,), _ = read_tests([kpa])
    assert resolution_MPa([k])["uniaxial"] == pytest.approx(np.sqrt((1e-6 + 1e-8) / 12),
                                                            rel=1e-9)


def test_relaxation_test_writes_prony_terms_into_the_material_file(tmp_path, capsys):
    """A relaxation test made from two known terms: the material file carries terms whose
    g(t) is the data's (the fit's own bound: the terms trade off, the curve does not), and
    spsc.materials.viscosity reads them back with their source."""
    from spsc.materials import viscosity
    from spsc.materials.prony import Prony

    true = Prony(((0.8, 0.05), (0.4, 2.0)))
    t = np.logspace(-3, 2, 60)
    relax = _csv(tmp_path, "relax.csv", "t_s,stress_MPa\n" + "".join(
        f"{a:.9g},{0.7 * g:.9g}\n" for a, g in zip(t, true.relaxation(t))))
    lam = np.linspace(1.0, 3.0, 41)
    data = _csv(tmp_path, "nh.csv", "stretch,stress_MPa\n" + "".join(
        f"{a:.4f},{b:.6f}\n" for a, b in zip(lam, NH.stress("uniaxial", lam, [0.5]))))
    out = tmp_path / "visco.material.json"
    rc, stdout, _ = _run(["fit-material", data, "--relaxation", relax, "--out", out], capsys)
    assert rc == 0 and "prony (relax.csv, 60 points)" in stdout
    rec = json.loads(out.read_text())
    assert rec["prony"]["data"]["points"] == 60 and "relax.csv" in rec["prony"]["source"]
    prony, source = viscosity(str(out))
    np.testing.assert_allclose(prony.relaxation(t), true.relaxation(t), rtol=1e-4)
    assert "relax.csv" in source
    cat, why = viscosity("tpu60a")
    assert cat.terms == ((0.646, 1.0),) and "3.8 N" in why
    assert viscosity("elastic50a")[0] is None


def test_a_bad_relaxation_file_is_one_line(tmp_path, capsys):
    data = _csv(tmp_path, "nh.csv", "stretch,stress_MPa\n1.0,0\n1.5,0.5\n2.0,1.0\n2.5,1.5\n")
    bad = _csv(tmp_path, "relax.csv", "time,a,b\n1,2,3\n")
    rc, _, err = _run(["fit-material", data, "--relaxation", bad], capsys)
    assert rc == 2 and "--relaxation" in err and "t_s" in err and len(err.splitlines()) == 1
