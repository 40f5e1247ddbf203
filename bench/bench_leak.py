"""Leaks (issue 51, the paper's sec. 3.2 leak test), the figures of its closing note:

1. ``spsc simulate`` of a Type B chamber at 40 kPa, isolated for 30 minutes, leaking through
   a stated orifice (C = 5e-9 dm³/(s·bar), isothermal gas): the pressure after 30 min against
   the closed form of an isothermal orifice leak (:func:`spsc.dynamics.leak.leak_pressure`)
   on the chamber's effective volume V + P ∂V/∂P at rest;
2. ``spsc sense`` on ``examples/leak-test.toml``'s trace (air, 1 kPa in 30 min, a press
   halfway): its events and the leak's rate against the trace's own loss;
3. ``spsc sense`` on the same chamber sealed, its sensor reading a room that cools by 2.07 K
   and warms back over the 30 minutes (1 kPa down and back): no leak.

    python bench/bench_leak.py [--cache DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import tempfile
import time
from pathlib import Path

import numpy as np
from spsc.cli.main import main
from spsc.core.constants import P_AMB_KPA
from spsc.dynamics import Gas, Valve
from spsc.dynamics.leak import LeakSpec, leak_pressure
from spsc.dynamics.profile import PressProfile
from spsc.dynamics.scenario import read_scenario
from spsc.dynamics.simulate import chamber_map_for, leak_valve, simulate

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "leak-test.toml"
SENSE = ["--pressure-column", "pressure_measured_kPa", "--type", "B", "--pressure", "40",
         "--reservoir", "40000", "--gas", "1.4,0.5", "--quiet"]


def closed_form(cache) -> dict:
    sc = read_scenario(EXAMPLE)
    sc = dataclasses.replace(sc, gas=Gas(1.0), leak=LeakSpec(C=5e-9), sensor=None, dt=10.0,
                             press=PressProfile.of([[0, 0], [1800, 0]]))
    m = chamber_map_for(sc, cache_dir=cache)
    s = m.at(0.0)
    v, dv = float(s.volume(40.0)), float(s.volume(40.0, 1))
    eff = v + (40.0 + P_AMB_KPA) * dv
    sim = simulate(sc, cache_dir=cache)
    p_sim = float(sim.trace.pressure_kPa.iloc[-1])
    p_cf = leak_pressure(40.0, 1800.0, eff, Valve(5e-9))
    p_rigid = leak_pressure(40.0, 1800.0, v, Valve(5e-9))
    return {"C": 5e-9, "volume_mm3": v, "effective_mm3": eff, "p_simulated_kPa": p_sim,
            "p_closed_form_kPa": p_cf, "p_rigid_volume_kPa": p_rigid,
            "pressure_error_pct": 100 * (p_sim - p_cf) / p_cf,
            "drop_error_pct": 100 * ((40 - p_sim) - (40 - p_cf)) / (40 - p_cf),
            "leak_valve_C": leak_valve(sc, m)}


def sense(log: Path, out: Path, cache) -> list:
    code = main(["sense", str(log), *SENSE, "--out", str(out)]
                + (["--cache", str(cache)] if cache else []))
    assert code == 0
    return json.loads((out / "events.json").read_text())["events"]


def main_(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cache", default=None)
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    cf = closed_form(args.cache)
    print(f"1. closed form: Type B at rest, C = {cf['C']:g} dm³/(s·bar), isothermal, 30 min: "
          f"simulated {cf['p_simulated_kPa']:.5f} kPa, closed form on V + P dV/dP "
          f"({cf['effective_mm3']:.0f} mm³) {cf['p_closed_form_kPa']:.5f} kPa: pressure "
          f"{cf['pressure_error_pct']:+.4f} %, drop {cf['drop_error_pct']:+.3f} % (rigid V "
          f"{cf['volume_mm3']:.0f} mm³ would give {cf['p_rigid_volume_kPa']:.5f} kPa)")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        sim = simulate(read_scenario(EXAMPLE), cache_dir=args.cache)
        trace = sim.trace
        trace.to_parquet(tmp / "leak.parquet")
        rest = trace[(trace.t_s < 899) | (trace.t_s > 905)]
        true_rate = -np.polyfit(rest.t_s, rest.pressure_kPa, 1)[0] * 1800
        events = sense(tmp / "leak.parquet", tmp / "s1", args.cache)
        leak = [e for e in events if e["kind"] == "leak"]
        print(f"2. leak log (1 kPa in 30 min, air, a press at 900 s): events "
              f"{[(e['kind'], round(e['t_s'], 2)) for e in events]}; true loss "
              f"{true_rate:.4f} kPa/30 min, reported "
              + (f"{leak[0]['rate_kPa_per_30min']:.4f} ({100 * (leak[0]['rate_kPa_per_30min'] / true_rate - 1):+.2f} %)"
                 if leak else "none"))
        sealed = simulate(dataclasses.replace(read_scenario(EXAMPLE), leak=None),
                          cache_dir=args.cache).trace
        t = sealed.t_s.to_numpy()
        dT = 1.0 / (40.0 + P_AMB_KPA) * 293.15  # K: 1 kPa at 40 kPa gauge
        room = 293.15 - dT * np.sin(np.pi * t / 1800.0)
        swing = sealed.copy()
        for col in ("pressure_kPa", "pressure_measured_kPa"):
            swing[col] = (swing[col] + P_AMB_KPA) * room / 293.15 - P_AMB_KPA
        swing.to_parquet(tmp / "swing.parquet")
        events = sense(tmp / "swing.parquet", tmp / "s2", args.cache)
        print(f"3. thermal swing (the room {dT:.2f} K down and back, 1 kPa): events "
              f"{[(e['kind'], round(e['t_s'], 2)) for e in events]}; leak reported: "
              f"{any(e['kind'] == 'leak' for e in events)}")
    print(f"({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main_()
