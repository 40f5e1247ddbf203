"""The MuJoCo scenes of ``spsc virtual`` (issue 50, items 1 and 2):

* consistency: the plate scene (``examples/scenes/plate-profile.toml``: the Type B dome's pad
  pressed slowly to 4 mm on a stiff servo, isothermal, valve closed) against ``spsc curve
  --model surrogate`` at the plate's own travel (largest force error over the press, relative
  to the curve's largest force; largest pressure error, relative to the curve's pressure
  rise), and the valve opened under load against ``spsc simulate``'s integrator driven along
  the plate's own travel (the settled pressure);
* speed: the gripper scene (``examples/scenes/gripper-soft.toml``: Table 1 Type D pads on the
  wall model's map, 1 ms physics steps, two chambers, no video) as scene seconds per wall
  second, best and median of ``--repeat`` runs after the map is built; the pads' step alone
  is ``bench/bench_virtual.py``'s.

    python bench/bench_virtual_scenes.py [--repeat 3] [--cache DIR]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pandas as pd

from spsc.dynamics.circuit import Circuit
from spsc.dynamics.profile import PressProfile
from spsc.dynamics.simulate import chamber_map_for, simulate
from spsc.virtual.chambers import VirtualChambers
from spsc.virtual.gripper import run_gripper
from spsc.virtual.scene import read_scene

ROOT = Path(__file__).resolve().parent.parent
SCENES = ROOT / "examples" / "scenes"


def consistency(cache: Path) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        subprocess.run([str(Path(sys.executable).parent / "spsc"), "virtual", str(SCENES / "plate-profile.toml"),
                        "--out", str(out / "v"), "--quiet", "--cache", str(cache)], check=True)
        subprocess.run([str(Path(sys.executable).parent / "spsc"), "curve", "--model", "surrogate", "--type",
                        "B", "--l", "0", "--pressure", "40", "--stroke", "4", "--points", "33",
                        "--json", str(out / "c.json"), "--quiet"], check=True,
                       capture_output=True)
        df = pd.read_parquet(out / "v" / "trace.parquet")
        c = json.loads((out / "c.json").read_text())["curve"]
    y, f, p = (np.asarray(c[k]) for k in ("y_mm", "force_N", "pressure_kPa"))
    press = (df.t_s > 0.6) & (df.t_s < 8.5) & (df.travel_mm_1 > 0.25)
    yy = df.travel_mm_1[press].to_numpy()
    df_err = np.abs(df.force_N_1[press].to_numpy() - np.interp(yy, y, f)).max() / f.max()
    dp_err = np.abs(df.pressure_kPa_1[press].to_numpy() - np.interp(yy, y, p)).max() / \
        (p.max() - p[0])
    sc = read_scene(SCENES / "plate-profile.toml").scenario
    knots = df.iloc[::10]
    sc = dataclasses.replace(sc, press=PressProfile.of(list(zip(
        knots.t_s, np.maximum(knots.travel_mm_1, 0.0)))))
    sim = simulate(sc, cache_dir=cache).trace
    t_end = float(knots.t_s.iloc[-1])
    settled_sim = float(np.interp(t_end, sim.t_s, sim.pressure_kPa))
    settled = float(df.pressure_kPa_1[df.t_s <= t_end].iloc[-1])
    return {"force_err_rel_max": df_err, "pressure_err_rel_rise_max": dp_err,
            "settled_kPa": settled, "settled_simulate_kPa": settled_sim,
            "settled_err_rel": abs(settled - settled_sim) / settled_sim}


def speed(cache: Path, repeat: int) -> dict:
    scene = read_scene(SCENES / "gripper-soft.toml")
    sc = scene.scenario
    t0 = time.perf_counter()
    m = chamber_map_for(sc, cache_dir=cache)
    t_map = time.perf_counter() - t0
    g = sc.chamber.geometry()
    runs = []
    for _ in range(repeat):
        pads = VirtualChambers(m, Circuit(sc.setup_kPa, sc.reservoir_mm3, sc.valve, sc.gas),
                               count=2, sensor=sc.sensor, y0_mm=m.y_range[0])
        t0 = time.perf_counter()
        run_gripper(pads, scene.obj, scene.grasp, pad_mm=(g.h, g.w, g.w + g.l),
                    valve_events=sc.events)
        runs.append(time.perf_counter() - t0)
    return {"scene_s": scene.duration_s, "map_s": t_map, "runs_s": runs,
            "real_time_best": scene.duration_s / min(runs),
            "real_time_median": scene.duration_s / float(np.median(runs))}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cache", default=str(ROOT / "build" / "cache"))
    a = ap.parse_args(argv)
    cache = Path(a.cache)
    c = consistency(cache)
    print(f"plate scene vs spsc curve --model surrogate: force within "
          f"{100 * c['force_err_rel_max']:.3f} % of the curve's largest, pressure within "
          f"{100 * c['pressure_err_rel_rise_max']:.3f} % of its rise")
    print(f"valve opened under load: settled {c['settled_kPa']:.4f} kPa, spsc simulate "
          f"{c['settled_simulate_kPa']:.4f} kPa ({100 * c['settled_err_rel']:.4f} %)")
    s = speed(cache, a.repeat)
    print(f"gripper scene (Type D pads, wall map {s['map_s']:.1f} s; two chambers, 1 ms steps): "
          f"{s['scene_s']:g} s of scene in {min(s['runs_s']):.2f} s best, "
          f"{float(np.median(s['runs_s'])):.2f} s median: {s['real_time_best']:.2f}x / "
          f"{s['real_time_median']:.2f}x real time")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
