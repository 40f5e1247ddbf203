"""A compliant object (``--object-stiffness K``, :mod:`spsc.fem.engine.spring`): the rigid
indenter on a linear spring whose far end follows the travel. The curve is the rigid one at
the indenter's own travel, F(y) = F_rigid(y − F/k)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.core.contact import check_object_stiffness
from spsc.core.errors import ParameterError
from spsc.fem.engine import CloseValve, Inflate, Press, solve
from spsc.fem.wall import wall_curve
from spsc.fem.wall.model import WallModel
from spsc.materials import material

DOME = dataclasses.replace(preset("B"), l=0.0)


@pytest.fixture(scope="module")
def soft():
    """The 40 kPa Type B dome pressed 3 mm through a 3 N/mm object."""
    return wall_curve(DOME, material("tpu60a"), pressure_kPa=40, stroke_mm=3, points=13,
                      object_stiffness=3.0)


def _rigid_at(travel):
    model = WallModel(DOME, material("tpu60a"))
    res = solve(model, [Inflate(0.04, 4), CloseValve(0.0, 1.0), Press.through(travel)])
    assert res.converged, res.message
    return np.array([r.force for r in res.of("press")])


def test_the_curve_is_the_rigid_one_at_the_indenter_s_travel(soft):
    """The identity of issue 27 to 1e-6 (measured 3e-11): the rigid chamber pressed to the
    indenter's travels gives the spring's forces; and the indenter stands where the spring
    balances them, y_p = y − F/k (to the balance's tolerance, 1e-7 of the force)."""
    assert soft.solver.converged, soft.solver.message
    yp = soft.series["indenter_travel_mm"]
    assert_allclose(yp, soft.y_mm - soft.force_N / 3.0, rtol=0, atol=1e-7)
    assert np.all(np.diff(yp) > 0) and yp[-1] < 0.6 * soft.y_mm[-1]
    assert_allclose(_rigid_at(yp[1:]), soft.force_N[1:], rtol=1e-6)
    assert soft.setup["object_stiffness_N_per_mm"] == 3.0


def test_a_stiff_object_is_the_rigid_plate_and_a_softer_one_gives_less_force(soft):
    """k = 1e6 N/mm moves the indenter by F/k ≈ 1e-5 mm: the rigid curve to 1e-4; softer
    objects give less force at every travel."""
    y = np.linspace(0.0, 3.0, 13)
    rigid = _rigid_at(y[1:])
    stiff = wall_curve(DOME, material("tpu60a"), pressure_kPa=40, stroke_mm=3, points=13,
                       object_stiffness=1e6)
    assert_allclose(stiff.force_N[1:], rigid, rtol=1e-4)
    mid = wall_curve(DOME, material("tpu60a"), pressure_kPa=40, stroke_mm=3, points=13,
                     object_stiffness=10.0)
    assert np.all(soft.force_N[1:] < mid.force_N[1:]) and np.all(mid.force_N[1:] < rigid)


def test_spsc_curve_object_stiffness_through_the_command_line(tmp_path, soft):
    from spsc.cli.main import main
    from spsc.core.curve import Curve

    out = tmp_path / "s.json"
    assert main(["curve", "--model", "wall", "--type", "B", "--l", "0", "--stroke", "3",
                 "--points", "13", "--object-stiffness", "3", "--quiet", "--json",
                 str(out)]) == 0
    c = Curve.from_json(out)
    assert_allclose(c.force_N, soft.force_N, rtol=1e-12)
    assert_allclose(c.series["indenter_travel_mm"], soft.series["indenter_travel_mm"],
                    rtol=1e-12)


@pytest.mark.parametrize("value", [0, -1, "soft", float("nan"), float("inf")])
def test_bad_object_stiffness_is_refused_in_one_line(value):
    with pytest.raises(ParameterError, match=r"^object_stiffness = .* allowed > 0 \(N/mm"):
        check_object_stiffness(value)
    with pytest.raises(ParameterError, match=r"^object_stiffness"):
        wall_curve(DOME, material("tpu60a"), points=3, stroke_mm=1, object_stiffness=value)


@pytest.mark.slow
def test_the_3d_fem_on_a_spring_is_its_rigid_curve_at_the_indenter_s_travel():
    """The same identity in the 3D FEM (Type B quarter, 1.5 mm mesh, one layer: the identity
    does not need a converged mesh), to 1e-6."""
    from spsc.fem.solid.chamber import build_model, chamber_run, run_chamber

    g, m = preset("B"), material("tpu60a")
    kw = dict(pressure_kPa=40, stroke_mm=1.5, points=4, mesh_size_mm=1.5, layers=1)
    curve, _, _ = run_chamber(chamber_run(g, m, object_stiffness=4.0, **kw))
    assert curve.solver.converged, curve.solver.message
    yp = curve.series["indenter_travel_mm"]
    assert_allclose(yp, curve.y_mm - curve.force_N / 4.0, rtol=0, atol=1e-7)
    model = build_model(chamber_run(g, m, **kw))
    rigid = solve(model, [Inflate(0.04, 4), CloseValve(0.0, 1.0), Press.through(yp[1:])])
    assert_allclose([r.force for r in rigid.of("press")], curve.force_N[1:], rtol=1e-6)
