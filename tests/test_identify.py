"""Identification from bench data (eqs. 39–40): round trips on synthetic bench files, errors."""

import numpy as np
import pytest

from spsc.core.errors import ParameterError
from spsc.cad.geometry import preset
from spsc.core.curve import Curve
from spsc.membrane.identify import identify, predict, read_bench
from spsc.membrane.lumped import Setup, lumped_curve
from spsc.materials import material
from spsc.membrane.solver import solve
from spsc.cli.main import main

VB = 6505.0


def _known():
    y = np.linspace(0, 6, 25)
    return y, 60.0 * y + 6.0 * y**2, 40.0 * y**2 + 2.0 * y**3, 0.8 * y**1.5  # A, ΔV, F_el


def _write(path, y, f, p, fel=None, header=None):
    cols = header or (["y_mm", "force_N", "pressure_kPa"] + (["elastic_force_N"] if fel is not None else []))
    rows = [",".join(cols)]
    for i in range(len(y)):
        vals = [y[i], f[i], p[i]] + ([fel[i]] if fel is not None else [])
        rows.append(",".join(repr(float(v)) for v in vals))
    path.write_text("# synthetic bench file\n" + "\n".join(rows) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("vr", [0.0, 40000.0])
def test_round_trip_recovers_area_and_volume_change(tmp_path, vr):
    y, a, dv, fel = _known()
    bench = lumped_curve(y, a, dv, Setup(40.0, VB, vr), elastic_force_N=fel)
    f = _write(tmp_path / "b.csv", y, bench.force_N, bench.pressure_kPa, fel)
    ident = identify(read_bench(f), pressure_kPa=40.0, bladder_volume_mm3=VB, reservoir_mm3=vr)
    # eqs. 39–40 invert eqs. 6–7 exactly: round-off through repr() only (ΔV with a 40 cm³
    # reservoir comes from a ~1e-3 pressure ratio, hence the looser absolute tolerance)
    np.testing.assert_allclose(ident.contact_area_mm2, a, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(ident.volume_change_mm3, dv, rtol=1e-8, atol=1e-7)
    # prediction at another setup equals the lumped model run directly on the known curves
    pred = predict(ident, pressure_kPa=10.0, reservoir_mm3=40000.0 - vr, bladder_volume_mm3=VB,
                   elastic_force_N=fel)
    ref = lumped_curve(y, a, dv, Setup(10.0, VB, 40000.0 - vr), elastic_force_N=fel)
    np.testing.assert_allclose(pred.force_N, ref.force_N, rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(pred.pressure_kPa, ref.pressure_kPa, rtol=1e-8, atol=1e-9)


def test_round_trip_on_a_membrane_curve(tmp_path):
    """A bench made by the membrane model: identification returns its A(y) and ΔV(y) when
    V_b,i is the inflated volume (eq. 40 assumes the volume at rest)."""
    r = solve(preset("D"), material("tpu60a"), pressure_kPa=40.0, stroke_mm=6.0, points=13)
    c = r.curve
    f = _write(tmp_path / "m.csv", c.y_mm, c.force_N, c.pressure_kPa)
    ident = identify(read_bench(f), pressure_kPa=40.0, bladder_volume_mm3=c.inflated_volume_mm3)
    np.testing.assert_allclose(ident.contact_area_mm2, c.contact_area_mm2, rtol=1e-9, atol=1e-9)
    # ΔV from a pressure ratio solved to 1e-9: ~1e-9 × V ≈ 1e-5 mm³
    np.testing.assert_allclose(ident.volume_change_mm3, c.volume_change_mm3, rtol=1e-6, atol=1e-4)


def test_cli_identify_writes_predictions(tmp_path, capsys):
    y, a, dv, fel = _known()
    bench = lumped_curve(y, a, dv, Setup(40.0, VB, 0.0))
    f = _write(tmp_path / "b.csv", y, bench.force_N, bench.pressure_kPa)
    out = tmp_path / "id.json"
    rc = main(["identify", str(f), "--pressure", "40", "--bladder-volume", str(VB),
               "--predict-pressures", "10,40", "--json", str(out)])
    assert rc == 0
    import json
    d = json.loads(out.read_text(encoding="utf-8"))
    assert len(d["extra"]["predictions"]) == 4  # 2 pressures × 2 reservoirs
    ident = Curve.from_json(out)  # a Curve JSON (docs/design.md), predictions in "extra"
    assert ident.model == "identified"
    np.testing.assert_allclose(ident.contact_area_mm2, a, rtol=1e-9, atol=1e-9)
    hi40 = d["extra"]["predictions"][1]
    np.testing.assert_allclose(hi40["curve"]["force_N"], bench.force_N, rtol=1e-9, atol=1e-12)
    rc = main(["identify", str(f), "--pressure", "40", "--type", "D"])  # V_b,i of Table 1 type D
    assert rc == 0 and "6505.2 mm³" in capsys.readouterr().out


@pytest.mark.parametrize("header, rows, needle", [
    (["y_mm", "force_N"], None, "missing column = 'pressure_kPa'"),
    (["y_mm", "force_N", "pressure_Pa"], None, "column pressure_Pa"),
    (["y_m", "force_N", "pressure_kPa"], None, "column y_m"),
    (None, "nonmono", "y must increase"),
    (None, "absolute", "check the units"),
    (None, "text", "a number"),
])
def test_malformed_bench_files_are_one_line_errors(tmp_path, capsys, header, rows, needle):
    y, a, dv, _ = _known()
    c = lumped_curve(y, a, dv, Setup(40.0, VB))
    f, p = c.force_N.copy(), c.pressure_kPa.copy()
    yy = y.copy()
    if rows == "nonmono":
        yy[5] = yy[3]
    if rows == "absolute":
        p = p + 101.325
    path = tmp_path / "bad.csv"
    if header is not None:
        n = len(header)
        body = "\n".join(",".join(str(v) for v in (yy[i], f[i], p[i])[:n]) for i in range(len(y)))
        path.write_text(",".join(header) + "\n" + body + "\n", encoding="utf-8")
    else:
        _write(path, yy, f, p)
        if rows == "text":
            text = path.read_text(encoding="utf-8")
            path.write_text(text.replace(repr(float(f[3])), "12,5x", 1).replace("12,5x", "12.5x"),
                            encoding="utf-8")
    with pytest.raises(ParameterError) as e:
        identify(read_bench(path), pressure_kPa=40.0, bladder_volume_mm3=VB)
    assert needle in str(e.value) and "\n" not in str(e.value)
    rc = main(["identify", str(path), "--pressure", "40", "--bladder-volume", str(VB)])
    err = capsys.readouterr().err
    assert rc == 2 and err.count("\n") == 1 and err.startswith("spsc identify: error:")


def test_missing_file_and_missing_volume(tmp_path, capsys):
    assert main(["identify", str(tmp_path / "none.csv"), "--pressure", "40", "--type", "B"]) == 2
    assert "no such file" in capsys.readouterr().err
    f = tmp_path / "x.csv"
    f.write_text("y_mm,force_N,pressure_kPa\n0,0,40\n1,1,41\n2,2,42\n", encoding="utf-8")
    assert main(["identify", str(f), "--pressure", "40"]) == 2
    assert "bladder volume" in capsys.readouterr().err
