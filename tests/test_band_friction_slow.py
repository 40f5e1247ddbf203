"""A band under the plate's unknown friction (issue 49): the wall model's Type B dome pressed
1 mm with μ drawn from 0 to the sticking plate; every draw's stiffness lies between the
frictionless and the sticking plate's (friction only holds the wall back)."""

from __future__ import annotations

import pytest

from spsc.cad.geometry import preset
from spsc.core.setup import Setup
from spsc.materials import material
from spsc.models import get
from spsc.study.band import band
from spsc.study.tolerance import parse_tolerance

pytestmark = pytest.mark.slow


def test_the_friction_band_lies_between_frictionless_and_sticking():
    def setup(friction):
        return Setup.of(preset("B", l=0), material("tpu60a"), pressure_kPa=40,
                        stroke_mm=1.0, points=5, friction=friction)

    wall = get("wall")
    options = wall.Options()
    slip = wall.curve(setup("0"), options).curve.mean_stiffness()
    stick = wall.curve(setup("stick"), options).curve.mean_stiffness()
    tol = parse_tolerance({"friction": {"dist": "uniform", "low": 0.0, "high": "stick"}})
    r = band(setup("0"), options, "wall", tol, n=8, seed=0, workers=2)
    q = r["stiffness_N_per_mm"]
    assert r["computed"] == r["samples"] == 24 and r["refused"] == 0
    assert slip < stick
    # a hair of Newton's tolerance either side (rtol 1e-8 on forces of ~5 N)
    assert slip * (1 - 1e-6) <= q["p5"] <= q["p50"] <= q["p95"] <= stick * (1 + 1e-6)
    assert q["p95"] > slip * (1 + 1e-3)  # the friction shows
