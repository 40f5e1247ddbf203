"""FEM benchmark: the issue's target run and the sparse-solver measurement.

    python bench/bench_fem.py                      # Type B, 40 kPa, 4 mm in 10 steps, mesh study
    python bench/bench_fem.py --sizes 1.0:2 0.7:3  # mesh-size:layers pairs
    python bench/bench_fem.py --solvers 1.0:2      # factorisation timings on one tangent

Set OMP_NUM_THREADS / MKL_NUM_THREADS to the cores you grant it. Prints one line per run:
unknowns, seconds, Newton iterations, force at the full stroke and its change against the
previous (coarser) mesh; ``--json F`` writes the same.
"""

from __future__ import annotations

import argparse
import json
import os
import time

import numpy as np

from spsc.cad.geometry import preset
from spsc.fem.engine.linsolve import available_solvers, factorize
from spsc.fem.solid.model import FEMModel, Load
from spsc.fem.solid.mesh import spsc_wall
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.materials import material


def _pair(text):
    size, _, layers = text.partition(":")
    return float(size), int(layers or 2)


def bench_run(args):
    out, previous = [], None
    for size, layers in args.sizes:
        run = chamber_run(preset(args.type), material(args.material), pressure_kPa=args.pressure,
                         reservoir_mm3=args.reservoir, stroke_mm=args.stroke, points=args.points,
                         mesh_size_mm=size, layers=layers)
        t0 = time.perf_counter()
        curve, result, model = run_chamber(run, cache_dir=args.cache)
        seconds = time.perf_counter() - t0
        force = float(curve.force_N[-1])
        change = None if previous is None else abs(force / previous - 1)
        row = {"size_mm": size, "layers": layers, "tets": model.mesh.n_tets,
               "unknowns": model.disc.n, "seconds": round(seconds, 1), "ok": result.converged,
               "threads": os.environ.get("OMP_NUM_THREADS", "unset"),
               "steps": args.points - 1,
               "newton_iterations": sum(r.iterations for r in result.records),
               "force_N": force, "pressure_kPa": float(curve.pressure_kPa[-1]),
               "contact_area_mm2": float(curve.contact_area_mm2[-1]),
               "inflated_volume_mm3": curve.inflated_volume_mm3,
               "force_change_vs_previous": change, "message": result.message,
               "instability": result.instability}
        print(json.dumps(row), flush=True)
        out.append(row)
        previous = force
    return out


def bench_solvers(args):
    size, layers = args.solvers
    model = FEMModel.build(spsc_wall(preset(args.type), size, layers=layers),
                           material(args.material))
    ev = model.evaluate(model.zero_state(), Load(pressure=args.pressure * 1e-3))
    free = ~model.fixed
    A = ev.K[free][:, free]
    b = np.ones(A.shape[0])
    rows = []
    names = args.solver_list or available_solvers()
    for name in names:
        t0 = time.perf_counter()
        f = factorize(A, name)
        t1 = time.perf_counter()
        x = f(b)
        t2 = time.perf_counter()
        f2 = factorize(A, name)  # same pattern: PARDISO reuses its analysis
        t3 = time.perf_counter()
        del f2
        row = {"solver": name, "unknowns": A.shape[0], "nnz": A.nnz,
               "factor_s": round(t1 - t0, 3), "solve_s": round(t2 - t1, 3),
               "refactor_s": round(t3 - t2, 3), "negative_pivots": f.negative,
               "pressure_unknowns": model.disc.n_p,
               "residual": float(np.linalg.norm(A @ x - b) / np.linalg.norm(b))}
        print(json.dumps(row), flush=True)
        rows.append(row)
    return rows


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--type", default="B")
    p.add_argument("--material", default="tpu60a")
    p.add_argument("--pressure", type=float, default=40.0, help="kPa")
    p.add_argument("--reservoir", type=float, default=0.0, help="mm³")
    p.add_argument("--stroke", type=float, default=4.0, help="mm")
    p.add_argument("--points", type=int, default=11, help="plate positions (10 steps)")
    p.add_argument("--sizes", type=_pair, nargs="+", default=[(1.5, 1), (1.0, 2), (0.7, 3)],
                   help="mesh-size:layers pairs, coarse to fine")
    p.add_argument("--solvers", type=_pair, help="time the solvers on this mesh-size:layers")
    p.add_argument("--solver-list", nargs="+", help="solver names (default: all available)")
    p.add_argument("--cache", default="build/cache/fem")
    p.add_argument("--json", help="write the rows here")
    args = p.parse_args(argv)
    rows = bench_solvers(args) if args.solvers else bench_run(args)
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    main()
