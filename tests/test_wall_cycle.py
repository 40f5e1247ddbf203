"""The wall model in time with a Prony-series wall (Type B dome, vented, 0 → 6 mm → 0):

* the relaxed law retraces itself (no hysteresis without viscosity);
* τ → 0: the relaxed law at any speed; τ → ∞: the instantaneous law, the isochoric stress
  (1 + β) times the relaxed one, so the vented chamber's force (1 + β) times (the volumetric
  part is not scaled: a bulk ratio of 2000 becomes 1333, ~1e-3 on the force);
* with a finite τ the loop dissipates (its area > 0) and unloading runs below loading.
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.fem.viscous import Prony
from spsc.fem.wall.cycle import wall_cycle
from spsc.materials import material

G = preset("B", l=0.0)
KW = dict(stroke_mm=3.0, speed_mm_s=1.0, points=7)


@pytest.fixture(scope="module")
def relaxed():
    return wall_cycle(G, material("tpu60a"), None, **KW)


def test_the_relaxed_law_retraces_itself(relaxed):
    assert relaxed.complete
    assert_allclose(relaxed.force_unload_N, relaxed.force_load_N, atol=1e-9)
    assert abs(relaxed.dissipated_mJ) < 1e-9


def test_fast_and_slow_limits_of_the_prony_wall(relaxed):
    slow = wall_cycle(G, material("tpu60a"), Prony(((0.5, 1e-9),)), **KW)
    assert_allclose(slow.force_load_N, relaxed.force_load_N, rtol=1e-9, atol=1e-12)
    fast = wall_cycle(G, material("tpu60a"), Prony(((0.5, 1e9),)), **KW)
    assert_allclose(fast.force_load_N[1:], 1.5 * relaxed.force_load_N[1:], rtol=3e-3)
    assert_allclose(fast.force_unload_N[1:], 1.5 * relaxed.force_load_N[1:], rtol=3e-3)


def test_a_viscous_cycle_dissipates(relaxed):
    r = wall_cycle(G, material("tpu60a"), Prony(((0.5, 1.0),)), **KW)
    assert r.complete
    assert r.dissipated_mJ > 0.05 * float(np.trapezoid(relaxed.force_load_N, relaxed.y_mm))
    assert np.all(r.force_unload_N[1:-1] < r.force_load_N[1:-1])
    assert r.hysteresis_N > 0.1
