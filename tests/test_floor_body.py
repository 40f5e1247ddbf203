"""A new body is one class and one line in the engine's registry: the base under the cavity
(:class:`spsc.fem.engine.bodies.Floor`), which the paper's puncture probe presses the dome's
membrane onto (sec. 3.2). The dome at 50 kPa with its 40 cm³ reservoir, the probe's cone
(half-angle 30°, tip radius 0.05 mm) lowered 14.38 mm: with the floor the cavity wall stays
on or above the base and the base pushes back; without it the wall passes through the base.
A coarse mesh (0.5 mm, two layers): these are the body's checks, not the puncture's
convergence."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.core.errors import ParameterError
from spsc.core.indenter import parse_indenter
from spsc.fem.engine import CloseValve, Inflate, Load, Press, solve
from spsc.fem.engine.bodies import BODIES, Floor
from spsc.fem.wall.model import WallModel, WallSettings
from spsc.materials import material

CONE = parse_indenter("cone:angle=60,r=0.05")
TRAVEL = (6.0, 12.0, 14.0, 14.3, 14.38)


def _pressed(floor: bool):
    m = WallModel(preset("B", l=0.0), material("tpu60a"),
                  WallSettings(mesh_size_mm=0.5, layers=2), floor=floor)
    res = solve(m, [Inflate(0.05, 4), CloseValve(40000.0), Press.through(TRAVEL, indenter=CONE)])
    assert res.converged, res.message
    return m, res


@pytest.fixture(scope="module")
def with_floor():
    return _pressed(True)


def _cavity_z(m, rec) -> np.ndarray:
    sec = m.part.section
    return sec.positions(rec.x[:m.n_u])[sec.cavity, 1]


def test_the_floor_is_one_class_in_the_registry():
    assert Floor in BODIES


def test_the_cavity_wall_stays_on_or_above_the_base(with_floor):
    m, res = with_floor
    for rec in res.records:
        assert _cavity_z(m, rec).min() >= -1e-9, rec.plate


def test_without_the_floor_the_wall_passes_through_the_base():
    m, res = _pressed(False)
    assert _cavity_z(m, res.records[-1]).min() < -0.05  # 0.073 mm below it
    assert "floor" not in res.records[-1].bodies


def test_the_base_pushes_back_once_the_membrane_is_pinched(with_floor):
    """No push before the inner apex reaches the base (travel 14 mm: 0.33 mm above it), a
    push at the last point, every active unknown's reaction pushing (r ≥ 0, up)."""
    m, res = with_floor
    pressed = [r for r in res.records if r.kind == "press"]
    assert pressed[2].bodies["floor"] == 0.0
    last = pressed[-1]
    assert last.bodies["floor"] > 1.0  # 2.55 N
    r = m.evaluate(last.x, Load(pressure=last.pressure)).r
    on = m.floor.dofs[np.abs(m.floor.height[m.floor.dofs] + last.x[m.floor.dofs]) < 1e-12]
    assert on.size and np.all(r[on] >= -1e-9 * r[on].max())


def test_vertical_equilibrium_plate_equals_base_plus_clamp(with_floor):
    """The wall's internal forces and the gas's follower load are self-equilibrated in z
    (Σ r_z = 0 over every unknown), so the probe's force is carried by the base and the
    clamped edge: F_probe = F_floor + R_clamp (to round-off; a floor force of the wrong sign
    or on the wrong unknowns breaks it by newtons)."""
    m, res = with_floor
    last = res.records[-1]
    r = m.evaluate(last.x, Load(pressure=last.pressure)).r
    z = np.arange(1, m.n_u, 2)
    clamp = r[z[m.fixed[z]]].sum()
    assert_allclose(last.force, last.bodies["floor"] + clamp, rtol=1e-9)


def test_a_floor_on_the_stadium_is_refused_in_one_line():
    with pytest.raises(ParameterError, match="floor"):
        WallModel(preset("B"), material("tpu60a"), floor=True)
