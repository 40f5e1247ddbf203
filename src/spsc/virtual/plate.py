"""The simplest MuJoCo scene of a chamber (issue 50): a rigid plate on a vertical slide, pushed
by a force actuator onto an SPSC pad; the pad's force acts back on the plate every step (a
compliant contact as an applied force, which MuJoCo's documentation gives for forces computed
outside its solver: ``qfrc_applied``), and the pad's valve is switched by timed events.

MuJoCo is an optional extra (``pip install spsc[sim]``); it is imported here only, the core
never does. Units at the edges: mm, N, s; MuJoCo works in SI (m).
"""

from __future__ import annotations

import numpy as np

from .gripper import SceneStopped, mujoco_module

__all__ = ["PLATE_XML", "press_plate"]

#: a plate of 50 g on a frictionless vertical slide (z up, z = 0 at first contact with the
#: pad inflated at its setup pressure), damped (20 N s/m) so a press settles in a fraction of
#: a second, gravity off (the actuator's force is the press), 1 ms steps
PLATE_XML = """
<mujoco model="spsc-plate">
  <option timestep="{dt}" gravity="0 0 0" integrator="implicitfast"/>
  <asset>
    <texture type="skybox" builtin="gradient" rgb1="0.93 0.94 0.96" rgb2="0.62 0.66 0.72"
             width="64" height="64"/>
  </asset>
  <worldbody>
    <light pos="0 -0.2 0.3" dir="0 0.6 -0.8"/>
    <camera name="side" pos="0 -0.12 0.01" xyaxes="1 0 0 0 0 1" fovy="40"/>
    <geom name="pad" type="box" size="0.0055 0.0055 0.0065" pos="0 0 -0.0065"
          rgba="0.25 0.55 0.95 0.85" contype="0" conaffinity="0"/>
    <body name="plate" pos="0 0 0">
      <joint name="z" type="slide" axis="0 0 1" damping="20"/>
      <geom type="box" size="0.02 0.02 0.002" mass="0.05"/>
    </body>
  </worldbody>
  <actuator>{actuator}</actuator>
</mujoco>
"""
#: the press as a force (N) on the plate, or its travel on a position servo (20 N/mm: the
#: 50 g plate rings at 100 Hz, well inside a 1 ms step's stable range)
MOTOR = '<motor name="press" joint="z" gear="1"/>'
SERVO = '<position name="press" joint="z" kp="2e4" kv="40"/>'


def press_plate(chambers, force_N, t_end_s: float, *, valve_events=(), z0_mm: float = 0.5,
                travel_mm=None, dt: float = 1e-3, frame=None, fps: float = 30.0):
    """Run the plate scene: the actuator pushes down with ``force_N(t)`` (N, a number or a
    function of t s) — or, with ``travel_mm(t)`` (mm past first contact) given, a position
    servo drives the plate along it (``force_N`` unused) — the pad (chamber 0 of ``chambers``,
    :class:`~spsc.virtual.chambers.VirtualChambers`) pushes back with its force at the
    plate's travel; ``valve_events`` ((t_s, open) pairs) switch its valve. The plate starts
    ``z0_mm`` above first contact. Returns the trace: ``t_s``, ``valve_open``, and for the
    pad (chamber 1) ``travel_mm_1`` (the plate's travel past first contact), ``force_N_1``,
    ``pressure_kPa_1``, ``sensor_kPa_1`` (as read), ``stiffness_N_per_mm_1``. Raises
    :class:`~spsc.virtual.gripper.SceneStopped` (the trace so far kept) when the plate
    presses past the pad's map. ``dt``: the physics step (s); ``frame(model, data)`` is called
    ``fps`` times a second of scene (a renderer)."""
    mj = mujoco_module()
    model = mj.MjModel.from_xml_string(PLATE_XML.format(
        actuator=MOTOR if travel_mm is None else SERVO, dt=f"{dt:g}"))
    data = mj.MjData(model)
    data.qpos[0] = z0_mm * 1e-3
    dt = model.opt.timestep
    push = force_N if callable(force_N) else (lambda t, f=float(force_N): f)
    events = sorted(valve_events)
    valve = bool(chambers.valve[0])
    y_lo, y_hi = chambers.table.y_range
    rows, frames = [], 0
    for k in range(int(round(t_end_s / dt))):
        t = k * dt
        while events and events[0][0] <= t + 1e-12:
            valve = bool(events.pop(0)[1])
        mj.mj_step1(model, data)
        y = -data.qpos[0] * 1e3  # mm pressed past first contact
        if y > y_hi:
            raise SceneStopped(f"the plate pressed {y:.3g} mm at t = {t:.3f} s, past the "
                               f"pad's map ({y_hi:.3g} mm): a smaller force or a deeper "
                               "press.max_travel_mm", _columns(rows))
        out = chambers.step(max(y, y_lo), valve, dt)
        f = float(out["force_N"][0]) if y > y_lo else 0.0
        data.qfrc_applied[0] = f  # the pad pushes the plate up
        data.ctrl[0] = -push(t) if travel_mm is None else -1e-3 * float(travel_mm(t))
        rows.append((t, valve, y, f, out["pressure_kPa"][0], out["measured_kPa"][0],
                     out["stiffness_N_per_mm"][0]))
        if frame is not None and t + 1e-9 >= frames / fps:
            gid = mj.mj_name2id(model, mj.mjtObj.mjOBJ_GEOM, "pad")  # drawn compressed
            h = 0.0065 - 0.5e-3 * min(max(y, 0.0), 12.0)
            model.geom_size[gid][2], model.geom_pos[gid][2] = h, -0.013 + h
            frame(model, data)
            frames += 1
        mj.mj_step2(model, data)
    return _columns(rows)


def _columns(rows) -> dict:
    names = ("t_s", "valve_open", "travel_mm_1", "force_N_1", "pressure_kPa_1",
             "sensor_kPa_1", "stiffness_N_per_mm_1")
    return {k: np.array([r[j] for r in rows], bool if k == "valve_open" else float)
            for j, k in enumerate(names)}
