"""The sticking plate (``--friction stick``): how accurate it is, and how much of the gap to the
paper's bench it explains.

1. Increments: the Type B dome (Table 1 footprint, l = 0) at 40 kPa pressed 3 mm with the
   stick increment 0.2 ... 0.0125 mm; the force at y = 1, 2, 3 mm against the finest.
2. Work: the vented dome pressed 2 mm; ∫F dy against the wall's stored energy, frictionless
   and sticking.
3. Wall against 3D FEM: Type B (Table 1, the stadium) at 40 kPa pressed 2 mm, frictionless
   and sticking, the 3D FEM on its 1 mm quarter mesh with two layers (minutes).
4. The headline: the wall model's Table 1 means (types A-D, p_i 10-40 kPa, 6 mm, high and low
   mode as the report: V_r = 0 and 40 cm³), frictionless, with Coulomb friction (μ = 0.3, 0.6)
   and sticking, beside the paper's bench.
   The curves run on Dask (``--workers``, default one per core).

    python bench/bench_friction.py [--part increments,work,fem,headline] [--frictions 0,0.3,0.6,stick]
                                   [--workers N] [--material NAME|FILE.json] [--json F]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time

import numpy as np
from scipy.integrate import simpson

from spsc.cad.geometry import preset
from spsc.fem.engine import CloseValve, Inflate, Load, Press, solve
from spsc.fem.wall import wall_curve
from spsc.fem.wall.model import WallModel
from spsc.materials import material

#: the paper's bench (Table 1 means over types, strokes and p_i 10-40 kPa, TPU 60A)
BENCH = {"stiffness_high": 8.0, "stiffness_low": 5.0, "sensitivity_high": 6.1,
         "sensitivity_low": 0.5}
MODES = {"high": 0.0, "low": 40000.0}
PRESSURES = (10.0, 20.0, 30.0, 40.0)


def _dome():
    return WallModel(dataclasses.replace(preset("B"), l=0.0), material("tpu60a"))


def increments() -> dict:
    model = _dome()
    base = model.settings.newton_settings()
    y = np.linspace(0.0, 3.0, 13)
    out = {}
    for h in (0.2, 0.1, 0.05, 0.025, 0.0125):
        t = time.perf_counter()
        res = solve(model, [Inflate(0.04, 4), CloseValve(0.0, 1.0),
                            Press.through(y[1:], stick=True)],
                    settings=dataclasses.replace(base, stick_increment=h))
        f = [r.force for r in res.of("press")]
        out[h] = {"F_1_2_3": [f[3], f[7], f[11]], "seconds": time.perf_counter() - t}
    free = solve(model, [Inflate(0.04, 4), CloseValve(0.0, 1.0), Press.through(y[1:])],
                 settings=base)
    f = [r.force for r in free.of("press")]
    out["frictionless"] = {"F_1_2_3": [f[3], f[7], f[11]]}
    finest = np.array(out[0.0125]["F_1_2_3"])
    print("1. stick increment (mm): F at y = 1, 2, 3 mm (N), and against 0.0125 mm")
    for h, row in out.items():
        f = np.array(row["F_1_2_3"])
        rel = ", ".join(f"{v:+.2%}" for v in f / finest - 1)
        print(f"   {h!s:>12}: " + ", ".join(f"{v:.4f}" for v in f) + f"   ({rel})")
    return {str(k): v for k, v in out.items()}


def work() -> dict:
    model = _dome()
    y = np.linspace(0.0, 2.0, 17)
    out = {}
    print("2. vented dome, 2 mm: plate work ∫F dy against the stored energy (mJ)")
    for stick in (False, True):
        res = solve(model, [Press.through(y[1:], stick=stick)])
        F = np.array([0.0] + [r.force for r in res.of("press")])
        stored = model.potential(res.records[-1].x, Load()) - \
            model.potential(model.zero_state(), Load())
        w = float(simpson(F, x=y))
        out["stick" if stick else "0"] = {"work": w, "stored": stored, "rel": w / stored - 1}
        print(f"   {'stick' if stick else 'frictionless':>12}: work {w:.5f}, stored "
              f"{stored:.5f}, {w / stored - 1:+.1e}")
    return out


def fem() -> dict:
    from spsc.fem.solid.chamber import chamber_run, run_chamber

    g, m = preset("B"), material("tpu60a")
    out = {}
    for fr in ("0", "stick"):
        t = time.perf_counter()
        w = wall_curve(g, m, pressure_kPa=40.0, stroke_mm=2.0, points=5, friction=fr)
        tw = time.perf_counter() - t
        t = time.perf_counter()
        f, _, _ = run_chamber(chamber_run(g, m, pressure_kPa=40.0, stroke_mm=2.0, points=5,
                                          friction=fr), cache_dir="build/cache")
        out[fr] = {"wall": list(w.force_N), "fem": list(f.force_N), "wall_s": tw,
                   "fem_s": time.perf_counter() - t,
                   "wall_P": list(w.pressure_kPa), "fem_P": list(f.pressure_kPa)}
    print("3. Type B, 40 kPa: force at y = 0.5 ... 2 mm (N)")
    for fr in ("0", "stick"):
        for mdl in ("wall", "fem"):
            print(f"   {mdl:>5} {fr:>5}: " + ", ".join(f"{v:.4f}" for v in out[fr][mdl][1:])
                  + f"  ({out[fr][mdl + '_s']:.0f} s)")
    for mdl in ("wall", "fem"):
        rise = np.array(out["stick"][mdl][1:]) / np.array(out["0"][mdl][1:]) - 1
        print(f"   {mdl}: stick raises the force by " + ", ".join(f"{v:+.1%}" for v in rise))
    return out


def _curve(t, p, mode, friction, mat="tpu60a"):
    c = wall_curve(preset(t), material(mat), pressure_kPa=p, reservoir_mm3=MODES[mode],
                   stroke_mm=6.0, points=25, friction=friction)
    return (t, p, mode, friction), c


def headline(workers, frictions=("0", "stick"), types="ABCD", mat="tpu60a") -> dict:
    from spsc.study.executor import dask_client
    from spsc.study.metrics import headline as means

    jobs = [(t, p, mode, fr) for fr in frictions for mode in MODES
            for t in types for p in PRESSURES]
    t0 = time.perf_counter()
    with dask_client(workers) as client:
        futures = [client.submit(_curve, *j, mat, pure=False) for j in jobs]
        curves = dict(f.result() for f in futures)
    seconds = time.perf_counter() - t0
    out = {}
    for fr in frictions:
        row = {}
        for mode in MODES:
            h = means({t: [curves[(t, p, mode, fr)] for p in PRESSURES] for t in types})
            row[f"stiffness_{mode}"] = h["stiffness"]
            row[f"sensitivity_{mode}"] = h["sensitivity"]
            row[f"types_{mode}"] = h["types"]
        partial = [k for k, c in curves.items() if k[3] == fr and not c.solver.converged]
        row["partial"] = [list(k) for k in partial]
        out[fr] = row
    print(f"4. the wall model's Table 1 means of types {types} ({mat}), {len(jobs)} curves "
          f"in {seconds:.0f} s")
    print("   friction      | k high | k low | S high | S low  (N/mm, kPa/mm)")
    for name, row in (("bench (paper)", BENCH), *((fr, out[fr]) for fr in frictions)):
        print(f"   {name:<13} | {row['stiffness_high']:6.2f} | {row['stiffness_low']:5.2f} | "
              f"{row['sensitivity_high']:6.2f} | {row['sensitivity_low']:5.2f}")
    for fr in frictions:
        if fr == "0" or "0" not in out:
            continue
        print(f"   friction {fr} against frictionless: " + ", ".join(
            f"{q} {out[fr][q] / out['0'][q] - 1:+.1%}" for q in BENCH))
    for fr in frictions:
        if out[fr]["partial"]:
            print(f"   partial curves ({fr}): {out[fr]['partial']}")
    out["seconds"] = seconds
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--part", default="increments,work,fem,headline")
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--types", default="ABCD", help="the Table 1 types of the means")
    ap.add_argument("--frictions", default="0,0.3,0.6,stick",
                    help="the plates of the Table 1 means (0, a Coulomb coefficient, stick)")
    ap.add_argument("--material", default="tpu60a",
                    help="the material of the Table 1 means (a catalogue name or FILE.json)")
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    parts = args.part.split(",")
    out = {}
    if "increments" in parts:
        out["increments"] = increments()
    if "work" in parts:
        out["work"] = work()
    if "fem" in parts:
        out["fem"] = fem()
    if "headline" in parts:
        out["headline"] = headline(args.workers, tuple(args.frictions.split(",")), args.types,
                                   args.material)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=1, default=float)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
