"""FEM against the membrane model on the Table 1 types, and the FEM's own checks (issue 4).

    python bench/bench_fem_compare.py                       # Types A–D, 40 kPa, high stiffness
    python bench/bench_fem_compare.py --types B --size 2 --layers 1   # quicker, coarse
    python bench/bench_fem_compare.py --thin-wall           # l = 0 dome, t0 = 1, 0.5, 0.25
    python bench/bench_fem_compare.py --quarter-vs-full     # open chamber, quarter vs full
    python bench/bench_fem_compare.py --axisym              # l = 0 dome: 3D vs axisymmetric

Comparison table (docs/design.md, "Comparing models and the paper"): the membrane carries no bending, its force is
p·A, so the FEM plate force F is compared with membrane p·A + FEM F_el (the FEM's open chamber,
p = 0, same mesh), and the FEM pressure with the membrane pressure, at y = 1, 2, 3, 4 mm;
``F/pA%`` is FEM F against membrane p·A alone (the open chamber's bending force does not add
onto the inflated wall's: a wall in tension does not fold like the open dome).
Set OMP_NUM_THREADS / MKL_NUM_THREADS to the cores you grant it. ``--json F`` writes the rows.
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from spsc.cad.geometry import preset
from spsc.fem.solid.mesh import cached_mesh, spsc_wall
from spsc.fem.solid.model import FEMModel
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.fem.engine import Inflate, solve
from spsc.materials import material
from spsc.membrane.solver import inflate as membrane_inflate
from spsc.membrane.solver import solve as membrane_solve

__all__ = ["compare_type", "thin_wall", "quarter_vs_full", "axisymmetric", "main"]


def _at(curve, y):
    """Force (N) and pressure (kPa) of ``curve`` at plate travel y (NaN if not converged)."""
    i = int(np.argmin(np.abs(curve.y_mm - y)))
    if abs(curve.y_mm[i] - y) > 1e-9 or not curve.converged[i]:
        return math.nan, math.nan
    return float(curve.force_N[i]), float(curve.pressure_kPa[i])


def _reached(curve) -> float:
    ok = np.nonzero(curve.converged)[0]
    return float(curve.y_mm[ok[-1]]) if ok.size else math.nan


def compare_type(name, *, mat, pressure, stroke, points, size, layers, at, cache=None):
    """One row per type: FEM (pressurised and open), membrane; FEM F vs p·A + F_el."""
    g = preset(name)
    common = dict(stroke_mm=stroke, points=points, mesh_size_mm=size, layers=layers)
    t0 = time.perf_counter()
    fem, res, model = run_chamber(chamber_run(g, mat, pressure_kPa=pressure, **common),
                                  cache_dir=cache)
    t_fem = time.perf_counter() - t0
    t0 = time.perf_counter()
    fel, res_el, _ = run_chamber(chamber_run(g, mat, pressure_kPa=0.0, **common), cache_dir=cache)
    t_el = time.perf_counter() - t0
    t0 = time.perf_counter()
    mem = membrane_solve(g, mat, pressure_kPa=pressure, stroke_mm=stroke, points=points)
    t_mem = time.perf_counter() - t0
    row = {"type": name, "dofs": model.disc.n, "size_mm": size, "layers": layers,
           "fem_converged_to_stroke": bool(fem.all_converged),
           "fem_reached_mm": _reached(fem), "fem_message": res.message,
           "fem_instability": res.instability,
           "fel_converged_to_stroke": bool(fel.all_converged),
           "fel_reached_mm": _reached(fel), "fel_message": res_el.message,
           "fel_instability": res_el.instability,
           "membrane_converged_to_stroke": bool(mem.converged),
           "seconds_fem": round(t_fem, 1), "seconds_fel": round(t_el, 1),
           "seconds_membrane": round(t_mem, 2),
           "inflated_volume_fem_mm3": fem.inflated_volume_mm3,
           "inflated_volume_membrane_mm3": mem.curve.inflated_volume_mm3,
           "nominal_volume_mm3": fem.nominal_volume_mm3, "points": []}
    for y in at:
        F, P = _at(fem, y)
        Fel, _ = _at(fel, y)
        Fm, Pm = _at(mem.curve, y)
        pred = Fm + Fel
        row["points"].append({"y_mm": y, "fem_F_N": F, "fem_P_kPa": P, "fem_Fel_N": Fel,
                              "membrane_pA_N": Fm, "membrane_P_kPa": Pm,
                              "membrane_pA_plus_Fel_N": pred,
                              "F_diff_pct": 100 * (F / pred - 1),
                              "F_vs_pA_pct": 100 * (F / Fm - 1),
                              "P_diff_pct": 100 * (P / Pm - 1)})
    return row


def _print_compare(rows):
    print(f"{'type':4} {'y':>4} {'F_fem':>8} {'F_el':>7} {'pA_mem':>8} {'pA+F_el':>8} "
          f"{'dF%':>6} {'F/pA%':>6} {'P_fem':>7} {'P_mem':>7} {'dP%':>6}")
    for r in rows:
        for p in r["points"]:
            print(f"{r['type']:4} {p['y_mm']:4.1f} {p['fem_F_N']:8.3f} {p['fem_Fel_N']:7.3f} "
                  f"{p['membrane_pA_N']:8.3f} {p['membrane_pA_plus_Fel_N']:8.3f} "
                  f"{p['F_diff_pct']:6.1f} {p['F_vs_pA_pct']:6.1f} {p['fem_P_kPa']:7.3f} "
                  f"{p['membrane_P_kPa']:7.3f} "
                  f"{p['P_diff_pct']:6.2f}")
        print(f"{r['type']:4} converged to stroke: FEM {'yes' if r['fem_converged_to_stroke'] else 'no'}"
              f" (to {r['fem_reached_mm']:g} mm), F_el {'yes' if r['fel_converged_to_stroke'] else 'no'}"
              f" (to {r['fel_reached_mm']:g} mm), membrane "
              f"{'yes' if r['membrane_converged_to_stroke'] else 'no'}; dofs {r['dofs']}; "
              f"time FEM {r['seconds_fem']} s + F_el {r['seconds_fel']} s, membrane "
              f"{r['seconds_membrane']} s; inflated volume FEM {r['inflated_volume_fem_mm3']:.1f}"
              f" membrane {r['inflated_volume_membrane_mm3']:.1f} mm³")
        for key in ("fem_instability", "fel_instability"):
            if r[key]:
                print(f"{r['type']:4} {key}: {r[key]}")
    print(flush=True)


# -- thin walls: the FEM approaches the membrane ------------------------------------------------
def thin_wall(*, mat, type_name="B", thicknesses=(1.0, 0.5, 0.25), pressure_per_mm=40.0,
              size=1.0, layers=2, increments=4, cache=None):
    """l = 0 dome of ``type_name`` at t0 = ``thicknesses`` (mm), inflated (no gas, no plate) to
    p = ``pressure_per_mm`` · t0 (kPa): FEM against the membrane (on the cavity surface, carrying
    the wall's t0). Returns one row per t0: volume changes and apex heights."""
    rows = []
    for t in thicknesses:
        g = preset(type_name, l=0.0, t0=t)
        p = pressure_per_mm * t
        t0 = time.perf_counter()
        mesh = cached_mesh(spsc_wall, cache_dir=cache, g=g, size=size, layers=layers, full=False)
        model = FEMModel.build(mesh, mat)
        res = solve(model, [Inflate(p * 1e-3, increments)])
        secs = time.perf_counter() - t0
        inf = membrane_inflate(g, mat, p)
        V0 = g.cavity_volume()
        V_fem = res.records[-1].volume if res.converged else math.nan
        X = model.disc.X
        cav = model.mesh.nodes_on("cavity")
        axis = cav[(np.abs(X[cav, 0]) < 1e-9) & (np.abs(X[cav, 1]) < 1e-9)]
        apex_fem = float(np.max(X[axis, 2] + model.displacement(res.records[-1].x)[axis, 2]))
        dv_fem = V_fem - res.records[0].volume
        dv_mem = inf.shape.volume_mm3 - V0
        apex_mem = float(inf.shape.eta[0])
        rows.append({"t0_mm": t, "pressure_kPa": p, "dofs": model.disc.n, "ok": res.converged,
                     "seconds": round(secs, 1),
                     "dV_fem_mm3": dv_fem, "dV_membrane_mm3": dv_mem,
                     "dV_diff_pct": 100 * (dv_fem / dv_mem - 1),
                     "apex_rise_fem_mm": apex_fem - g.h, "apex_rise_membrane_mm": apex_mem - g.h,
                     "apex_rise_diff_pct": 100 * ((apex_fem - g.h) / (apex_mem - g.h) - 1)})
    return rows


def _print_thin(rows):
    print(f"{'t0':>5} {'p_kPa':>6} {'dofs':>7} {'dV_fem':>8} {'dV_mem':>8} {'dV%':>6} "
          f"{'rise_fem':>8} {'rise_mem':>8} {'rise%':>6} {'s':>6}")
    for r in rows:
        print(f"{r['t0_mm']:5.2f} {r['pressure_kPa']:6.1f} {r['dofs']:7d} {r['dV_fem_mm3']:8.2f} "
              f"{r['dV_membrane_mm3']:8.2f} {r['dV_diff_pct']:6.2f} {r['apex_rise_fem_mm']:8.4f} "
              f"{r['apex_rise_membrane_mm']:8.4f} {r['apex_rise_diff_pct']:6.2f} "
              f"{r['seconds']:6.1f}")
    print(flush=True)


# -- quarter against full model of the open chamber ---------------------------------------------
def quarter_vs_full(*, mat, type_name="B", stroke=4.0, points=9, size=2.0, layers=1,
                    imperfection=0.02, cache=None):
    """Open chamber (p = 0) pressed by the plate: quarter model, full model, and full model with
    an asymmetric imperfection (the wall leans along +x by ``imperfection`` · (z/h)² mm), all on
    the same mesh. The mirrored full mesh alone keeps the symmetric path by construction (only
    its tangent's inertia can flag a bifurcation); the imperfect one is free to take an
    asymmetric buckling mode, so if it follows the quarter model the quarter answer holds."""
    from spsc.fem.solid.mesh import TetMesh
    from spsc.fem.engine import solve as fem_solve

    rows = []
    g = preset(type_name)
    for label, full, lean in (("quarter", False, 0.0), ("full", True, 0.0),
                              ("full+imperfection", True, imperfection)):
        run = chamber_run(g, mat, pressure_kPa=0.0, stroke_mm=stroke, points=points,
                         mesh_size_mm=size, layers=layers, full=full)
        t0 = time.perf_counter()
        if lean:
            mesh = cached_mesh(spsc_wall, cache_dir=cache, g=g, size=size, layers=layers,
                               full=True)
            X = mesh.nodes.copy()
            X[:, 0] += lean * np.clip(X[:, 2] / g.h, 0.0, None) ** 2
            model = FEMModel.build(TetMesh(X, mesh.tets, mesh.facets, mesh.symmetry), mat)
            res = fem_solve(model, run.steps())
            force = np.full(points, np.nan)
            force[0] = 0.0
            press = [r.force for r in res.of("press")]
            force[1: 1 + len(press)] = press
        else:
            curve, res, model = run_chamber(run, cache_dir=cache)
            force = curve.force_N
        rows.append({"part": label, "dofs": model.disc.n,
                     "seconds": round(time.perf_counter() - t0, 1), "ok": res.converged,
                     "message": res.message, "instability": res.instability,
                     "y_mm": np.linspace(0.0, stroke, points).tolist(),
                     "force_N": np.asarray(force, float).tolist()})
    return rows


def _print_qf(rows):
    print(f"{'y':>5} " + " ".join(f"{r['part']:>18}" for r in rows) + "  max diff% vs quarter")
    q = np.array(rows[0]["force_N"])
    for i, y in enumerate(rows[0]["y_mm"]):
        f = [r["force_N"][i] for r in rows]
        d = max((abs(v / q[i] - 1) * 100 for v in f[1:] if q[i]), default=0.0)
        print(f"{y:5.2f} " + " ".join(f"{v:18.4f}" for v in f) + f"  {d:.3f}")
    for r in rows:
        print(f"{r['part']}: dofs {r['dofs']}, {r['seconds']} s, {r['message']}"
              + (f"; {r['instability']}" if r["instability"] else ""))
    print(flush=True)


# -- the independent axisymmetric model ------------------------------------------------------
def axisymmetric(*, mat, type_name="B", pressure=40.0, stroke=4.0, size=1.0, layers=2,
                 axi_meshes=((40, 4), (80, 8)), cache=None):
    """l = 0 dome of ``type_name``: the 3D quarter model (``size``, ``layers``) and the
    axisymmetric FElupe model (``spsc_support.verify.axisym_felupe``, ``axi_meshes`` = (profile
    elements, layers) pairs), inflated to ``pressure`` kPa, valve closed, plate to ``stroke``
    mm in 1 mm increments. One row per model."""
    from spsc_support.verify.axisym_felupe import AxisymmetricDome

    g = preset(type_name, l=0.0)
    n = int(round(stroke))
    rows = []
    for n_profile, lay in axi_meshes:
        t0 = time.perf_counter()
        m = AxisymmetricDome(g, mat, n_profile=n_profile, layers=lay)
        x, recs = m.inflate(pressure * 1e-3, 4)
        out = m.press(x, pressure * 1e-3, float(n), n)
        rows.append({"model": f"axisymmetric {n_profile}x{lay}", "dofs": m.n,
                     "seconds": round(time.perf_counter() - t0, 1),
                     "dV_mm3": recs[-1].volume - recs[0].volume,
                     "force_N": [r.force for r in out],
                     "pressure_kPa": [r.pressure * 1e3 for r in out]})
    t0 = time.perf_counter()
    curve, res, model = run_chamber(chamber_run(g, mat, pressure_kPa=pressure, stroke_mm=float(n),
                                               points=n + 1, mesh_size_mm=size, layers=layers),
                                    cache_dir=cache)
    rows.append({"model": f"3D quarter {size:g} mm/{layers}", "dofs": model.disc.n,
                 "seconds": round(time.perf_counter() - t0, 1), "ok": res.converged,
                 "dV_mm3": curve.inflated_volume_mm3 - curve.nominal_volume_mm3,
                 "force_N": curve.force_N[1:].tolist(),
                 "pressure_kPa": curve.pressure_kPa[1:].tolist()})
    return rows


def _print_axi(rows):
    ref = rows[-2]  # the finest axisymmetric mesh
    for r in rows:
        dv = 100 * (r["dV_mm3"] / ref["dV_mm3"] - 1)
        f = " ".join(f"{a:7.3f}({100 * (a / b - 1):+.2f}%)"
                     for a, b in zip(r["force_N"], ref["force_N"]))
        p = " ".join(f"{a:7.3f}({100 * (a / b - 1):+.2f}%)"
                     for a, b in zip(r["pressure_kPa"], ref["pressure_kPa"]))
        print(f"{r['model']:22} dofs {r['dofs']:6d} {r['seconds']:6.1f} s  dV {r['dV_mm3']:7.2f} "
              f"({dv:+.2f}%)\n    F(y=1..) {f}\n    P(y=1..) {p}")
    print(flush=True)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--types", nargs="+", default=["A", "B", "C", "D"])
    p.add_argument("--material", default="tpu60a")
    p.add_argument("--pressure", type=float, default=40.0, help="kPa")
    p.add_argument("--stroke", type=float, default=4.0, help="mm")
    p.add_argument("--points", type=int, default=9, help="plate positions (0.5 mm apart)")
    p.add_argument("--size", type=float, default=1.0, help="mesh size, mm")
    p.add_argument("--layers", type=int, default=2)
    p.add_argument("--thin-wall", action="store_true", help="the thin-wall table instead")
    p.add_argument("--thicknesses", type=float, nargs="+", default=[1.0, 0.5, 0.25])
    p.add_argument("--quarter-vs-full", action="store_true", help="open chamber, quarter/full")
    p.add_argument("--axisym", action="store_true", help="l = 0 dome, 3D vs axisymmetric")
    p.add_argument("--cache", default="build/cache/fem")
    p.add_argument("--json", help="write the rows here")
    args = p.parse_args(argv)
    mat = material(args.material)
    if args.thin_wall:
        rows = thin_wall(mat=mat, thicknesses=args.thicknesses, size=args.size,
                         layers=args.layers, cache=args.cache)
        _print_thin(rows)
    elif args.axisym:
        rows = axisymmetric(mat=mat, pressure=args.pressure, stroke=args.stroke, size=args.size,
                            layers=args.layers, cache=args.cache)
        _print_axi(rows)
    elif args.quarter_vs_full:
        rows = quarter_vs_full(mat=mat, stroke=args.stroke, points=args.points, size=args.size,
                               layers=args.layers, cache=args.cache)
        _print_qf(rows)
    else:
        at = [y for y in (1.0, 2.0, 3.0, 4.0) if y <= args.stroke + 1e-9]
        rows = []
        for name in args.types:
            row = compare_type(name, mat=mat, pressure=args.pressure, stroke=args.stroke,
                               points=args.points, size=args.size, layers=args.layers, at=at,
                               cache=args.cache)
            rows.append(row)
            _print_compare([row])
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=1)
    return rows


if __name__ == "__main__":
    main()
