"""Where a wall curve's time goes: cProfile of one warm Table 1 stadium curve (Type B, 40 kPa,
inflation + 17 plate positions over 4 mm), the issue-26 figure, top functions by cumulative
time. Run on a quiet machine.

    python bench/profile_wall.py [--dome] [--top 30]
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import time

from spsc.cad.geometry import preset
from spsc.fem.wall import wall_curve
from spsc.materials import material


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dome", action="store_true", help="l = 0 instead of Table 1's l")
    ap.add_argument("--top", type=int, default=30)
    args = ap.parse_args(argv)
    g = preset("B", l=0.0) if args.dome else preset("B")
    kw = dict(pressure_kPa=40, stroke_mm=4, points=18)
    wall_curve(g, material("tpu60a"), **kw)  # warm: imports, first BLAS, PARDISO's library
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    c = wall_curve(g, material("tpu60a"), **kw)
    prof.disable()
    print(f"{time.perf_counter() - t0:.3f} s under the profiler, {c.solver.iterations} Newton "
          f"iterations, {c.solver.details['unknowns']} unknowns")
    pstats.Stats(prof).sort_stats("cumulative").print_stats(args.top)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
