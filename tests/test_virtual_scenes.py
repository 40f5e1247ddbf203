"""Virtual scenes in MuJoCo (issue 50): the pads' contact with an object (series spring,
Coulomb with a stuck contact), the objects' extents, the plate scene against spsc curve and
spsc simulate, the gripper holding, slipping and switching, scene files refused in one line."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

from spsc.core.errors import ParameterError
from spsc.virtual.contact import PadContact, friction, series_travel
from spsc.virtual.objects import GraspObject

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "examples" / "scenes"


def test_series_travel_of_a_linear_pad_is_the_springs_in_series():
    """F = K y against an object k_o: y = k_o s / (K + k_o) exactly (the linearisation is
    exact for a linear pad), the object's indentation s - y carries the same force."""
    K, ko, s = 3.0, 1.5, np.array([0.5, 2.0, -1.0])
    y = series_travel(s, ko, y0_mm=0.7, f0_N=K * 0.7, k_pad=K, y_lo_mm=-2.0)
    assert_allclose(y[:2], ko * s[:2] / (K + ko), rtol=1e-14)
    assert_allclose(K * y[:2], ko * (s[:2] - y[:2]), rtol=1e-14)
    assert y[2] == -1.0  # no overlap: the pad's own travel
    assert_allclose(series_travel(s, math.inf, 0.0, 0.0, K, -2.0), s)  # rigid
    assert series_travel(-5.0, ko, 0.0, 0.0, K, -2.0) == -2.0  # the map's top


def test_friction_sticks_below_the_cap_and_slips_at_it():
    c = PadContact(mu=0.5, shear_N_per_mm=4.0)
    ft, d, slip = friction(np.zeros((1, 2)), [[0.0, 1.0]], [10.0], 0.1, c)  # 0.1 mm
    assert_allclose(ft, [[0.0, -0.4]], rtol=1e-14)
    assert not slip[0]
    ft, d, slip = friction(d, [[0.0, 20.0]], [10.0], 0.1, c)  # 2.1 mm: 8.4 N > 5 N
    assert slip[0]
    assert_allclose(ft, [[0.0, -5.0]], rtol=1e-14)
    assert_allclose(np.linalg.norm(d), 5.0 / 4.0, rtol=1e-14)  # the anchor slid
    ft, d, slip = friction(d, [[0.0, 0.0]], [0.0], 0.1, c)  # lifted off: reset
    assert_allclose(d, 0.0)
    assert not slip[0]


def test_object_extents_turn_with_the_object():
    box = GraspObject("box", (30, 20, 40))
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # 90° about z
    assert box.support_mm(np.eye(3), (1, 0, 0)) == 15.0
    assert box.support_mm(turn, (1, 0, 0)) == 10.0
    diag = np.array([1.0, 1.0, 0.0]) / math.sqrt(2)
    assert_allclose(box.support_mm(np.eye(3), diag), (15 + 10) / math.sqrt(2), rtol=1e-14)
    cyl = GraspObject("cylinder", (20, 50))
    tilt = np.array([[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]])  # axis along x
    assert cyl.support_mm(np.eye(3), (1, 0, 0)) == 10.0
    assert_allclose(cyl.support_mm(tilt, (1, 0, 0)), 25.0, rtol=1e-14)
    assert GraspObject("sphere", (24,)).half_height_mm == 12.0


@pytest.mark.parametrize("kwargs, says", [
    ({"shape": "cone"}, "object.shape"), ({"size_mm": (30, 30)}, "object.size_mm"),
    ({"mass_g": -1}, "object.mass_g"), ({"size_mm": (30, 30, 1e4)}, "object.size_mm (z)")])
def test_a_bad_object_is_one_line(kwargs, says):
    with pytest.raises(ParameterError, match=says.replace("(", r"\(").replace(")", r"\)")):
        GraspObject(**kwargs)


# -- the scenes in MuJoCo ------------------------------------------------------------------

mujoco = pytest.importorskip("mujoco", reason="the sim extra (make installs it)")


def _dome(path, tmp_path) -> Path:
    """The example with the Type D dome on the surrogate's map (the wall model's stadium map
    takes ~18 s to build; bench/bench_virtual_scenes.py runs the example itself)."""
    scene = tmp_path / Path(path).name
    scene.write_text(Path(path).read_text().replace('model = "wall"', 'model = "surrogate"\nl = 0'))
    return scene


def _run(path, tmp_path, *extra):
    from spsc.cli.main import main

    out = tmp_path / (Path(path).stem + "-out")
    assert main(["virtual", str(path), "--out", str(out), "--quiet",
                 "--cache", str(tmp_path / "cache"), *extra]) == 0
    import pandas as pd

    return pd.read_parquet(out / "trace.parquet"), json.loads((out / "scene.json").read_text())


@pytest.mark.slow
def test_the_plate_scene_is_the_static_curve_and_simulates_switch(tmp_path):
    """Pressed slowly along a travel profile (isothermal, valve closed), the pad's force and
    pressure at the plate's travel are spsc curve's (the same surrogate) within 1 % of the
    curve's largest force and of its pressure rise; the valve opened under load settles where
    spsc simulate's integrator, driven along the plate's own travel, settles (0.5 %)."""
    from spsc.cli.main import main
    from spsc.dynamics.profile import PressProfile
    from spsc.dynamics.simulate import simulate
    from spsc.virtual.scene import read_scene

    df, info = _run(SCENES / "plate-profile.toml", tmp_path)
    assert info["kind"] == "plate" and info["stopped"] is None
    assert main(["curve", "--model", "surrogate", "--type", "B", "--l", "0", "--pressure", "40",
                 "--stroke", "4", "--points", "17", "--json", str(tmp_path / "c.json"),
                 "--quiet"]) == 0
    c = json.loads((tmp_path / "c.json").read_text())["curve"]
    curve = type("C", (), {k: np.asarray(c[k]) for k in ("y_mm", "force_N", "pressure_kPa")})
    press = (df.t_s > 0.6) & (df.t_s < 8.5) & (df.travel_mm_1 > 0.25)
    y = df.travel_mm_1[press].to_numpy()
    f = np.interp(y, curve.y_mm, curve.force_N)
    p = np.interp(y, curve.y_mm, curve.pressure_kPa)
    assert_allclose(df.force_N_1[press], f, rtol=0, atol=0.01 * curve.force_N.max())
    rise = curve.pressure_kPa.max() - 40.0
    assert_allclose(df.pressure_kPa_1[press], p, rtol=0, atol=0.01 * rise)
    sc = read_scene(SCENES / "plate-profile.toml").scenario
    knots = df.iloc[::10]
    travel = np.maximum(knots.travel_mm_1, 0.0)  # above the pad: no contact either way
    sc = dataclasses.replace(sc, press=PressProfile.of(list(zip(knots.t_s, travel))))
    sim = simulate(sc, cache_dir=tmp_path / "cache").trace
    assert df.valve_open.iloc[-1] and not df.valve_open.iloc[8000]
    t_end = float(knots.t_s.iloc[-1])
    settled = float(np.interp(t_end, sim.t_s, sim.pressure_kPa))
    assert_allclose(df.pressure_kPa_1[df.t_s <= t_end].iloc[-1], settled, rtol=5e-3)


def test_the_gripper_holds_its_object_by_friction(tmp_path):
    """Lifted and held: the object rises with the hand, both pads push alike and the
    friction carries its weight (m g within 1 %: the stuck contact has settled); the valve
    opened mid-hold drops both pads' pressure and force."""
    df, info = _run(_dome(SCENES / "gripper-soft.toml", tmp_path), tmp_path)
    held = (df.t_s > 2.7) & (df.t_s < 2.85)
    assert_allclose(df.object_z_mm[held], df.lift_mm[held], atol=0.5)
    assert_allclose(df.force_N_1[held], df.force_N_2[held], rtol=1e-6)
    before, after = (df.t_s > 2.1) & (df.t_s < 2.2), held
    assert df.pressure_kPa_1[after].mean() < df.pressure_kPa_1[before].mean() - 1.0
    assert df.force_N_1[after].mean() < df.force_N_1[before].mean()
    assert not df.slipping_1.any() and not df.slipping_2.any()
    assert info["object"]["mass_g"] == 50


def test_a_heavy_slippery_object_slips_out(tmp_path):
    """Twice the weight the pads' friction can carry: the slip is flagged, the object stays
    behind the rising hand."""
    text = _dome(SCENES / "gripper-soft.toml", tmp_path).read_text().replace("mass_g = 50",
                                                                              "mass_g = 400") \
        .replace("friction = 0.8", "friction = 0.05")
    scene = tmp_path / "slip.toml"
    scene.write_text(text)
    df, _ = _run(scene, tmp_path)
    up = (df.t_s > 1.5) & (df.t_s < 1.8)  # the hand rising, the object left behind
    assert df.slipping_1[up].all() and df.slipping_2[up].all()
    assert (df.lift_mm - df.object_z_mm)[(df.t_s > 1.9) & (df.t_s < 2.9)].min() > 25.0


@pytest.mark.parametrize("change, says", [
    (("[[events]]\nt = 2.2", "[[events]]\nt = 9.0"), "events[0].t"),
    (('type = "D"', 'design = "missing.design.json"'), "design"),
    (('model = "wall"', 'model = "surrogate"\nl = 4'), "chamber.l"),  # l/w 4/11: none
    (('shape = "box"', 'shape = "torus"'), "object.shape"),
    (("duration_s = 4.5", "duration_s = 4.5\nspeed = 2"), "grasp.speed"),
    (("[object]", "[press]\nforce = [[0, 1]]\n[object]"), "[press]"),
    (("duration_s = 4.5", "duration_s = 4.5\n[output]\ndt = 0.01"), "output.dt")])
def test_a_bad_scene_is_refused_in_one_line_before_it_runs(tmp_path, capsys, change, says):
    from spsc.cli.main import main

    bad = tmp_path / "bad.toml"
    bad.write_text((SCENES / "gripper-soft.toml").read_text().replace(*change))
    assert main(["virtual", str(bad), "--out", str(tmp_path / "w")]) == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "w").exists()


def test_a_scene_that_presses_past_the_map_stops_and_keeps_its_trace(tmp_path, capsys):
    from spsc.cli.main import main

    text = _dome(SCENES / "gripper-soft.toml", tmp_path).read_text().replace(
        "[1.0, 25], [3.6, 25]", "[1.0, 12], [3.6, 12]")
    scene = tmp_path / "deep.toml"
    scene.write_text(text)
    assert main(["virtual", str(scene), "--out", str(tmp_path / "w"), "--quiet"]) == 1
    assert "past its map" in capsys.readouterr().err
    import pandas as pd

    assert len(pd.read_parquet(tmp_path / "w" / "trace.parquet")) > 100


def test_a_scene_takes_its_chamber_from_a_design_file(tmp_path):
    """[chamber] design = FILE (beside the scene file): the design's seven parameters, and
    the material of spsc design's design.json unless the scene names one."""
    from spsc.cad.geometry import PARAMS, preset
    from spsc.virtual.scene import read_scene

    dome = preset("C", l=0)
    (tmp_path / "designs").mkdir()
    (tmp_path / "designs" / "design.json").write_text(json.dumps({
        "schema": "spsc.design", "schema_version": 1,
        "best": {"trial": 3, "params": {**dome.as_dict(), "material": "elastic50a",
                                        "pressure": 25.0, "reservoir": 0.0}}}))
    text = (SCENES / "gripper-soft.toml").read_text().replace(
        'type = "D"\nmaterial = "tpu60a"\nmodel = "wall"',
        'design = "designs/design.json"\nmodel = "surrogate"')
    (tmp_path / "s.toml").write_text(text)
    sc = read_scene(tmp_path / "s.toml").scenario
    assert {k: getattr(sc.chamber.geometry(), k) for k in PARAMS} == dome.as_dict()
    assert sc.chamber.material == "elastic50a"
    (tmp_path / "t.toml").write_text(text.replace('model = "surrogate"',
                                                  'model = "surrogate"\nmaterial = "tpu60a"'))
    assert read_scene(tmp_path / "t.toml").scenario.chamber.material == "tpu60a"


def test_the_video_is_an_mp4_of_the_scene_or_one_line_without_opengl(tmp_path):
    """--video (a fresh process, as a user runs it: MuJoCo picks its OpenGL backend when it
    is first imported): frames rendered offscreen at 30 per second of scene into an MP4 a
    player opens (its header, and its frame count read back by ffmpeg); without an OpenGL
    context the refusal is one line, before the scene runs."""
    import subprocess
    import sys

    scene = _dome(SCENES / "gripper-soft.toml", tmp_path)
    scene.write_text(scene.read_text().replace("duration_s = 4.5", "duration_s = 1.0")
                     .replace("t = 2.2", "t = 0.8"))
    spsc = Path(sys.executable).parent / "spsc"
    run = subprocess.run([str(spsc), "virtual", str(scene), "--out", str(tmp_path / "v"),
                          "--quiet", "--video"], capture_output=True, text=True)
    if run.returncode == 2:
        assert "--video" in run.stderr and len(run.stderr.strip().splitlines()) == 1
        assert not (tmp_path / "v").exists()
        pytest.skip(f"no OpenGL context here: {run.stderr.strip()}")
    assert run.returncode == 0, run.stderr
    mp4 = tmp_path / "v" / "scene.mp4"
    assert mp4.read_bytes()[4:8] == b"ftyp"
    import imageio_ffmpeg

    probe = subprocess.run([imageio_ffmpeg.get_ffmpeg_exe(), "-i", str(mp4), "-f", "null", "-"],
                           capture_output=True, text=True)
    frames = [ln for ln in probe.stderr.splitlines() if "frame=" in ln]
    assert frames and int(frames[-1].split("frame=")[1].split()[0]) == 30
