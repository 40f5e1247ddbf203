"""The surrogate's speed and size (issue 48). Time it on a quiet machine.

    python bench/bench_surrogate.py [--sweep] [--design]     (make bench-surrogate [FULL=1])

Prints: the shipped file's size and load time (a fresh process), one 25-point curve warm
inside Python (with and without the error estimate), curve points per second batched on one
core (designs × 25 points, mean only), and ``spsc curve --model surrogate`` as a whole process
beside ``spsc curve --model membrane`` and ``--model wall`` on the same dome (Type B profile,
l = 0), as medians of five runs. The time domain's map of a new stadium
of Table 1's proportions (the table1 surrogate). ``--sweep``: also the wall model's map of it,
and ``spsc sweep --model surrogate --samples 100000`` over the domes (two workers,
printability judged) as a process; ``--design``: ``spsc design
--model surrogate`` with two targets, its wall confirmation included, as a process.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one core, as the issue asks

from spsc.models.surrogate.domain import BOUNDS  # noqa: E402
from spsc.models.surrogate.predict import SHIPPED, load  # noqa: E402

DOME = np.array([[11.0, 13.0, 0.0, 1.0, 2.0, 2.2, 0.0]])
MU = 5.0 / 3.0


def _median_s(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def file_figures() -> None:
    code = ("import time; t = time.perf_counter(); from spsc.models.surrogate.predict import "
            "load; load(); print(time.perf_counter() - t)")
    runs = [float(subprocess.run([sys.executable, "-c", code], capture_output=True,
                                 text=True, check=True).stdout) for _ in range(5)]
    print(f"file {SHIPPED.name}: {SHIPPED.stat().st_size / 1e6:.2f} MB; import + load in a "
          f"fresh process: median {statistics.median(runs):.3f} s (min {min(runs):.3f})")


def one_curve() -> None:
    sur = load()
    y = np.linspace(0, 6, 25)[None, :]
    for _ in range(50):  # warm: the caches, the k-d trees, the allocator
        sur.curves(DOME, MU, y, 40.0, 0.0, 1.0)
    times = []
    for _ in range(1000):
        t = time.perf_counter()
        sur.curves(DOME, MU, y, 40.0, 0.0, 1.0)
        times.append(time.perf_counter() - t)
    err = _median_s(lambda: sur.curves(DOME, MU, y, 40.0, 0.0, 1.0, draws=32), 20)
    print(f"one 25-point curve, warm: median {1000 * statistics.median(times):.2f} ms (min "
          f"{1000 * min(times):.2f}, 1000 runs; mean only); {1000 * err:.1f} ms with the error "
          "estimate (32 posterior draws)")


def batched(m: int = 20_000) -> None:
    sur = load()
    rng = np.random.default_rng(0)
    lo = np.array([BOUNDS[k][0] for k in ("h/w", "t0/w", "n1", "n2", "cy")])
    hi = np.array([BOUNDS[k][1] for k in ("h/w", "t0/w", "n1", "n2", "cy")])
    r = lo + rng.random((m, 5)) * (hi - lo)
    w = 11.0
    params = np.column_stack([np.full(m, w), r[:, 0] * w, np.zeros(m), r[:, 1] * w,
                              r[:, 2], r[:, 3], r[:, 4]])
    y = np.linspace(0, 1, 25)[None, :] * (0.3 * params[:, 1:2])
    p = rng.uniform(10, 50, m)
    from threadpoolctl import threadpool_limits

    for threads in (1, None):  # one core (one BLAS thread), then BLAS's own threads
        with threadpool_limits(threads):
            sur.curves(params[:500], MU, y[:500], p[:500], 40_000.0, 1.0)  # warm
            t = time.perf_counter()
            out = sur.curves(params, MU, y, p, 40_000.0, 1.0)
            dt = time.perf_counter() - t
        where = "on one core (one BLAS thread)" if threads else "with BLAS's threads"
        print(f"batched: {m:,} designs x 25 points in {dt:.2f} s = {m * 25 / dt:,.0f} "
              f"points/s {where} ({np.mean(out['converged']):.4f} of points converged)")


def processes() -> None:
    base = [sys.executable, "-m", "spsc.cli.main", "curve", "--type", "B", "--l", "0",
            "--pressure", "40", "--quiet"]
    out = {}
    for model in ("surrogate", "membrane", "wall"):
        times = []
        for _ in range(5):
            t = time.perf_counter()
            subprocess.run(base + ["--model", model], capture_output=True, check=True)
            times.append(time.perf_counter() - t)
        out[model] = statistics.median(times)
    print("spsc curve as a process (Type B profile as a dome, 40 kPa, closed; median of 5): "
          + ", ".join(f"{k} {v:.2f} s" for k, v in out.items())
          + f"; membrane / surrogate = {out['membrane'] / out['surrogate']:.2f}, "
          f"wall / surrogate = {out['wall'] / out['surrogate']:.2f}")


DOMES = ["--w", "8:14", "--h", "11:16", "--l", "0", "--t0", "0.6:1.5", "--n1", "2:3",
         "--n2", "1:4", "--cy", "0:0.6", "--pressure", "10:40"]


def _timed(argv: list[str]) -> tuple[float, str]:
    t = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "spsc.cli.main", *argv], capture_output=True,
                          text=True)
    return time.perf_counter() - t, done.stdout


def sweep(samples: int = 100_000) -> None:
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        seconds, out = _timed(["sweep", "--model", "surrogate", "--samples", str(samples),
                               *DOMES, "--workers", "2", "--quiet", "--out",
                               f"{d}/s.parquet"])
        import pandas as pd

        df = pd.read_parquet(f"{d}/s.parquet")
    print(f"spsc sweep --model surrogate --samples {samples:,} (domes, 2 workers, fdm "
          f"printability judged) as a process: {seconds:.1f} s; per design "
          f"{1000 * df['seconds'].mean():.2f} ms of worker time; "
          + ", ".join(f"{k} {v}" for k, v in df["status"].value_counts().items()))


def design() -> None:
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        seconds, out = _timed(["design", "--model", "surrogate", "--target",
                               "stiffness_high=5", "--target", "sensitivity_high=3", "--l", "0",
                               "--seed", "1", "--workers", "2", "--verify", "none",
                               "--no-build", "--quiet", "--out", f"{d}/run"])
        import json

        doc = json.loads((Path(d) / "run" / "design.json").read_text())
    c = doc["confirmed"]
    print(f"spsc design --model surrogate, two targets (stiffness_high=5, sensitivity_high=3), "
          f"as a process: {seconds:.1f} s ({doc['trials']} trials in "
          f"{doc['run']['loop_seconds']:.1f} s, the wall confirmation of "
          f"{len(c['candidates'])} designs {c['seconds']:.1f} s); goal "
          f"{'met' if doc['met'] else 'NOT met'} by the wall model")


def stadium_map(wall: bool = False) -> None:
    """The chamber map ``spsc simulate`` builds for a new stadium of Table 1's proportions
    (Type C's profile at w = 9 mm, c_y = 0.25, silicone 40A; the table1 surrogate), as a
    fresh process would (the file's load included), and with ``wall`` the wall model's."""
    from spsc.cad.geometry import preset
    from spsc.dynamics.chamber_map import build_map
    from spsc.dynamics.surrogate_map import surrogate_map
    from spsc.materials import material

    k = 9.0 / 11.0
    g = preset("C", w=9.0, h=13 * k, l=3 * k, t0=k, cy=0.25)
    mat = material("silicone40a")
    kw = dict(setup_kPa=10.0, top_kPa=20.0, y_max_mm=4.0)
    load.cache_clear()
    t = time.perf_counter()
    surrogate_map(g, mat, **kw)
    first = time.perf_counter() - t
    warm = _median_s(lambda: surrogate_map(g, mat, **kw), 20)
    line = (f"the time domain's map of a new stadium (Type C profile, w = 9 mm, Table 1's "
            f"proportions, c_y = 0.25, silicone 40A): {first:.3f} s with the files' load, "
            f"{1000 * warm:.1f} ms warm")
    if wall:
        t = time.perf_counter()
        build_map(g, mat, **kw)
        line += f"; the wall model's {time.perf_counter() - t:.1f} s"
    print(line)


if __name__ == "__main__":
    file_figures()
    one_curve()
    batched()
    processes()
    stadium_map(wall="--sweep" in sys.argv)
    if "--sweep" in sys.argv:
        sweep()
    if "--design" in sys.argv:
        design()
