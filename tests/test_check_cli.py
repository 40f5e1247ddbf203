"""The gate's inputs — the design dict, STL/3MF files — and ``spsc check`` on the command line:
the sidecar design file, check.json, one-line errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from spsc_support.check_shapes import R_OUT, M, arrays, bladder, port_design, write_stl
from spsc.cad.check import check_mesh, design_path_for, parse_design
from spsc.core.errors import ParameterError
from spsc.cli.main import main


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


@pytest.mark.parametrize("solid, design, wording", [
    # a closed box with a box-shaped cavity and no port: nothing is capped, nothing said of one
    (lambda: M.cube((20.0, 20.0, 20.0), True) - M.cube((10.0, 10.0, 10.0), True), {},
     "1 enclosed cavity (no port in the design: nothing capped)"),
    # the hollow sphere with its bore open and the design's port: the port is capped
    (lambda: bladder(), port_design(), "1 enclosed cavity with the port capped"),
    # the same open bore without a port in the design: no cavity, and why
    (lambda: bladder(), {}, "no enclosed cavity: a solid part, or a bore open to the outside"),
    (lambda: M.cube((5.0, 5.0, 5.0)), {}, "no enclosed cavity: a solid part"),
])
def test_cavity_count_words_what_was_capped(solid, design, wording):
    rep = check_mesh(arrays(solid()), design=design)
    assert wording in rep["cavity_count"].message
    assert "port capped" not in rep["cavity_count"].message or "port" in design


def test_check_json_names_the_mesh_relative_to_itself(tmp_path, monkeypatch):
    """check.json's source is relative to check.json's folder, not to where spsc ran: the
    folder moved elsewhere, or the report written into another folder, still finds the mesh."""
    import shutil

    part = tmp_path / "a"
    part.mkdir()
    write_stl(part / "part.stl", bladder())
    monkeypatch.chdir(tmp_path)
    assert main(["check", "a/part.stl"]) in (0, 1)
    (tmp_path / "r" / "x").mkdir(parents=True)
    assert main(["check", "a/part.stl", "--json", "r/x/c.json"]) in (0, 1)
    shutil.move(tmp_path / "a", tmp_path / "b")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    beside = json.loads((tmp_path / "b" / "check.json").read_text(encoding="utf-8"))
    assert beside["source"] == "part.stl" and (tmp_path / "b" / beside["source"]).is_file()
    other = json.loads((tmp_path / "r" / "x" / "c.json").read_text(encoding="utf-8"))
    assert other["source"] == "../../a/part.stl"
