"""Slow FEM cases (``make test-slow`` (and ``make test-all``)): mesh independence, pytetwild against the structured
mesh, the open chamber's instability report."""

import numpy as np
import pytest

from spsc.cad.geometry import preset
from spsc.fem.solid.mesh import spsc_wall
from spsc.fem.solid.tetwild import spsc_wall_tetwild
from spsc.fem.solid.model import FEMModel
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.fem.engine import Inflate, solve
from spsc.materials import material

pytestmark = pytest.mark.slow
MAT = material("tpu60a")


def test_structured_and_tetwild_meshes_inflate_alike():
    """Same chamber, two independent meshes (swept P2 with curved edges; pytetwild, straight
    P2): the inflation volume change at 40 kPa agrees. Measured 8.629 % vs 8.614 % (0.2 %)."""
    g = preset("B")
    changes = []
    for mesh in (spsc_wall_tetwild(g, 2.0, epsilon=1e-3), spsc_wall(g, 1.0, layers=2)):
        res = solve(FEMModel.build(mesh, MAT), [Inflate(0.04, 4)])
        assert res.converged, res.message
        changes.append(res.records[-1].volume / res.records[0].volume - 1)
    np.testing.assert_allclose(changes[0], changes[1], rtol=1e-2)


def test_halving_the_mesh_changes_the_force_by_less_than_2_percent(tmp_path):
    """The issue's criterion on Type B, 40 kPa, high stiffness (stroke shortened to 2 mm to keep
    the test minutes long; bench/bench_fem.py runs the full 4 mm). Measured 0.9 % at 4 mm."""
    forces = []
    for size, layers in ((2.0, 1), (1.0, 2)):
        run = chamber_run(preset("B"), MAT, pressure_kPa=40.0, stroke_mm=2.0, points=5,
                         mesh_size_mm=size, layers=layers)
        curve, result, _ = run_chamber(run, cache_dir=tmp_path)
        assert result.converged, result.message
        forces.append(curve.force_N[1:])
    np.testing.assert_allclose(forces[0], forces[1], rtol=2e-2)


def test_open_chamber_softening_is_reported(tmp_path):
    """Type B open to the atmosphere: the dome inverts under the plate (the paper's central
    nearly-zero-slope phase); the run says so instead of passing it off silently."""
    run = chamber_run(preset("B"), MAT, pressure_kPa=0.0, stroke_mm=6.0, points=13,
                     mesh_size_mm=2.0, layers=1)
    curve, result, _ = run_chamber(run, cache_dir=tmp_path)
    assert result.instability, result.message
    assert "negative" in result.instability or "snap" in result.instability
    assert curve.setup["instability"] == result.instability
