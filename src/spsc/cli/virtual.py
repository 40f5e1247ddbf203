"""``spsc virtual``: chambers inside a robot simulator, headless (issue 50).

    spsc virtual SCENE.toml --out DIR [--video] [--cache DIR] [--quiet]

SCENE.toml is a scenario of ``spsc simulate`` (its ``[chamber]``, ``[circuit]`` with the valve,
gas and sensor, timed ``[[events]]``) with a ``[scene]`` table naming the MuJoCo scene
(:mod:`spsc.virtual.scene`): ``kind = "plate"`` (a plate pressing one pad, by a force ``[press]
force`` or along a travel ``[press] profile``) or ``kind = "gripper"`` (two jaws with SPSC pads
grasping an ``[object]`` along a ``[grasp]``). The pads step on their map every MuJoCo step and
push back. Writes DIR/trace.parquet (t_s, valve_open and per pad i travel_mm_i, force_N_i,
pressure_kPa_i, sensor_kPa_i, ...), DIR/trace.png, DIR/scene.json and with ``--video``
DIR/scene.mp4 (rendered offscreen). ``spsc sense DIR/trace.parquet --pressure-column
sensor_kPa_1 ...`` reads a pad's trace back. MuJoCo is the optional extra ``pip install
spsc[sim]`` (``make``'s environment has it). Exit 0; 1 when the scene stopped early (the
trace so far written); 2 on invalid input (one line on stderr).
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from spsc.cli.options import add_quiet_option, check_output_dir
from spsc.core.errors import ParameterError

__all__ = ["register", "run"]

#: frames per second of --video
FPS = 30


def register(subparsers) -> None:
    p = subparsers.add_parser("virtual", help="chambers inside a MuJoCo scene (a plate, a "
                              "two-finger gripper), headless: their force on the scene, their "
                              "sensors' traces", description=__doc__.split("\n\n")[0])
    p.add_argument("scene", metavar="SCENE.toml", help="a scenario of spsc simulate with a "
                   "[scene] table (kind = \"plate\" | \"gripper\")")
    p.add_argument("--out", required=True, metavar="DIR", help="trace.parquet, trace.png, "
                   "scene.json (and scene.mp4) here")
    p.add_argument("--video", action="store_true", help="render the scene offscreen to "
                   f"DIR/scene.mp4 ({FPS} frames per second of scene)")
    p.add_argument("--cache", metavar="DIR", default=None, help="where wall-model maps are "
                   "kept (default: spsc-cache beside --out)")
    add_quiet_option(p)
    p.set_defaults(func=run)


def run(args) -> int:
    from spsc.dynamics.circuit import Circuit
    from spsc.dynamics.simulate import chamber_map_for
    from spsc.virtual.chambers import VirtualChambers
    from spsc.virtual.gripper import SceneStopped, mujoco_module
    from spsc.virtual.scene import read_scene

    scene = read_scene(args.scene)
    out = Path(check_output_dir("--out", args.out))
    if args.cache is not None:
        check_output_dir("--cache", args.cache)
    if args.video:  # offscreen, no display: EGL unless the user picked a backend
        os.environ.setdefault("MUJOCO_GL", "egl")
    mujoco_module()  # the extra: refused before any work when missing
    video = _Video(out / "scene.mp4") if args.video else None
    sc = scene.scenario
    cache = Path(args.cache) if args.cache else out.absolute().parent / "spsc-cache"
    t0 = time.perf_counter()
    m = chamber_map_for(sc, cache_dir=cache)
    count = 2 if scene.kind == "gripper" else 1
    from spsc.dynamics.simulate import leak_valve

    pads = VirtualChambers(m, Circuit(sc.setup_kPa, sc.reservoir_mm3, sc.valve, sc.gas,
                                      leak_valve(sc, m)), count=count, sensor=sc.sensor, y0_mm=m.y_range[0],
                           valve_open=sc.valve_open)
    t_map = time.perf_counter() - t0
    stopped = None
    try:
        trace = _run(scene, pads, video)
    except SceneStopped as exc:
        trace, stopped = exc.trace, str(exc)
    finally:
        if video is not None:
            video.close()
    seconds = time.perf_counter() - t0 - t_map
    out.mkdir(parents=True, exist_ok=True)
    _write(scene, trace, out, {"map_s": t_map, "scene_s": seconds, "stopped": stopped,
                               "source": str(args.scene)})
    if stopped:
        print(f"spsc virtual: stopped: {stopped}; the trace so far is in {out}",
              file=sys.stderr)
        return 1
    if not args.quiet:
        print(_summary(scene, trace, seconds, t_map))
        print(f"written: {out / 'trace.parquet'}, {out / 'trace.png'}, {out / 'scene.json'}"
              + (f", {out / 'scene.mp4'}" if video else ""))
    return 0


def _run(scene, pads, video) -> dict:
    from spsc.dynamics.profile import PressProfile
    from spsc.virtual.gripper import run_gripper
    from spsc.virtual.plate import press_plate

    sc = scene.scenario
    frame = video.frame if video else None
    if scene.kind == "gripper":
        g = sc.chamber.geometry()
        return run_gripper(pads, scene.obj, scene.grasp, pad_mm=(g.h, g.w, g.w + g.l),
                           valve_events=sc.events, frame=frame, fps=FPS, dt=sc.dt)
    if isinstance(sc.press, PressProfile):
        return press_plate(pads, 0.0, sc.press.duration, valve_events=sc.events,
                           travel_mm=lambda t: float(sc.press.y(t)), dt=sc.dt, frame=frame,
                           fps=FPS)
    return press_plate(pads, lambda t: float(sc.press.force(t)), sc.press.duration,
                       valve_events=sc.events, dt=sc.dt, frame=frame, fps=FPS)


_PROBE = '<mujoco><visual><global offwidth="640" offheight="480"/></visual></mujoco>'


class _Video:
    """Frames rendered offscreen (MuJoCo's renderer) into an MP4 (imageio-ffmpeg)."""

    def __init__(self, path: Path, size=(640, 480)):
        try:
            import imageio_ffmpeg
        except ImportError:
            raise ParameterError("--video", "imageio-ffmpeg", "the sim extra installed (pip "
                                 "install spsc[sim])") from None
        self.path, self.size, self._renderer, self._writer = path, size, None, None
        self._ffmpeg = imageio_ffmpeg
        self._renderer_for(_PROBE).close()  # refused before the scene runs, not at its end

    def _renderer_for(self, model):
        mj = sys.modules["mujoco"]
        if isinstance(model, str):
            model = mj.MjModel.from_xml_string(model)
        try:
            return mj.Renderer(model, self.size[1], self.size[0])
        except Exception as exc:  # no OpenGL context here
            raise ParameterError("--video", "offscreen rendering", "an OpenGL context (EGL "
                                 "or OSMesa: MUJOCO_GL=egl|osmesa; "
                                 f"{str(exc)[:60]})") from None

    def frame(self, model, data) -> None:
        mj = sys.modules["mujoco"]
        if self._renderer is None:
            self._renderer = self._renderer_for(model)
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._writer = self._ffmpeg.write_frames(str(self.path), self.size, fps=FPS,
                                                     macro_block_size=1)
            self._writer.send(None)
        cam = mj.mj_name2id(model, mj.mjtObj.mjOBJ_CAMERA, "side")
        self._renderer.update_scene(data, camera=cam if cam >= 0 else -1)
        self._writer.send(self._renderer.render().tobytes())

    def close(self) -> None:
        if self._writer is not None:
            self._writer.close()
        if self._renderer is not None:
            self._renderer.close()


def _summary(scene, trace, seconds, t_map) -> str:
    d = scene.duration_s
    head = (f"spsc virtual: {scene.kind} scene, {d:g} s in {seconds:.1f} s "
            f"({d / max(seconds, 1e-9):.2f}x real time; the map {t_map:.1f} s)")
    if scene.kind == "plate":
        return (head + f"; at the end: travel {trace['travel_mm_1'][-1]:.3f} mm, force "
                f"{trace['force_N_1'][-1]:.3f} N, pressure {trace['pressure_kPa_1'][-1]:.2f} kPa "
                f"(read {trace['sensor_kPa_1'][-1]:.2f})")
    f = trace["force_N_1"] + trace["force_N_2"]
    slip = trace["slipping_1"].astype(bool) | trace["slipping_2"].astype(bool)
    return (head + f"; grip force up to {f.max() / 2:.2f} N per pad, the object lifted "
            f"{trace['object_z_mm'].max():.1f} mm, slipping {slip.mean() * 100:.0f} % of "
            f"the time, pad 1 up to {trace['pressure_kPa_1'].max():.2f} kPa")


def _write(scene, trace: dict, out: Path, info: dict) -> None:
    import pandas as pd

    from spsc.core.jsonio import write_json
    from spsc.core.provenance import provenance

    pd.DataFrame(trace).to_parquet(out / "trace.parquet", index=False)
    sc, code = scene.scenario, provenance()
    write_json(out / "scene.json", {
        "kind": scene.kind, "duration_s": scene.duration_s, "chamber": dict(sc.chamber.params),
        "material": sc.chamber.material, "model": sc.chamber.model, "setup_kPa": sc.setup_kPa,
        "reservoir_mm3": sc.reservoir_mm3, "valve_events": [list(e) for e in sc.events],
        "object": None if scene.obj is None else {
            "shape": scene.obj.shape, "size_mm": list(scene.obj.size_mm),
            "mass_g": scene.obj.mass_g,
            "stiffness_N_per_mm": scene.obj.contact.object_N_per_mm,
            "friction": scene.obj.contact.mu}, **info,
        "code": {"commit": code.commit, "clean": code.clean, "describe": code.describe()}})
    from spsc.virtual.figure import scene_figure

    scene_figure(scene.kind, trace, out / "trace.png")
