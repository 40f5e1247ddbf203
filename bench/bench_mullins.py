"""The Mullins effect as a source of the paper's hysteresis (issue 52, item 1): Ogden–Roxburgh
softening (:mod:`spsc.fem.mullins`) on the wall of the vented Table 1 chambers squeezed 6 mm
at 1 mm/s (sec. 3.1: 8.1, 3.8, 4.0, 4.5 N for A-D):

1. the softening alone, its constants **assumed** (no published cyclic data of printed TPU 60A
   with these constants: r = 2, m = 0.02 MPa — a third of the wall's largest energy density
   at 6 mm —, β = 0, the 1999 model): what it adds to each type, and the order it gives;
   alone it cannot reach Type B's 3.8 N (r → 1 at m = 0.02 MPa gives 3.6 N);
2. every source together — the softening as assumed, Coulomb friction μ = 0.3 (assumed) and
   the Prony term (τ = 1 s) whose β is **calibrated** on Type B's 3.8 N — and Types A, C, D
   **predicted** with the same constants;
3. Type B's second cycle with the softening alone (pseudo-elastic: a chamber squeezed before,
   as a bench's later cycles, dissipates almost nothing of it).

    python bench/bench_mullins.py [--r 2] [--m 0.02] [--beta 0] [--mu 0.3] [--json OUT]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from scipy.optimize import brentq

from spsc.cad.geometry import preset
from spsc.fem.mullins import MullinsParams
from spsc.fem.wall.cycle import wall_cycle
from spsc.materials import material

PAPER = {"A": 8.1, "B": 3.8, "C": 4.0, "D": 4.5}


def loop(kind: str, prm, cycles: int = 1, prony=None, friction=None):
    return wall_cycle(preset(kind), material("tpu60a"), prony, stroke_mm=6.0, speed_mm_s=1.0,
                      points=25, mullins=prm, cycles=cycles, friction=friction)


def _row(kind, res) -> dict:
    err = 100 * (res.hysteresis_N / PAPER[kind] - 1)
    print(f"  Type {kind}: {res.hysteresis_N:.2f} N at {res.hysteresis_at_mm:.2f} mm (paper "
          f"{PAPER[kind]} N, {err:+.0f} %), {res.dissipated_mJ:.1f} mJ, peak "
          f"{res.force_load_N[-1]:.2f} N" + ("" if res.complete else f" ({res.message})"),
          flush=True)
    return {"hysteresis_N": res.hysteresis_N, "at_mm": res.hysteresis_at_mm,
            "dissipated_mJ": res.dissipated_mJ, "peak_N": float(res.force_load_N[-1]),
            "complete": res.complete, "error_pct": err}


def _order(rows) -> str:
    done = [k for k in rows if rows[k]["hysteresis_N"] == rows[k]["hysteresis_N"]]
    missing = sorted(set(rows) - set(done))
    return " < ".join(sorted(done, key=lambda k: rows[k]["hysteresis_N"])) + (
        f" ({', '.join(missing)} not completed)" if missing else "")


def main(argv=None) -> int:
    from spsc.materials.prony import Prony

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--r", type=float, default=2.0)
    ap.add_argument("--m", type=float, default=0.02)
    ap.add_argument("--beta", type=float, default=0.0)
    ap.add_argument("--mu", type=float, default=0.3)
    ap.add_argument("--json", default=None)
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    prm = MullinsParams(a.r, a.m, a.beta)
    print(f"1. the softening alone (r = {a.r}, m = {a.m} MPa, beta = {a.beta}; assumed)")
    alone = {k: _row(k, loop(k, prm)) for k in "ABCD"}
    print(f"   order, smallest first: {_order(alone)} (paper B < C < D < A)")
    print(f"2. together: the softening, Coulomb mu = {a.mu} (assumed), the Prony term (tau = 1 s)"
          " with beta calibrated on Type B")

    def miss(b):
        res = loop("B", prm, prony=Prony(((b, 1.0),)), friction=a.mu)
        print(f"   beta = {b:.4f}: Type B {res.hysteresis_N:.3f} N", flush=True)
        return res.hysteresis_N - PAPER["B"]

    beta = 0.0 if miss(1e-6) >= 0 else brentq(miss, 1e-6, 0.646, xtol=2e-3)
    prony = Prony(((max(beta, 1e-6), 1.0),))
    print(f"   calibrated: beta = {beta:.4f} ({time.perf_counter() - t0:.0f} s so far)")
    together = {k: _row(k, loop(k, prm, prony=prony, friction=a.mu)) for k in "ABCD"}
    print(f"   order, smallest first: {_order(together)} (paper B < C < D < A)")
    second = loop("B", prm, cycles=2)
    print(f"3. Type B, the softening alone, second cycle: {second.hysteresis_N:.3f} N, "
          f"{second.dissipated_mJ:.2f} mJ (first {alone['B']['dissipated_mJ']:.1f} mJ)")
    print(f"{time.perf_counter() - t0:.0f} s")
    if a.json:
        Path(a.json).write_text(json.dumps({
            "mullins": {"r": a.r, "m": a.m, "beta": a.beta}, "mu": a.mu, "alone": alone,
            "together": {"prony_beta": beta, "types": together},
            "second_B": {"hysteresis_N": second.hysteresis_N,
                         "dissipated_mJ": second.dissipated_mJ},
            "seconds": time.perf_counter() - t0}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
