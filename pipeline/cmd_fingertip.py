"""``spsc fingertip``: build the fused two-chamber fingertip with FSR pockets and check it."""

from __future__ import annotations

import argparse
import time

from .cmd_bladder import gate
from .options import check_output_dir, number

#: Chord sag (mm) and angle (rad) of the fingertip's export mesh: its many small features would
#: give 600k triangles at the bladder's settings; the SLA gate (0.5 mm) has ample margin.
MESH_TOLERANCE = (0.005, 0.1)


def register(sub) -> None:
    p = sub.add_parser("fingertip", help="build the fused fingertip (sec. 4.1) and check it",
                       description="Two Type A chambers (pulp, distal edge) fused into one cavity, "
                       "five FSR05 pockets on raised pads, rear port, slot and screw mount.")
    p.add_argument("--angle", type=number("angle", "deg"), default=45.0,
                   help="angle between the pulp and distal chamber axes, deg (30-90)")
    p.add_argument("--pocket-diameter", type=number("pocket_diameter", "mm"), default=8.0,
                   help="FSR pocket diameter, mm")
    p.add_argument("--pocket-depth", type=number("pocket_depth", "mm"), default=0.5,
                   help="FSR pocket depth, mm")
    p.add_argument("--process", default="sla", help="process of the gate: sla (Silicone 40A, "
                   "the paper's choice), fdm or molding")
    p.add_argument("--out", default="build/fingertip", help="output folder")
    p.add_argument("--no-check", action="store_true", help="skip the printability gate")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from spsc.cad.process import process
    from spsc.cad.specs import FingertipSpec, PocketSpec

    # every check before the CAD import (3 s) and the build (35 s), not after them
    process(args.process)
    outdir = check_output_dir("--out", args.out)
    spec = FingertipSpec(angle=args.angle,
                         pocket=PocketSpec(diameter=args.pocket_diameter, depth=args.pocket_depth))
    from spsc.cad.export import export_part, tessellate
    from spsc.cad.fingertip import build_fingertip, measure_pockets

    t0 = time.perf_counter()
    tip = build_fingertip(spec)
    t_build = time.perf_counter() - t0
    mesh = tessellate(tip.solid, *MESH_TOLERANCE)
    written = export_part(tip.solid, tip.design, outdir, "fingertip", mesh=mesh)
    bb = tip.solid.BoundingBox()
    print(f"fingertip: {bb.xlen:.1f} x {bb.ylen:.1f} x {bb.zlen:.1f} mm, angle {spec.angle:g} deg, "
          f"{len(tip.design['pockets'])} FSR pockets; cavity {tip.design['cavity_volume_mm3']:.0f} "
          f"mm³ (B-rep); built in {t_build:.1f} s, {written['triangles']} triangles")
    for kind in ("step", "stl", "3mf"):
        print(f"  {written['paths'][kind]}")
    if args.no_check:
        return 0
    pockets = measure_pockets(mesh, tessellate(tip.cavity, *MESH_TOLERANCE), tip.design)
    return gate(written["paths"]["stl"], tip.design, args.process, outdir,
                extra=_pocket_checks(pockets, spec))


def _pocket_checks(m: dict, spec) -> list:
    """Gating checks of the pockets: all designed pockets found, wall under them >= t0."""
    from spsc.cad.check import Check

    t0 = min(spec.pulp.t0, spec.distal.t0)
    wall = m["min_wall_under_pockets_mm"]
    return [
        Check("pocket_count", m["pocket_count"] == m["pockets_designed"], m["pocket_count"],
              m["pockets_designed"], f"FSR pockets found {m['pocket_count']} of "
              f"{m['pockets_designed']} designed"),
        Check("wall_under_pockets", wall >= t0 - 0.01, wall, t0,
              f"min wall under pockets {wall:.3f} mm (design t0 {t0:g} mm, pocket floor "
              f"{spec.pocket.clearance:g} mm above the wall's tangent plane)",
              {"per_pocket_mm": m["wall_under_each_pocket_mm"]}),
    ]
