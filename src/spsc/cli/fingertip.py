"""``spsc fingertip``: build the fused two-chamber fingertip with FSR pockets and check it;
with ``--fem``, then run its FEM study (:mod:`.fingertip_fem`) into ``OUT/fem``."""

from __future__ import annotations

import argparse
import time

from spsc.cli.bladder import gate

from spsc.cli.options import Once, check_output_dir, number



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
    g = p.add_argument_group("FEM study (--fem; 12-47 min per curve on 2 shared cores at 2 mm)")
    g.add_argument("--fem", action="store_true",
                   help="press the built fingertip on the pulp and the distal edge, high and low "
                   "mode, 10 and 40 kPa (3D FEM, Silicone 40A): curves, FSR pocket forces, the "
                   "single Type A and the fast estimate -> OUT/fem (curves reused when present)")
    g.add_argument("--mesh-size", type=number("mesh size", "mm"), default=None, metavar="MM",
                   help="element edge at the chambers' walls, mm (default 2; graded to 4x "
                   "in the body)")
    g.add_argument("--cases", default=None, metavar="SITE-MODE-KPA,...", action=Once,
                   help="only these cases, e.g. pulp-high-40,distal-high-40 (default all 8)")
    p.set_defaults(func=run)


def _cases(text):
    from spsc.core.errors import ParameterError

    from spsc.studies.fingertip import CASES, case_name

    if text is None:
        return CASES
    known = {case_name(*c).replace("kPa", ""): c for c in CASES}
    out = []
    for item in str(text).split(","):
        key = item.strip().replace("kPa", "")
        if key not in known:
            raise ParameterError("cases", text, "a comma list of " + ", ".join(known))
        if known[key] in out:
            raise ParameterError("cases", text, f"each case once ({item.strip()} is given "
                                 "twice: it would run twice)")
        out.append(known[key])
    return tuple(out)


def run(args: argparse.Namespace) -> int:
    from spsc.cad.process import process
    from spsc.cad.specs import FingertipSpec, PocketSpec

    # every check before the CAD import (3 s) and the build (35 s), not after them
    process(args.process)
    outdir = check_output_dir("--out", args.out)
    study = None
    if args.fem:
        from spsc.core.errors import require

        from spsc.studies.fingertip import FingertipStudy

        size = 2.0 if args.mesh_size is None else require("mesh size", args.mesh_size, ge=0.3,
                                                          le=4.0, unit="mm")
        study = FingertipStudy(mesh_size_mm=size, cases=_cases(args.cases))
    elif args.mesh_size is not None or args.cases is not None:
        from spsc.core.errors import ParameterError
        raise ParameterError("--mesh-size" if args.mesh_size is not None else "--cases",
                             args.mesh_size if args.mesh_size is not None else args.cases,
                             "only with --fem")
    spec = FingertipSpec(angle=args.angle,
                         pocket=PocketSpec(diameter=args.pocket_diameter, depth=args.pocket_depth))
    from spsc.cad.export import export_part, tessellate
    # CAD (cadquery, 1.5 s to import) only when a fingertip is built, not for every verb
    from spsc.cad.fingertip import MESH_TOLERANCE, build_fingertip, measure_pockets

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
    code = 0
    if not args.no_check:
        pockets = measure_pockets(mesh, tessellate(tip.cavity, *MESH_TOLERANCE), tip.design)
        code = gate(written["paths"]["stl"], tip.design, args.process, outdir,
                    extra=_pocket_checks(pockets, spec))
    if study is None or code != 0:
        return code
    return _run_fem(study, spec, written["paths"]["stl"], tip.design, outdir / "fem")


def _run_fem(study, spec, stl, design, out) -> int:
    import sys

    from spsc.studies.fingertip import run_study
    from spsc.studies.fingertip_figures import draw_all

    summary = run_study(study, out, stl=stl, design=design, spec=spec,
                        log=lambda m: print(m, file=sys.stderr, flush=True))
    figures = draw_all(summary, out)
    print(f"fingertip FEM study -> {out}/summary.json; figures: " + ", ".join(figures.values()))
    for name, row in summary["cases"].items():
        fem = row["fem"]
        fast = row.get("fast_error", {})
        ratio = row.get("sensitivity_ratio_fused_to_single")
        print(f"  {name}: sensitivity {fem['mean_sensitivity_kPa_per_mm']} kPa/mm, stiffness "
              f"{fem['mean_stiffness_N_per_mm']} N/mm"
              + (f", fused/single sensitivity {ratio:.3f}" if ratio else "")
              + (f", fast estimate error F {fast['force_max']:.1%} P-rise "
                 f"{fast['pressure_rise_max']:.1%}" if fast.get("force_max") is not None else "")
              + ("" if fem["converged"] else f" (NOT CONVERGED: {fem['message']})"))
    return 0 if all(r["fem"]["converged"] for r in summary["cases"].values()) else 1


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
