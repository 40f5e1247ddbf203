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


@pytest.mark.slow
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


def test_the_motor_fits_and_is_held_without_play():
    """The motor fills the pocket's height exactly: in place it cuts nothing; lifted 0.05 mm its
    whole top face goes into the flat ceiling (π r² × 0.05), lowered 0.05 mm its rim goes into
    the ledge (π (r² − r_seat²) × 0.05); sideways it has the ring's clearance."""
    import math

    h = _haptic()
    motor = _motor(h)
    r, r_seat = FIT0774.diameter / 2, FIT0774.diameter / 2 - HapticSpec().ledge
    assert (motor ^ h.solid).volume() < 1e-6
    assert h.motor_z[1] - h.motor_z[0] == pytest.approx(FIT0774.height, abs=1e-12)
    up = (motor.translate([0, 0, 0.05]) ^ h.solid).volume()
    down = (motor.translate([0, 0, -0.05]) ^ h.solid).volume()
    # the 256-gon motor's area is 0.01 % short of the circle's; the ledge's hole is the mesh
    # kernel's coarser polygon, whose area is a few 0.1 % short of its circle's (measured:
    # the annulus 0.12 % large)
    assert_allclose(up, math.pi * r**2 * 0.05, rtol=1e-3)
    assert_allclose(down, math.pi * (r**2 - r_seat**2) * 0.05, rtol=3e-3)
    assert (motor.translate([HapticSpec().clearance - 0.02, 0, 0]) ^ h.solid).volume() < 1e-6
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


@pytest.mark.slow
@pytest.mark.long
def test_the_motor_stiffens_the_first_millimetre(tmp_path):
    """The haptic chamber in the part FEM (coarse, 2 mm), pressed 2 mm at the apex, with the
    pocket empty and with the motor: the motor carries force from the first points on, makes the
    first millimetre stiffer (measured at 1.2 mm: +27 % at y = 1 mm, +51 % over the first mm) and
    the plate force still equals the mount's reaction (the motor's push on ceiling and ledge is
    an internal pair). About 3 min."""
    import json

    import numpy as np

    from spsc.cad.export import write_stl
    from spsc.fem.solid.model import Load
    from spsc.fem.part.run import part_run, part_curve, part_model
    from spsc.fem.engine import Settings, solve
    from spsc.materials import material

    h = _haptic()
    stl = write_stl(manifold_mesh(h.solid), tmp_path / "haptic.stl")
    design = json.loads(json.dumps(h.design))
    curves = {}
    for motor in (False, True):
        run = part_run(str(stl), material("tpu60a"), "z<=0", plate_at=(0.0, 0.0, 14.0),
                      pressure_kPa=40.0, stroke_mm=2.0, points=5, mesh_size_mm=2.0,
                      design=design, motor=motor)
        model, _, surface = part_model(run, cache_dir=tmp_path)
        res = solve(model, run.steps(), settings=Settings())
        assert res.converged, res.message
        curves[motor] = part_curve(run, model, res, surface)
    last = res.records[-1]
    r = model.evaluate(last.x, Load(pressure=last.pressure), tangent=False).r
    fixed_z = model.fixed[: model.disc.n_u].reshape(-1, 3)[:, 2]
    assert_allclose(last.force, r[: model.disc.n_u].reshape(-1, 3)[fixed_z, 2].sum(), rtol=1e-5)
    held = curves[True].series["force_motor_N"]
    assert held[2] > 1.0 and np.all(held <= curves[True].force_N + 1e-9)
    # y = 1 mm: +27 % at 1.2 mm; a coarser mesh is stiffer in both, so ask for half of it
    assert curves[True].force_N[2] > 1.13 * curves[False].force_N[2]


def test_the_haptic_study_reuses_a_curve_only_while_command_part_and_code_are_the_same(
        tmp_path, monkeypatch):
    """``spsc haptic``'s curves (each a ``spsc fem --part`` run of minutes) are kept with the
    key of what computed them: computed once, read back, computed again when the part file
    changes."""
    from spsc.core.curve import Curve
    from spsc.studies import haptic

    stl = tmp_path / "parts" / "bladder-D" / "bladder-D.stl"
    stl.parent.mkdir(parents=True)
    stl.write_bytes(b"solid a\nendsolid a\n")
    runs = []

    def fake_spsc(*argv):
        runs.append(argv)
        y = [0.0, 0.5, 1.0]
        Curve(y, [0.0, 1.0, 2.0], [40.0, 41.0, 42.0], [0.0, 1.0, 2.0], [0.0, 1.0, 2.0],
              model="fem").to_json(argv[argv.index("--json") + 1])
        return 0

    monkeypatch.setattr(haptic, "_spsc", fake_spsc)
    out = tmp_path / "out"
    out.mkdir()
    first = haptic._case(out, tmp_path / "parts", "plain", "bladder-D", (), 1.2)
    again = haptic._case(out, tmp_path / "parts", "plain", "bladder-D", (), 1.2)
    assert len(runs) == 1 and again.force_N.tolist() == first.force_N.tolist()
    haptic._case(out, tmp_path / "parts", "plain", "bladder-D", (), 1.0)  # another mesh
    assert len(runs) == 2
    stl.write_bytes(b"solid b\nendsolid b\n")  # another part
    haptic._case(out, tmp_path / "parts", "plain", "bladder-D", (), 1.0)
    assert len(runs) == 3
