"""A curved body that sticks (``--indenter sphere:R=10 --friction stick``,
:meth:`spsc.fem.engine.bodies.Plate.lean`): a node anchored where it touched is carried with
the body (the body only translates), so it keeps its place on the body's surface; the body
does no work but its force times its travel; a huge sphere that sticks is the sticking plate;
and sticking holds the wall from spreading, so it takes more force. The wall model's Type B
dome of TPU 60A at 40 kPa, pressed 2 mm."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import simpson

from spsc.cad.geometry import preset
from spsc.core.indenter import parse_indenter
from spsc.fem.engine import CloseValve, Inflate, Load, Press, solve
from spsc.fem.engine.active_set import heights
from spsc.fem.engine.friction import lateral
from spsc.fem.wall.model import WallModel
from spsc.materials import material

SPHERE = parse_indenter("sphere:R=10")
Y = np.linspace(0.0, 2.0, 17)


@pytest.fixture(scope="module")
def dome():
    return WallModel(dataclasses.replace(preset("B"), l=0.0), material("tpu60a"))


def _press(model, indenter, stick, pressure_kPa=40.0):
    steps = [Inflate(pressure_kPa * 1e-3, 4), CloseValve(0.0, 1.0)] if pressure_kPa else []
    res = solve(model, steps + [Press.through(Y[1:], stick=stick, indenter=indenter)])
    assert res.converged, res.message
    return res.of("press")


@pytest.fixture(scope="module")
def pressed(dome):
    return {(body, stick): _press(dome, ind, stick) for body, ind in
            (("sphere", SPHERE), ("plate", None), ("huge", parse_indenter("sphere:R=1e4")))
            for stick in (False, True)}


def _on_body(model, rec, indenter):
    dofs = model.surface.dofs
    return dofs[np.abs(heights(model, rec.x, dofs, indenter) - rec.plate) < 1e-9]


def test_a_stuck_node_is_carried_with_the_body(dome, pressed):
    """Between two records every node on the sphere at both (and anchored at the first)
    keeps its radial displacement to round-off and moves down exactly as the sphere does."""
    recs = pressed["sphere", True]
    checked = 0
    for a, b in zip(recs, recs[1:]):
        both = np.intersect1d(_on_body(dome, a, SPHERE), _on_body(dome, b, SPHERE))
        lat = lateral(dome, both)[0]
        free = lat >= 0
        if not np.any(free):
            continue
        assert np.max(np.abs(b.x[lat[free]] - a.x[lat[free]])) < 1e-12
        assert_allclose(b.x[both] - a.x[both], b.plate - a.plate, atol=1e-9)
        checked += free.sum()
    assert checked > 20
    assert all(r.shear > 0 for r in recs[1:])
    assert all(r.shear == 0.0 for r in pressed["sphere", False])


def test_frictionless_nodes_slide_on_the_sphere(dome, pressed):
    recs = pressed["sphere", False]
    slid = 0.0
    for a, b in zip(recs, recs[1:]):
        both = np.intersect1d(_on_body(dome, a, SPHERE), _on_body(dome, b, SPHERE))
        lat = lateral(dome, both)[0]
        lat = lat[lat >= 0]
        slid = max(slid, np.max(np.abs(b.x[lat] - a.x[lat]), initial=0.0))
    assert slid > 1e-3  # mm: the contact patch spreads on the frictionless sphere


def test_a_sticking_sphere_is_stiffer(pressed):
    """Held from spreading on the sphere, the wall takes more force past the first point
    (measured +1.0 % at 0.125 mm to +3.1 % at 2 mm)."""
    free = np.array([r.force for r in pressed["sphere", False]])
    held = np.array([r.force for r in pressed["sphere", True]])
    assert np.all(held[1:] > free[1:] * 1.005)


def test_a_huge_sticking_sphere_is_the_sticking_plate(pressed):
    """R = 1e4 mm against the plate, both sticking: within 0.5 % from y = 1 mm (the sphere's
    sag a²/2R ≈ 1e-3 mm over a 5 mm contact; measured within 0.06 %, the shear within 0.12 %)."""
    for a, b in zip(pressed["plate", True][7:], pressed["huge", True][7:]):
        assert_allclose(b.force, a.force, rtol=5e-3)
        assert_allclose(b.shear, a.shear, rtol=2e-2)


def test_the_sticking_sphere_s_work_is_the_wall_s_stored_energy(dome):
    """Vented dome: a stuck node moves with the sphere, so the sphere's force does work
    only through its travel: ∫F dy equals the stored energy's rise. Simpson on 16
    increments (measured 2e-4; a stuck node sliding would break it)."""
    recs = _press(dome, SPHERE, True, pressure_kPa=0.0)
    F = np.array([0.0] + [r.force for r in recs])
    stored = dome.potential(recs[-1].x, Load()) - dome.potential(dome.zero_state(), Load())
    assert_allclose(simpson(F, x=Y), stored, rtol=2e-3)
