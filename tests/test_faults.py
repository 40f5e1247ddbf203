"""Faults keep what was computed: a failed membrane inflation returns and writes the states its
pressure continuation reached; a membrane model asked to press a vented chamber says, in one
line, that a membrane carries no force without pressure and names the models that do."""

import json

import numpy as np
import pytest

from spsc.cad.geometry import preset
from spsc.core.errors import ParameterError
from spsc.membrane.simplified import simplified_curve
from spsc.membrane.solver import solve
from spsc.cli.main import main


def test_failed_inflation_keeps_the_states_it_reached():
    """Type D at 500 kPa: the continuation stops below the setup pressure (measured 195 kPa);
    the result carries every converged pressure with its volume and apex, and the last shape."""
    g = preset("D")
    r = solve(g, "tpu60a", pressure_kPa=500.0, stroke_mm=2.0, points=3)
    info = r.curve.solver
    assert not info.converged and "continuation reached" in info.message
    path = info.details["inflation_path"]
    p = np.array([s["pressure_kPa"] for s in path])
    v = np.array([s["volume_mm3"] for s in path])
    assert len(path) >= 2 and np.all(np.diff(p) > 0) and 0 < p[-1] < 500.0
    assert np.all(np.diff(v) > 0) and v[0] > g.cavity_volume()  # inflating: volume grows
    assert r.inflated is not None and r.inflated.pressure_kPa == pytest.approx(p[-1], rel=1e-9)
    assert r.curve.inflated_volume_mm3 == pytest.approx(v[-1], rel=1e-6)
    assert r.shapes[0] is r.inflated


def test_failed_inflation_is_written(tmp_path, capsys):
    out = tmp_path / "d500.json"
    assert main(["membrane", "--type", "D", "--pressure", "500", "--quiet", "--meridians",
                 "--json", str(out)]) == 1
    assert "not converged" in capsys.readouterr().err
    data = json.loads(out.read_text(encoding="utf-8"))
    assert data["solver"]["details"]["inflation_path"]
    assert data["inflated_volume_mm3"] > 0
    assert data["extra"]["meridians_mm"][0] is not None  # the shape reached, in the JSON


@pytest.mark.parametrize("model", [solve, simplified_curve])
def test_membrane_models_refuse_a_vented_chamber_naming_the_wall_model(model):
    kwargs = {"material": "tpu60a"} if model is solve else {}
    g = preset("B")
    with pytest.raises(ParameterError, match=r"^pressure = 0.0 is invalid: .*no force without "
                       r"pressure.*--model wall --pressure 0"):
        model(g, pressure_kPa=0.0, stroke_mm=2.0, points=3, **kwargs)
    # inflation only (stroke 0) at zero pressure is the nominal shape, not a fault
    r = solve(g, "tpu60a", pressure_kPa=0.0, stroke_mm=0.0, points=1)
    assert r.curve.solver.converged
    np.testing.assert_allclose(r.curve.inflated_volume_mm3, g.cavity_volume(), rtol=1e-3)
