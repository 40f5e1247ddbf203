"""The mold (issue 15): its gate on good molds, and the gate failing on broken ones.

Volume identities are exact up to boolean round-off (manifold3d), so a good mold shows ~1e-9
relative error; the 0.5 % bound is the issue's. The broken molds are what the issue names: a piece
moved by 1 mm, a core too small, a piece with an undercut.
"""

from dataclasses import replace
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.cad.geometry import preset
from spsc.cad.mold.build import build_mold
from spsc.cad.mold.gate import mold_gate
from spsc.cad.mold.spec import MoldSpec
from spsc.cad.specs import BladderSpec
from spsc.core.errors import ParameterError


@lru_cache(maxsize=None)
def _mold(t, process="casting", parting=None):
    return build_mold(BladderSpec(preset(t)), MoldSpec(process=process), parting=parting)


@lru_cache(maxsize=None)
def _gate(t, process="casting"):
    return mold_gate(_mold(t, process))


@pytest.mark.slow
@pytest.mark.parametrize("t,process", [("B", "casting"), ("D", "casting"),
                                       ("A", "compression")])
def test_mold_passes_its_gate(t, process):
    rep = _gate(t, process)
    assert rep.passed, rep.summary()
    # the identities hold to round-off on a good mold, far inside the 0.5 % bound
    assert abs(rep["wall_volume"].value) < 1e-6
    assert rep["wall_volume"].details["symmetric_difference"] < 1e-6
    # the core is the analytic cavity + bore to the mesh's sag (0.05 %)
    assert abs(rep["core_volume"].value) < 1e-3
    assert rep["key_clearance"].value == pytest.approx(0.2 * np.cos(np.radians(15)), abs=0.01)


def test_parting_follows_the_undercut():
    # Types A–C narrow upward from the base: a horizontal split has no undercut
    for t in "B":
        m = _mold(t)
        assert m.parting == "z" and max(m.undercut["z"].values()) < 1e-6
    # Type D is widest 4.9 mm above its base: the upper half would be locked by its lower
    # flank; the vertical split frees it, and the flange holes get pins pulled first
    d = _mold("D")
    assert d.parting == "x"
    assert d.undercut["z"]["upper"] > 100.0
    assert max(d.undercut["x"].values()) < 1e-6
    pins = [p for p in d.pieces if p.role == "pin"]
    assert len(pins) == 4 and all(p.order < d.piece("left").order for p in pins)


def test_casting_feeds_and_compression_grooves():
    cast, comp = _mold("B"), _mold("A", "compression")
    assert set(cast.channels) == {"sprue", "riser", "vents"}
    assert set(comp.channels) == {"flash_groove"}
    # the groove is a closed ring in the lower half's parting face (less the core's corridor)
    g = comp.channels["flash_groove"]
    lo, hi = np.asarray(g.bounding_box()).reshape(2, 3)
    assert hi[2] == pytest.approx(comp.plane_origin[2], abs=1e-6)
    assert_allclose(hi[2] - lo[2], 1.0, atol=1e-6)
    assert g.volume() > 50.0


def test_shrinkage_scales_the_cavity():
    b = BladderSpec(preset("B"))
    m0 = build_mold(b, MoldSpec(shrinkage_pct=0.0), parting="z")
    m2 = build_mold(b, MoldSpec(shrinkage_pct=2.0), parting="z")
    # volume goes with the cube of 1 / (1 - s)
    assert_allclose(m2.part.volume() / m0.part.volume(), (1 / 0.98) ** 3, rtol=1e-9)


def test_gate_fails_on_a_moved_piece():
    m = _mold("B")
    pieces = tuple(replace(p, solid=p.solid.translate([0.0, 1.0, 0.0])) if p.name == "upper"
                   else p for p in m.pieces)
    rep = mold_gate(replace(m, pieces=pieces), printability=False)
    assert not rep.passed
    assert {"overlap", "wall_volume"} <= set(rep.failed)
    assert "upper" in rep["overlap"].message


def test_gate_fails_on_a_small_core():
    m = _mold("B")
    core = m.piece("core").solid
    c = np.asarray(core.bounding_box()).reshape(2, 3).mean(axis=0)
    small = core.translate((-c).tolist()).scale([0.98] * 3).translate(c.tolist())
    pieces = tuple(replace(p, solid=small) if p.role == "core" else p for p in m.pieces)
    rep = mold_gate(replace(m, pieces=pieces), printability=False)
    assert "core_volume" in rep.failed and "wall_volume" in rep.failed
    assert rep["core_volume"].value < -0.03


def test_gate_fails_on_an_undercut():
    rep = mold_gate(_mold("D", parting="z"), printability=False)
    assert rep.failed == ("pull_upper",)
    assert rep["pull_upper"].value > 100.0
    assert "undercut" in rep["pull_upper"].message


# 5 s of make test's 3 minutes (the B-rep mold through OCCT): with the slow cases (CI runs both)
@pytest.mark.slow
def test_brep_mold_matches_the_mesh_mold():
    b = BladderSpec(preset("D"))
    mesh = _mold("D")
    brep = build_mold(b, MoldSpec(), kernel="brep")
    assert brep.parting == mesh.parting
    for p, q in zip(mesh.pieces, brep.pieces):
        assert p.name == q.name and q.solid.isValid()
        # the mesh's circles are chords of the B-rep's (sag 0.004 mm: < 0.3 % on a 1.7 mm pin)
        assert_allclose(q.solid.Volume(), p.solid.volume(), rtol=3e-3)


@pytest.mark.parametrize("kw,name", [({"process": "injection"}, "process"),
                                     ({"shrinkage_pct": -1}, "shrinkage"),
                                     ({"clearance": 0.0}, "clearance"),
                                     ({"material": "pla"}, "material"),
                                     ({"parting": "y"}, "parting")])
def test_bad_mold_parameters(kw, name):
    with pytest.raises(ParameterError, match=f"^{name} = "):
        MoldSpec(**kw)


@pytest.mark.slow
def test_mold_command_writes_every_piece(tmp_path, capsys):
    import json

    from spsc.cli.main import main

    out = tmp_path / "m"
    assert main(["mold", "--type", "B", "--process", "compression", "--out", str(out),
                 "--no-render"]) == 0
    info = json.loads((out / "mold.json").read_text())
    assert [p["role"] for p in info["pieces"]] == ["half", "half", "core"]
    for p in info["pieces"]:
        for kind in ("stl", "3mf", "step"):
            assert (out / f"{p['name']}.{kind}").stat().st_size > 1000
    assert info["gate"]["passed"] and (out / "gate.json").exists()
    assert info["parting"]["plane"].startswith("horizontal")
    assert set(info["channels_mm3"]) == {"flash_groove"}
    # the STL the slicer gets is the piece the gate measured
    from spsc.cad.meshload import load_mesh
    from spsc.cad.meshtopo import signed_volume

    v, f = load_mesh(out / "upper.stl")
    assert_allclose(signed_volume(v, f), info["pieces"][1]["volume_mm3"], rtol=1e-6)
    assert "MOLD PASSED" in capsys.readouterr().out


@pytest.mark.slow
def test_mold_of_a_bladder_file(tmp_path):
    from spsc.cli.main import main

    assert main(["bladder", "--type", "C", "--out", str(tmp_path / "b"), "--no-check"]) == 0
    assert main(["mold", str(tmp_path / "b" / "bladder-C.stl"), "--out", str(tmp_path / "m"),
                 "--no-step", "--no-render"]) == 0
    import json

    info = json.loads((tmp_path / "m" / "mold.json").read_text())
    assert info["bladder"]["geometry"]["n2"] == 1.0


def test_a_moved_mold_folder_reads_back_from_anywhere(tmp_path, monkeypatch):
    """mold.json names its files relative to its own folder: written with an absolute --out,
    moved, and read from another directory, every piece is found and is the piece it lists."""
    import json
    import shutil

    from spsc.cad.meshload import load_mesh
    from spsc.cad.meshtopo import signed_volume
    from spsc.cad.mold.export import read_mold, write_mold

    monkeypatch.chdir(tmp_path)
    write_mold(_mold("B"), None, tmp_path / "a")
    raw = json.loads((tmp_path / "a" / "mold.json").read_text())
    assert all("/" not in f for p in raw["pieces"] for f in p["files"].values())
    shutil.move(tmp_path / "a", tmp_path / "b")
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    info = read_mold(tmp_path / "b")
    files = [f for p in info["pieces"] for f in p["files"].values()]
    files += [info["part_in_mold"]["file"], info["assembly"]]
    assert len(files) == 8 and all(Path(f).is_file() for f in files)
    for p in info["pieces"]:
        v, f = load_mesh(p["files"]["stl"])
        assert_allclose(abs(signed_volume(v, f)), p["volume_mm3"], rtol=1e-6)


@pytest.mark.parametrize("text, needle", [
    ("[1, 2]", "design = '{p}' is invalid: allowed a JSON object (this file holds a JSON array)"),
    ('"x"', "a JSON object (this file holds a JSON string)"),
    ('{"kind": "bladder", "geometry": [1]}', "geometry = [1] is invalid"),
    ('{"kind": "bladder", "geometry": {"w": 11}}', "geometry = {'w': 11} is invalid"),
    ('{"kind": "bladder", "genus": "4", "geometry": {"w": 11, "h": 13, "l": 3, "t0": 1, '
     '"n1": 2, "n2": 2.2, "cy": 0.6}}', "genus = '4' is invalid"),
    ('{"kind": "fingertip"}', "a bladder's design file"),
])
def test_mold_of_a_bad_design_file_is_one_line(tmp_path, capsys, text, needle):
    from spsc.cli.main import main

    (tmp_path / "p.stl").write_text("solid x\nendsolid x\n")
    design = tmp_path / "p.design.json"
    design.write_text(text)
    assert main(["mold", str(tmp_path / "p.stl"), "--out", str(tmp_path / "m")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle.replace("{p}", str(design)) in err[0], err
    assert not (tmp_path / "m").exists()


def test_read_mold_refuses_what_is_not_a_mold(tmp_path):
    from spsc.cad.mold.export import read_mold

    (tmp_path / "mold.json").write_text('{"pieces": 3}')
    with pytest.raises(ParameterError, match="^mold = .* a mold.json written by spsc mold"):
        read_mold(tmp_path)
