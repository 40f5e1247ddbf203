"""The time domain's figures (issue 28), on the wall model's chamber map:

1. quasi-static limit: 0 → 4 mm in 100 s, isothermal, valve closed (open) against
   ``spsc curve --model wall`` high (low) mode;
2. the valve: a fast press with the valve closed, a hold, the valve opened — the end pressure
   against the static low mode; the equalisation time constant against the linearised circuit;
   adiabatic and isothermal closed-chamber presses against P Vⁿ = const;
3. the switch under load (high → low at 3 mm): the pressure drop and the time to settle within
   2 % of it;
4. speed: a 5 s scenario at 1 kHz output (map built, map cached).

    python bench/bench_time.py [--type B] [--dome] [--json F]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from spsc.cad.geometry import preset
from spsc.dynamics import Gas, Valve, sonic_conductance
from spsc.dynamics.chamber_map import build_map
from spsc.dynamics.circuit import Circuit, integrate
from spsc.dynamics.gas import R_AIR
from spsc.dynamics.profile import PressProfile
from spsc.dynamics.scenario import parse_scenario
from spsc.dynamics.simulate import simulate
from spsc.fem.wall import wall_curve
from spsc.materials import material

PA = 101.325
V_R = 40000.0
VALVE = Valve(sonic_conductance(0.3))


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0)))


def quasi_static(m, high, low):
    out = {}
    for name, opened, ref in (("high", False, high), ("low", True, low)):
        tr = integrate(m, Circuit(40.0, V_R, VALVE, Gas(1.0)),
                       PressProfile.of([[0, 0], [100, 4]]), valve_open=opened, dt=0.05)
        y = ref.y_mm[1:]
        out[name] = {"pressure_max_rel": _rel(np.interp(y, tr.y_mm, tr.pressure_kPa),
                                              ref.pressure_kPa[1:]),
                     "force_max_rel": _rel(np.interp(y, tr.y_mm, tr.force_N), ref.force_N[1:])}
    return out


def valve_opening(m, low, depth=3.0):
    tr = integrate(m, Circuit(40.0, V_R, VALVE, Gas(1.0)),
                   PressProfile.of([[0, 0], [0.05, depth], [2.0, depth]]), [(0.2, True)],
                   dt=1e-4)
    p_static = float(np.interp(depth, low.y_mm, low.pressure_kPa))
    p = tr.pressure_kPa[-1]
    # the linearised circuit at the end state: τ = 1/(k R T (1/C_c + 1/V_r))
    s = m.at(depth)
    pa = (p + PA) * 1e3
    cc = (float(s.volume(p)) + pa * float(s.volume(p, 1)) / 1e3) * 1e-9
    tau = 1.0 / (VALVE.conductance(pa, 293.15) * R_AIR * 293.15 * (1 / cc + 1 / (V_R * 1e-9)))
    d = (tr.pressure_kPa - tr.reservoir_kPa) * 1e3
    w = (d < 5e-4 * pa) & (d > 1e-7 * pa) & (tr.t_s > 0.2)
    measured = -1.0 / np.polyfit(tr.t_s[w], np.log(d[w]), 1)[0]
    return {"end_pressure_kPa": p, "static_low_kPa": p_static,
            "end_vs_static_rel": abs(p / p_static - 1), "tau_measured_ms": measured * 1e3,
            "tau_linearised_ms": tau * 1e3, "tau_rel": abs(measured / tau - 1),
            "fit_samples": int(w.sum())}


def closed_forms(m, depth=3.0):
    out = {}
    for name, gas, n in (("adiabatic", Gas(1.4), 1.4), ("isothermal", Gas(1.0), 1.0)):
        tr = integrate(m, Circuit(40.0, 0.0, VALVE, gas),
                       PressProfile.of([[0, 0], [0.05, depth]]), dt=1e-4)
        pv = (tr.pressure_kPa + PA) * tr.volume_mm3 ** n
        out[name] = {"p_end_kPa": float(tr.pressure_kPa[-1]),
                     "p_v_n_max_rel": float(np.max(np.abs(pv / pv[0] - 1)))}
    return out


def switch_under_load(m, depth=3.0, t_switch=1.0):
    tr = integrate(m, Circuit(40.0, V_R, VALVE, Gas(1.4, thermal_time_s=0.5)),
                   PressProfile.of([[0, 0], [0.3, depth], [3.0, depth]]), [(t_switch, True)],
                   dt=1e-4)
    k = np.searchsorted(tr.t_s, t_switch)
    before, after = tr.pressure_kPa[k - 1], tr.pressure_kPa[k:]
    # settled: within 2 % of the drop from the pressure it relaxes to just after the switch
    # (the gas then drifts with the thermal time constant, which is not the switch)
    window = tr.t_s[k:] - t_switch
    end = after[window <= 0.2][-1]
    drop = before - end
    out_of_band = np.abs(after[window <= 0.2] - end) > 0.02 * abs(drop)
    idx = np.flatnonzero(out_of_band)
    settle = window[idx[-1] + 1] if idx.size else 0.0
    return {"before_kPa": float(before), "after_kPa": float(end), "drop_kPa": float(drop),
            "force_before_N": float(tr.force_N[k - 1]),
            "force_after_N": float(tr.force_N[k:][window <= 0.2][-1]),
            "settle_2pct_ms": float(settle * 1e3)}


def speed(g_params, cache):
    doc = {"chamber": g_params,
           "circuit": {"setup_kPa": 40, "reservoir_mm3": V_R,
                       "valve": {"area_mm2": 0.3, "state": "closed"},
                       "gas": {"n": 1.4, "thermal_time_s": 0.5},
                       "sensor": {"preset": "elvh", "rate_Hz": 1000}},
           "press": {"profile": [[0, 0], [0.3, 3], [2.5, 3], [2.8, 0], [5, 0]]},
           "events": [{"t": 1.0, "valve": "open"}, {"t": 3.2, "valve": "close"}],
           "output": {"dt": 0.001}}
    sc = parse_scenario(doc)
    t0 = time.perf_counter()
    first = simulate(sc, cache_dir=cache)
    t1 = time.perf_counter()
    again = simulate(sc, cache_dir=cache)
    t2 = time.perf_counter()
    # the map's levels on two local worker processes (spsc simulate's default on 2 cores)
    dask = simulate(sc, cache_dir=None, workers=2)
    t3 = time.perf_counter()
    return {"samples": len(first.trace), "first_run_s": t1 - t0, "map_s": first.seconds["map"],
            "integrate_s": first.seconds["integrate"], "cached_run_s": t2 - t1,
            "cached_integrate_s": again.seconds["integrate"],
            "first_run_2_workers_s": t3 - t2, "map_2_workers_s": dask.seconds["map"]}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--type", default="B")
    ap.add_argument("--dome", action="store_true", help="l = 0")
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    params = {"type": args.type, **({"l": 0.0} if args.dome else {})}
    g = preset(args.type, **({"l": 0.0} if args.dome else {}))
    mat = material("tpu60a")
    t = time.perf_counter()
    m = build_map(g, mat, setup_kPa=40.0, top_kPa=80.0, y_max_mm=4.0)
    print(f"map: {time.perf_counter() - t:.1f} s, {m.y_mm.size} travels x "
          f"{m.pressure_kPa.size} pressures")
    kw = dict(pressure_kPa=40.0, stroke_mm=4.0, points=17)
    high, low = wall_curve(g, mat, **kw), wall_curve(g, mat, reservoir_mm3=V_R, **kw)
    rows = {"chamber": params, "quasi_static": quasi_static(m, high, low),
            "valve": valve_opening(m, low), "closed_forms": closed_forms(m),
            "switch": switch_under_load(m)}
    import tempfile

    with tempfile.TemporaryDirectory() as cache:
        rows["speed"] = speed(params, cache)
    print(json.dumps(rows, indent=1, default=float))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1, default=float)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
