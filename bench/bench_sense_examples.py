"""``spsc sense`` on the traces of the project's own scenarios (issue 53): each example of
``examples/`` simulated (``spsc simulate``: air, n = 1.4 with its thermal time, the ELVH at
1 kHz), its measured pressure read back by the estimator as ``spsc sense`` runs it (the same
chamber map, its defaults), once with the isothermal gas (``--gas 1``, the paper's static
tests) and once with the scenario's own gas (``--gas N,TAU``); against the trace's truth:

* the events: contact and release (the true ones where the true force rises above or falls
  to 0.01 N), with their time error, and events with no true counterpart (phantoms);
* the force error while the true force is above 0.5 N (median and largest |ΔF|, and relative
  to the true force), per mode;
* the 95 % band's coverage: the share of samples whose true force is inside the band, over
  the whole trace and while touching, per mode (target ≥ 95 %).

    python bench/bench_sense_examples.py [--examples press-hold-switch,...] [--cache DIR]
        [--json OUT]

Equivalent command for one trace (after ``spsc simulate EXAMPLE --out DIR``):
``spsc sense DIR/trace.parquet --pressure-column pressure_measured_kPa --type B --pressure 40
--reservoir 40000 --gas 1.4,0.5 --out OUT``.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from spsc.dynamics import Gas
from spsc.dynamics.scenario import read_scenario
from spsc.dynamics.simulate import simulate
from spsc.sensing import DenseMap, EstimatorParams, SenseParams, SenseStream
from spsc.sensing.chamber import chamber_map
from spsc.sensing.detectors import ContactParams
from spsc.sensing.log import noise_of

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ("press-hold-switch", "press-force-creep")
TOUCH_N, LOADED_N = 0.01, 0.5
#: a detected event within this window of the true one (s) is a hit
WINDOW = {"contact": (-0.02, 0.4), "release": (-0.15, 0.3)}


def true_events(t, f) -> list[tuple[float, str]]:
    touching = f > TOUCH_N
    out = []
    for i in np.flatnonzero(np.diff(touching.astype(int))):
        out.append((float(t[i + 1]), "contact" if touching[i + 1] else "release"))
    return out


def match(found: list[dict], truth: list[tuple[float, str]]) -> dict:
    """Hits (with their time error), misses and phantoms of contact and release."""
    used, hits, misses = set(), [], []
    for t, kind in truth:
        lo, hi = WINDOW[kind]
        cand = [i for i, e in enumerate(found) if e["kind"] == kind and i not in used
                and lo <= e["t_s"] - t <= hi]
        if cand:
            i = min(cand, key=lambda i: abs(found[i]["t_s"] - t))
            used.add(i)
            hits.append({"kind": kind, "true_s": t, "found_s": found[i]["t_s"],
                         "error_ms": 1e3 * (found[i]["t_s"] - t)})
        else:
            misses.append({"kind": kind, "true_s": t})
    phantoms = [{"kind": e["kind"], "t_s": e["t_s"]} for i, e in enumerate(found)
                if e["kind"] in WINDOW and i not in used]
    return {"hits": hits, "misses": misses, "phantoms": phantoms}


def sense(dense, log, gas, setup, reservoir, valve_open) -> tuple[SenseStream, dict]:
    noise = noise_of(log.pressure_measured_kPa.to_numpy())
    prm = SenseParams(EstimatorParams(setup, reservoir, noise, 0.05, valve_open=valve_open,
                                      gas=gas), ContactParams(), rate_Hz=1000.0)
    s = SenseStream(dense, prm)
    cols = {k: [] for k in ("force", "lo", "hi", "mode")}
    for t, p, v in zip(log.t_s.tolist(), log.pressure_measured_kPa.tolist(),
                       log.valve_open.tolist()):
        st, _ = s.push(t, p, v)
        cols["force"].append(st.force_N)
        cols["lo"].append(st.force_lo_N)
        cols["hi"].append(st.force_hi_N)
        cols["mode"].append(st.mode)
    return s, {k: np.asarray(v) for k, v in cols.items()}


def score(trace, est, events) -> dict:
    f = trace.force_N.to_numpy()
    t = trace.t_s.to_numpy()
    mode = np.where(trace.valve_open.to_numpy() > 0, "low", "high")
    inside = (f >= est["lo"] - 1e-9) & (f <= est["hi"] + 1e-9)
    err = est["force"] - f
    out = {"coverage_all": float(inside.mean()), "events": match(events, true_events(t, f))}
    for m in ("high", "low"):
        touch = (f > TOUCH_N) & (mode == m)
        loaded = (f > LOADED_N) & (mode == m)
        if touch.any():
            out[f"coverage_touching_{m}"] = float(inside[touch].mean())
        if loaded.any():
            e = np.abs(err[loaded])
            out[f"force_err_{m}"] = {"median_N": float(np.median(e)), "max_N": float(e.max()),
                                     "median_rel": float(np.median(e / f[loaded])),
                                     "max_rel": float((e / f[loaded]).max())}
    touch = f > TOUCH_N
    out["coverage_touching"] = float(inside[touch].mean()) if touch.any() else None
    return out


def run_example(name: str, cache: Path) -> dict:
    sc = read_scenario(ROOT / "examples" / f"{name}.toml")
    sim = simulate(sc, cache_dir=cache)
    tr = sim.trace
    m = chamber_map(sc.chamber.params, material=sc.chamber.material, setup_kPa=sc.setup_kPa,
                    reservoir_mm3=sc.reservoir_mm3, stroke_mm=4.0, cache_dir=cache)
    dense = DenseMap(m)
    res = {"scenario": name, "gas": {"n": sc.gas.n, "thermal_time_s": sc.gas.thermal_time_s},
           "true_events": true_events(tr.t_s.to_numpy(), tr.force_N.to_numpy())}
    for label, gas in (("isothermal", Gas(1.0)), ("scenario_gas", sc.gas)):
        s, est = sense(dense, tr, gas, sc.setup_kPa, sc.reservoir_mm3, sc.valve_open)
        res[label] = score(tr, est, s.events)
        res[label]["events_found"] = [{"t_s": e["t_s"], "kind": e["kind"]} for e in s.events]
    return res


def _print(r: dict) -> None:
    print(f"== {r['scenario']} (gas n = {r['gas']['n']}, τ = {r['gas']['thermal_time_s']} s); "
          "true events: " + ", ".join(f"{k} {t:.3f} s" for t, k in r["true_events"]))
    for label in ("isothermal", "scenario_gas"):
        s = r[label]
        ev = s["events"]
        hits = ", ".join(f"{h['kind']} {h['error_ms']:+.0f} ms" for h in ev["hits"])
        print(f"  {label:13s} events: hits [{hits}] misses {len(ev['misses'])} "
              f"phantoms {[(p['kind'], round(p['t_s'], 3)) for p in ev['phantoms']]}")
        for m in ("high", "low"):
            fe = s.get(f"force_err_{m}")
            cov = s.get(f"coverage_touching_{m}")
            if fe:
                print(f"    {m:4s}: |ΔF| median {fe['median_N']:.3f} N ({100 * fe['median_rel']:.1f} %),"
                      f" max {fe['max_N']:.3f} N ({100 * fe['max_rel']:.1f} %); band coverage "
                      f"touching {100 * cov:.1f} %")
        print(f"    coverage: all samples {100 * s['coverage_all']:.1f} %, touching "
              f"{100 * s['coverage_touching']:.1f} %")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--examples", default=",".join(EXAMPLES))
    ap.add_argument("--cache", default=str(ROOT / "build" / "cache"))
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    results = [run_example(n.strip(), Path(a.cache)) for n in a.examples.split(",")]
    for r in results:
        _print(r)
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1, default=float) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
