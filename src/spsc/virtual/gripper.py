"""A two-finger gripper whose pads are SPSCs, in MuJoCo (issue 50): the jaws close on an object
resting on a table, lift it, hold it (a valve switched mid-grasp softens the pads), put it down
and open. Each pad is a :class:`~spsc.virtual.chambers.VirtualChambers` chamber on its map; its
contact with the object is computed outside MuJoCo's solver (:mod:`spsc.virtual.contact`: the
pad in series with the object's own stiffness, Coulomb friction with a stuck contact's shear
stiffness) and applied to the object and the jaw as forces at the contact point every step
(``mj_applyFT`` into ``qfrc_applied``, the route MuJoCo's documentation gives for forces from
outside its solver). MuJoCo integrates the bodies: the object's weight and inertia, its contact
with the table, the jaws and the lift on position servos.

MuJoCo is the optional extra ``pip install spsc[sim]``; this module imports it only when a scene
runs. Units at the edges: mm, N, s, g; MuJoCo works in SI.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError, require

from .contact import friction, series_travel
from .objects import GraspObject

__all__ = ["Grasp", "gripper_xml", "run_gripper", "mujoco_module", "SceneStopped"]


class SceneStopped(RuntimeError):
    """The scene could not go on (a pad pressed past its map); the trace so far is kept in
    ``trace``."""

    def __init__(self, message: str, trace: dict):
        super().__init__(message)
        self.trace = trace


def mujoco_module():
    try:
        import mujoco
    except ImportError:
        raise ParameterError("scene", "mujoco", "the MuJoCo extra installed (pip install "
                             "spsc[sim]; make's environment has it)") from None
    return mujoco


def _knots(name, value):
    try:
        pts = np.asarray(value, float)
    except (TypeError, ValueError):
        pts = np.empty(0)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 1 or not np.isfinite(pts).all():
        raise ParameterError(name, value, "[[t_s, mm], ...] knots, times rising from 0")
    if pts[0, 0] != 0 or np.any(np.diff(pts[:, 0]) <= 0):
        raise ParameterError(name, value, "knots whose times rise strictly from 0 s")
    return tuple(map(tuple, pts))


@dataclass(frozen=True)
class Grasp:
    """The gripper's motion: the distance between the pads' faces ``opening_mm`` and the lift
    of the hand above its start ``lift_mm``, each [t_s, mm] knots (piecewise linear, held after
    the last), over ``duration_s``; the jaws' and the lift's position servos ``jaw_kp_N_per_mm``
    and ``lift_kp_N_per_mm`` (N/mm)."""

    opening_mm: tuple = ((0.0, 60.0), (0.5, 60.0), (1.0, 24.0))
    lift_mm: tuple = ((0.0, 0.0), (1.2, 0.0), (1.7, 30.0))
    duration_s: float = 3.0
    jaw_kp_N_per_mm: float = 100.0
    lift_kp_N_per_mm: float = 20.0

    def __post_init__(self):
        object.__setattr__(self, "opening_mm", _knots("grasp.opening_mm", self.opening_mm))
        object.__setattr__(self, "lift_mm", _knots("grasp.lift_mm", self.lift_mm))
        require("grasp.duration_s", self.duration_s, gt=0, le=600, unit="s")
        for t, v in self.opening_mm:
            require("grasp.opening_mm", v, ge=0, le=500, unit="mm")
        for t, v in self.lift_mm:
            require("grasp.lift_mm", v, ge=-50, le=500, unit="mm")
        require("grasp.jaw_kp_N_per_mm", self.jaw_kp_N_per_mm, gt=0, le=1e4, unit="N/mm")
        require("grasp.lift_kp_N_per_mm", self.lift_kp_N_per_mm, gt=0, le=1e4, unit="N/mm")

    def at(self, t: float) -> tuple[float, float]:
        """(opening, lift) commanded at ``t`` (mm)."""
        o, lf = np.asarray(self.opening_mm), np.asarray(self.lift_mm)
        return float(np.interp(t, o[:, 0], o[:, 1])), float(np.interp(t, lf[:, 0], lf[:, 1]))


def gripper_xml(obj: GraspObject, pad_mm: tuple, grasp: Grasp, dt: float = 1e-3) -> str:
    """The scene's MJCF: the table, the object at rest on it, the hand (a lift on a vertical
    slide carrying two jaws on horizontal slides, each with a pad of ``pad_mm`` = (depth,
    width, height) whose face is the jaw's origin) at the object's mid-height. Only the object
    and the table collide in MuJoCo; the pads act through applied forces."""
    d, w, h = (1e-3 * v for v in pad_mm)
    zc = 1e-3 * obj.half_height_mm
    jaw_m, base_m = 0.2, 0.5
    jaw_kp, lift_kp = 1e3 * grasp.jaw_kp_N_per_mm, 1e3 * grasp.lift_kp_N_per_mm
    jaw_c, lift_c = 1.6 * (jaw_kp * jaw_m) ** 0.5, 1.6 * (lift_kp * (base_m + 2 * jaw_m)) ** 0.5
    no = 'contype="0" conaffinity="0"'

    def jaw(i, side):
        return f"""
      <body name="jaw_{i}" pos="0 0 0" gravcomp="1">
        <joint name="jaw_{i}" type="slide" axis="1 0 0" damping="{jaw_c:.4g}"/>
        <geom name="pad_{i}" type="box" size="{d / 2:g} {w / 2:g} {h / 2:g}"
              pos="{-side * d / 2:g} 0 0" mass="0.005" {no} rgba="0.25 0.55 0.95 0.85"/>
        <geom type="box" size="0.006 {w / 2 + 0.004:g} {h / 2 + 0.006:g}"
              pos="{-side * (d + 0.006):g} 0 0.004" mass="{jaw_m:g}" {no} rgba="0.3 0.3 0.35 1"/>
      </body>"""

    return f"""
<mujoco model="spsc-gripper">
  <option timestep="{dt:g}" gravity="0 0 -9.81" integrator="implicitfast"/>
  <visual>
    <global offwidth="960" offheight="720"/>
    <headlight ambient="0.35 0.35 0.35" diffuse="0.5 0.5 0.5"/>
  </visual>
  <asset>
    <texture type="skybox" builtin="gradient" rgb1="0.93 0.94 0.96" rgb2="0.62 0.66 0.72"
             width="64" height="64"/>
  </asset>
  <worldbody>
    <light pos="0.1 -0.3 0.5" dir="-0.2 0.6 -0.8" diffuse="0.6 0.6 0.6"/>
    <camera name="side" pos="0.02 -0.17 {zc + 0.055:g}" xyaxes="1 0.1 0 0 0.2 1" fovy="45"/>
    <geom name="table" type="plane" size="0.3 0.3 0.01" rgba="0.85 0.85 0.82 1"/>
    <body name="hand" pos="0 0 {zc:g}" gravcomp="1">
      <joint name="lift" type="slide" axis="0 0 1" damping="{lift_c:.4g}"/>
      <geom type="box" size="0.05 0.012 0.006" pos="0 0 {h / 2 + 0.03:g}" mass="{base_m:g}"
            {no} rgba="0.3 0.3 0.35 1"/>{jaw(1, 1)}{jaw(2, -1)}
    </body>
    <body name="object" pos="0 0 {zc:g}">
      <freejoint/>
      {obj.mjcf_geom()}
    </body>
  </worldbody>
  <actuator>
    <position name="lift" joint="lift" kp="{lift_kp:g}"/>
    <position name="jaw_1" joint="jaw_1" kp="{jaw_kp:g}"/>
    <position name="jaw_2" joint="jaw_2" kp="{jaw_kp:g}"/>
  </actuator>
</mujoco>
"""


_COLUMNS = ("travel_mm", "overlap_mm", "force_N", "pad_force_N", "pressure_kPa",
            "sensor_kPa", "stiffness_N_per_mm", "slipping")


def run_gripper(pads, obj: GraspObject, grasp: Grasp, *, pad_mm: tuple, valve_events=(),
                frame=None, fps: float = 30.0, dt: float = 1e-3) -> dict:
    """Run the grasp: ``pads`` (two :class:`VirtualChambers`, the pads of jaws 1 and 2),
    the object ``obj``, the motion ``grasp``; ``valve_events`` ((t_s, open) pairs) switch both
    pads' valves; ``frame(model, data)`` is called ``fps`` times a second of scene (a renderer);
    ``dt`` the physics step (s).
    Returns the trace: ``t_s``, ``valve_open``, ``opening_mm`` (the jaws' faces apart),
    ``lift_mm``, ``object_z_mm`` (its centre's rise above its rest), and per pad i
    ``travel_mm_i`` (the pad's own travel past first contact), ``overlap_mm_i`` (the object's
    undeformed surface past the pad's face), ``force_N_i`` (the normal force applied),
    ``pad_force_N_i`` (the chamber's), ``pressure_kPa_i``, ``sensor_kPa_i`` (as read),
    ``stiffness_N_per_mm_i``, ``slipping_i``. Raises :class:`SceneStopped` (with the trace so
    far) when a pad would press past its map."""
    sim = _Hand(obj, grasp, pad_mm, dt)
    mj, model, data = sim.mj, sim.model, sim.data
    dt = model.opt.timestep
    c, (y_lo, y_hi) = obj.contact, pads.table.y_range
    state, valve, events = pads.read(), bool(pads.valve[0]), sorted(valve_events)
    anchor, was_touching, rows, frames = np.zeros((2, 2)), np.zeros(2, bool), [], 0
    for k in range(int(round(grasp.duration_s / dt))):
        t = k * dt
        while events and events[0][0] <= t + 1e-12:
            valve = bool(events.pop(0)[1])
        mj.mj_step1(model, data)  # positions and velocities at t; the forces go in before step2
        s = sim.overlaps(y_lo)
        y = _pad_travel(pads, s, c.object_N_per_mm, state, y_lo)
        if np.any(y > y_hi):
            i = int(np.argmax(y))
            raise SceneStopped(f"pad {i + 1} pressed {y[i]:.3g} mm at t = {t:.3f} s, past its "
                               f"map's {y_hi:.3g} mm: a wider opening or a deeper "
                               "press.max_travel_mm", _columns(rows))
        touching = s > 0
        # the dashpot acts on a contact that goes on (an edge sliding onto a pad is no impact)
        rate = np.where(touching & was_touching, (y - pads.y) / dt, 0.0)
        was_touching = touching
        state = pads.step(y, valve, dt)
        fpad = np.where(touching, state["force_N"], 0.0)
        fn = np.where(touching, np.maximum(fpad + 1e-3 * c.damping_N_s_per_m * rate, 0.0), 0.0)
        points, v_rel = sim.contact_points()
        ft, anchor, slipping = friction(anchor, v_rel, fn, dt, c)
        sim.apply(fn, ft, points)
        opening, lift = grasp.at(t)
        data.ctrl[:] = (1e-3 * lift, -0.5e-3 * opening, 0.5e-3 * opening)
        rows.append((t, valve, *sim.pose(), y, s, fn, fpad, state["pressure_kPa"],
                     state["measured_kPa"], state["stiffness_N_per_mm"], slipping & touching))
        if frame is not None and t + 1e-9 >= frames / fps:
            sim.squeeze_pads(y)  # drawn compressed by their travel
            frame(model, data)
            frames += 1
        mj.mj_step2(model, data)
    return _columns(rows)


def _pad_travel(pads, s, k_obj, state, y_lo):
    """The pads' travels at the overlaps ``s`` with the object's stiffness in series: the
    last step's linearisation, then Newton on F_pad(y) = k_o (s − y) (a contact that starts,
    the pad at rest with no stiffness, or a fast squeeze)."""
    y = series_travel(s, k_obj, pads.y, state["force_N"], state["stiffness_N_per_mm"], y_lo)
    for _ in range(4 if np.isfinite(k_obj) else 0):
        f, k = pads.force_at(y)
        y_next = series_travel(s, k_obj, y, f, k, y_lo)
        done = np.abs(y_next - y).max() < 1e-6
        y = y_next
        if done:
            break
    return y


class _Hand:
    """The MuJoCo model and data of the scene, and what the contact needs of them (mm)."""

    #: each pad pushes the object along its normal
    NORMAL = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]])

    def __init__(self, obj, grasp, pad_mm, dt):
        mj = self.mj = mujoco_module()
        self.model = mj.MjModel.from_xml_string(gripper_xml(obj, pad_mm, grasp, dt))
        self.data = mj.MjData(self.model)
        self.obj, self.half_h, self.depth = obj, 0.5 * pad_mm[2], 1e-3 * pad_mm[0]
        self.ids = {n: mj.mj_name2id(self.model, mj.mjtObj.mjOBJ_BODY, n)
                    for n in ("object", "jaw_1", "jaw_2")}
        o0, l0 = grasp.at(0.0)
        for i, side in ((1, -1), (2, 1)):
            j = mj.mj_name2id(self.model, mj.mjtObj.mjOBJ_JOINT, f"jaw_{i}")
            self.data.qpos[self.model.jnt_qposadr[j]] = side * 0.5e-3 * o0
        self.data.qpos[self.model.jnt_qposadr[0]] = 1e-3 * l0
        self._vel = np.zeros(6)
        mj.mj_forward(self.model, self.data)

    def _face(self, i):
        return 1e3 * self.data.xpos[self.ids[f"jaw_{i + 1}"]]

    def overlaps(self, y_lo) -> np.ndarray:
        """Each pad's overlap with the object's undeformed surface (mm); a pad above or
        below the object has none (``y_lo``)."""
        obj, d = self.obj, self.data
        self.cpos = 1e3 * d.xpos[self.ids["object"]]
        rot = d.xmat[self.ids["object"]].reshape(3, 3)
        up = obj.support_mm(rot, (0.0, 0.0, 1.0))
        s = np.empty(2)
        for i in range(2):
            face = self._face(i)
            s[i] = (face[0] - self.cpos[0]) * self.NORMAL[i, 0] + obj.support_mm(
                rot, -self.NORMAL[i])
            if abs(self.cpos[2] - face[2]) > self.half_h + up:
                s[i] = min(s[i], y_lo)
        return s

    def contact_points(self):
        """Each contact's point (mm, on the pad's face at the object's centre, within the
        pad) and the object's sliding velocity on the pad there (mm/s, in the face's plane)."""
        mj, body = self.mj, self.mj.mjtObj.mjOBJ_BODY
        points, v_rel, vel = [], np.zeros((2, 2)), self._vel
        mj.mj_objectVelocity(self.model, self.data, body, self.ids["object"], vel, 0)
        w, v = vel[:3].copy(), 1e3 * vel[3:]
        for i in range(2):
            face = self._face(i)
            p = np.array([face[0], self.cpos[1], np.clip(self.cpos[2], face[2] - self.half_h,
                                                         face[2] + self.half_h)])
            points.append(p)
            mj.mj_objectVelocity(self.model, self.data, body, self.ids[f"jaw_{i + 1}"], vel, 0)
            v_rel[i] = (v + np.cross(w, p - self.cpos) - 1e3 * vel[3:])[1:]
        return points, v_rel

    def apply(self, fn, ft, points) -> None:
        """The pads' normal ``fn`` and tangential ``ft`` forces (N) on the object at
        ``points``, and their reactions on the jaws."""
        mj, d, zero = self.mj, self.data, np.zeros(3)
        d.qfrc_applied[:] = 0.0
        for i in range(2):
            force = self.NORMAL[i] * fn[i] + np.array([0.0, ft[i, 0], ft[i, 1]])
            point = 1e-3 * points[i]
            mj.mj_applyFT(self.model, d, force, zero, point, self.ids["object"], d.qfrc_applied)
            mj.mj_applyFT(self.model, d, -force, zero, point, self.ids[f"jaw_{i + 1}"],
                          d.qfrc_applied)

    def squeeze_pads(self, y_mm) -> None:
        """Draw each pad compressed by its travel ``y_mm`` (its face moved back)."""
        for i, side in ((0, 1.0), (1, -1.0)):
            gid = self.mj.mj_name2id(self.model, self.mj.mjtObj.mjOBJ_GEOM, f"pad_{i + 1}")
            y = 1e-3 * min(max(float(y_mm[i]), 0.0), self.depth - 1e-4)
            self.model.geom_size[gid][0] = 0.5 * (self.depth - y)
            self.model.geom_pos[gid][0] = -side * (y + 0.5 * (self.depth - y))

    def pose(self) -> tuple:
        """(the jaws' faces apart, the hand's lift, the object's rise above its rest), mm."""
        d = self.data
        return (self._face(1)[0] - self._face(0)[0], 1e3 * d.qpos[self.model.jnt_qposadr[0]],
                1e3 * d.xpos[self.ids["object"]][2] - self.obj.half_height_mm)


def _columns(rows) -> dict:
    out = {k: np.array([r[j] for r in rows]) for j, k in
           enumerate(("t_s", "valve_open", "opening_mm", "lift_mm", "object_z_mm"))}
    for j, name in enumerate(_COLUMNS):
        col = np.array([r[5 + j] for r in rows]).reshape(len(rows), 2)
        for i in (0, 1):
            out[f"{name}_{i + 1}"] = col[:, i]
    return out
