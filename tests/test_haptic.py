"""The haptic chamber (issue 15): Type D with a FIT0774 motor pocket on a 0.8 mm support film,
a sealed wire exit, printed in one piece with a pause; its gate and its geometry."""

from functools import lru_cache

import manifold3d as m3
import pytest
from numpy.testing import assert_allclose

from spsc.cad.check import check_mesh
from spsc.cad.geometry import preset
from spsc.cad.haptic import FIT0774, HapticSpec, build_haptic
from spsc.cad.meshbuild import manifold_mesh
from spsc.cad.specs import BladderSpec
from spsc.core.errors import ParameterError

D = BladderSpec(preset("D"))


@lru_cache(maxsize=None)
def _haptic(windows=4):
    return build_haptic(D, HapticSpec(windows=windows))


def _motor(h):
    z0, z1 = h.motor_z
    return m3.Manifold.cylinder(z1 - z0, FIT0774.diameter / 2, FIT0774.diameter / 2,
                                256).translate([0.0, 0.0, z0])


def test_haptic_chamber_passes_the_gate():
    h = _haptic()
    m = manifold_mesh(h.solid)
    rep = check_mesh((m.vertices, m.faces), design=h.design, process="fdm")
    assert rep.passed, rep.summary()
    # one cavity: the film's windows and the ledge's hole join every part of it
    assert rep["cavity_count"].value == 1
    # the support film is inside the cavity: the cavity is the analytic one less the film
    assert_allclose(rep["cavity_volume"].value, h.design["cavity_volume_mm3"], rtol=2e-3)
    assert h.design["support_volume_mm3"] > 100.0


def test_the_wire_exit_opens_the_cavity_until_sealed():
    h = _haptic()
    m = manifold_mesh(h.solid)
    inlet_only = dict(h.design, port=h.design["port"][0])
    rep = check_mesh((m.vertices, m.faces), design=inlet_only, process="fdm")
    assert rep["cavity_count"].passed is False


def test_windows_are_handles():
    # each window but the first is a handle of the surface: the genus follows the design
    h = _haptic(windows=2)
    assert h.solid.genus() == h.design["genus"] == 4 + 1 + 2
    assert _haptic().solid.genus() == 9


def test_the_motor_fits_and_touches_the_top():
    h = _haptic()
    motor = _motor(h)
    # in the pocket without cutting the part, its top rim within the clearance of the dome
    assert (motor ^ h.solid).volume() < 1e-6
    assert motor.min_gap(h.solid, 1.0) <= HapticSpec().clearance + 0.05
    # it goes in from above at the pause: the dome's opening there is the pocket's width
    g = D.geometry
    assert g.radius_at(h.design["print"]["pause_at_mm"]) >= FIT0774.diameter / 2
    assert h.design["print"]["pause_at_mm"] == pytest.approx(h.motor_z[1])


def test_brep_matches_mesh():
    b = build_haptic(D, kernel="brep")
    assert b.solid.isValid()
    assert_allclose(b.solid.Volume(), _haptic().solid.volume(), rtol=2e-3)


@pytest.mark.parametrize("kw,name", [({"film": 0.1}, "haptic.film"),
                                     ({"wire": 5.0}, "haptic.wire"),
                                     ({"windows": -1}, "haptic.windows")])
def test_bad_haptic_parameters(kw, name):
    with pytest.raises(ParameterError, match=f"^{name} = "):
        HapticSpec(**kw)


def test_a_chamber_too_narrow_for_the_motor():
    with pytest.raises(ParameterError, match="^haptic = .* for the FIT0774"):
        build_haptic(BladderSpec(preset("B", w=4.0, h=5.0)))
