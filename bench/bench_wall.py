"""The wall model against the converged 3D FEM, its mesh convergence, its speed, and the
membrane's wrinkling on/off table (issue 11).

    python bench/bench_wall.py errors      # wall vs 3D FEM, every reference curve
    python bench/bench_wall.py wrinkling   # membrane tension-field vs taut law vs 3D FEM
    python bench/bench_wall.py convergence # wall mesh refinement, observed order
    python bench/bench_wall.py speed       # one curve: inflation + 17 plate positions, 4 mm

The 3D references are written by ``bench/fem_reference.py`` into build/reference/ (about
40 min from nothing; each case is cached). Errors: max over the plate positions y ≥ 1 mm of
|model/FEM − 1| for the force F and the pressure rise P − p_i (the open chamber: F only).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from spsc.cad.geometry import preset
from spsc.core.curve import Curve
from spsc.fem.wall import WallSettings, wall_curve
from spsc.materials import material
from spsc.membrane.solver import SolverSettings, solve

REF = Path("build/reference")


def _geometry(ref: Curve):
    g = ref.geometry
    return preset("A", **{k: g[k] for k in ("w", "h", "l", "t0", "n1", "n2", "cy")})


def _setup(ref: Curve) -> dict:
    s = ref.setup
    return dict(pressure_kPa=s["p_i_kPa"], reservoir_mm3=s["reservoir_mm3"],
                stroke_mm=float(ref.y_mm[-1]), points=len(ref))


def errors(model: Curve, ref: Curve, y_min: float = 1.0) -> tuple[float, float, float]:
    """(max |F/F_ref − 1|, max |ΔP/ΔP_ref − 1|, last y compared) over the plate positions
    y ≥ y_min both converged (a solve stopped at an instability is compared up to it, the
    unstable point excluded; NaN if no point is common; ΔP NaN for the open chamber)."""
    k = (ref.y_mm >= y_min - 1e-9) & ref.converged & model.converged
    if not k.any():
        return float("nan"), float("nan"), float("nan")
    eF = np.abs(model.force_N[k] / ref.force_N[k] - 1.0)
    dp_ref = ref.pressure_kPa[k] - ref.pressure_kPa[0]
    dp = model.pressure_kPa[k] - model.pressure_kPa[0]
    eP = float(np.max(np.abs(dp / dp_ref - 1.0))) if np.all(dp_ref > 0) else float("nan")
    return float(np.max(eF)), eP, float(ref.y_mm[k][-1])


def _settings(args) -> WallSettings:
    return WallSettings(mesh_size_mm=args.mesh_size, layers=args.layers,
                        sweep_size_mm=args.sweep_size)


def _refs(pattern: str = "*"):
    return sorted(REF.glob(f"{pattern}.json"))


def run_errors(args) -> None:
    print(f"{'case':24} {'F err %':>8} {'dP err %':>9} {'to y mm':>8} {'time s':>7}  wall message")
    for path in _refs(args.only or "*"):
        ref = Curve.from_json(path)
        t0 = time.perf_counter()
        c = wall_curve(_geometry(ref), material(ref.material or "tpu60a"), **_setup(ref),
                       settings=_settings(args))
        dt = time.perf_counter() - t0
        eF, eP, y_to = errors(c, ref)
        print(f"{path.stem:24} {100 * eF:8.2f} {100 * eP:9.2f} {y_to:8.2f} {dt:7.2f}  "
              f"{c.solver.message}", flush=True)


def run_wrinkling(args) -> None:
    print(f"{'case':24} {'F err % on':>11} {'F err % off':>12} {'dP err % on':>12} "
          f"{'dP err % off':>13}")
    tot = {True: [], False: []}
    for path in _refs(args.only or "*"):
        ref = Curve.from_json(path)
        if ref.setup["p_i_kPa"] == 0:
            continue  # the membrane has no open-chamber force
        row = {}
        for wr in (True, False):
            r = solve(_geometry(ref), material(ref.material or "tpu60a"), **_setup(ref),
                      settings=SolverSettings(wrinkling=wr))
            # a membrane curve that stops short counts as not converged
            row[wr] = errors(r.curve, ref)[:2] if r.curve.all_converged else (np.nan, np.nan)
            tot[wr].append(row[wr])
        print(f"{path.stem:24} {100 * row[True][0]:11.2f} {100 * row[False][0]:12.2f} "
              f"{100 * row[True][1]:12.2f} {100 * row[False][1]:13.2f}", flush=True)
    for wr in (True, False):
        a = np.array(tot[wr], float)
        print(f"wrinkling {'on ' if wr else 'off'}: mean F err {100 * np.nanmean(a[:, 0]):.2f} %, "
              f"mean dP err {100 * np.nanmean(a[:, 1]):.2f} %, cases not converged "
              f"{int(np.sum(~np.isfinite(a).all(axis=1)))}")


def run_convergence(args) -> None:
    """Uniform refinement (element length halved, layers doubled): the quantities at y = 4 mm
    and the inflated volume, their errors against the finest mesh, and the observed order from
    successive differences, p = log2(|q1 − q2| / |q2 − q3|)."""
    g = preset(args.type, l=0.0) if args.dome else preset(args.type)
    meshes = [(2.0, 1), (1.0, 2), (0.5, 4), (0.25, 8)]
    if not args.dome:  # the stadium's hexahedra: three levels, the sweep refined alike
        meshes = meshes[:3]
    default = (WallSettings().profile_size(not args.dome), WallSettings().layers)
    if default not in meshes:
        meshes.insert(0, default)
    sweep = WallSettings().sweep_size_mm
    rows = {}
    for size, layers in meshes:
        t0 = time.perf_counter()
        c = wall_curve(g, material("tpu60a"), pressure_kPa=40, stroke_mm=4, points=9,
                       settings=WallSettings(mesh_size_mm=size, layers=layers,
                                             sweep_size_mm=sweep * size / default[0]))
        rows[(size, layers)] = (c.force_N[-1], c.pressure_kPa[-1] - 40, c.inflated_volume_mm3,
                                time.perf_counter() - t0, c.solver.details["unknowns"])
    ref = rows[meshes[-1]]
    print(f"Type {args.type} {'dome' if args.dome else 'Table 1'}, 40 kPa high, y = 4 mm; errors "
          f"against the finest mesh ({meshes[-1][0]} mm, {meshes[-1][1]} layers)")
    print(f"{'size mm':>8} {'layers':>6} {'unknowns':>8} {'F(4) N':>9} {'F err':>9} "
          f"{'dP err':>9} {'V_inf err':>9} {'s':>6}")
    for key in sorted(rows, key=lambda k: -k[0] * 100 + k[1]):
        F, P, V, dt, n = rows[key]
        print(f"{key[0]:8.3f} {key[1]:6d} {n:8d} {F:9.4f} {abs(F / ref[0] - 1):9.2e} "
              f"{abs(P / ref[1] - 1):9.2e} {abs(V / ref[2] - 1):9.2e} {dt:6.2f}")
    uniform = [rows[m] for m in [(2.0, 1), (1.0, 2), (0.5, 4), (0.25, 8)] if m in rows]
    for name, i in (("inflated volume", 2), ("pressure rise", 1), ("force", 0)):
        q = [u[i] for u in uniform]
        orders = [np.log2(abs(q[k] - q[k + 1]) / abs(q[k + 1] - q[k + 2]))
                  for k in range(len(q) - 2) if q[k + 1] != q[k + 2]]
        print(f"observed order ({name}, successive differences): "
              + ", ".join(f"{o:.2f}" for o in orders))


def run_speed(args) -> None:
    g = preset(args.type) if not args.dome else preset(args.type, l=0.0)
    kw = dict(pressure_kPa=40, stroke_mm=4, points=18)
    settings = _settings(args)
    wall_curve(g, material("tpu60a"), **kw, settings=settings)  # warm: imports, first BLAS
    times = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        c = wall_curve(g, material("tpu60a"), **kw, settings=settings)
        times.append(time.perf_counter() - t0)
    t_mem = []
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        solve(g, material("tpu60a"), **kw)
        t_mem.append(time.perf_counter() - t0)
    print(f"Type {args.type} {'dome' if args.dome else 'Table 1'}, 40 kPa, inflation + 17 plate "
          f"positions over 4 mm: wall {min(times):.3f} s (best of {args.repeat}, "
          f"{c.solver.iterations} Newton iterations, {c.solver.details['unknowns']} unknowns, "
          f"mesh {c.solver.details['mesh_size_mm']} mm / {c.solver.details['layers']} layers), "
          f"membrane {min(t_mem):.3f} s")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("what", choices=("errors", "wrinkling", "convergence", "speed"))
    ap.add_argument("--only", default="", help="glob on the reference names, e.g. 'dome-*'")
    ap.add_argument("--mesh-size", type=float, default=None,
                    help="element length along the profile, mm (default: the model's)")
    ap.add_argument("--layers", type=int, default=WallSettings().layers)
    ap.add_argument("--sweep-size", type=float, default=WallSettings().sweep_size_mm)
    ap.add_argument("--type", default="B")
    ap.add_argument("--dome", action="store_true", help="l = 0 instead of Table 1's l")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    {"errors": run_errors, "wrinkling": run_wrinkling, "convergence": run_convergence,
     "speed": run_speed}[args.what](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
