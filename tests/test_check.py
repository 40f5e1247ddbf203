"""The printability gate (cad/check.py) on solids built with manifold3d, and ``spsc check``."""

from __future__ import annotations

import json
import math

import manifold3d as mf
import numpy as np
import pytest
import trimesh

from spsc.cad import meshtopo
from spsc.cad.check import check_mesh, design_path_for, parse_design
from spsc.core.errors import ParameterError
from spsc.cad.process import PROCESSES, process
from spsc.pipeline.cli import main

M = mf.Manifold
R_OUT, R_IN, BORE = 12.0, 11.0, 1.5


def arrays(solid: mf.Manifold):
    g = solid.to_mesh64()
    return np.asarray(g.vert_properties)[:, :3].copy(), np.asarray(g.tri_verts).astype(np.int64)


def bladder(r_out=R_OUT, r_in=R_IN, n=64, bore=BORE, shift=(0.0, 0.0, 0.0), bore_n=32):
    """Hollow sphere (cavity centred on the origin) with a bore through its bottom."""
    solid = M.sphere(r_out, n).translate(shift) - M.sphere(r_in, n)
    if bore:
        solid = solid - M.cylinder(r_out + 2, bore, bore, bore_n).translate((0, 0, -(r_out + 2)))
    return solid


def port_design(r_out=R_OUT, r_in=R_IN, bore=BORE, **extra):
    """Plug from below the port tip up to where the bore meets the (analytic) cavity sphere."""
    z1 = -math.sqrt(r_in**2 - bore**2)
    return {"port": {"axis_point": [0, 0, 0], "axis_dir": [0, 0, -1], "radius": bore,
                     "z_range": [-(r_out + 1), z1]}, **extra}


def face_plane_radius(v, f, inner: bool) -> float:
    """Smallest distance from the origin to the plane of a face of the inner (or outer) sphere
    of a hollow sphere: the inscribed polyhedron holds the ball of that radius."""
    sel = (np.linalg.norm(v[f], axis=2).max(axis=1) < (R_IN + R_OUT) / 2) == inner
    n = meshtopo.face_normals(v, f[sel])
    return float(np.abs(np.einsum("ij,ij->i", n, v[f[sel, 0]])).min())


def write_stl(path, solid_or_arrays, ascii=False):
    v, f = solid_or_arrays if isinstance(solid_or_arrays, tuple) else arrays(solid_or_arrays)
    trimesh.Trimesh(v, f, process=False).export(path, file_type="stl_ascii" if ascii else "stl")
    return path


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


# -- design dict, files, command line ------------------------------------------------------------
def test_design_validation_names_the_parameter():
    with pytest.raises(ParameterError, match="port.radius"):
        parse_design({"port": {"axis_point": [0, 0, 0], "axis_dir": [0, 0, 1], "radius": -1,
                               "z_range": [0, 1]}})
    with pytest.raises(ParameterError, match="axis_dir"):
        parse_design({"port": {"axis_point": [0, 0, 0], "axis_dir": [1, 0, 0], "radius": 1,
                               "z_range": [0, 1]}})
    with pytest.raises(ParameterError, match="genus"):
        parse_design({"genus": 1.5})
    assert parse_design({"note": "ignored"}) == {"volume_rtol": 0.002}


def test_stl_ascii_and_3mf_load_the_same_mesh(tmp_path):
    import lib3mf

    v, f = arrays(bladder(bore=0, n=32))
    ref = check_mesh((v, f))
    asc = check_mesh(write_stl(tmp_path / "a.stl", (v, f), ascii=True))
    wrapper = lib3mf.get_wrapper()
    model = wrapper.CreateModel()
    obj = model.AddMeshObject()
    pos, tri = [], []
    for p in v:
        q = lib3mf.Position()
        q.Coordinates[0], q.Coordinates[1], q.Coordinates[2] = (float(c) for c in p)
        pos.append(q)
    for t in f:
        q = lib3mf.Triangle()
        q.Indices[0], q.Indices[1], q.Indices[2] = (int(i) for i in t)
        tri.append(q)
    obj.SetGeometry(pos, tri)
    shift = wrapper.GetIdentityTransform()
    shift.Fields[3][2] = 5.0  # build item raised by 5 mm
    model.AddBuildItem(obj, shift)
    model.QueryWriter("3mf").WriteToFile(str(tmp_path / "a.3mf"))
    m3 = check_mesh(tmp_path / "a.3mf")
    for rep in (asc, m3):
        assert rep.passed
        np.testing.assert_allclose(rep["cavity_volume"].value, ref["cavity_volume"].value,
                                   rtol=1e-6)  # ASCII STL prints ~7 significant digits
    np.testing.assert_allclose(m3["bbox"].details["min_mm"][2], -R_OUT + 5.0, atol=1e-6)


def test_triangle_soup_with_jitter_is_welded():
    # STL repeats every shared vertex per face; OCC writes a sphere's pole 1e-17 apart, and
    # signed zeros; welding to 1e-9 mm joins them (a jitter of 1e-12 mm stands for both)
    v, f = arrays(M.cube((2.0, 2.0, 2.0)).translate((-1.0, 0.0, 0.0)))
    soup = v[f].reshape(-1, 3)
    soup = soup + np.random.default_rng(1).uniform(-1e-12, 1e-12, soup.shape)
    faces = np.arange(len(soup)).reshape(-1, 3)
    # plus a sliver on an edge that welding collapses (kept, it would make that edge non-manifold)
    soup = np.vstack([soup, soup[faces[0, 1]] + 1e-12])
    faces = np.vstack([faces, [faces[0, 0], faces[0, 1], len(soup) - 1]])
    rep = check_mesh((soup, faces))
    assert rep.passed and rep["watertight"].passed and rep["genus"].value == 0


def test_3mf_rejected_by_lib3mf_is_read_from_its_xml(tmp_path):
    # cadquery's 3MF exporter writes object id 0 and an incomplete [Content_Types].xml
    import zipfile

    v, f = arrays(M.cube((2.0, 3.0, 4.0)))
    xml = ['<?xml version="1.0"?><model unit="centimeter" xmlns="http://schemas.microsoft.com/'
           '3dmanufacturing/core/2015/02"><resources><object id="0" type="model"><mesh><vertices>']
    xml += [f'<vertex x="{a!r}" y="{b!r}" z="{c!r}" />' for a, b, c in v.tolist()]
    xml.append("</vertices><triangles>")
    xml += [f'<triangle v1="{a}" v2="{b}" v3="{c}" />' for a, b, c in f]
    xml.append('</triangles></mesh></object></resources><build>'
               '<item objectid="0" transform="1 0 0 0 1 0 0 0 1 0 0 1" /></build></model>')
    path = tmp_path / "cq.3mf"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("[Content_Types].xml", '<?xml version="1.0"?><Types xmlns="http://schemas.'
                   'openxmlformats.org/package/2006/content-types"><Override PartName="/3D/'
                   '3dmodel.model" ContentType="application/vnd.ms-package.3dmanufacturing-'
                   '3dmodel+xml" /></Types>')
        z.writestr("_rels/.rels", '<?xml version="1.0"?><Relationships xmlns="http://schemas.'
                   'openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/'
                   '3dmodel.model" Id="rel-1" Type="http://schemas.microsoft.com/3dmanufacturing/'
                   '2013/01/3dmodel" /></Relationships>')
        z.writestr("3D/3dmodel.model", "".join(xml))
    rep = check_mesh(path)
    assert rep.passed
    # centimetres -> mm, and the item's transform raises it by 1 cm
    np.testing.assert_allclose(rep["bbox"].value, [20.0, 30.0, 40.0], rtol=1e-12)
    np.testing.assert_allclose(rep["bbox"].details["min_mm"], [0.0, 0.0, 10.0], atol=1e-12)


def test_cli_passes_with_sidecar_and_writes_check_json(tmp_path, capsys):
    stl = write_stl(tmp_path / "part.stl", bladder())
    design_path_for(stl).write_text(json.dumps(port_design(genus=0)), encoding="utf-8")
    assert main(["check", str(stl)]) == 0
    out = capsys.readouterr().out
    assert "min wall" in out and "PASSED" in out
    data = json.loads((tmp_path / "check.json").read_text(encoding="utf-8"))
    checks = {c["name"]: c for c in data["checks"]}
    assert data["passed"] and checks["genus"]["passed"] is True  # the sidecar's genus was used
    assert checks["min_wall"]["passed"] is True  # and its port capped the bore


def test_cli_fails_with_one_line_naming_the_checks(tmp_path, capsys):
    v, f = arrays(bladder(r_out=11.5))
    stl = write_stl(tmp_path / "thin.stl", (v, f[3:]))
    assert main(["check", str(stl), "--json", str(tmp_path / "r.json")]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["spsc check: FAILED: watertight"]
    stl = write_stl(tmp_path / "thin2.stl", (v, f))
    (tmp_path / "d.json").write_text(json.dumps(port_design(r_out=11.5)), encoding="utf-8")
    assert main(["check", str(stl), "--design", str(tmp_path / "d.json")]) == 1
    assert capsys.readouterr().err.strip() == "spsc check: FAILED: min_wall"
    args = ["check", str(stl), "--design", str(tmp_path / "d.json"), "--min-wall", "0.4"]
    assert main(args) == 0


@pytest.mark.parametrize("argv_tail, needle", [
    (["missing.stl"], "no such file"),
    (["garbage.stl"], "readable STL"),
    (["good.stl", "--min-wall", "-1"], "--min-wall = '-1'"),
    (["good.stl", "--min-wall", "abc"], "--min-wall = 'abc'"),
    (["good.stl", "--process", "sls"], "process = 'sls'"),
    (["good.stl", "--design", "@bad.json"], "design"),
])
def test_cli_bad_input_is_one_line_and_exit_2(tmp_path, capsys, argv_tail, needle):
    (tmp_path / "garbage.stl").write_bytes(b"\x00\x01 not a mesh")
    (tmp_path / "bad.json").write_text("{not json", encoding="utf-8")
    write_stl(tmp_path / "good.stl", M.cube((1.0, 1.0, 1.0)))
    rest = [str(tmp_path / a[1:]) if a.startswith("@") else a for a in argv_tail[1:]]
    argv = ["check", str(tmp_path / argv_tail[0]), *rest]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("spsc check: error:") and needle in err[0]


def test_cli_reads_a_bounds_form_sidecar_of_a_real_bladder(tmp_path, capsys):
    """The sidecar written by ``spsc bladder`` (bbox as [[min], [max]]) is read by ``spsc check``."""
    from spsc.cad.bladder import BladderSpec, build_bladder
    from spsc.cad.export import export_part
    from spsc.cad.geometry import preset
    from spsc.cad.meshbuild import bladder_mesh

    b = build_bladder(BladderSpec(preset("C")))
    w = export_part(b.solid, b.design, tmp_path, "c", mesh=bladder_mesh(b.spec))
    assert main(["check", str(w["paths"]["stl"])]) == 0
    assert "PASSED" in capsys.readouterr().out
