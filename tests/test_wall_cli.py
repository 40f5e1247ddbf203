"""`spsc curve --model wall` and the membrane's `--wrinkling` option."""

import numpy as np

from spsc.core.curve import Curve


def test_spsc_curve_model_wall_writes_the_curve_json(tmp_path):
    from spsc.cli.main import main

    out = tmp_path / "w.json"
    rc = main(["curve", "--model", "wall", "--type", "C", "--l", "0", "--mesh-size", "1",
               "--stroke", "1", "--points", "3", "--quiet", "--json", str(out)])
    assert rc == 0
    c = Curve.from_json(out)
    assert c.model == "wall" and c.solver.converged and c.solver.details["mesh_size_mm"] == 1.0
    assert c.force_N[-1] > c.force_N[1] > 0 and c.pressure_kPa[-1] > 40


def test_the_membrane_taut_law_is_an_option(tmp_path):
    from spsc.cli.main import main

    paths = {}
    for wr in ("on", "off"):
        paths[wr] = tmp_path / f"{wr}.json"
        assert main(["curve", "--model", "membrane", "--type", "B", "--l", "0", "--wrinkling",
                     wr, "--stroke", "4", "--points", "9", "--json", str(paths[wr])]) == 0
    on, off = (Curve.from_json(paths[k]) for k in ("on", "off"))
    assert on.solver.details["wrinkling"] and not off.solver.details["wrinkling"]
    # B's cap goes into hoop compression late in the stroke: the laws part there (measured
    # 6.9 vs 6.6 N at 3 mm), and agree while the membrane is taut (y = 1 mm)
    np.testing.assert_allclose(on.force_N[2], off.force_N[2], rtol=1e-6)
    assert abs(on.force_N[-1] / off.force_N[-1] - 1) > 0.02
