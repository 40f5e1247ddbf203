"""The paper's puncture test in the wall model (``spsc puncture``,
:mod:`spsc.fem.wall.puncture`): the failure criterion read from the catalogue or a material
file, the failure force read where the stretch first reaches it, the command's refusals; and
(slow) the probe through the Type B dome onto its base."""

from __future__ import annotations

import json

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cli.main import main
from spsc.core.errors import ParameterError
from spsc.fem.wall.puncture import MESHES, Puncture
from spsc.materials.catalogue import CATALOGUE, failure
from spsc.materials.failure import Failure


def _walk(stretch, force):
    n = len(stretch)
    y = np.arange(1.0, n + 1.0)
    z = np.zeros(n)
    return Puncture("m", MESHES[0], "stick", y, np.asarray(force, float), z, z,
                    np.asarray(stretch, float), z, n + 1.0, True, "converged", 0.0)


def test_the_failure_force_is_read_where_the_stretch_first_reaches_the_criterion():
    """λ_b = 1 + ε_b/100 = 2.6 (eq. B1), between λ 2 and 3 at 2 and 4 N: 3.2 N, travel 2.6."""
    w = _walk([1.5, 2.0, 3.0, 3.5], [1.0, 2.0, 4.0, 5.0])
    f = w.failure(Failure(160.0))
    assert f["reached"]
    assert_allclose([f["force_N"], f["travel_mm"]], [3.2, 2.6], rtol=1e-12)
    below = w.failure(Failure(950.0))  # λ_b 10.5 never reached: a lower bound
    assert not below["reached"] and below["force_N"] == 5.0 and below["stretch"] == 3.5


def test_the_catalogue_cites_its_criteria_and_says_where_it_has_none():
    for name in CATALOGUE:
        c, source = failure(name)
        if c is None:
            assert "no datasheet" in source and "failure entry" in source
        else:
            assert "datasheet" in source or "manufacturer" in source
    assert failure("tpu60a")[0].stretch == pytest.approx(10.5)
    assert failure("elastic50a")[0].stretch == pytest.approx(2.6)


def _material_file(path, entry):
    record = {"schema": "spsc.material", "schema_version": 1, "name": "my-tpu",
              "law": "neo-hookean", "constants": {"C10": 5.0 / 6.0}}
    if entry is not None:
        record["failure"] = entry
    path.write_text(json.dumps(record))
    return str(path)


def test_a_material_file_carries_its_own_criterion(tmp_path):
    own = _material_file(tmp_path / "own.json", {"elongation_pct": 400, "strength_MPa": 8,
                                                 "source": "my test"})
    c, source = failure(own)
    assert (c.elongation_pct, c.strength_MPa, source) == (400.0, 8.0, "my test")
    none = failure(_material_file(tmp_path / "none.json", None))
    assert none[0] is None and "no failure entry" in none[1]
    for bad, key in (({"strength_MPa": 8}, "failure"), ({"elongation_pct": -5},
                     "failure.elongation_pct"), ({"elongation_pct": 300, "x": 1}, "failure.x")):
        with pytest.raises(ParameterError, match=key) as err:
            failure(_material_file(tmp_path / f"bad{len(key)}.json", bad))
        assert "\n" not in str(err.value)


@pytest.mark.parametrize("argv, name", [
    (["--l", "3"], "l"), (["--mesh", "huge"], "mesh"), (["--friction", "0.3"], "friction"),
    (["--elongation-at-break", "-5"], "elongation"), (["--probe", "plate"], "probe"),
    (["--pressure", "-1"], "pressure"), (["--json", "out.txt"], "--json")])
def test_bad_input_is_refused_in_one_line(argv, name, capsys):
    assert main(["puncture", "--quiet"] + argv) == 2
    err = capsys.readouterr().err.strip()
    assert name in err and "\n" not in err


@pytest.mark.slow
def test_the_probe_presses_the_dome_flat_and_pinches_it_on_the_base(tmp_path, capsys):
    """TPU 60A on the coarse mesh: the walk reaches a micrometre above the base; the
    largest stretch is under the tip (on the axis) and grows with the travel; the base
    pushes only once the membrane is pinched; the 950 % criterion is not reached (the
    force, about 17 N, is a lower bound). With --elongation-at-break 160 the same walk
    breaks in its first millimetres, below 1 N."""
    out = tmp_path / "p.json"
    assert main(["puncture", "--quiet", "--json", str(out)]) == 0
    run = json.loads(out.read_text())["runs"][0]
    pts = run["points"]
    assert run["converged"] and run["clearance_mm"] - pts[-1]["travel_mm"] < 2e-3
    lam = np.array([p["stretch"] for p in pts])
    assert np.all(np.diff(lam) > -1e-3 * lam[1:])  # no fall beyond round-off
    assert all(p["radius_mm"] < 0.05 for p in pts[4:])
    floor = np.array([p["floor_N"] for p in pts])
    assert floor[-1] > 1.0 and np.all(floor[[p["travel_mm"] < 14.0 for p in pts]] == 0)
    assert not run["failure"]["reached"] and 14 < run["failure"]["force_N"] < 25
    out2 = tmp_path / "q.json"
    assert main(["puncture", "--quiet", "--elongation-at-break", "160", "--json",
                 str(out2)]) == 0
    f = json.loads(out2.read_text())["runs"][0]["failure"]
    assert f["reached"] and f["force_N"] < 1.0 and f["travel_mm"] < 2.0
