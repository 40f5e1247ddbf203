"""The chamber as a sensor (issue 29), over generated scenarios on Types A–D (Table 1, 40 kPa,
the paper's 40 cm³ reservoir, the ELVH's noise at 1 kHz):

* contact onset latency (median, 95th percentile) from the true first contact, per mode,
  press speed and contact detector (the paper's thresholds, the CUSUM), from the instant
  the noise-free pressure had risen 1σ (what is the detector's and what the chamber's: near
  first contact the pressure rises slowly), and the bound no detector with false alarms once
  in 10¹⁰ samples beats at the median (:func:`bound_time`); the release's latency;
* precision, recall and F1 of contact, release, slip, switch (from the valve column and
  inferred from P) and stiff/soft objects, in all and per mode (the low mode moves the
  pressure by 0.1–0.5 kPa/mm against the sensor's 0.086 kPa: its limits are the noise's);
* false events per minute of quiet signal (the chamber at rest, read by the sensor): steady,
  warming by 0.02 kPa/s (the rest tracker's case) and cooling as a settling exponential;
* force error per type and mode over the holds (the trace's true force against the estimate);
* streaming samples per second on one core.

``--gas N,TAU`` generates the traces with that air (the examples' 1.4,0.5: adiabatic with
thermal relaxation; default 1, the isothermal gas of the paper's static tests) and senses them
with it; ``--sense-gas`` senses them with another (1: the isothermal estimator on air, what
``spsc sense`` without ``--gas`` did before issue 53).

The traces run on the same chamber maps the estimator reads (1 mm wall mesh: the map's own
accuracy against the 3D FEM is docs/theory/wall.md's, not what is measured here), built once
into ``--cache`` (default build/cache).

    python bench/bench_sense.py [--per-type 50] [--types ABCD] [--json F] [--cache DIR]
        [--gas N,TAU] [--sense-gas N,TAU]
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from spsc.cli.options import gas_option
from spsc.dynamics import Gas, Sensor
from spsc.dynamics.circuit import CircuitFailure
from spsc.sensing import DenseMap, EstimatorParams, SenseParams, SenseStream
from spsc.sensing.chamber import chamber_map
from spsc.sensing.detectors import ComplianceParams, ContactParams
from spsc_support import sense_traces as st

RES, SETUP, STROKE = 40000.0, 40.0, 3.0
#: the air the traces are generated with, and the one the estimator assumes (--gas, --sense-gas)
GAS, SENSE_GAS = Gas(1.0), Gas(1.0)
LEVER = 0.12  # mm of the chamber's travel per degree of closure on a rigid object
#: the windows a detection must fall in after (before) the true event, s
WINDOW = {"contact": (-0.02, 0.4), "release": (-0.15, 0.3), "slip": (-0.02, 0.2),
          "switch": (-0.01, 0.05), "stiff_object": (-0.1, 1.5), "soft_object": (-0.1, 1.5)}


def scenarios(m, rng, n, failed):
    """``n`` trials: presses, switches under load, slips and partial releases, grasps of
    objects on springs of 5–50 N/mm (stiff) and 0.3–1 N/mm (soft); the mode drawn for each. A draw the circuit cannot integrate is counted
    in ``failed`` and drawn again."""
    out, i = [], 0
    while len(out) < n:
        try:
            out.append(_scenario(m, rng, i))
        except CircuitFailure as exc:
            failed.append(str(exc))
        i += 1
    return out


def _scenario(m, rng, i):
    kinds = ["press"] * 12 + ["switch"] * 3 + ["slip"] * 3 + ["partial"] * 3 + ["grasp"] * 4
    kind = kinds[i % len(kinds)]
    seed = int(rng.integers(1 << 30))
    opened = bool(rng.integers(2)) and kind != "switch"
    depth = float(rng.uniform(1.0, 2.8))
    if kind == "press":
        t = st.press(m, depth_mm=depth, speed_mm_s=float(rng.choice([5, 10, 20, 50])),
                     hold_s=float(rng.uniform(0.2, 0.6)), valve_open=opened, seed=seed,
                     gas=GAS)
    elif kind == "switch":
        t = st.press(m, depth_mm=depth, speed_mm_s=10.0, hold_s=0.8, seed=seed,
                     switches=[(0.3 + (depth + 0.3) / 10.0 + 0.4, True)], gas=GAS)
    elif kind in ("slip", "partial"):
        t = st.slip_press(m, depth_mm=depth, slip=kind == "slip", valve_open=opened,
                          seed=seed, gas=GAS)
    else:
        # an object on a spring (N/mm), stiff or soft against these chambers: the chamber
        # takes 0.7–0.95 and 0.15–0.35 of the closure's first 10° (stiff or soft is the
        # trace's own share); below 0.2 N/mm the chamber barely feels the object at all
        k = float(np.exp(rng.uniform(np.log(5.0), np.log(50.0)) if i % 2 else
                         rng.uniform(np.log(0.3), np.log(1.0))))
        t = st.grasp(m, object_N_per_mm=k, lever_mm_per_deg=LEVER, valve_open=opened,
                     seed=seed, gas=GAS)
    t.meta["mode"] = "low" if opened else "high"
    t.meta["scenario"] = kind
    return t


def run_stream(dense, trial, method, *, valve=True):
    prm = SenseParams(EstimatorParams(SETUP, RES, trial.meta["noise_kPa"], 0.05,
                                      valve_open=trial.meta["valve_open"], gas=SENSE_GAS),
                      ContactParams(method=method),
                      compliance=ComplianceParams(stiff_mm_per_deg=0.5 * LEVER))
    s = SenseStream(dense, prm)
    log = trial.log
    fsr = [c for c in log if c.startswith("fsr_")]
    F = log[fsr].to_numpy() if fsr else None
    a = log.angle_deg.to_numpy() if "angle_deg" in log else None
    v = log.valve_open.to_numpy() if valve else None
    rows = list(zip(log.t_s.tolist(), log.pressure_kPa.tolist()))
    t0 = time.perf_counter()
    states = [s.push(t, p, None if v is None else v[i], None if F is None else F[i],
                     None if a is None else a[i])[0] for i, (t, p) in enumerate(rows)]
    return s, states, time.perf_counter() - t0


def match(true, got, counts, latencies, mode, trial=None, release=None):
    """Count true positives, false negatives and false positives per kind, in all and per
    mode (``counts[kind]``, ``counts[(mode, kind)]``); a contact's latency goes to
    ``latencies[mode]`` as (from the true contact, from its signal's 1σ, the press's speed),
    a release's (from the true release) to ``release[mode]``."""
    used = set()

    def add(kind, slot):
        for key in (kind, (mode, kind)):
            counts.setdefault(key, [0, 0, 0])[slot] += 1

    for e in true:
        lo, hi = WINDOW[e["kind"]]
        hit = next((k for k, g in enumerate(got) if k not in used and g["kind"] == e["kind"]
                    and lo <= g["t_s"] - e["t_s"] <= hi), None)
        if e["kind"] == "contact" and trial is not None:
            late = not bound_time(trial, e["t_s"]) - e["t_s"] <= hi  # NaN: never
            if late:  # no detector at 1e10 samples a false alarm sees it in the window
                add("contact beyond the bound", 0 if hit is not None else 1)
        if hit is None:
            add(e["kind"], 1)
        else:
            used.add(hit)
            add(e["kind"], 0)
            if e["kind"] == "release" and release is not None:
                release.setdefault(mode, []).append(got[hit]["t_s"] - e["t_s"])
            if e["kind"] == "contact":
                lat = got[hit]["t_s"] - e["t_s"]
                visible = signal_time(trial, e["t_s"]) if trial is not None else e["t_s"]
                speed = trial.meta.get("speed_mm_s") if trial is not None else None
                bound = (bound_time(trial, e["t_s"]) - e["t_s"]) if trial is not None \
                    else math.nan
                latencies.setdefault(mode, []).append((lat, got[hit]["t_s"] - visible, speed,
                                                       bound))
    for k, g in enumerate(got):
        if k not in used:
            add(g["kind"], 2)


def signal_time(trial, t_contact, sigmas=1.0):
    """When the noise-free pressure first rose ``sigmas`` σ of the sensor above its value at
    the true contact (NaN if never): a shift of less than σ is what no detector with a
    bounded false-alarm rate sees within a window, and the CUSUM's k is 1 σ."""
    t = trial.truth.t_s.to_numpy()
    p = trial.truth.pressure_kPa.to_numpy()
    k = int(np.searchsorted(t, t_contact))
    above = np.flatnonzero(p[k:] - p[k] > sigmas * trial.meta["noise_kPa"])
    return float(t[k + above[0]]) if above.size else math.nan


def bound_time(trial, t_contact, arl=1e10):
    """When the noise-free rise's cumulative Σ ((P − P_c)/σ)² from the true contact reaches
    2 ln(arl) (NaN if never): the log-likelihood ratio of the contact against the rest, which
    grows by s²/2 a sample for a shift of s σ, must reach ln(arl) for false alarms once in
    ``arl`` samples (Lorden 1971). So an oracle that knew the rise's shape and start sees the
    contact no sooner, at the median: a bound on any detector's median latency at that
    false-alarm rate (a single detection can come sooner by the noise's luck)."""
    t = trial.truth.t_s.to_numpy()
    p = trial.truth.pressure_kPa.to_numpy()
    k = int(np.searchsorted(t, t_contact))
    snr2 = np.cumsum(((p[k:] - p[k]) / trial.meta["noise_kPa"]) ** 2)
    above = np.flatnonzero(snr2 >= 2.0 * math.log(arl))
    return float(t[k + above[0]]) if above.size else math.nan


def force_errors(trial, states, acc):
    true = trial.truth.force_N.to_numpy()
    f = np.array([s.force_N for s in states])
    band = np.array([s.force_hi_N - s.force_N for s in states])
    t = trial.truth.t_s.to_numpy()
    hold = true > 0.5 * true.max()
    for e in trial.events:
        if e["kind"] == "switch":
            hold &= ~((t >= e["t_s"]) & (t < e["t_s"] + 0.05))
    key = (trial.meta["type"], "low" if trial.meta["valve_open"] else "high")
    a = acc.setdefault(key, {"rel": [], "within": [], "bias": []})
    a["rel"] += list(np.abs(f - true)[hold] / true[hold])
    a["within"] += list(np.abs(f - true)[hold] <= np.maximum(0.05 * true[hold], band[hold]))
    a["bias"].append(float(np.mean((f - true)[hold] / true[hold])))


#: the rest pressure's drift in the quiet signal (kPa at t s of ``seconds``)
DRIFTS = {
    "steady": lambda t, s: 0.0 * t,
    "warming 0.02 kPa/s, then steady": lambda t, s: 0.02 * np.minimum(t, s / 2),
    "cooling by 0.3 kPa, τ 60 s": lambda t, s: -0.3 * (1.0 - np.exp(-t / 60.0)),
}


def quiet(dense, method, seconds, seed, drift):
    t = np.arange(int(seconds * 1000)) * 1e-3
    p = Sensor.preset("elvh", seed=seed).read(SETUP + DRIFTS[drift](t, seconds))
    prm = SenseParams(EstimatorParams(SETUP, RES, Sensor.preset("elvh").noise_kPa, 0.05,
                                      gas=SENSE_GAS), ContactParams(method=method))
    s = SenseStream(dense, prm)
    for a, b in zip(t.tolist(), p.tolist()):
        s.push(a, b, 0)
    return len(s.events)


def prf(c):
    tp, fn, fp = c
    p = tp / (tp + fp) if tp + fp else float("nan")
    r = tp / (tp + fn) if tp + fn else float("nan")
    return p, r, 2 * p * r / (p + r) if p + r else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--per-type", type=int, default=50)
    ap.add_argument("--types", default="ABCD")
    ap.add_argument("--quiet-s", type=float, default=120.0)
    ap.add_argument("--cache", default="build/cache")
    ap.add_argument("--json", default="build/bench-sense.json")
    ap.add_argument("--gas", default="1", help="the traces' air: N[,TAU] (1: isothermal)")
    ap.add_argument("--sense-gas", default=None, help="the estimator's (default: --gas)")
    args = ap.parse_args()
    global GAS, SENSE_GAS
    GAS = gas_option("--gas", args.gas)
    SENSE_GAS = gas_option("--sense-gas", args.sense_gas) if args.sense_gas else GAS
    rng = np.random.default_rng(29)
    res = {m: {"counts": {}, "lat": {}, "rel": {}, "quiet_events": dict.fromkeys(DRIFTS, 0)}
           for m in ("cusum", "threshold")}
    inferred, acc, samples, seconds, t_map, failed = {}, {}, 0, 0.0, {}, []
    for typ in args.types:
        t0 = time.perf_counter()
        m = chamber_map({"type": typ}, setup_kPa=SETUP, reservoir_mm3=RES, stroke_mm=STROKE,
                        mesh_size=1.0, cache_dir=args.cache)
        dense = DenseMap(m)
        t_map[typ] = time.perf_counter() - t0
        trials = scenarios(m, rng, args.per_type, failed)
        for trial in trials:
            trial.meta["type"] = typ
            for method in ("cusum", "threshold"):
                s, states, dt = run_stream(dense, trial, method)
                match(trial.events, s.events, res[method]["counts"], res[method]["lat"],
                      trial.meta["mode"], trial, res[method]["rel"])
                if method == "cusum":
                    force_errors(trial, states, acc)
                    samples, seconds = samples + len(states), seconds + dt
            if trial.meta["scenario"] == "switch":
                s, _, _ = run_stream(dense, trial, "cusum", valve=False)
                match([e for e in trial.events if e["kind"] == "switch"],
                      [e for e in s.events if e["kind"] == "switch"], inferred, {}, "")
        for method in res:
            seed = int(rng.integers(1 << 30))
            for k, drift in enumerate(DRIFTS):
                res[method]["quiet_events"][drift] += quiet(dense, method, args.quiet_s,
                                                            seed + k, drift)
        print(f"Type {typ}: {len(trials)} scenarios (map {t_map[typ]:.1f} s); draws the "
              f"circuit could not integrate so far: {len(failed)}"
              + (f" (last: {failed[-1]})" if failed else ""), flush=True)
    report(args, res, inferred, acc, samples, seconds, len(args.types) * args.per_type)


def report(args, res, inferred, acc, samples, seconds, n):
    out = {"scenarios": n, "streaming_samples_per_s": samples / seconds, "detectors": {},
           "gas": [GAS.n, GAS.thermal_time_s], "sense_gas": [SENSE_GAS.n,
                                                             SENSE_GAS.thermal_time_s]}
    print(f"\n{n} scenarios, Types {args.types}, 1 kHz, ELVH noise (σ 0.086 kPa), "
          f"reservoir {RES:g} mm³, setup {SETUP:g} kPa; the traces' gas n = {GAS.n:g}, "
          f"τ = {GAS.thermal_time_s:g} s, sensed with n = {SENSE_GAS.n:g}, "
          f"τ = {SENSE_GAS.thermal_time_s:g} s")
    quiet_min = len(args.types) * args.quiet_s / 60.0
    for method, r in res.items():
        print(f"\n== contact detector: {method}")
        for mode, lat in sorted(r["lat"].items()):
            ms = 1e3 * np.array([x[:2] for x in lat])
            print(f"contact latency, {mode} mode: median {np.median(ms[:, 0]):.1f} ms, 95th "
                  f"percentile {np.percentile(ms[:, 0], 95):.1f} ms ({len(lat)} contacts); "
                  f"from the signal's 1σ: median {np.nanmedian(ms[:, 1]):.1f} ms, 95th "
                  f"{np.nanpercentile(ms[:, 1], 95):.1f} ms; the bound of any detector "
                  f"with false alarms once in 1e10 samples: median "
                  f"{np.nanmedian([1e3 * x[3] for x in lat]):.1f} ms")
            for v in sorted({x[2] for x in lat if x[2] is not None}):
                sub = 1e3 * np.array([(x[0], x[1], x[3]) for x in lat if x[2] == v])
                print(f"    presses at {v:g} mm/s: median {np.median(sub[:, 0]):.1f} ms "
                      f"(from 1σ {np.nanmedian(sub[:, 1]):.1f} ms; bound "
                      f"{np.nanmedian(sub[:, 2]):.1f} ms), 95th "
                      f"{np.percentile(sub[:, 0], 95):.1f} ms ({len(sub)})")
        for mode, lat in sorted(r["rel"].items()):
            ms = 1e3 * np.array(lat)
            print(f"release latency, {mode} mode: median {np.median(ms):.1f} ms, 5th and 95th "
                  f"percentiles {np.percentile(ms, 5):.1f}, {np.percentile(ms, 95):.1f} ms "
                  f"({len(lat)} releases; negative: before the load was gone)")
        print(f"{'event':24s} {'mode':5s} {'TP':>4s} {'FN':>4s} {'FP':>4s} {'precision':>9s} "
              f"{'recall':>6s} {'F1':>5s}")
        d = {}
        keys = sorted(r["counts"], key=lambda k: (k if isinstance(k, str) else k[1],
                                                  "" if isinstance(k, str) else k[0]))
        for key in keys:
            c = r["counts"][key]
            kind, mode = (key, "all") if isinstance(key, str) else (key[1], key[0])
            p, rc, f1 = prf(c)
            d[kind if mode == "all" else f"{kind}/{mode}"] = {
                "tp": c[0], "fn": c[1], "fp": c[2], "precision": p, "recall": rc, "f1": f1}
            print(f"{kind:24s} {mode:5s} {c[0]:4d} {c[1]:4d} {c[2]:4d} {p:9.3f} {rc:6.3f} "
                  f"{f1:5.3f}")
        print("('contact beyond the bound': true contacts whose bound_time is past the window's "
              f"{WINDOW['contact'][1]:g} s, seen anyway (TP) or missed (FN))")
        for drift, n in r["quiet_events"].items():
            print(f"false events in quiet signal, {drift}: {n} in {quiet_min:.0f} min "
                  f"({n / quiet_min:.3g}/min)")
        fpm = {drift: n / quiet_min for drift, n in r["quiet_events"].items()}
        out["detectors"][method] = {"events": d, "false_per_min": fpm, "latency_ms": {
            mode: {"median": float(np.median([x[0] for x in v]) * 1e3),
                   "p95": float(np.percentile([x[0] for x in v], 95) * 1e3),
                   "from_signal_median": float(np.nanmedian([x[1] for x in v]) * 1e3),
                   "from_signal_p95": float(np.nanpercentile([x[1] for x in v], 95) * 1e3),
                   "bound_median": float(np.nanmedian([x[3] for x in v]) * 1e3)}
            for mode, v in r["lat"].items()}, "release_latency_ms": {
            mode: {"median": float(np.median(v) * 1e3), "p5": float(np.percentile(v, 5) * 1e3),
                   "p95": float(np.percentile(v, 95) * 1e3)} for mode, v in r["rel"].items()}}
    if inferred:
        p, rc, f1 = prf(inferred["switch"])
        print(f"\nswitch inferred from P (no valve column): precision {p:.3f} recall {rc:.3f} "
              f"F1 {f1:.3f} ({inferred['switch']})")
        out["switch_inferred"] = {"precision": p, "recall": rc, "f1": f1}
    print("\nforce over the holds (true F > half its peak), estimate against the trace:")
    print(f"{'type':4s} {'mode':4s} {'median |e|/F':>12s} {'95th pct':>9s} {'mean bias':>9s} "
          f"{'within max(5 %, band)':>22s}")
    out["force"] = {}
    for (typ, mode), a in sorted(acc.items()):
        rel = np.array(a["rel"])
        row = {"median": float(np.median(rel)), "p95": float(np.percentile(rel, 95)),
               "bias": float(np.mean(a["bias"])), "within": float(np.mean(a["within"]))}
        out["force"][f"{typ}-{mode}"] = row
        print(f"{typ:4s} {mode:4s} {100 * row['median']:11.2f}% {100 * row['p95']:8.2f}% "
              f"{100 * row['bias']:8.2f}% {100 * row['within']:21.1f}%")
    print(f"\nstreaming: {samples} samples in {seconds:.2f} s = {samples / seconds:,.0f} "
          "samples/s on one core (estimator + CUSUM + slip + compliance)")
    Path(args.json).parent.mkdir(parents=True, exist_ok=True)
    Path(args.json).write_text(json.dumps(out, indent=2, default=float) + "\n")


if __name__ == "__main__":
    main()
