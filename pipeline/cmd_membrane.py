"""``spsc membrane``: the fast membrane model of one chamber, one setup — JSON, CSV and PNG.

    spsc membrane --type D --pressure 40 [--reservoir 40000] [--stroke 6] [--material tpu60a]
                  [--points 41] [--json F] [--csv F] [--png F]

Pressures kPa gauge, volumes mm³, lengths mm. Exit 0 when every plate position converged,
1 when some did not (what was computed is still written), 2 on invalid input.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from .options import add_geometry_options, add_setup_options, geometry_from_args


def register(subparsers) -> None:
    p = subparsers.add_parser("membrane", help="membrane model: inflation and plate contact",
                              description=__doc__.split("\n\n")[0])
    add_geometry_options(p)
    add_setup_options(p, stroke=6.0, points=41)
    p.add_argument("--model", choices=("membrane", "simplified"), default="membrane",
                   help="membrane (default) or the simplified intersection model")
    p.add_argument("--json", help="write the result JSON here")
    p.add_argument("--meridians", action="store_true",
                   help="add the deformed meridians (x, rho, eta per position) to the JSON")
    p.add_argument("--csv", help="write the curve CSV here")
    p.add_argument("--png", help="write a plot here")
    p.set_defaults(func=run)


def run(args) -> int:
    from spsc.membrane.materials import material
    from spsc.membrane.simplified import simplified_curve
    from spsc.membrane.solver import solve

    geom = geometry_from_args(args)
    mat = material(args.material)
    for msg in geom.design_space_warnings():
        print(f"spsc membrane: warning: {msg}", file=sys.stderr)
    result = None
    if args.model == "simplified":
        curve = simplified_curve(geom, pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
                                 stroke_mm=args.stroke, points=args.points,
                                 polytropic_n=args.polytropic_n, material=mat.name)
    else:
        result = solve(geom, mat, pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
                       stroke_mm=args.stroke, points=args.points, polytropic_n=args.polytropic_n)
        curve = result.curve
    ok = curve.all_converged
    data = curve.to_dict()
    data["mean_stiffness_N_per_mm"] = _finite(np.nanmean(curve.stiffness()) if ok else np.nan)
    data["mean_sensitivity_kPa_per_mm"] = _finite(np.nanmean(curve.sensitivity()) if ok else np.nan)
    if result is not None:
        data["solver"] = {"converged": result.converged, "message": result.message,
                          "y_reached_mm": _finite(result.y_reached_mm),
                          "seconds": round(result.seconds, 4),
                          "newton_iterations": result.newton_iterations,
                          "notes": list(result.notes)}
    if result is not None and args.meridians:
        data["meridians_mm"] = [None if sh is None else dict(zip(("x", "rho", "eta"), (
            [round(float(v), 6) for v in a] for a in sh.meridian()))) for sh in result.shapes]
    if args.json:
        Path(args.json).write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    if args.csv:
        curve.to_csv(args.csv)
    if args.png:
        plot(curve, result, args.png)
    _summary(curve, result, data)
    warned = [m for m, c in zip(curve.message, curve.converged) if c and m]
    if warned:
        print(f"spsc membrane: {warned[-1]} (and at {len(warned) - 1} other positions)",
              file=sys.stderr)
    if not ok:
        first = next(m for m, c in zip(curve.message, curve.converged) if not c)
        print(f"spsc membrane: not converged: {first}", file=sys.stderr)
        return 1
    return 0


def _finite(v):
    v = float(v)
    return v if np.isfinite(v) else None


def _summary(curve, result, data) -> None:
    s = curve.setup
    print(f"{curve.model} model, material {curve.material}, p_i = {s['p_i_kPa']:g} kPa, "
          f"V_r = {s['reservoir_mm3']:g} mm³")
    print(f"cavity volume {curve.nominal_volume_mm3:.1f} -> {curve.inflated_volume_mm3:.1f} mm³ "
          f"({100 * (curve.inflated_volume_mm3 / curve.nominal_volume_mm3 - 1):+.2f} %), "
          f"apex at {curve.inflated_height_mm:.3f} mm")
    print(f"{'y_mm':>7} {'force_N':>9} {'p_kPa':>8} {'A_mm2':>8} {'dV_mm3':>9}")
    step = max(1, (len(curve) - 1) // 10)
    for k in range(0, len(curve), step):
        print(f"{curve.y_mm[k]:7.3f} {curve.force_N[k]:9.4f} {curve.pressure_kPa[k]:8.3f} "
              f"{curve.contact_area_mm2[k]:8.2f} {curve.volume_change_mm3[k]:9.2f}")
    if data.get("mean_stiffness_N_per_mm") is not None:
        print(f"mean stiffness {data['mean_stiffness_N_per_mm']:.4g} N/mm, mean sensitivity "
              f"{data['mean_sensitivity_kPa_per_mm']:.4g} kPa/mm")
    if result is not None:
        print(f"solved in {result.seconds:.3f} s ({result.newton_iterations} Newton iterations)")


def plot(curve, result, path) -> None:
    """F, p, A, ΔV against y, and the deformed meridians (inflated and last position)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 3, figsize=(12, 6.5), constrained_layout=True)
    y = curve.y_mm
    for a, (val, lab) in zip(ax.flat, ((curve.force_N, "force (N)"),
                                       (curve.pressure_kPa, "gauge pressure (kPa)"),
                                       (curve.contact_area_mm2, "contact area (mm²)"),
                                       (curve.volume_change_mm3, "volume change (mm³)"),
                                       (curve.stiffness(), "stiffness dF/dy (N/mm)"))):
        a.plot(y, val, "o-", ms=2.5)
        a.set_xlabel("plate travel y (mm)")
        a.set_ylabel(lab)
        a.grid(alpha=0.3)
    a = ax.flat[5]
    if result is not None and result.inflated is not None:
        sh = result.inflated
        a.plot(sh.x, sh.y, "k:", label="nominal")
        a.plot(sh.rho, sh.eta, "b-", label="inflated")
        k = max(i for i, s in enumerate(result.shapes) if s is not None)
        last = result.shapes[k]
        if k > 0:
            _, rho, eta = last.meridian()
            a.plot(rho, eta, "r-", label=f"y = {curve.y_mm[k]:.2f} mm")
            a.axhline(last.eta[last.gamma_index], color="0.5", lw=0.8)
        a.set_aspect("equal")
        a.set_xlabel("radius (mm)")
        a.set_ylabel("height (mm)")
        a.legend(fontsize=8)
    else:
        a.axis("off")
    g = curve.geometry
    fig.suptitle(f"{curve.model}: w={g.get('w')}, h={g.get('h')}, l={g.get('l')}, "
                 f"n1={g.get('n1')}, n2={g.get('n2')}, cy={g.get('cy')}; {curve.material}, "
                 f"p_i={curve.setup.get('p_i_kPa')} kPa, V_r={curve.setup.get('reservoir_mm3')} mm³")
    fig.savefig(path, dpi=110)
    plt.close(fig)
