"""``spsc mold``: the mold for a bladder's wall (issue 15), its pieces as STL, 3MF and STEP, the
mold gate and an exploded render."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from spsc.core.errors import ParameterError

from spsc.cli.options import add_geometry_options, check_output_dir, geometry_given, integer, number


def register(sub) -> None:
    p = sub.add_parser("mold", help="make the mold of a bladder and gate it",
                       description="Build the mold of a bladder's wall: two halves split where "
                       "no undercut locks them, a lost (soluble) core held by its inlet stem, "
                       "pins for the flange holes when the halves part sideways, drafted keys, "
                       "bolt holes, and a sprue, riser and vents (casting) or a flash groove "
                       "(compression); every piece as STL, 3MF and STEP, mold.json, the mold "
                       "gate (gate.json) and an exploded render.")
    p.add_argument("part", nargs="?", default=None,
                   help="a bladder design file written by spsc bladder (NAME.design.json, or "
                   "its STL beside it); or give --type / the seven parameters")
    add_geometry_options(p)
    p.add_argument("--flange-holes", type=integer("flange_holes"), default=4,
                   help="screw holes of the bladder's flange: 0, 2 or 4")
    p.add_argument("--tube-id", type=number("tube_id", "mm"), default=3.0,
                   help="inner diameter of the tube on the port (mm)")
    p.add_argument("--process", default="casting", help="casting (poured, sprue and vents) or "
                   "compression (pressed shut, flash groove)")
    p.add_argument("--material", default="as40", help="moulding silicone: as40 (Easy "
                   "Composites AS40, the paper's) or dragonskin; sets the default shrinkage")
    p.add_argument("--shrinkage", type=number("shrinkage", "%"), default=None,
                   help="linear cure shrinkage, %% (default the silicone's: 0.1)")
    p.add_argument("--clearance", type=number("clearance", "mm"), default=0.2,
                   help="gap of the registration keys in their sockets, mm (0.05-1)")
    p.add_argument("--wall", type=number("wall", "mm"), default=5.0,
                   help="least mold material between the part and the outside, mm")
    p.add_argument("--parting", default="auto", help="auto (the split without undercut), z "
                   "(horizontal, through the port axis) or x (vertical, x = 0)")
    p.add_argument("--out", default=None, help="output folder (default build/NAME: "
                   "mold-TYPE for a preset's casting mold with the defaults, then NAME=VALUE "
                   "for each parameter or option that differs, as spsc bladder names its "
                   "folders: --type D --w 12 --process compression writes "
                   "build/mold-D-w=12-process=compression/; from a part file, "
                   "mold-STEM[-NAME=VALUE...])")
    p.add_argument("--no-step", action="store_true", help="skip the STEP files (B-rep, ~3 s)")
    p.add_argument("--no-render", action="store_true", help="skip the exploded render")
    p.set_defaults(func=run)


def _bladder(args):
    """The BladderSpec from the part's design file or the geometry options."""
    from spsc.cad.checkdesign import design_path_for, load_design, parse_design
    from spsc.cad.specs import bladder_spec

    if args.part is not None:
        if geometry_given(args):
            raise ParameterError("part", args.part, "a part file or --type/the seven "
                                 "parameters, not both")
        path = Path(args.part)
        mesh = path.suffix.lower() in (".stl", ".3mf", ".step")
        design = design_path_for(path) if mesh else path
        if not design.is_file():
            raise ParameterError("part", args.part, "a bladder written by spsc bladder "
                                 "(NAME.design.json or the STL beside it)")
        d = load_design(design)
        if d.get("kind") != "bladder" or "geometry" not in d:
            raise ParameterError("part", args.part, "a bladder's design file (molds of the "
                                 f"fingertip or other parts are not made yet; this is "
                                 f"{d.get('kind', 'unknown')!r})")
        stem = design.name.removesuffix(".design.json")
        geom = parse_design(d)["geometry"]  # the seven parameters, checked by the shared reader
        return bladder_spec(geom, int(d.get("genus", 4)), args.tube_id), \
            "-".join([stem if stem.startswith("mold") else f"mold-{stem}", *_options(args)])
    from spsc.cli.bladder import output_name
    from spsc.cli.options import geometry_from_args

    geom = geometry_from_args(args)
    name = output_name("mold", args, geom, (("flange_holes", args.flange_holes, 4),))
    return bladder_spec(geom, args.flange_holes, args.tube_id), "-".join([name, *_options(args)])


def _options(args) -> list[str]:
    """``NAME=VALUE`` for each mold option that is not its default (the folder's name)."""
    from spsc.cli.bladder import option_labels

    return option_labels((("tube_id", args.tube_id, 3.0), ("process", args.process, "casting"),
                          ("material", args.material, "as40"),
                          ("shrinkage", args.shrinkage, None), ("clearance", args.clearance, 0.2),
                          ("wall", args.wall, 5.0), ("parting", args.parting, "auto")))


def run(args: argparse.Namespace) -> int:
    from spsc.cad.mold.spec import MoldSpec

    bladder, name = _bladder(args)
    spec = MoldSpec(process=str(args.process).strip().lower(),
                    material=str(args.material).strip().lower(), shrinkage_pct=args.shrinkage,
                    clearance=args.clearance, wall=args.wall,
                    parting=str(args.parting).strip().lower())
    outdir = check_output_dir("--out", args.out if args.out is not None else f"build/{name}")

    from spsc.cad.mold.build import build_mold
    from spsc.cad.mold.export import write_mold
    from spsc.cad.mold.gate import mold_gate

    t0 = time.perf_counter()
    mold = build_mold(bladder, spec)
    t_mesh = time.perf_counter() - t0
    brep = None if args.no_step else build_mold(bladder, spec, kernel="brep",
                                                 parting=mold.parting)
    t_brep = time.perf_counter() - t0 - t_mesh
    gate = mold_gate(mold)
    t_gate = time.perf_counter() - t0 - t_mesh - t_brep
    info = write_mold(mold, brep, outdir, gate=gate)
    g = bladder.geometry
    print(f"{name}: {spec.process} mold of w={g.w:g} h={g.h:g} l={g.l:g} t0={g.t0:g} "
          f"n1={g.n1:g} n2={g.n2:g} cy={g.cy:g} mm in {spec.material} "
          f"(shrinkage {100 * spec.shrinkage:g} %, cavity x{spec.scale:.5f})")
    uc = ", ".join(f"{k}: " + " / ".join(f"{n} {v:.1f}" for n, v in d.items())
                   for k, d in mold.undercut.items())
    print(f"  parting {info['parting']['plane']} (undercut mm²: {uc or 'given'})")
    for p in info["pieces"]:
        pull = "dissolved" if p["pull"] is None else "pull ({:g}, {:g}, {:g})".format(*p["pull"])
        print(f"  {p['name']:<6} {p['role']:<4} {p['volume_mm3'] / 1000:7.2f} cm³  {pull}")
    print(f"  mesh {t_mesh:.1f} s, B-rep {t_brep:.1f} s, gate {t_gate:.1f} s")
    if not args.no_render:
        from spsc.report.mold_figures import render_mold

        print(f"  {render_mold(mold, outdir / 'exploded.png')}")
    print(gate.summary())
    print(f"  -> {outdir / 'mold.json'}")
    return 0 if gate.passed else 1
