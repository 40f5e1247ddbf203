"""How much of the types' hysteresis spread the paper's unstated rate and stroke explain
(issue 52, item 1): for each squeeze speed and stroke of a range, the Prony term (τ = 1 s) of
the viscous wall **calibrated** on the vented Type B chamber's 3.8 N at that speed and
stroke, then Types A, C and D **predicted** (sec. 3.1: 8.1, 4.0, 4.5 N); the errors and the
order at each, and the spread of each type's prediction over the range.

    python bench/bench_hysteresis_unknowns.py [--speeds 0.5,1,2,5] [--strokes 4,5,6] [--json OUT]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from spsc.cad.geometry import preset
from spsc.fem.wall.cycle import wall_cycle
from spsc.materials import material
from spsc.materials.prony import Prony

PAPER = {"A": 8.1, "B": 3.8, "C": 4.0, "D": 4.5}


def hysteresis(kind, beta, speed, stroke) -> float:
    r = wall_cycle(preset(kind), material("tpu60a"), Prony(((beta, 1.0),)), stroke_mm=stroke,
                   speed_mm_s=speed, points=int(round(4 * stroke)) + 1)
    return r.hysteresis_N if r.complete else float("nan")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--speeds", default="0.5,1,2,5")
    ap.add_argument("--strokes", default="4,5,6")
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    rows = []
    for stroke in (float(v) for v in a.strokes.split(",")):
        for speed in (float(v) for v in a.speeds.split(",")):
            try:
                beta = brentq(lambda b: hysteresis("B", b, speed, stroke) - PAPER["B"], 0.05,
                              8.0, xtol=2e-3)
            except ValueError:  # B's loop cannot reach 3.8 N here
                print(f"stroke {stroke:g} mm, {speed:g} mm/s: no beta in (0.05, 8) gives "
                      "Type B 3.8 N", flush=True)
                continue
            pred = {k: hysteresis(k, beta, speed, stroke) for k in "ACD"}
            order = " < ".join(sorted(["B", *[k for k in pred if pred[k] == pred[k]]],
                                      key=lambda k: PAPER["B"] if k == "B" else pred[k]))
            rows.append({"stroke_mm": stroke, "speed_mm_s": speed, "beta": beta, **pred,
                         "order": order})
            print(f"stroke {stroke:g} mm, {speed:g} mm/s: beta {beta:.3f}; " + ", ".join(
                f"{k} {pred[k]:.2f} N ({100 * (pred[k] / PAPER[k] - 1):+.0f} %)" for k in pred)
                + f"; order {order} ({time.perf_counter() - t0:.0f} s)", flush=True)
    for k in "ACD":
        v = np.array([r[k] for r in rows if r[k] == r[k]])
        if v.size:
            print(f"Type {k}: {v.min():.2f} to {v.max():.2f} N over the range (paper "
                  f"{PAPER[k]} N)")
    right = [r for r in rows if r["order"] == "B < C < D < A"]
    print(f"the paper's order B < C < D < A at {len(right)} of {len(rows)} settings")
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
