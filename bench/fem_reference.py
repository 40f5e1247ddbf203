"""3D FEM reference curves for the wall model's acceptance figures (issue 11), cached.

    python bench/fem_reference.py [--only LABEL-SUBSTRING] [--out build/reference]

Cases: the Table 1 domes (l = 0) of Types A–D at 40 kPa high, low (V_r = 40 cm³) and open, y to
4 mm; the Table 1 chambers (l = 3 mm) at 10 and 40 kPa high and low, and open, y to 6 mm; Type B
with l = 10 mm at 40 kPa high. Mesh 1 mm with 2 quadratic layers through the wall (the report's
converged mesh: 0.35 % from 1.5 mm on Type B). Each curve is written as Curve JSON; an existing
file is not recomputed.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from spsc.cad.geometry import preset
from spsc.fem.solid.chamber import chamber_run, run_chamber
from spsc.materials import material

LOW = 40_000.0


def cases():
    out = []
    for t in "ABCD":
        for mode, p, vr in (("high", 40, 0.0), ("low", 40, LOW), ("open", 0, 0.0)):
            out.append((f"dome-{t}-{mode}-p{p}", dict(type=t, l=0.0), p, vr, 4.0, 9))
    for t in "ABCD":
        for p in (10, 40):
            for mode, vr in (("high", 0.0), ("low", LOW)):
                out.append((f"table1-{t}-{mode}-p{p}", dict(type=t), p, vr, 6.0, 13))
        out.append((f"table1-{t}-open-p0", dict(type=t), 0, 0.0, 6.0, 13))
    out.append(("l10-B-high-p40", dict(type="B", l=10.0), 40, 0.0, 6.0, 13))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", default="")
    ap.add_argument("--out", default="build/reference")
    ap.add_argument("--mesh-size", type=float, default=1.0)
    ap.add_argument("--layers", type=int, default=2)
    ap.add_argument("--stroke", type=float, default=None,
                    help="plate travel, mm (default: each case's; e.g. 1 with --points 3 "
                    "for a refined check at y = 1 mm)")
    ap.add_argument("--points", type=int, default=None)
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for label, geo, p, vr, stroke, points in cases():
        if args.only and args.only not in label:
            continue
        stroke = args.stroke or stroke
        points = args.points or points
        path = out / f"{label}.json"
        if path.exists():
            continue
        g = preset(geo["type"], **{k: v for k, v in geo.items() if k != "type"})
        run = chamber_run(g, material("tpu60a"), pressure_kPa=p, reservoir_mm3=vr,
                         stroke_mm=stroke, points=points, mesh_size_mm=args.mesh_size,
                         layers=args.layers)
        t0 = time.perf_counter()
        curve, result, model = run_chamber(run)
        dt = time.perf_counter() - t0
        curve.to_json(path, extra={"seconds": dt, "dofs": model.disc.n,
                                   "message": result.message,
                                   "instability": result.instability})
        print(f"{label}: {dt:.0f} s, {model.disc.n} dofs, {result.message}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
