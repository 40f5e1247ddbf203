"""The squeeze cycle's hot spot by two discretisations (issue 51): the wall model (Q2 section,
recovered surface) against the 3D FEM (P2 tetrahedra of the quarter chamber) on Table 1's
Type B at the paper's fatigue test (50 kPa, 40 cm³, 6 mm): the peaks within 10 %, at the
same place."""

from __future__ import annotations

import math

import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.fem.solid.fields import cycle_fields
from spsc.fem.wall.durability import squeeze_cycle
from spsc.materials import material

pytestmark = pytest.mark.slow


def test_the_wall_and_the_3d_fem_find_the_same_hot_spot():
    g, mat = preset("B"), material("tpu60a")
    run = chamber_run(g, mat, pressure_kPa=50, reservoir_mm3=40000, stroke_mm=6, points=13)
    _, res, model = run_chamber(run)
    assert res.converged, res.message
    rest = [r for r in res.records if r.kind != "press"][-1]
    fem = cycle_fields(model, [rest.x] + [r.x for r in res.records if r.kind == "press"], g)
    wall = squeeze_cycle(g, mat).fields
    for name, rtol in (("stretch_max", 0.01), ("energy_amplitude", 0.10),
                       ("energy_max", 0.10), ("stretch_amplitude", 0.10)):
        a, b = fem.peak(name), wall.peak(name)
        # measured on the default meshes: -0.4 %, -7.4 %, -6.7 %, +1.0 % (the FEM's energy
        # rises toward the wall's under refinement: -4.4 % at 0.5 mm, 3 layers)
        assert_allclose(a["value"], b["value"], rtol=rtol, err_msg=name)
        assert a["face"] == b["face"], name
        assert math.hypot(a["height_mm"] - b["height_mm"], a["radius_mm"] - b["radius_mm"]) < 1.0
