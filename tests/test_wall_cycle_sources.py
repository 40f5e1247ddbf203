"""The squeeze-release cycle's sources of hysteresis, each switchable (issue 52): Coulomb
friction on the plate both ways (dissipates; mu -> infinity is the sticking plate, which is
elastic and retraces), and snap-throughs followed both ways (an elastic wall that snaps
dissipates the jump's energy)."""

from __future__ import annotations

import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.core.errors import ParameterError
from spsc.fem.wall.cycle import wall_cycle
from spsc.materials import material
from spsc.materials.catalogue import viscosity

MAT = material("tpu60a")
DOME_B = preset("B", l=0.0)


def _cycle(**kw):
    return wall_cycle(DOME_B, MAT, None, stroke_mm=3.0, points=7, **kw)


@pytest.mark.slow  # 7-10 s: make test-slow (make test stays under 3 min)
def test_coulomb_friction_dissipates_and_its_limits_do_not():
    plain, slip = _cycle(), _cycle(friction=0.3)
    stuck, grip = _cycle(friction="stick"), _cycle(friction=1e4)
    assert plain.complete and slip.complete and stuck.complete and grip.complete
    # measured 0.158 N and 0.205 mJ at mu = 0.3; the elastic cycles retrace (round-off)
    assert slip.hysteresis_N > 0.05 and slip.dissipated_mJ > 0.05
    for r in (plain, stuck, grip):
        assert abs(r.hysteresis_N) < 1e-3 and abs(r.dissipated_mJ) < 1e-3
    # mu -> infinity is the sticking plate, down to the solver's tolerance
    assert_allclose(grip.force_load_N, stuck.force_load_N, rtol=1e-6, atol=1e-8)
    assert _cycle(friction=0.0).hysteresis_N == plain.hysteresis_N  # mu = 0: frictionless


def test_snap_throughs_are_followed_both_ways_and_dissipate():
    g = preset("C", l=0.0)
    without = wall_cycle(g, MAT, None)
    snapping = wall_cycle(g, MAT, None, snaps=True)
    assert not without.complete  # the press stops where the wall snaps
    assert snapping.complete and snapping.jumps
    y, before, after, energy = snapping.jumps[0]
    assert 0 < y < 6.0 and after < before and energy > 0  # the force drops, energy released
    assert snapping.jump_energy_mJ == pytest.approx(sum(j[3] for j in snapping.jumps))


@pytest.mark.parametrize("kw", [{"prony": "tpu60a"}, {"friction": 0.3}])
def test_snaps_need_an_elastic_frictionless_wall(kw):
    prony = viscosity("tpu60a")[0] if kw.pop("prony", None) else None
    with pytest.raises(ParameterError, match="snaps"):
        wall_cycle(DOME_B, MAT, prony, snaps=True, **kw)
