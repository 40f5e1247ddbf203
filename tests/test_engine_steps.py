"""A step carries its own path: a new kind of step is one class (``increments``, ``begin``,
``path``) that the engine walks without knowing it. Here a toy ``Lift`` raises the plate after
a press; the elastic, frictionless dome retraces its press, so the lift's records must equal
the press's at the same plate heights (up to Newton's tolerance)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.fem.engine import solve
from spsc.fem.engine.steps import CloseValve, Inflate, Load, Path, Press
from spsc.fem.wall.model import WallModel
from spsc.materials import material


@dataclass(frozen=True)
class Lift:
    """Raise the plate by ``rise`` (mm) in ``increments`` recorded points."""

    rise: float
    increments: int = 4

    def begin(self, load, volume):
        return load

    def path(self, load, contact_height, settings):
        z = load.plate
        targets = [(i + 1) / self.increments for i in range(self.increments)]
        return Path(lambda t: Load(load.pressure, load.gas, z + t * self.rise), "press",
                    targets, lambda t: -t * self.rise)


def test_a_toy_step_walks_through_the_engine_and_retraces_the_press():
    model = WallModel(preset("B", l=0.0), material("tpu60a"))
    steps = [Inflate(0.04, 4), CloseValve(0.0), Press(2.0, 4), Lift(2.0, 4)]
    res = solve(model, steps)
    assert res.converged, res.message
    press = [r for r in res.records if r.step == 2]
    lift = [r for r in res.records if r.step == 3]
    assert len(press) == 4 and len(lift) == 4
    # the lift passes the press's plate heights in reverse: y = 1.5, 1.0, 0.5, 0 mm
    for down, up in zip(press[-2::-1], lift[:-1]):
        assert_allclose(up.plate, down.plate, rtol=0, atol=1e-12)
        # Newton's tolerance on the force (rtol 1e-8 of ~10 N) and history-free elasticity
        assert_allclose(up.force, down.force, rtol=1e-5, atol=1e-6)
        assert_allclose(up.pressure, down.pressure, rtol=1e-7)
    assert lift[-1].force < 1e-3 * press[-1].force  # back at first contact: no force
    assert np.isfinite([r.volume for r in lift]).all()
