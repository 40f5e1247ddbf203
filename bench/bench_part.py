"""FEM of any part (issue 14): the figures of its closing note.

    python bench/bench_part.py typeb [--sizes 1.0,0.8]        # figure 1: Type B STL vs structured
    python bench/bench_part.py convergence [--site pulp|distal] [--sizes 2.5,2,1.5]  # figure 2
    python bench/bench_part.py fingertip [--size 1.5]          # figure 3: the fingertip set

Every curve is written as JSON under ``build/bench-part/`` and reused when it exists (delete
the folder to measure again); the times printed are those the curve recorded (meshing + solve,
2-core machine). Type B: Table 1 (w 11, h 13, l 3, t0 1 mm), TPU 60A, high mode (no
reservoir), 40 kPa, plate 0–4 mm in 0.5 mm steps; the structured reference is the report's
converged mesh (quarter, 1 mm, 2 layers).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from spsc.core.curve import Curve

OUT = Path("build/bench-part")


def _spsc(*argv) -> None:
    subprocess.run([sys.executable, "-m", "spsc.cli.main", *argv], check=True)


def _curve(path: Path, make) -> Curve:
    if not path.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
        make(path)
    return Curve.from_json(path)


def _part_json(path, part, *extra):
    def make(p):
        code = subprocess.run([sys.executable, "-m", "spsc.cli.main", "fem", "--part",
                               str(part), "--json", str(p), "--force", *extra]).returncode
        if code not in (0, 1):
            raise SystemExit(f"spsc fem --part failed ({code})")
    return make


def typeb(args) -> dict:
    stl = OUT / "bladder-B" / "bladder-B.stl"
    if not stl.exists():
        _spsc("bladder", "--type", "B", "--out", str(stl.parent))
    design = json.loads((stl.parent / "bladder-B.design.json").read_text())
    setup = ["--pressure", "40", "--stroke", "4", "--points", "9"]
    ref = _curve(OUT / "typeb-structured.json",
                 lambda p: _spsc("fem", "--type", "B", *setup, "--mesh-size", "1.0",
                                 "--layers", "2", "--json", str(p), "--quiet"))
    rows = {"analytic_cavity_mm3": design["cavity_volume_mm3"], "structured": _summary(ref),
            "parts": {}}
    print(f"structured (quarter, 1 mm, 2 layers): {ref.solver.details.get('dofs')} unknowns, "
          f"{ref.solver.seconds:.0f} s; nominal cavity {ref.nominal_volume_mm3:.1f} mm³ "
          f"(analytic {design['cavity_volume_mm3']:.1f})")
    for size in args.sizes:
        c = _curve(OUT / f"typeb-part-{size:g}.json",
                   _part_json(None, stl, *setup, "--mesh-size", f"{size:g}", "--plate-at", "apex",
                              "--quiet"))
        k = (ref.y_mm >= 1 - 1e-9) & (ref.y_mm <= 4 + 1e-9)
        eF = c.force_N[k] / ref.force_N[k] - 1
        dp_ref = ref.pressure_kPa[k] - ref.pressure_kPa[0]
        eP = (c.pressure_kPa[k] - c.pressure_kPa[0]) / dp_ref - 1
        eV = c.nominal_volume_mm3 / design["cavity_volume_mm3"] - 1
        rows["parts"][f"{size:g}"] = {**_summary(c), "force_error": eF.tolist(),
                                      "pressure_rise_error": eP.tolist(),
                                      "cavity_volume_error": eV}
        print(f"part mesh {size:g} mm: {c.solver.details.get('dofs')} unknowns, "
              f"{c.solver.details.get('tetrahedra')} tets, {c.solver.seconds:.0f} s "
              f"(meshing {c.solver.details.get('mesh_seconds', float('nan')):.0f} s); "
              f"tet cavity {c.nominal_volume_mm3:.1f} mm³ ({100 * eV:+.3f} % of analytic)")
        print("   y_mm   F_ref     F_part   dF %    dP_ref   dP_part  d(dP) %")
        for y, fr, fp, e1, pr, pp, e2 in zip(ref.y_mm[k], ref.force_N[k], c.force_N[k], eF, dp_ref,
                                             c.pressure_kPa[k] - c.pressure_kPa[0], eP):
            print(f"  {y:5.2f} {fr:8.4f} {fp:8.4f} {100 * e1:+6.2f} {pr:8.4f} {pp:8.4f} "
                  f"{100 * e2:+6.2f}")
        print(f"  max |dF| {100 * np.max(np.abs(eF)):.2f} %, max |d(dP)| "
              f"{100 * np.max(np.abs(eP)):.2f} %")
    return rows


def _summary(c: Curve) -> dict:
    return {"y_mm": c.y_mm.tolist(), "force_N": c.force_N.tolist(),
            "pressure_kPa": c.pressure_kPa.tolist(), "seconds": c.solver.seconds,
            "dofs": c.solver.details.get("dofs"), "converged": bool(c.all_converged),
            "nominal_volume_mm3": c.nominal_volume_mm3}


def fingertip_stl() -> Path:
    stl = OUT / "fingertip" / "fingertip.stl"
    if not stl.exists():
        _spsc("fingertip", "--out", str(stl.parent))
    return stl


FINGERTIP_SETUP = ["--material", "silicone40a", "--stroke", "3", "--points", "7"]


def convergence(args) -> dict:
    stl = fingertip_stl()
    rows, previous = {}, None
    for size in args.sizes:
        t0 = time.perf_counter()
        c = _curve(OUT / f"fingertip-{args.site}-high-40-h{size:g}.json",
                   _part_json(None, stl, *FINGERTIP_SETUP, "--pressure", "40", "--plate-at",
                              args.site, "--mesh-size", f"{size:g}", "--quiet"))
        ran = time.perf_counter() - t0
        d = c.solver.details
        change = (f"F(3 mm) {100 * (c.force_N[-1] / previous.force_N[-1] - 1):+.2f} %, "
                  f"ΔP(3 mm) {100 * ((c.pressure_kPa[-1] - c.pressure_kPa[0]) / (previous.pressure_kPa[-1] - previous.pressure_kPa[0]) - 1):+.2f} % against the previous"
                  if previous is not None else "")
        print(f"fingertip {args.site} press, high, 40 kPa, mesh {size:g} mm: {d.get('dofs')} unknowns, "
              f"{d.get('tetrahedra')} tets, {c.solver.seconds:.0f} s per curve "
              f"(meshing {d.get('mesh_seconds', float('nan')):.0f} s){' (cached)' if ran < 5 else ''}; "
              f"F(3 mm) = {c.force_N[-1]:.4g} N, P = {c.pressure_kPa[-1]:.4g} kPa, "
              f"pockets {[round(float(v[-1]), 3) for v in c.series.values()]} N; {change}")
        rows[f"{size:g}"] = {**_summary(c), "pockets": {k: v.tolist() for k, v in c.series.items()}}
        previous = c
    return rows


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="what", required=True)
    t = sub.add_parser("typeb")
    t.add_argument("--sizes", type=lambda s: [float(x) for x in s.split(",")], default=[1.0])
    c = sub.add_parser("convergence")
    c.add_argument("--sizes", type=lambda s: [float(x) for x in s.split(",")],
                   default=[2.5, 2.0, 1.5])
    c.add_argument("--site", choices=("pulp", "distal"), default="pulp")
    args = p.parse_args(argv)
    rows = {"typeb": typeb, "convergence": convergence}[args.what](args)
    OUT.mkdir(parents=True, exist_ok=True)
    name = args.what + (f"-{args.site}" if args.what == "convergence" else "")
    (OUT / f"{name}.json").write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
