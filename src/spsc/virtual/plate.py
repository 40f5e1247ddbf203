"""The simplest MuJoCo scene of a chamber (issue 50): a rigid plate on a vertical slide, pushed
by a force actuator onto an SPSC pad; the pad's force acts back on the plate every step (a
compliant contact as an applied force, which MuJoCo's documentation gives for forces computed
outside its solver: ``qfrc_applied``), and the pad's valve is switched by timed events.

MuJoCo is an optional extra (``pip install spsc[sim]``); it is imported here only, the core
never does. Units at the edges: mm, N, s; MuJoCo works in SI (m).
"""

from __future__ import annotations

import numpy as np

from spsc.core.errors import ParameterError

__all__ = ["PLATE_XML", "press_plate"]

#: a plate of 50 g on a frictionless vertical slide (z up, z = 0 at first contact with the
#: pad inflated at its setup pressure), damped (20 N s/m) so a press settles in a fraction of
#: a second, gravity off (the actuator's force is the press), 1 ms steps
PLATE_XML = """
<mujoco model="spsc-plate">
  <option timestep="0.001" gravity="0 0 0" integrator="implicitfast"/>
  <worldbody>
    <body name="plate" pos="0 0 0">
      <joint name="z" type="slide" axis="0 0 1" damping="20"/>
      <geom type="box" size="0.02 0.02 0.002" mass="0.05"/>
    </body>
  </worldbody>
  <actuator><motor name="press" joint="z" gear="1"/></actuator>
</mujoco>
"""


def _mujoco():
    try:
        import mujoco
    except ImportError:
        raise ParameterError("scene", "mujoco", "the MuJoCo extra installed (pip install "
                             "spsc[sim]; make's environment has it)") from None
    return mujoco


def press_plate(chambers, force_N, t_end_s: float, *, valve_events=(), z0_mm: float = 0.5):
    """Run the plate scene: the actuator pushes down with ``force_N(t)`` (N, a number or a
    function of t s), the pad (chamber 0 of ``chambers``,
    :class:`~spsc.virtual.chambers.VirtualChambers`) pushes back with its force at the
    plate's travel; ``valve_events`` ((t_s, open) pairs) switch its valve. The plate starts
    ``z0_mm`` above first contact. Returns the trace: ``t_s``, ``y_mm`` (plate travel),
    ``force_N`` (the pad's), ``pressure_kPa``, ``measured_kPa``, ``valve_open``."""
    mj = _mujoco()
    model = mj.MjModel.from_xml_string(PLATE_XML)
    data = mj.MjData(model)
    data.qpos[0] = z0_mm * 1e-3
    dt = model.opt.timestep
    push = force_N if callable(force_N) else (lambda t, f=float(force_N): f)
    events = sorted(valve_events)
    valve = bool(chambers.valve[0])
    y_lo, y_hi = chambers.table.y_range
    rows = []
    for k in range(int(round(t_end_s / dt))):
        t = k * dt
        while events and events[0][0] <= t + 1e-12:
            valve = bool(events.pop(0)[1])
        y = -data.qpos[0] * 1e3  # mm pressed past first contact
        if y > y_hi:
            raise ParameterError("press", f"{y:.3g} mm", f"within the pad's map (at most "
                                 f"{y_hi:.3g} mm): a smaller force")
        out = chambers.step(max(y, y_lo), valve, dt)
        f = float(out["force_N"][0]) if y > y_lo else 0.0
        data.qfrc_applied[0] = f  # the pad pushes the plate up
        data.ctrl[0] = -push(t)
        mj.mj_step(model, data)
        rows.append((t + dt, y, f, out["pressure_kPa"][0], out["measured_kPa"][0], valve))
    cols = list(zip(*rows))
    return {"t_s": np.array(cols[0]), "y_mm": np.array(cols[1]), "force_N": np.array(cols[2]),
            "pressure_kPa": np.array(cols[3]), "measured_kPa": np.array(cols[4]),
            "valve_open": np.array(cols[5], bool)}
