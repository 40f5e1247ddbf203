"""The fast printability verdict (cad/printability.py): each check against a value known in
closed form, and (slow) against the printability gate on built bladders."""

from __future__ import annotations

import dataclasses
import math
import subprocess
import sys

import numpy as np
import pytest

from spsc.cad.geometry import SPSCGeometry, preset
from spsc.cad.printability import Verdict, printability
from spsc.cad.process import PROCESSES, Process
from spsc.cad.specs import BladderSpec, FlangeSpec, PortSpec
from spsc.core.errors import ParameterError


def sphere_cap(cy: float, t0: float, r: float = 10.0) -> SPSCGeometry:
    """A chamber whose cavity is a circle of radius ``r`` (n1 = n2 = 2, w̄ = h̄ = r) centred at
    height c_y r: h̄ = h / (1 + c_y) and w̄ = w / sqrt(1 − c_y²) (eqs. 12–14)."""
    return SPSCGeometry(w=r * math.sqrt(1 - cy**2), h=r * (1 + cy), l=0.0, t0=t0, n1=2.0,
                        n2=2.0, cy=cy)


# -- minimum wall ----------------------------------------------------------------------------------
@pytest.mark.parametrize("name", sorted(PROCESSES))
def test_wall_below_and_above_each_process_minimum(name):
    limit = PROCESSES[name].min_wall_mm
    thin = printability(preset("B", t0=limit - 0.05), name)
    assert not thin.ok
    assert thin.reasons == (f"wall {limit - 0.05:.3f} mm at (x 0.00, z 13.00) mm < {name} "
                            f"minimum {limit:g} mm",)
    assert printability(preset("B", t0=limit + 0.05), name).ok
    # at the limit: passes, as the gate does (its 0.01 mm tessellation allowance)
    assert printability(preset("B", t0=limit), name).ok


@pytest.mark.parametrize("kind", "ABCD")
def test_wall_of_a_smooth_profile_is_t0(kind):
    """The outer polyline's chords lie inside the true offset by their sag, < 0.002 mm with the
    export mesh's 161 points (geometry.MESH_PROFILE_POINTS), and never outside it."""
    g = preset(kind)
    wall = printability(g).measures["wall_mm"]
    assert g.t0 - 2e-3 < wall <= g.t0 + 1e-12


def test_wall_thinned_at_a_profile_corner():
    """n2 = 1 with c_y > 0 has a corner at the widest section (w̄, c_y h̄); the export mesh's
    outer polyline crosses the corner's offset arc on a chord, which the gate measures
    (0.731 mm for this design) and the verdict must see."""
    g = preset("D", n2=1.0, cy=0.5)
    v = printability(g, "fdm")
    x, z = v.measures["wall_at_mm"]
    np.testing.assert_allclose([x, z], [g.w_bar, g.z_widest], atol=1e-6)
    assert 0.70 < v.measures["wall_mm"] < 0.76
    assert not v.ok and v.reasons[0].startswith("wall 0.735 mm at (x 15.56, z 4.33) mm < fdm")
    assert printability(g, "sla").ok  # 0.735 mm is over SLA's 0.5 mm


def test_no_wall_region_fails_as_in_the_gate():
    """The gate judges the cavity above z = t0 (the bladder's wall_region): a cavity lower than
    its wall has no point there, and the gate fails min_wall."""
    v = printability(preset("D", h=1.2, t0=1.3), "sla")
    assert not v.ok and v.measures["wall_mm"] is None
    assert "wall region" in v.reasons[0]


# -- overhang --------------------------------------------------------------------------------------
@pytest.mark.parametrize("cy, t0", [(0.6, 1.0), (0.6, 0.4), (0.8, 1.0), (0.3, 2.0)])
def test_overhang_of_a_sphere_cap_standing_on_its_base(cy, t0):
    """Cavity a circle of radius r centred c_y r above the base: the outer wall is the circle of
    radius r + t0, which meets z = 0 where its normal is asin(c_y r / (r + t0)) below the
    horizontal, the steepest downward face (degrees from vertical)."""
    g = sphere_cap(cy, t0)
    v = printability(g, "fdm")
    expected = math.degrees(math.asin(cy * 10.0 / (10.0 + t0)))
    np.testing.assert_allclose(v.measures["overhang_deg"], expected, rtol=0, atol=1e-6)
    assert any(r.startswith("overhang") for r in v.reasons) == (expected > 45.0)


def test_overhang_against_each_process_limit():
    g = sphere_cap(0.8, 1.0)  # asin(8 / 11) = 46.7 deg: over FDM's 45, under SLA's 60
    fdm = printability(g, "fdm")
    assert fdm.reasons == ("overhang 46.7° > fdm limit 45° (outer wall of the bulge below the "
                           "widest section, where it meets the base plane)",)
    assert printability(g, "sla").ok and printability(g, "molding").ok


def test_overhang_of_types_without_a_bulge_is_zero_and_type_d_is_near_the_fdm_limit():
    for kind in "ABC":
        assert printability(preset(kind)).measures["overhang_deg"] == 0.0
    v = printability(preset("D"), "fdm")
    assert v.ok and 43.0 < v.measures["overhang_deg"] < 43.2
    assert v.summary.startswith("fdm: wall 1.000 ≥ 0.8 mm, overhang 43.1 ≤ 45°, cavity ceiling")


def test_cavity_ceiling_is_reported_not_gated():
    """The cavity's apex faces straight down (n1 > 1): a bridge in every closed bladder, which
    the gate reports and does not gate. With n1 = 1 the apex is a cone's tip: its normal is
    (1/w̄, n2/h̄) normalised (gradient of x/w̄ + |z/h̄ − c_y|^n2)."""
    assert printability(preset("B")).measures["ceiling_deg"] == 90.0
    g = preset("B", n1=1.0)
    expected = math.degrees(math.atan2(g.n2 / g.h_bar, 1.0 / g.w_bar))
    v = printability(g, "sla")
    np.testing.assert_allclose(v.measures["ceiling_deg"], expected, rtol=1e-12)
    assert "cavity ceiling" in v.summary and not any("ceiling" in r for r in v.reasons)


# -- port and flange -------------------------------------------------------------------------------
def test_port_and_flange_walls():
    p, f = PortSpec(), FlangeSpec()
    assert p.wall == pytest.approx(0.8) and f.ligament == pytest.approx(1.3)
    assert BladderSpec(preset("B"), f, p).bore_roof == pytest.approx(3.5 - 1.875 - 0.7)
    g = preset("B")
    assert printability(g, "fdm", port=p).ok  # 0.8 mm nipple wall: at the FDM minimum
    molding = printability(g, "molding", port=p)
    assert molding.reasons == ("port wall 0.800 mm < molding minimum 1 mm",
                               "bore roof 0.925 mm < molding minimum 1 mm")
    assert printability(g, "molding").ok  # the chamber alone: what the gate judges
    thin = printability(g, "fdm", flange=FlangeSpec(hole_diameter=5.6))
    assert thin.reasons == ("flange ligament 0.200 mm < fdm minimum 0.8 mm",)
    assert printability(g, "fdm", flange=FlangeSpec(holes=0, hole_diameter=5.6)).ok
    with pytest.raises(ParameterError, match="port.tube_id"):
        printability(g, port=PortSpec(tube_id=4.5))


# -- input -----------------------------------------------------------------------------------------
@pytest.mark.parametrize("bad", ["sls", "", None, 3])
def test_unknown_process_is_one_line_naming_the_allowed(bad):
    with pytest.raises(ParameterError) as exc:
        printability(preset("D"), bad)
    msg = str(exc.value)
    assert "\n" not in msg
    assert msg.startswith(f"process = {bad!r} is invalid") and "fdm, sla, molding" in msg


def test_process_object_and_geometry_type():
    custom = Process("resin-x", 0.3, 30.0, "a test process")
    v = printability(preset("D"), custom)
    assert v.process == "resin-x" and not v.ok
    assert v.reasons == ("overhang 43.1° > resin-x limit 30° (outer wall of the bulge below the "
                         "widest section, where it meets the base plane)",)
    with pytest.raises(ParameterError, match="geometry = 'dict'"):
        printability({"w": 11}, "fdm")


def test_verdict_is_frozen():
    v = printability(preset("A"))
    assert isinstance(v, Verdict) and v.ok and v.reasons == ()
    with pytest.raises(dataclasses.FrozenInstanceError):
        v.ok = False


def test_verdict_builds_no_solid():
    """The verdict's speed comes from not building the part: in a fresh interpreter, judging
    every preset on every process imports neither CAD kernel (cadquery, manifold3d)."""
    script = ("import sys\n"
              "from spsc.cad.geometry import preset\n"
              "from spsc.cad.printability import printability\n"
              "for t in 'ABCD':\n"
              "    for p in ('fdm', 'sla', 'molding'):\n"
              "        printability(preset(t), p)\n"
              "print(sorted(m for m in ('cadquery', 'OCP', 'manifold3d', 'pymeshlab')"
              " if m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"
