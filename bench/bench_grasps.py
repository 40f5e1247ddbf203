"""``spsc sense`` on simulated grasps (issue 50, item 3): N grasps of the two-finger gripper
(``spsc virtual``'s gripper scene, Table 1 Type D pads on the wall model's map, 40 kPa, 40 cm³
reservoirs, air n = 1.4 relaxing in 0.5 s, the sensor at 1 kHz with 0.02 kPa noise) of
generated objects — a box, a cylinder or a sphere, 20–45 mm across, 20–250 g, its own
stiffness log-uniform over 0.3–30 N/mm, friction 0.3–1.0 — squeezed to a grip force of
1–6 N, lifted, held (the valves opened mid-hold in half of them), put down and let go. Each
pad 1 trace is read back by the estimator as ``spsc sense`` runs it (the same map, the trace's
gas), against the simulator's contact force and events:

* force error while the contact force is above 0.5 N: median and 95th percentile of |ΔF|
  (N and relative), over every loaded sample of every grasp, per mode;
* events: contact, release (the true ones where the force rises above or falls to 0.01 N)
  and switch (the valve command), precision, recall and F1 over all grasps; a slip is not
  scored (the slip detector needs the FSRs the pads do not carry).

    python bench/bench_grasps.py [--grasps 50] [--seed 1] [--cache DIR] [--json OUT]

One grasp by hand: ``spsc virtual examples/scenes/gripper-soft.toml --out V`` then ``spsc sense
V/trace.parquet --pressure-column sensor_kPa_1 --type D --pressure 40 --reservoir 40000
--gas 1.4,0.5 --out S``.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path

import numpy as np

from spsc.dynamics.circuit import Circuit
from spsc.dynamics.simulate import chamber_map_for
from spsc.sensing import DenseMap, EstimatorParams, SenseParams, SenseStream
from spsc.sensing.chamber import chamber_map
from spsc.sensing.detectors import ContactParams
from spsc.sensing.log import noise_of
from spsc.virtual.chambers import MapTable, VirtualChambers
from spsc.virtual.gripper import run_gripper
from spsc.virtual.scene import parse_scene

ROOT = Path(__file__).resolve().parent.parent
TOUCH_N, LOADED_N = 0.01, 0.5
#: a detected event within this window of the true one (s) is a hit
WINDOW = {"contact": (-0.02, 0.4), "release": (-0.15, 0.3), "switch": (-0.01, 0.05)}
BASE = {"chamber": {"type": "D", "material": "tpu60a", "model": "wall"},
        "circuit": {"setup_kPa": 40, "reservoir_mm3": 40000, "valve": {"C": 0.06},
                    "gas": {"n": 1.4, "thermal_time_s": 0.5},
                    "sensor": {"rate_Hz": 1000, "noise_kPa": 0.02}},
        "scene": {"kind": "gripper"}}


def grasp_doc(rng, travel_for) -> dict:
    """One generated grasp scene (a TOML document as a dict)."""
    shape = rng.choice(["box", "cylinder", "sphere"])
    width = rng.uniform(20, 45)
    size = {"box": [width, rng.uniform(20, 45), rng.uniform(25, 60)],
            "cylinder": [width, rng.uniform(25, 60)], "sphere": [width]}[shape]
    k = float(np.exp(rng.uniform(np.log(0.3), np.log(30))))
    grip = rng.uniform(1.0, 6.0)
    squeeze = travel_for(grip) + grip / k  # each side: the pad's travel and the object's
    while width - 2 * squeeze < 6.0:  # a soft, narrow object: squeezed less
        grip *= 0.8
        squeeze = travel_for(grip) + grip / k
    close, lift0 = rng.uniform(0.6, 1.2), rng.uniform(1.3, 1.6)
    hold = lift0 + 0.6
    down = hold + rng.uniform(1.0, 1.6)
    opened = down + 0.8
    doc = dict(BASE, object={"shape": str(shape), "size_mm": size,
                             "mass_g": float(rng.uniform(20, 250)), "stiffness_N_per_mm": k,
                             "friction": float(rng.uniform(0.3, 1.0))},
               grasp={"opening_mm": [[0, width + 20], [0.3, width + 20],
                                     [close, width - 2 * squeeze], [down + 0.6, width - 2 * squeeze],
                                     [opened, width + 20]],
                      "lift_mm": [[0, 0], [lift0, 0], [hold, 25], [down, 25], [down + 0.6, 0]],
                      "duration_s": opened + 0.7})
    if rng.random() < 0.5:
        doc["events"] = [{"t": float(rng.uniform(hold + 0.2, down - 0.3)), "valve": "open"}]
    return doc


def true_events(t, f, valve) -> list[tuple[float, str]]:
    touching = f > TOUCH_N
    out = [(float(t[i + 1]), "contact" if touching[i + 1] else "release")
           for i in np.flatnonzero(np.diff(touching.astype(int)))]
    out += [(float(t[i + 1]), "switch") for i in np.flatnonzero(np.diff(valve.astype(int)))]
    return sorted(out)


def match(found: list[dict], truth: list[tuple[float, str]]) -> dict:
    """Hits, misses and phantoms per kind."""
    used, out = set(), {k: {"hits": 0, "misses": 0, "phantoms": 0} for k in WINDOW}
    for t, kind in truth:
        lo, hi = WINDOW[kind]
        cand = [i for i, e in enumerate(found) if e["kind"] == kind and i not in used
                and lo <= e["t_s"] - t <= hi]
        if cand:
            used.add(min(cand, key=lambda i: abs(found[i]["t_s"] - t)))
            out[kind]["hits"] += 1
        else:
            out[kind]["misses"] += 1
    for i, e in enumerate(found):
        if e["kind"] in WINDOW and i not in used:
            out[e["kind"]]["phantoms"] += 1
    return out


def run(n: int, seed: int, cache: Path) -> dict:
    rng = np.random.default_rng(seed)
    probe = parse_scene(dict(grasp_doc(np.random.default_rng(0), lambda f: 1.0)))
    sc = probe.scenario
    m = chamber_map_for(sc, cache_dir=cache)
    table, geo = MapTable(m), sc.chamber.geometry()
    closed = VirtualChambers(m, Circuit(40.0, 0.0, None, sc.gas), table=table, y0_mm=0.0)
    ys = np.linspace(0.0, m.y_range[1], 200)
    fs = np.array([closed.force_at(y)[0][0] for y in ys])

    def travel_for(f):  # the pad's travel at a force, its gas held (the grip's estimate)
        return float(np.interp(f, fs, ys))

    sense_map = DenseMap(chamber_map({"type": "D"}, setup_kPa=40.0, reservoir_mm3=40000.0,
                                     stroke_mm=4.0, cache_dir=cache))
    errs = {"high": [], "low": []}
    events = {k: {"hits": 0, "misses": 0, "phantoms": 0} for k in WINDOW}
    sim_s = scene_s = 0.0
    grasps = []
    for g in range(n):
        scene = parse_scene(grasp_doc(rng, travel_for))
        pads = VirtualChambers(m, Circuit(40.0, 40000.0, sc.valve, sc.gas), count=2,
                               sensor=dataclasses.replace(sc.sensor, seed=g),
                               y0_mm=m.y_range[0], table=table)
        t0 = time.perf_counter()
        tr = run_gripper(pads, scene.obj, scene.grasp, pad_mm=(geo.h, geo.w, geo.w + geo.l),
                         valve_events=scene.scenario.events)
        sim_s += time.perf_counter() - t0
        scene_s += scene.duration_s
        t, f, v = tr["t_s"], tr["force_N_1"], tr["valve_open"].astype(bool)
        prm = SenseParams(EstimatorParams(40.0, 40000.0, noise_of(tr["sensor_kPa_1"]), 0.05,
                                          gas=sc.gas), ContactParams(), rate_Hz=1000.0)
        s = SenseStream(sense_map, prm)
        est = np.array([s.push(ti + 1e-3, p, vi)[0].force_N
                        for ti, p, vi in zip(t, tr["sensor_kPa_1"], v)])
        loaded = f > LOADED_N
        for mode, sel in (("high", loaded & ~v), ("low", loaded & v)):
            errs[mode].append(np.c_[np.abs(est[sel] - f[sel]), f[sel]])
        found = [{"t_s": e["t_s"] - 1e-3, "kind": e["kind"]} for e in s.events]
        res = match(found, true_events(t, f, v))
        for k in WINDOW:
            for c in events[k]:
                events[k][c] += res[k][c]
        grasps.append({"object": scene.obj.shape, "k_N_per_mm": scene.obj.contact.object_N_per_mm,
                       "grip_N": float(f.max()), "lifted_mm": float(tr["object_z_mm"].max()),
                       "slipped": bool(tr["slipping_1"].any()), "events": res})
        print(f"  grasp {g + 1:3d}: {scene.obj.shape:8s} k {scene.obj.contact.object_N_per_mm:6.2f}"
              f" N/mm, grip {f.max():4.2f} N, lifted {tr['object_z_mm'].max():5.1f} mm; "
              + ", ".join(f"{k} {r['hits']}/{r['hits'] + r['misses']}+{r['phantoms']}"
                          for k, r in res.items()), flush=True)
    out = {"grasps": n, "seed": seed, "scene_s": scene_s, "sim_s": sim_s, "events": events,
           "per_grasp": grasps}
    for mode, chunks in errs.items():
        e = np.concatenate(chunks) if chunks else np.empty((0, 2))
        if len(e):
            out[f"force_{mode}"] = {"samples": int(len(e)), "median_N": float(np.median(e[:, 0])),
                                    "p95_N": float(np.percentile(e[:, 0], 95)),
                                    "median_rel": float(np.median(e[:, 0] / e[:, 1])),
                                    "p95_rel": float(np.percentile(e[:, 0] / e[:, 1], 95))}
    for k, r in events.items():
        p = r["hits"] / max(r["hits"] + r["phantoms"], 1)
        rc = r["hits"] / max(r["hits"] + r["misses"], 1)
        r["precision"], r["recall"], r["f1"] = p, rc, 2 * p * rc / max(p + rc, 1e-12)
    tot = {c: sum(r[c] for r in events.values()) for c in ("hits", "misses", "phantoms")}
    p = tot["hits"] / max(tot["hits"] + tot["phantoms"], 1)
    rc = tot["hits"] / max(tot["hits"] + tot["misses"], 1)
    out["f1_all"] = 2 * p * rc / max(p + rc, 1e-12)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--grasps", type=int, default=50)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cache", default=str(ROOT / "build" / "cache"))
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    r = run(a.grasps, a.seed, Path(a.cache))
    print(f"{r['grasps']} grasps, {r['scene_s']:.0f} s of scene simulated in {r['sim_s']:.0f} s "
          f"({r['scene_s'] / r['sim_s']:.2f}x real time, 1 ms steps, two pads)")
    for mode in ("high", "low"):
        e = r.get(f"force_{mode}")
        if e:
            print(f"force error, {mode} mode ({e['samples']} loaded samples): median "
                  f"{e['median_N']:.3f} N ({100 * e['median_rel']:.1f} %), 95th percentile "
                  f"{e['p95_N']:.3f} N ({100 * e['p95_rel']:.1f} %)")
    for k, e in r["events"].items():
        print(f"{k:8s}: {e['hits']} hits, {e['misses']} misses, {e['phantoms']} phantoms; "
              f"precision {e['precision']:.3f}, recall {e['recall']:.3f}, F1 {e['f1']:.3f}")
    print(f"events F1 (contact, release, switch together): {r['f1_all']:.3f}")
    if a.json:
        Path(a.json).write_text(json.dumps(r, indent=1, default=float) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
