"""Benchmark and headline table of the membrane model.

    .venv/bin/python bench/bench_membrane.py [--size table1|GS1] [--repeat 3] [--full]

Prints, for Types A–D × p_i ∈ {10, 40} kPa × {high, low} stiffness: converged over the full
stroke (0–6 mm, 41 positions), mean stiffness dF/dy (N/mm), mean sensitivity dP/dy (kPa/mm) and
the time per curve (inflation + 40 plate positions, best of --repeat, one core). --full adds
the docs/design.md headline means over p_i = 10, 20, 30, 40 kPa, the JND depths at 10 kPa and the
GS1 inflation percentages with Elastic 50A at 10 kPa (sec. 2.3.3).
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from spsc.cad.geometry import preset  # noqa: E402
from spsc.membrane.lumped import jnd_depth, mean_sensitivity, mean_stiffness  # noqa: E402
from spsc.materials import material  # noqa: E402
from spsc.membrane.solver import solve  # noqa: E402

MODES = {"high": 0.0, "low": 40000.0}


def timed(geometry, mat, p, vr, repeat):
    best, result = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        result = solve(geometry, mat, pressure_kPa=p, reservoir_mm3=vr, stroke_mm=6.0, points=41)
        best = min(best, time.perf_counter() - t)
    return result, best


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", default="table1")
    ap.add_argument("--material", default="tpu60a")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--full", action="store_true")
    args = ap.parse_args(argv)
    mat = material(args.material)
    solve(preset("B", args.size), mat, pressure_kPa=10.0, points=5)  # warm-up (imports, caches)
    print(f"membrane model, size {args.size}, material {mat.name}, stroke 0-6 mm, 41 positions")
    print(f"{'type':4} {'p_i':>4} {'mode':5} {'converged':9} {'stiff N/mm':>10} "
          f"{'sens kPa/mm':>11} {'F(6) N':>7} {'p(6) kPa':>8} {'time s':>7} {'Newton':>6}")
    times = []
    for t in "ABCD":
        g = preset(t, args.size)
        for p in (10.0, 40.0):
            for mode, vr in MODES.items():
                r, dt = timed(g, mat, p, vr, args.repeat)
                times.append(dt)
                c = r.curve
                ok = "yes" if r.converged else f"no ({r.y_reached_mm:.2f} mm)"
                k = mean_stiffness(c) if r.converged else float("nan")
                s = mean_sensitivity(c) if r.converged else float("nan")
                print(f"{t:4} {p:4.0f} {mode:5} {ok:9} {k:10.3f} {s:11.3f} {c.force_N[-1]:7.2f} "
                      f"{c.pressure_kPa[-1]:8.2f} {dt:7.3f} {r.iterations:6d}")
    print(f"time per curve: median {np.median(times):.3f} s, max {np.max(times):.3f} s")
    if not args.full:
        return
    print("\nheadline means over p_i = 10, 20, 30, 40 kPa (docs/design.md)")
    print(f"{'type':4} {'mode':5} {'stiff N/mm':>10} {'sens kPa/mm':>11}")
    allm = {m: ([], []) for m in MODES}
    curves10 = {}
    for t in "ABCD":
        g = preset(t, args.size)
        for mode, vr in MODES.items():
            cs = [solve(g, mat, pressure_kPa=p, reservoir_mm3=vr).curve for p in (10, 20, 30, 40)]
            curves10[t, mode] = cs[0]
            ok = all(c.all_converged for c in cs)
            k, s = (mean_stiffness(cs), mean_sensitivity(cs)) if ok else (np.nan, np.nan)
            allm[mode][0].append(k)
            allm[mode][1].append(s)
            print(f"{t:4} {mode:5} {k:10.3f} {s:11.3f}")
    for mode in MODES:
        print(f"all  {mode:5} {np.mean(allm[mode][0]):10.3f} {np.mean(allm[mode][1]):11.3f}")
    print("\nJND depth at p_i = 10 kPa (|F_high - F_low| >= max(10 % F_low, 5 N)), membrane force p·A only")
    for t in "ABCD":
        print(f"{t}: {jnd_depth(curves10[t, 'high'], curves10[t, 'low']):.3f} mm")
    print("\nGS1 inflation at 10 kPa, Elastic 50A (paper sec. 2.3.3: A 5.2 %, B 10.5 %, C 0.1 %, D 12.6 %)")
    e50 = material("elastic50a")
    for t in "ABCD":
        r = solve(preset(t, "GS1"), e50, pressure_kPa=10.0, stroke_mm=0.0)
        c = r.curve
        print(f"{t}: {100 * (c.inflated_volume_mm3 / c.nominal_volume_mm3 - 1):.2f} %")


if __name__ == "__main__":
    main()
