"""Generated sensing logs for the tests and ``bench/bench_sense.py``: the time-domain circuit
(:func:`spsc.dynamics.circuit.integrate`) pressed along a profile, read by the paper's ELVH
sensor (:class:`spsc.dynamics.Sensor`), with what really happened (the true force, travel and
events) beside the log.

FSR readings are synthesised from the true force: a contact point at ``pos`` (0: fsr_1, the
base; 1: fsr_N, the tip) spreads the force over the N sensors with a Gaussian of width
``FSR_WIDTH`` (of the array), plus white noise of ``FSR_NOISE_N``. The finger's closure α
drives the press through the object: before contact the finger approaches; after it the
chamber takes ``share`` of the closure's travel ``lever_mm_per_deg`` (1 for a rigid object,
less for a soft one that takes the rest).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from spsc.dynamics import Gas, Sensor, Valve, sonic_conductance
from spsc.dynamics.circuit import Circuit, integrate
from spsc.dynamics.profile import PressProfile, SpringProfile
from spsc.sensing.table import RINGING_N

__all__ = ["Trial", "run", "press", "slip_press", "grasp", "fsr_columns", "APPROACH_MM"]

FSR_WIDTH, FSR_NOISE_N, FSR_COUNT = 0.2, 0.01, 5
#: the plate starts this far above first contact (mm)
APPROACH_MM = 0.3


@dataclass
class Trial:
    """A generated log: ``log`` (t_s, pressure_kPa, valve_open[, fsr_*][, angle_deg]), the
    ``truth`` (t_s, force_N, y_mm, pressure_kPa, valve_open), the true ``events`` (t_s, kind)
    and what was generated (``meta``)."""

    log: pd.DataFrame
    truth: pd.DataFrame
    events: list = field(default_factory=list)
    meta: dict = field(default_factory=dict)


def run(chamber_map, pairs, *, setup_kPa=40.0, reservoir_mm3=40000.0, valve_open=False,
        switches=(), rate_Hz=1000.0, seed=0, noise_kPa=None, gas=None,
        object_N_per_mm=None) -> Trial:
    """The circuit pressed along ``pairs`` ([t_s, y_mm]; with ``object_N_per_mm`` the far end
    of the object's spring, :class:`~spsc.dynamics.profile.SpringProfile`) with the valve
    ``valve_open`` and ``switches`` ((t_s, opened), ...), sampled at ``rate_Hz`` by the ELVH
    (its σ, or ``noise_kPa``); the true contact and release from the true force."""
    circuit = Circuit(setup_kPa, reservoir_mm3, Valve(sonic_conductance(0.3)), gas or Gas(1.0))
    profile = PressProfile.of(pairs) if object_N_per_mm is None else \
        SpringProfile.of(pairs, object_N_per_mm)
    tr = integrate(chamber_map, circuit, profile, list(switches),
                   valve_open=valve_open, dt=1.0 / rate_Hz)
    over = {} if noise_kPa is None else {"noise_kPa": noise_kPa}
    sensor = Sensor.preset("elvh", rate_Hz=rate_Hz, seed=seed, **over)
    log = pd.DataFrame({"t_s": tr.t_s, "pressure_kPa": sensor.read(tr.pressure_kPa),
                        "valve_open": tr.valve_open.astype(int)})
    truth = pd.DataFrame({"t_s": tr.t_s, "force_N": tr.force_N, "y_mm": tr.y_mm,
                          "pressure_kPa": tr.pressure_kPa, "valve_open": tr.valve_open})
    events = contact_events(truth)
    events += [{"t_s": float(t), "kind": "switch", "valve": "open" if o else "closed"}
               for t, o, _ in tr.switches]
    return Trial(log, truth, sorted(events, key=lambda e: e["t_s"]),
                 {"noise_kPa": sensor.noise_kPa, "rate_Hz": rate_Hz, "seed": seed,
                  "valve_open": valve_open, "reservoir_mm3": reservoir_mm3})


def contact_events(truth, floor_N: float = RINGING_N) -> list[dict]:
    """Contact where the true force first exceeds ``floor_N``, release where it falls back.
    The floor (5 mN, the estimator's own bound on the map's residue, :data:`RINGING_N`;
    under 0.1 % of these presses' peak) is above the map's interpolation residue: between
    its pressure levels the map's spline in P leaves forces where the plate is off the
    chamber — a few µN at the setup pressure, which made 3 ms "contacts" after a fast
    release, and up to 1.7 mN below it, where a release of air leaves the gas cooled (0.2–0.3
    mm above the chamber as the plate backs off: 117 such "contacts" in 200 traces of air
    with a floor of 0.1 mN, 14 with 1 mN)."""
    on = (truth.force_N.to_numpy() > floor_N).astype(int)
    edges = np.flatnonzero(np.diff(on)) + 1
    t = truth.t_s.to_numpy()
    return [{"t_s": float(t[k]), "kind": "contact" if on[k] else "release"} for k in edges]


def press(chamber_map, *, depth_mm, speed_mm_s, hold_s, lead_s=0.3, tail_s=0.4, **kw) -> Trial:
    """Approach, press to ``depth_mm`` at ``speed_mm_s``, hold, release at the same speed."""
    ramp = (depth_mm + APPROACH_MM) / speed_mm_s
    t1 = lead_s + ramp
    pairs = [[0.0, -APPROACH_MM], [lead_s, -APPROACH_MM], [t1, depth_mm], [t1 + hold_s, depth_mm],
             [t1 + hold_s + ramp, -APPROACH_MM], [t1 + hold_s + ramp + tail_s, -APPROACH_MM]]
    trial = run(chamber_map, pairs, **kw)
    trial.meta.update(kind="press", depth_mm=depth_mm, speed_mm_s=speed_mm_s, hold_s=hold_s)
    return trial


def fsr_columns(force_N, pos, rng, n: int = FSR_COUNT) -> dict:
    """fsr_1..fsr_n (N) of the force ``force_N`` at the contact positions ``pos`` (0..1)."""
    centres = np.linspace(0.0, 1.0, n)
    w = np.exp(-0.5 * ((np.asarray(pos)[:, None] - centres[None, :]) / FSR_WIDTH) ** 2)
    w /= w.sum(axis=1, keepdims=True)
    f = np.asarray(force_N)[:, None] * w + FSR_NOISE_N * rng.standard_normal(w.shape)
    return {f"fsr_{i + 1}": np.maximum(f[:, i], 0.0) for i in range(n)}


def slip_press(chamber_map, *, depth_mm, slip: bool, drop=0.4, slip_s=0.08, speed_mm_s=10.0,
               hold_s=0.4, seed=0, **kw) -> Trial:
    """A press held, then an unloading of ``drop`` of the depth in ``slip_s``: with ``slip``
    the contact point runs toward the tip (0.35 -> 0.85) as it does (Fig. 10b), without it it
    stays (a partial release, not a slip); then held and released."""
    ramp = (depth_mm + APPROACH_MM) / speed_mm_s
    t1 = 0.3 + ramp
    t2 = t1 + hold_s
    t3 = t2 + slip_s
    low = depth_mm * (1 - drop)
    back = (low + APPROACH_MM) / speed_mm_s
    pairs = [[0, -APPROACH_MM], [0.3, -APPROACH_MM], [t1, depth_mm], [t2, depth_mm], [t3, low],
             [t3 + 0.3, low], [t3 + 0.3 + back, -APPROACH_MM], [t3 + 0.6 + back, -APPROACH_MM]]
    trial = run(chamber_map, pairs, seed=seed, **kw)
    t = trial.truth.t_s.to_numpy()
    pos = np.where(t < t2, 0.35, np.where(t > t3, 0.85, 0.35 + 0.5 * (t - t2) / slip_s)) \
        if slip else np.full(t.size, 0.35)
    rng = np.random.default_rng(seed + 7919)
    for k, v in fsr_columns(trial.truth.force_N.to_numpy(), pos, rng).items():
        trial.log[k] = v
    if slip:
        trial.events.append({"t_s": float(t2), "kind": "slip"})
        trial.events.sort(key=lambda e: e["t_s"])
    trial.meta.update(kind="slip" if slip else "partial release", depth_mm=depth_mm,
                      t_slip_s=t2)
    return trial


def grasp(chamber_map, *, share=None, object_N_per_mm=None, lever_mm_per_deg=0.12,
          alpha_c=20.0, alpha_end=None, omega_deg_s=40.0, hold_s=0.3, judged_deg=10.0,
          **kw) -> Trial:
    """The finger closes at ``omega_deg_s`` from 0°, meets the object at ``alpha_c``, closes on
    to ``alpha_end`` (default 25° further), holds, opens; past the contact it travels
    ``lever_mm_per_deg``. Either the chamber takes ``share`` of that travel (a kinematic
    object), or the object is a spring of ``object_N_per_mm`` between the finger and the
    plate (:class:`~spsc.dynamics.profile.SpringProfile`: the chamber takes what the forces
    share out, little at first where the chamber is soft, less as it stiffens). The object is
    stiff when the chamber's travel per degree, fitted over the ``judged_deg`` after the
    true contact, is at least half the lever (``meta["share"]``: that slope over the lever).
    The log's ``angle_deg`` is α."""
    if (share is None) == (object_N_per_mm is None):
        raise ValueError("grasp: give share or object_N_per_mm")
    alpha_end = alpha_c + 25.0 if alpha_end is None else alpha_end
    a = np.array([0.0, alpha_c, alpha_end])
    far = lever_mm_per_deg * (alpha_end - alpha_c) * (1.0 if share is None else share)
    y = np.array([-APPROACH_MM, 0.0, far])
    t = a / omega_deg_s
    t_hold = t[-1] + hold_s
    times = np.r_[t, t_hold, t_hold + t[-1] - t[::-1][1:], t_hold + t[-1] + 0.3]
    ys = np.r_[y, y[-1], y[::-1][1:], -APPROACH_MM]
    alphas = np.r_[a, a[-1], a[::-1][1:], 0.0]
    trial = run(chamber_map, list(zip(times.tolist(), ys.tolist())),
                object_N_per_mm=object_N_per_mm, **kw)
    alpha = np.interp(trial.log.t_s, times, alphas)
    trial.log["angle_deg"] = alpha
    first = next(e for e in trial.events if e["kind"] == "contact")
    if object_N_per_mm is not None:
        tt = trial.truth.t_s.to_numpy()
        span = (tt >= first["t_s"]) & (alpha <= alpha[tt >= first["t_s"]][0] + judged_deg) \
            & (tt <= t[-1])
        share = float(np.polyfit(alpha[span], trial.truth.y_mm.to_numpy()[span], 1)[0]
                      / lever_mm_per_deg)
    trial.events.append({"t_s": first["t_s"], "kind": "stiff_object" if share >= 0.5 else
                         "soft_object"})
    trial.events.sort(key=lambda e: e["t_s"])
    trial.meta.update(kind="grasp", share=share, lever_mm_per_deg=lever_mm_per_deg,
                      object_N_per_mm=object_N_per_mm,
                      depth_mm=float(trial.truth.y_mm.max()))
    return trial
