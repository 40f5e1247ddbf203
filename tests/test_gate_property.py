"""Property test of the printability gate over the valid design space: every random valid
bladder (types A–D in the paper's family, any material, flange holes and tube, a wall at or
above the process minimum) is built soundly (watertight, manifold, one part, no
self-intersection, the designed cavity, genus and box) and the gate's verdict is the
printability rule's (spsc.cad.printability, which also fills a sweep's ``printable`` column):
it passes, or fails on the rule alone (a Type D bulge steeper than the process's overhang limit),
or the design is refused with a named one-line error. A self-intersection or a wall failure
here is a geometry bug (issue 10 found Type C with four flange holes). The fast suite draws a
few designs; ``make test-slow`` (and ``make test-all``) more; ``bench/bench_badinput.py
--designs 200`` 200 through the CLI and ``bench/bench_printability.py`` compares the gate with
the sweep on 200.
"""

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from spsc_support.fuzz_cases import random_design
from spsc.cad import meshtopo
from spsc.cad.bladder import BladderSpec, FlangeSpec, PortSpec, build_bladder
from spsc.cad.check import check_mesh
from spsc.cad.export import write_stl
from spsc.cad.geometry import SPSCGeometry, preset
from spsc.cad.printability import printability
from spsc.cad.meshbuild import (MESH_PROFILE_POINTS, bladder_mesh, chamber_manifold,
                                hull_meridian)
from spsc.core.errors import ParameterError
from spsc.cli.bladder import MATERIAL_PROCESS

# each draw builds and checks a part (about 10 s): no shrinking, the failing seed is printed
SLOW_DRAWS = dict(deadline=None, phases=[Phase.explicit, Phase.reuse, Phase.generate],
                  suppress_health_check=[HealthCheck.too_slow])


def _gate(seed: int) -> None:
    d = random_design(np.random.default_rng(seed))
    try:
        g = preset(d["type"], **{k: d[k] for k in ("w", "h", "l", "t0", "n1", "n2", "cy")})
        spec = BladderSpec(g, FlangeSpec(holes=d["flange_holes"]),
                           PortSpec(tube_id=d["tube_id"]))
    except ParameterError as exc:  # a named one-line rejection is an allowed outcome
        assert "\n" not in str(exc) and " = " in str(exc)
        return
    b = build_bladder(spec)
    process = MATERIAL_PROCESS[d["material"]]
    report = check_mesh(bladder_mesh(spec).to_trimesh(), design=b.design, process=process)
    rule = printability(g, process)
    assert set(report.failed) <= {"printability"}, (d, report.failed, report.summary())
    assert report.passed == rule.ok, (d, report.failed, rule.reasons)


@pytest.mark.slow
@settings(max_examples=2, derandomize=True, **SLOW_DRAWS)
@given(st.integers(0, 2**32 - 1))
def test_random_valid_designs_pass_the_gate(seed):
    _gate(seed)


@pytest.mark.slow
@pytest.mark.long
@settings(max_examples=30, derandomize=True, **SLOW_DRAWS)
@given(st.integers(0, 2**32 - 1))
def test_random_valid_designs_pass_the_gate_many(seed):
    _gate(seed)


def test_issue_10_type_c_with_four_holes_passes():
    """The design issue 10 found self-intersecting (spsc bladder --type C --w 7.054 --h 8.082
    --l 11.644 --t0 1.038 --material silicone40a --flange-holes 4 --tube-id 3.77)."""
    g = preset("C", w=7.054, h=8.082, l=11.644, t0=1.038)
    spec = BladderSpec(g, FlangeSpec(holes=4), PortSpec(tube_id=3.77))
    report = check_mesh(bladder_mesh(spec).to_trimesh(), design=build_bladder(spec).design,
                        process="sla")
    assert report.passed, report.failed
    assert report["self_intersections"].value == 0


# -- issue 10: Type C (n2 = 1, c_y = 0) at the wall's root ------------------------------------
# The outer offset ends above the base plane and is prolonged along its last chord, then sunk
# into the plate along the same line: the ring where the offset ends lay exactly on the hull's
# facets, and QuickHull folded them (meshbuild.hull_meridian).

def _hull_self_intersections(pts, l, sink=0.0) -> int:
    mesh = chamber_manifold(pts, l, sink=sink).to_mesh()
    return meshtopo.self_intersecting_faces(np.asarray(mesh.vert_properties)[:, :3],
                                            np.asarray(mesh.tri_verts, np.int64))


def test_hull_meridian_leaves_out_points_on_a_chord():
    line = np.column_stack([np.linspace(0.0, 10.0, 7), np.linspace(10.0, 0.0, 7)])
    np.testing.assert_array_equal(hull_meridian(line), line[[0, -1]])
    g = preset("C")  # the offset's last point is on the chord from the one before to the base
    outer = g.outer_profile_points(MESH_PROFILE_POINTS)
    np.testing.assert_array_equal(hull_meridian(outer), np.delete(outer, -2, axis=0))
    inner, _ = g.profile_points(MESH_PROFILE_POINTS)  # curved throughout: nothing left out
    np.testing.assert_array_equal(hull_meridian(inner), inner)


@pytest.mark.parametrize("params", [
    dict(w=10.38, h=10.33, l=9.443, t0=1.215, n1=2.804),  # 18 folded faces before the fix
    dict(w=10.0, h=10.0, l=8.0, t0=1.0, n1=1.0),  # a cone: every meridian point on a chord
], ids=["type-c", "cone"])
def test_type_c_chamber_hulls_do_not_self_intersect(params):
    g = SPSCGeometry(n2=1.0, cy=0.0, **params)
    flange = FlangeSpec()
    assert _hull_self_intersections(g.outer_profile_points(MESH_PROFILE_POINTS), g.l,
                                    sink=flange.thickness / 2) == 0
    assert _hull_self_intersections(g.profile_points(MESH_PROFILE_POINTS)[0], g.l) == 0


def _gate_stl(tmp_path, spec, material):
    """The gate as ``spsc bladder`` runs it: on the STL written (float32 vertices)."""
    stl = write_stl(bladder_mesh(spec), tmp_path / "bladder.stl")
    return check_mesh(stl, design=build_bladder(spec).design, process=MATERIAL_PROCESS[material])


def test_cone_bladder_passes_the_gate(tmp_path):
    """n1 = n2 = 1 (outside the verified design space, inside the limits) failed manifold,
    self-intersections and cavity count, as one of issue 10's designs did."""
    spec = BladderSpec(SPSCGeometry(w=10.0, h=10.0, l=8.0, t0=1.0, n1=1.0, n2=1.0, cy=0.0))
    report = _gate_stl(tmp_path, spec, "tpu60a")
    assert report.passed, report.failed


@pytest.mark.slow
@pytest.mark.parametrize("d", [
    dict(w=5.416, h=9.197, l=0, t0=0.5171, n1=6.307, material="elastic50a", holes=2, tube=1.63),
    dict(w=12.13, h=20.2, l=15.22, t0=1.054, n1=4.221, material="tpu60a", holes=2, tube=3.43),
    dict(w=14.67, h=7.587, l=0, t0=2.009, n1=4.416, material="elastic50a", holes=4, tube=3.16),
    dict(w=9.324, h=5.825, l=14.22, t0=1.769, n1=6.132, material="tpu60a", holes=2, tube=2.86),
    dict(w=7.054, h=8.082, l=11.644, t0=1.038, n1=2.0, material="silicone40a", holes=4,
         tube=3.77),
    dict(w=11.63, h=6.04, l=12.74, t0=1.098, n1=5.569, material="tpu60a", holes=2, tube=2.19),
], ids=["seed11-24", "seed11-92", "seed11-106", "seed11-131", "four-holes", "folded-here"])
def test_issue_10_type_c_designs_pass(tmp_path, d):
    """The four Type C designs bench_badinput --designs 200 --seed 11 failed and the four-hole
    one (elsewhere; they pass here even without the fix), and one that failed here with 14
    self-intersecting faces, through the STL as ``spsc bladder`` checks it."""
    g = SPSCGeometry(w=d["w"], h=d["h"], l=d["l"], t0=d["t0"], n1=d["n1"], n2=1.0, cy=0.0)
    spec = BladderSpec(g, FlangeSpec(holes=d["holes"]), PortSpec(tube_id=d["tube"]))
    report = _gate_stl(tmp_path, spec, d["material"])
    assert report.passed, report.failed
    assert report["self_intersections"].value == 0
