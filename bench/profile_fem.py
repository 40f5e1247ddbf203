"""Where a 3D FEM chamber curve's time goes: cProfile of one Type B curve (Table 1, 40 kPa,
3 mm in 6 increments, 1 mm × 2 layers: the issue-26 row), the mesh loaded from the cache
(built on a first, unprofiled call). Top functions by cumulative time. Run on a quiet machine.

    python bench/profile_fem.py [--dome] [--size 1.0] [--layers 2] [--top 30]
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import time

from spsc.cad.geometry import preset
from spsc.fem.engine.settings import SEMISMOOTH_CONTACT, Settings
from spsc.fem.solid.chamber import build_model, chamber_run, run_chamber
from spsc.materials import material


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dome", action="store_true", help="l = 0 instead of Table 1's l")
    ap.add_argument("--size", type=float, default=1.0, help="mesh size (mm)")
    ap.add_argument("--layers", type=int, default=2)
    ap.add_argument("--top", type=int, default=30)
    ap.add_argument("--cache", default="build/cache/fem")
    args = ap.parse_args(argv)
    g = preset("B", l=0.0) if args.dome else preset("B")
    run = chamber_run(g, material("tpu60a"), pressure_kPa=40, stroke_mm=3, points=7,
                      mesh_size_mm=args.size, layers=args.layers)
    build_model(run, cache_dir=args.cache)  # the mesh into the cache, imports, first BLAS
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    # the settings `spsc curve --model fem` takes (spsc.models.fem)
    settings = Settings(warm_start=True, low_rank=16, **SEMISMOOTH_CONTACT)
    curve, result, model = run_chamber(run, cache_dir=args.cache, settings=settings)
    prof.disable()
    print(f"{time.perf_counter() - t0:.2f} s under the profiler, {result.iterations} Newton "
          f"iterations, {model.disc.n} unknowns, converged: {result.converged}")
    pstats.Stats(prof).sort_stats("cumulative").print_stats(args.top)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
