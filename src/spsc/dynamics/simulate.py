"""A scenario run: the chamber map (built or read from the cache), the circuit integrated,
the sensor read, the trace as a table.

The map covers the plate travels of the press and the gauge pressures from 0 to a ceiling
above what the closed chamber reaches at the deepest travel (the adiabatic bound when the gas
is not isothermal); the trace stops, keeping what it computed, if the gas leaves it anyway.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from spsc.core.constants import P_AMB_KPA

from .chamber_map import ChamberMap, build_map
from .circuit import Circuit, CircuitFailure, integrate

__all__ = ["Simulation", "simulate", "chamber_map_for", "COLUMNS"]

#: the trace's columns, in order (``pressure_measured_kPa`` with a sensor)
COLUMNS = ("t_s", "y_mm", "force_N", "pressure_kPa", "reservoir_kPa", "valve_open",
           "contact_mm2", "volume_mm3", "chamber_K", "reservoir_K", "chamber_mg",
           "reservoir_mg")
_PA_KPA = P_AMB_KPA  # kPa


@dataclass
class Simulation:
    """What a scenario run gives: the ``trace`` (DataFrame of :data:`COLUMNS`), the sensor's
    samples (``measured``, or None), the map it ran on, whether it reached the end and why
    not, the seconds of each phase."""

    scenario: object
    trace: pd.DataFrame
    measured: pd.DataFrame | None
    chamber_map: ChamberMap | None  # None: the wall stepped in time (:mod:`.wall_time`)
    complete: bool = True
    message: str = "complete"
    seconds: dict = field(default_factory=dict)
    switches: list = field(default_factory=list)  # the valve's: (t_s, opened, why)
    stiffness_steps: list = field(default_factory=list)  # step_metrics of each target step


def _closed_ceiling(m: ChamberMap, setup: float, y0: float, y1: float, n: float) -> float:
    """The gauge pressure (kPa) of the chamber closed at ``setup`` and ``y0``, pressed to
    ``y1`` adiabatically with exponent ``n`` (isothermal: 1): the highest the gas reaches."""
    v0 = float(m.at(y0).volume(setup))
    s = m.at(y1)
    p = setup
    for _ in range(60):  # fixed point (P + Pa) V(P)ⁿ = (P0 + Pa) V0ⁿ
        p = (setup + _PA_KPA) * (v0 / float(s.volume(p))) ** n - _PA_KPA
    return p


def _piston_ceiling(m: ChamberMap, sc, y0: float, y1: float, n: float) -> float:
    """The gauge pressure (kPa) of the pooled gas at the deepest travel ``y1`` with the piston
    at the smallest volume the controller asks for there (its set points, :mod:`.stiffness`),
    compressed adiabatically with exponent ``n`` from the setup at ``y0``."""
    from .chamber import Chamber
    from .stiffness import set_point

    ch = Chamber(m, sc.gas)
    t = sc.gas.ambient_K
    v0 = float(m.at(y0).volume(sc.setup_kPa)) + sc.reservoir_mm3
    mass = (sc.setup_kPa + _PA_KPA) * 1e3 * v0 * 1e-9 / (sc.gas.R * t) * 1e6  # mg
    want = [set_point(ch, y1, mass, t, k, sc.stiffness.reservoir_mm3)
            for _, k in sc.stiffness.target]
    v_r = min([v for v in want if v == v] + [sc.reservoir_mm3])
    p = sc.setup_kPa
    for _ in range(60):  # (P + Pa)(V(P) + V_r)ⁿ = (P0 + Pa) V0ⁿ
        p = (sc.setup_kPa + _PA_KPA) * (v0 / (float(m.at(y1).volume(p)) + v_r)) ** n - _PA_KPA
    return p


def chamber_map_for(scenario, *, cache_dir=None, progress=None, workers: int | None = 1,
                    scheduler: str | None = None) -> ChamberMap:
    """The map the scenario needs, from the cache (``cache_dir``/dynamics, keyed by the
    chamber, the grid and the code) or built (its levels on ``workers`` local processes or
    ``scheduler``'s cluster, :func:`~.chamber_map.build_map`); with ``[chamber] model =
    "surrogate"`` read from the wall model's surrogate (:func:`~.surrogate_map.surrogate_map`)."""
    from spsc.fem.wall.model import WallSettings
    from spsc.materials import material

    spec, sc = scenario.chamber, scenario
    geometry, mat = spec.geometry(), material(spec.material)
    settings = WallSettings(mesh_size_mm=spec.mesh_size, layers=spec.layers)
    lo, hi = sc.press.extent
    top = max(2.0 * sc.setup_kPa, sc.setup_kPa + 30.0)
    while True:
        if spec.model == "surrogate":  # milliseconds: nothing to cache
            from .surrogate_map import surrogate_map

            m = surrogate_map(geometry, mat, setup_kPa=sc.setup_kPa, top_kPa=top,
                              y_max_mm=max(hi, 0.0))
        else:
            m = _cached(geometry, mat, settings, sc.setup_kPa, top, max(hi, 0.0), cache_dir,
                        progress, {"workers": workers, "scheduler": scheduler})
        n = 1.0 if sc.gas.isothermal else sc.gas.n
        need = _closed_ceiling(m, sc.setup_kPa, max(lo, m.y_range[0]), max(hi, 0.0), n)
        if sc.stiffness is not None:
            need = max(need, _piston_ceiling(m, sc, max(lo, m.y_range[0]), max(hi, 0.0), n))
        if need <= top:
            return m
        top = 1.15 * need


def _cached(geometry, mat, settings, setup, top, y_max, cache_dir, progress,
            where) -> ChamberMap:
    from spsc.study.keyed import KeyedFile, input_key

    inputs = {"geometry": geometry.as_dict(), "material": repr(mat), "settings": repr(settings),
              "setup_kPa": setup, "top_kPa": top, "y_max_mm": y_max}
    if cache_dir is None:
        return build_map(geometry, mat, setup_kPa=setup, top_kPa=top, y_max_mm=y_max,
                         settings=settings, progress=progress, **where)
    key = input_key(inputs, ["spsc.dynamics.chamber_map"])
    f = KeyedFile(Path(cache_dir) / "dynamics" / f"map-{key[:16]}.npz", key)
    if f.valid:
        with np.load(f.path) as d:
            return ChamberMap.from_arrays(d)
    m = build_map(geometry, mat, setup_kPa=setup, top_kPa=top, y_max_mm=y_max,
                  settings=settings, progress=progress, **where)
    f.path.parent.mkdir(parents=True, exist_ok=True)
    np.savez(f.path, **m.as_arrays())
    f.mark()
    return m


def _frame(trace) -> pd.DataFrame:
    return pd.DataFrame({c: getattr(trace, c) for c in COLUMNS}).astype({"valve_open": int})


def _sample(sensor, df) -> pd.DataFrame:
    """The sensor's samples of the trace's chamber pressure (linear between outputs)."""
    ts = sensor.times(float(df.t_s.iloc[-1]))
    true = np.interp(ts, df.t_s, df.pressure_kPa)
    return pd.DataFrame({"t_s": ts, "pressure_kPa": true,
                         "pressure_measured_kPa": sensor.read(true)})


def leak_valve(scenario, chamber_map):
    """The scenario's leak as an orifice (None: sealed); a leak given as a loss over a time
    resolved on the chamber at rest at the setup pressure, its effective volume V + P ∂V/∂P
    (:mod:`.leak`) with the reservoir's if the valve is open at t = 0."""
    if scenario.leak is None:
        return None
    y0 = float(scenario.press.y(0.0)) if hasattr(scenario.press, "y") else 0.0
    s, p = chamber_map.at(min(max(y0, chamber_map.y_range[0]), chamber_map.y_range[1])), \
        scenario.setup_kPa
    effective = float(s.volume(p)) + (p + P_AMB_KPA) * float(s.volume(p, 1))
    if scenario.valve_open:
        effective += scenario.reservoir_mm3
    return scenario.leak.valve(p, effective, scenario.gas.ambient_K)


def simulate(scenario, *, cache_dir=None, progress=None, map_progress=None,
             workers: int | None = 1, scheduler: str | None = None) -> Simulation:
    """Run ``scenario`` (:class:`~.scenario.Scenario`): ``progress(t, t_end)`` while
    integrating, ``map_progress(done, total)`` while building the map (on ``workers`` or
    ``scheduler``, :func:`chamber_map_for`)."""
    from .wall_time import run_stepped, stepped

    t0 = time.perf_counter()
    if stepped(scenario):  # a viscous, rubbing or vented wall: no map holds its history
        col, complete, message, seconds = run_stepped(scenario, progress)
        df = pd.DataFrame({c: col[c] for c in COLUMNS})
        return _sampled(Simulation(scenario, df, None, None, complete, message,
                                   {"wall": seconds}))
    m = chamber_map_for(scenario, cache_dir=cache_dir, progress=map_progress, workers=workers,
                        scheduler=scheduler)
    t1 = time.perf_counter()
    circuit = Circuit(scenario.setup_kPa, scenario.reservoir_mm3, scenario.valve, scenario.gas,
                      leak_valve(scenario, m))
    complete, message, switches, steps = True, "complete", [], []
    if scenario.stiffness is not None:
        df, stopped, steps = _controlled(m, circuit, scenario, progress)
        complete, message = stopped is None, stopped or "complete"
    else:
        try:
            trace = integrate(m, circuit, scenario.press, scenario.events,
                              valve_open=scenario.valve_open, dt=scenario.dt, progress=progress,
                              triggers=scenario.triggers)
        except CircuitFailure as exc:
            trace, complete, message = exc.trace, False, str(exc)
        df, switches = _frame(trace), list(trace.switches)
    t2 = time.perf_counter()
    return _sampled(Simulation(scenario, df, None, m, complete, message,
                               {"map": t1 - t0, "integrate": t2 - t1}, switches, steps))


def _sampled(sim: Simulation) -> Simulation:
    """``sim`` with its sensor's samples (each output instant holds the last one taken)."""
    df, sensor = sim.trace, sim.scenario.sensor
    if sensor is not None and len(df):
        sim.measured = _sample(sensor, df)
        k = np.searchsorted(sim.measured.t_s.to_numpy(), df.t_s.to_numpy() + 1e-12, "right") - 1
        df["pressure_measured_kPa"] = sim.measured.pressure_measured_kPa.to_numpy()[k]
    return sim


def _controlled(m, circuit, scenario, progress):
    """(the trace, why it stopped or None, the step metrics of each target change) of a
    scenario with continuous stiffness control."""
    from .stiffness import integrate_controlled, step_metrics

    df, stopped = integrate_controlled(m, circuit, scenario.press, scenario.stiffness,
                                       dt=scenario.dt, progress=progress)
    steps = []
    for t_step, k in scenario.stiffness.target[1:]:
        if len(df) and df.t_s.iloc[-1] > t_step:
            upto = df.t_s.to_numpy() < min([t for t, _ in scenario.stiffness.target
                                            if t > t_step] + [np.inf])
            steps.append({"t_s": t_step, "target_N_per_mm": k,
                          **step_metrics(df.t_s[upto], df.stiffness_N_per_mm[upto], t_step)})
    return df, stopped, steps


def frequency_response(scenario, *, cache_dir=None, map_progress=None,
                       workers: int | None = 1, scheduler: str | None = None):
    """(the Bode table of :func:`~.frequency.bode` at the scenario's ``[bode]`` point, a
    summary: the operating point, the low- and high-frequency limits, the frequency where the
    sensitivity is halfway between them (in log), the map's seconds)."""
    from .frequency import bode, linearise

    if scenario.leak is not None:
        from spsc.core.errors import ParameterError

        raise ParameterError("circuit.leak", scenario.leak.describe(), "none with --bode (a "
                             "leaking chamber has no rest to linearise about)")
    t0 = time.perf_counter()
    b = scenario.bode
    from .wall_time import BODE_POINTS, bode_stepped, stepped

    if stepped(scenario):
        points = b["points"] if "points" in scenario.source.get("bode", {}) else BODE_POINTS
        freqs = np.logspace(np.log10(b["f_min_Hz"]), np.log10(b["f_max_Hz"]), points)
        from .wall_time import why_stepped

        table, lin = bode_stepped(scenario, freqs, map_progress)
        summary = _bode_summary(table, b, lin, freqs, time.perf_counter() - t0)
        return table, {**summary, "wall": f"{why_stepped(scenario)}, stepped in time (no inertia)"}
    m = chamber_map_for(scenario, cache_dir=cache_dir, progress=map_progress, workers=workers,
                        scheduler=scheduler)
    circuit = Circuit(scenario.setup_kPa, scenario.reservoir_mm3, scenario.valve, scenario.gas)
    freqs = np.logspace(np.log10(b["f_min_Hz"]), np.log10(b["f_max_Hz"]), b["points"])
    table = bode(m, circuit, b["y_mm"], b["valve_open"], freqs)
    lin = linearise(m, circuit, b["y_mm"], b["valve_open"])
    return table, _bode_summary(table, b, lin, freqs, time.perf_counter() - t0)


def _bode_summary(table, b, lin, freqs, seconds) -> dict:
    """The operating point, the low- and high-frequency limits and the frequency where the
    sensitivity (the stiffness, when the sensitivity is flat) is halfway between them."""
    sens = table.sensitivity_kPa_per_mm.to_numpy()
    s = sens if np.ptp(sens) > 1e-9 * max(abs(sens).max(), 1e-12) else \
        table.stiffness_N_per_mm.to_numpy()  # vented: no pressure to read
    mid = np.sqrt(s[0] * s[-1])
    cross = np.flatnonzero((s[:-1] - mid) * (s[1:] - mid) <= 0)
    f_mid = None
    if cross.size and s[-1] != s[0] and mid > 0:
        pair, fs = s[cross[0]:cross[0] + 2], freqs[cross[0]:cross[0] + 2]
        order = np.argsort(pair)
        f_mid = float(np.exp(np.interp(np.log(mid), np.log(pair[order]), np.log(fs[order]))))
    summary = {"y_mm": b["y_mm"], "valve_open": b["valve_open"],
               "pressure_kPa": lin["pressure_kPa"], "force_N": lin["force_N"],
               "stiffness_low_f_N_per_mm": float(table.stiffness_N_per_mm.iloc[0]),
               "stiffness_high_f_N_per_mm": float(table.stiffness_N_per_mm.iloc[-1]),
               "sensitivity_low_f_kPa_per_mm": float(sens[0]),
               "sensitivity_high_f_kPa_per_mm": float(sens[-1]),
               "sensitivity_halfway_Hz": f_mid, "map_seconds": seconds}
    return summary
