"""The printability gate (cad/check.py) on solids built with manifold3d (the command line and
file formats: test_check_cli.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from spsc.cad import meshtopo
from spsc.cad.check import check_mesh, parse_design
from spsc.core.errors import ParameterError
from spsc.cad.process import PROCESSES, process

from spsc_support.check_shapes import (BORE, R_IN, R_OUT, M, arrays, bladder, face_plane_radius,
                          port_design)


# -- process catalogue ---------------------------------------------------------------------------
def test_process_catalogue():
    assert process("FDM").min_wall_mm == 0.8  # paper sec. 2.2
    assert set(PROCESSES) == {"fdm", "sla", "molding"}
    with pytest.raises(ParameterError, match="process = 'sls'"):
        process("sls")


# -- a good part and each defect -----------------------------------------------------------------
def test_good_bladder_passes():
    rep = check_mesh(arrays(bladder()), design=port_design(genus=0, bbox_mm=[24, 24, 24]))
    assert rep.passed and rep.failed == ()
    for name in ("watertight", "manifold", "oriented", "self_intersections", "one_part", "genus",
                 "min_wall", "bbox"):
        assert rep[name].passed is True, name
    assert rep["overhang"].passed is None  # report-only
    assert "PASSED" in rep.summary()


def test_hole_fails_watertight():
    v, f = arrays(bladder())
    rep = check_mesh((v, f[5:]))
    assert "watertight" in rep.failed
    assert rep["watertight"].value > 0


def test_concatenated_overlapping_shells_self_intersect():
    v, f = arrays(M.sphere(5, 32))
    both = (np.vstack([v, v + [3.0, 0, 0]]), np.vstack([f, f + len(v)]))
    rep = check_mesh(both)
    assert "self_intersections" in rep.failed
    assert rep["watertight"].passed and rep["manifold"].passed  # only the crossing is wrong


def test_vertices_pushed_through_the_wall_self_intersect():
    v, f = arrays(bladder())
    cap = (v[:, 2] > 11.5) & (np.linalg.norm(v, axis=1) > 11.5)  # the outer skin's top
    assert cap.sum() >= 3
    v[cap, 2] -= 1.5  # through the 1 mm wall into the cavity
    rep = check_mesh((v, f))
    assert "self_intersections" in rep.failed


def test_coplanar_facets_split_by_a_boolean_are_not_self_intersections():
    # this boolean leaves disjoint coplanar facets in the bore that vcg's test flags to rounding
    solid = M.sphere(12, 64) - M.sphere(11, 64) - M.cylinder(4, 1.5, 1.5, 16).translate(
        (0, 0, -12.5))
    v, f = arrays(solid)
    ms = meshtopo.meshset(v, f)
    ms.compute_selection_by_self_intersections_per_face()
    assert ms.current_mesh().selected_face_number() > 0, "reproducer no longer exercised"
    assert meshtopo.self_intersecting_faces(v, f) == 0


def test_two_disjoint_parts():
    rep = check_mesh(arrays(M.sphere(5, 32) + M.sphere(5, 32).translate((20.0, 0, 0))))
    assert rep.failed == ("one_part",)
    assert rep["one_part"].value == 2


def test_closed_cavity_is_one_part_of_two_shells():
    rep = check_mesh(arrays(bladder(bore=0)))
    assert rep["one_part"].passed and rep["one_part"].value == 1
    assert "2 shell" in rep["one_part"].message


def test_inside_out_mesh_fails_oriented():
    v, f = arrays(M.sphere(5, 32))
    assert "oriented" in check_mesh((v, f[:, ::-1])).failed


# -- wall thickness ------------------------------------------------------------------------------
def test_thin_wall_fails_fdm_but_passes_a_thinner_process_limit():
    # 128 segments: the facets' sagitta (< 0.01 mm) stays within the gate's WALL_TOL_MM
    solid, design = bladder(r_out=11.5, n=128), port_design(r_out=11.5)
    v, f = arrays(solid)
    fdm = check_mesh((v, f), design=design)
    assert fdm.failed == ("min_wall",)
    # cavity vertices lie on r = 11; the outer polyhedron lies between the ball of its nearest
    # face plane and the sphere r = 11.5, so the exact bound on the measured wall is:
    assert face_plane_radius(v, f, inner=False) - R_IN <= fdm["min_wall"].value <= 0.5 + 1e-9
    assert check_mesh(arrays(solid), design=design, process="sla").passed  # sla: 0.5 mm
    assert check_mesh(arrays(solid), design=design, min_wall=0.45).passed


def test_min_wall_location_and_exclusion():
    # outer sphere shifted +0.3 mm in x: the wall is 1.3 mm at +x and 0.7 mm at -x
    solid = bladder(shift=(0.3, 0.0, 0.0))
    v, f = arrays(solid)
    rep = check_mesh((v, f), design=port_design())
    mw = rep["min_wall"]
    sagitta = R_OUT - face_plane_radius(v - [0.3, 0, 0], f, inner=False)  # outer facets
    assert 0.7 - sagitta <= mw.value <= 0.7 + 1e-9
    # the thinnest spot is at -x; 1 mm is about a facet (2 pi 11 / 64) of the cavity
    np.testing.assert_allclose(mw.details["location_mm"], [-R_IN, 0, 0], atol=1.0)
    assert mw.details["percentile_1_mm"] >= mw.value
    # excluding a ball around the thin spot moves the minimum away from it
    thin = [-R_IN, 0, 0]
    far = check_mesh((v, f), design=port_design(
        exclude=[{"center": thin, "radius": 6.0}]))["min_wall"]
    # the wall of the shifted sphere at angle theta from -x is 12 - |p - c|; points outside the
    # ball lie at theta >= 2 asin(6 / 22) from the thin spot
    theta = 2 * math.asin(6.0 / (2 * R_IN))
    wall = R_OUT - math.sqrt(R_IN**2 + 0.3**2 + 2 * 0.3 * R_IN * math.cos(theta))
    assert wall - sagitta <= far.value <= R_OUT - R_IN + 0.3
    assert far.value > mw.value + 0.03  # 0.7435 - 0.7: the exclusion matters
    assert np.linalg.norm(np.subtract(far.details["location_mm"], thin)) > 6.0
    # a wall region above z = 0 leaves only the upper hemisphere (and the thin spot at z = 0)
    upper = check_mesh(arrays(solid), design=port_design(wall_region={"z_min": 2.0}))["min_wall"]
    assert upper.details["location_mm"][2] >= 2.0


def test_open_bore_without_port_is_not_measured():
    rep = check_mesh(arrays(bladder()))
    assert rep["min_wall"].passed is None and rep["cavity_volume"].passed is None
    assert rep.passed  # nothing gating failed, but the summary says min wall was not measured
    assert "port" in rep["min_wall"].message


def test_port_cap_that_misses_the_bore_fails():
    design = port_design()
    design["port"]["axis_point"] = [6.0, 0, 0]  # plug beside the bore: the cavity stays open
    rep = check_mesh(arrays(bladder()), design=design)
    assert "min_wall" in rep.failed


# -- cavity volume -------------------------------------------------------------------------------
def test_cavity_volume_of_a_closed_sphere_within_its_tessellation_bound():
    v, f = arrays(bladder(bore=0, n=128))
    exact = 4.0 / 3.0 * math.pi * R_IN**3
    # the inscribed polyhedron holds the ball of radius d_min (its nearest face plane) and lies in
    # the sphere: (d_min / r)^3 - 1 <= error <= 0, an exact bound
    lower = (face_plane_radius(v, f, inner=True) / R_IN) ** 3 - 1.0
    assert -0.005 < lower < 0
    rep = check_mesh((v, f), design={"cavity_volume_mm3": exact, "volume_rtol": -lower})
    err = rep["cavity_volume"].details["relative_error"]
    assert lower <= err <= 0
    assert rep["cavity_volume"].passed
    off = check_mesh((v, f), design={"cavity_volume_mm3": exact * 1.01})
    assert off.failed == ("cavity_volume",)  # 1 % off > default rtol 0.002


def test_capped_cavity_volume_matches_the_analytic_sphere_minus_the_bore_cap():
    z1 = math.sqrt(R_IN**2 - BORE**2)
    cap = math.pi * (R_IN - z1) ** 2 * (2 * R_IN + z1) / 3  # the segment below the plug top
    exact = 4.0 / 3.0 * math.pi * R_IN**3 - cap
    v, f = arrays(bladder(n=128))
    rep = check_mesh((v, f), design=port_design(cavity_volume_mm3=exact))
    # the inscribed facets lose at most the bound of the test above; the plug top, flat at the
    # analytic rim height, adds the tiny gap up to the faceted floor (< the same bound)
    bound = 1.0 - (face_plane_radius(v, f, inner=True) / R_IN) ** 3
    err = rep["cavity_volume"].details["relative_error"]
    assert -bound <= err <= bound


# -- genus and bounding box ----------------------------------------------------------------------
@pytest.mark.parametrize("holes", [0, 1, 3])
def test_genus_counts_through_holes(holes):
    plate = M.cube((40.0, 10.0, 3.0))
    for k in range(holes):
        plate = plate - M.cylinder(5.0, 1.5, 1.5, 24).translate((6.0 + 10.0 * k, 5.0, -1.0))
    rep = check_mesh(arrays(plate), design={"genus": holes})
    assert rep["genus"].value == holes and rep["genus"].passed
    assert check_mesh(arrays(plate), design={"genus": holes + 1}).failed == ("genus",)


def test_bbox_against_design():
    plate = arrays(M.cube((40.0, 10.0, 3.0)))
    assert check_mesh(plate, design={"bbox_mm": [40.3, 10.2, 3.4]}).passed  # within 0.5 mm
    assert check_mesh(plate, design={"bbox_mm": [41.0, 10.0, 3.0]}).failed == ("bbox",)
    # bounds: the corners count too (the cube spans [0, 40] x [0, 10] x [0, 3])
    assert check_mesh(plate, design={"bbox_mm": [[0.2, 0, 0], [40.2, 10, 3]]}).passed
    assert check_mesh(plate, design={"bbox_mm": [[1, 0, 0], [41, 10, 3]]}).failed == ("bbox",)
    with pytest.raises(ParameterError, match="bbox_mm"):
        parse_design({"bbox_mm": [[1, 0, 0], [0, 10, 3]]})


# -- overhang ------------------------------------------------------------------------------------
def test_overhang_of_a_tee_and_a_closed_box_cavity():
    tee = M.cube((4.0, 4.0, 10.0)).translate((8.0, 8.0, 0.0)) + \
        M.cube((20.0, 20.0, 2.0)).translate((0.0, 0.0, 10.0))
    oh = check_mesh(arrays(tee))["overhang"]
    assert oh.passed is None
    np.testing.assert_allclose(oh.value["outer_mm2"], 20 * 20 - 4 * 4, rtol=1e-9)  # slab underside
    box = M.cube((20.0, 20.0, 20.0)) - M.cube((10.0, 10.0, 10.0)).translate((5.0, 5.0, 5.0))
    oh = check_mesh(arrays(box))["overhang"]
    assert oh.value["outer_mm2"] == 0  # the bottom face stands on the plate
    np.testing.assert_allclose(oh.value["cavity_mm2"], 100.0, rtol=1e-9)  # the cavity ceiling
    np.testing.assert_allclose(oh.details["cavity_percent"], 100 / 6, rtol=1e-9)


def test_overhang_angle_follows_the_process():
    # frustum on its small end: 64 facets leaning ~50 deg from vertical (> 45 fdm, < 60 sla)
    r1, h, n = 5.0, 10.0, 64
    r2 = r1 + h * math.tan(math.radians(50.0))
    v, f = arrays(M.cylinder(h, r1, r2, n))
    s = math.pi / n
    slant = math.hypot(h, (r2 - r1) * math.cos(s))
    lateral = n * (math.sin(s) * (r1 + r2)) * slant  # n trapezoids, exact for the polygon
    np.testing.assert_allclose(check_mesh((v, f))["overhang"].value["outer_mm2"], lateral,
                               rtol=1e-9)
    assert check_mesh((v, f), process="sla")["overhang"].value["outer_mm2"] == 0
