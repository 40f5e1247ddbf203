"""``spsc fem``: the 3D hyperelastic FEM check of one chamber, one setup — the membrane's JSON.

    spsc fem --type B --pressure 40 [--reservoir 40000] [--stroke 4] [--points 11]
             [--material tpu60a] [--mesh-size 1.0] [--layers 2] [--full]
             [--json F] [--csv F] [--vtu DIR]

Quarter model of the wall (clamped on z = 0, symmetry planes x = 0, y = 0), P2/P1 mixed
tetrahedra, follower cavity pressure, closed gas volume with reservoir after inflation, rigid
frictionless plate. ``--pressure 0`` is the open chamber (F_el). Pressures kPa gauge, volumes
mm³, lengths mm. Exit 0 when every point converged, 1 when not (what converged is written),
2 on invalid input.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from spsc.core.errors import require
from spsc.pipeline.options import (add_geometry_options, add_setup_options,
                                   geometry_from_args)


def register(subparsers) -> None:
    p = subparsers.add_parser("fem", help="3D hyperelastic FEM: inflation and plate contact",
                              description=__doc__.split("\n\n")[0])
    add_geometry_options(p)
    add_setup_options(p, stroke=4.0, points=11)
    p.add_argument("--mesh-size", type=float, default=1.0,
                   help="element edge along the wall surfaces, mm (default 1.0)")
    p.add_argument("--layers", type=int, default=2,
                   help="quadratic elements through the wall thickness (default 2)")
    p.add_argument("--full", action="store_true", help="full model instead of the quarter")
    p.add_argument("--solver", default="auto", help="sparse solver: pardiso, superlu (auto)")
    p.add_argument("--json", help="write the result JSON here")
    p.add_argument("--csv", help="write the curve CSV here")
    p.add_argument("--vtu", help="write one VTU per converged step into this directory")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    from tqdm import tqdm

    from spsc.fem.run import ChamberRun, run_chamber, write_vtu
    from spsc.fem.solver import Settings
    from spsc.membrane.materials import material

    geom = geometry_from_args(args)
    for msg in geom.design_space_warnings():
        print(f"spsc fem: warning: {msg}", file=sys.stderr)
    require("points", args.points, ge=2)
    run_spec = ChamberRun(geom, material(args.material), pressure_kPa=args.pressure,
                          reservoir_mm3=args.reservoir, stroke_mm=args.stroke,
                          points=args.points, size_mm=args.mesh_size, layers=args.layers,
                          polytropic_index=args.polytropic_n, full=args.full)
    total = run_spec.points - 1 + (run_spec.inflate_increments if run_spec.pressure_kPa > 0 else 0)
    bar = tqdm(total=total, desc="spsc fem", unit="step", disable=args.quiet, file=sys.stderr)

    def progress(done, total):
        bar.total = total
        bar.update(done - bar.n)

    t0 = time.perf_counter()
    curve, result, model = run_chamber(run_spec, settings=Settings(solver=args.solver),
                                       progress=progress)
    bar.close()
    seconds = time.perf_counter() - t0
    data = curve.to_dict()
    data["solver"] = {"converged": result.ok, "message": result.message,
                      "instability": result.instability, "dofs": model.disc.n,
                      "tetrahedra": model.mesh.n_tets, "seconds": round(seconds, 2),
                      "newton_iterations": sum(r.iterations for r in result.records)}
    if args.json:
        Path(args.json).write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    if args.csv:
        curve.to_csv(args.csv)
    if args.vtu:
        write_vtu(model, result, args.vtu)
    _summary(curve, data)
    if result.instability:
        print(f"spsc fem: instability: {result.instability}", file=sys.stderr)
    if not result.ok:
        print(f"spsc fem: not converged: {result.message}", file=sys.stderr)
        return 1
    return 0


def _summary(curve, data) -> None:
    s = curve.setup
    print(f"fem model ({s['model_part']}, {data['solver']['dofs']} unknowns, "
          f"{data['solver']['seconds']} s), material {curve.material}, "
          f"p_i = {s['p_i_kPa']:g} kPa, V_r = {s['reservoir_mm3']:g} mm³")
    print(f"cavity volume {curve.nominal_volume_mm3:.1f} -> {curve.inflated_volume_mm3:.1f} mm³ "
          f"({100 * (curve.inflated_volume_mm3 / curve.nominal_volume_mm3 - 1):+.2f} %), "
          f"apex at {curve.inflated_height_mm:.3f} mm")
    print(f"{'y_mm':>7} {'force_N':>9} {'p_kPa':>8} {'A_mm2':>8} {'dV_mm3':>9}")
    for row in zip(curve.y_mm, curve.force_N, curve.pressure_kPa, curve.contact_area_mm2,
                   curve.volume_change_mm3):
        print(f"{row[0]:7.3f} {row[1]:9.4f} {row[2]:8.3f} {row[3]:8.2f} {row[4]:9.2f}")
