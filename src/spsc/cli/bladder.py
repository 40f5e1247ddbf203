"""``spsc bladder``: build a printable bladder, export STEP/STL/3MF and run the printability gate."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from spsc.cad.specs import bladder_spec

from spsc.cli.options import (add_geometry_options, check_output_dir, geometry_from_args, integer,
                      number, warn)

MATERIAL_PROCESS = {"tpu60a": "fdm", "elastic50a": "sla", "silicone40a": "sla", "as40": "molding"}


def register(sub) -> None:
    p = sub.add_parser("bladder", help="build a printable bladder and check it",
                       description="Build the bladder (wall + floor/flange + barbed port) of a "
                       "chamber, write STEP, STL, 3MF and the printability report check.json. "
                       "The folder (and the files' stem) is named for what is in it: "
                       "build/bladder-TYPE/ for a preset as it is, then each value that differs "
                       "from the preset's or the default, as NAME=VALUE: --type D --w 12 "
                       "writes build/bladder-D-w=12/, --type D --w 12 --material elastic50a "
                       "build/bladder-D-w=12-material=elastic50a/, the seven parameters "
                       "without --type build/bladder-w=..-h=..-l=..-t0=..-n1=..-n2=..-cy=../; "
                       "--haptic adds -haptic. --out picks the folder instead.")
    add_geometry_options(p)
    p.add_argument("--material", default="tpu60a",
                   help="tpu60a (FDM), elastic50a or silicone40a (SLA), as40 (molding); "
                   "selects the process whose limits (minimum wall, overhang) the gate's "
                   "printability rule applies, the same rule as spsc sweep's printable column")
    p.add_argument("--out", default=None, help="output folder (default build/NAME, NAME as "
                   "above; the files are NAME.step, .stl, .3mf, .design.json either way)")
    p.add_argument("--flange-holes", type=integer("flange_holes"), default=4,
                   help="screw holes: 0, 2 or 4")
    p.add_argument("--tube-id", type=number("tube_id", "mm"), default=3.0,
                   help="inner diameter of the tube (mm)")
    p.add_argument("--haptic", action="store_true",
                   help="the haptic chamber of sec. 4.2: a pocket holding a DFRobot FIT0774 "
                   "vibration motor (10 x 2.7 mm) against the inner top, on a 0.8 mm 45° "
                   "support film, a sealed wire exit; printed in one piece with a pause to "
                   "insert the motor (the design file gives the height)")
    p.add_argument("--no-check", action="store_true", help="skip the printability gate")
    p.set_defaults(func=run)


def process_for(material_name: str) -> str:
    """The printing process of a catalogue material; a material file (.json) carries no
    process, so the bladder refuses it in one line."""
    from spsc.core.errors import ParameterError
    from spsc.materials import material

    if str(material_name).strip().lower().endswith(".json"):
        raise ParameterError("material", material_name, "a catalogue material ("
                             + ", ".join(MATERIAL_PROCESS) + "): it picks the printing "
                             "process and its minimum wall; a material file carries no process")
    return MATERIAL_PROCESS[material(material_name).name]


def output_name(prefix: str, args: argparse.Namespace, geom, extras=()) -> str:
    """The name of an output folder, for what is in it: ``prefix``, the preset (``--type``,
    and ``--footprint`` when not table1), then ``NAME=VALUE`` for each of the seven parameters
    that differs from the preset's (all seven without ``--type``), then :func:`option_labels`
    of ``extras``. Numbers as ``:g`` (mm)."""
    from spsc.cad.geometry import PARAMS, preset

    parts, base = [prefix], {}
    if args.type:
        parts.append(str(args.type).strip().upper())
        if str(args.footprint).strip().lower() != "table1":
            parts.append(str(args.footprint).strip().upper())
        base = preset(args.type, size=args.footprint).as_dict()
    g = geom.as_dict()
    parts += [f"{k}={g[k]:g}" for k in PARAMS if base.get(k) != g[k]]
    return "-".join(parts + option_labels(extras))


def option_labels(extras) -> list[str]:
    """``NAME=VALUE`` for each ``(name, value, default)`` whose value is given and is not the
    default (numbers as ``:g``, words in lower case)."""
    out = []
    for label, value, default in extras:
        if isinstance(value, str):
            value = value.strip().lower()
        if value is not None and value != default:
            out.append(f"{label}={value:g}" if isinstance(value, float) else f"{label}={value}")
    return out


def run(args: argparse.Namespace) -> int:
    # every check before the CAD kernel is even imported (2 s): a bad input fails at once
    geom = geometry_from_args(args)
    process = process_for(args.material)
    from spsc.materials import material

    name = output_name("bladder", args, geom, (("material", material(args.material).name,
                                                "tpu60a"),
                                               ("flange_holes", args.flange_holes, 4),
                                               ("tube_id", args.tube_id, 3.0)))
    if args.haptic:
        name += "-haptic"
    outdir = check_output_dir("--out", args.out if args.out is not None else f"build/{name}")
    spec = bladder_spec(geom, args.flange_holes, args.tube_id)
    if args.haptic:
        from spsc.cad.haptic import motor_top

        motor_top(spec)  # the motor fits, or one line before anything is built
    for msg in geom.design_space_warnings():
        warn("bladder", msg)

    from spsc.cad.bladder import build_bladder
    from spsc.cad.export import export_part
    from spsc.cad.meshbuild import bladder_mesh

    t0 = time.perf_counter()
    if args.haptic:
        from spsc.cad.haptic import build_haptic
        from spsc.cad.meshbuild import manifold_mesh

        mesh_part = build_haptic(spec)
        solid, design = build_haptic(spec, kernel="brep").solid, mesh_part.design
        mesh = manifold_mesh(mesh_part.solid)
    else:
        bladder = build_bladder(spec)
        solid, design, mesh = bladder.solid, bladder.design, bladder_mesh(spec)
    t_build = time.perf_counter() - t0
    written = export_part(solid, design, outdir, name, mesh=mesh)
    t_export = time.perf_counter() - t0 - t_build
    g = geom
    print(f"{name}: w={g.w:g} h={g.h:g} l={g.l:g} t0={g.t0:g} n1={g.n1:g} n2={g.n2:g} "
          f"cy={g.cy:g} mm; material {args.material} ({process.upper()})")
    print(f"  analytic cavity volume {g.cavity_volume() / 1000:.3f} cm³; "
          f"{written['triangles']} triangles; built in {t_build:.1f} s, exported in "
          f"{t_export:.1f} s")
    if args.haptic:
        mo = design["motor"]
        print(f"  motor {mo['name']} ({mo['diameter_mm']:g} x {mo['height_mm']:g} mm) at "
              f"z = {mo['z_bottom_mm']:.2f}-{mo['z_top_mm']:.2f} mm: pause the print at "
              f"z = {design['print']['pause_at_mm']:.2f} mm to insert it; its support (film, "
              f"ring, ceiling) {design['support_volume_mm3']:.0f} mm³")
    for kind in ("step", "stl", "3mf"):
        print(f"  {written['paths'][kind]}")
    if args.no_check:
        return 0
    return gate(written["paths"]["stl"], design, process, outdir)


def gate(stl: Path, design: dict, process: str, outdir: Path, extra: list = ()) -> int:
    """Run the printability gate on ``stl`` (plus ``extra`` part-specific checks), write
    check.json and print the summary; 0 if passed, 1 naming the failed checks. With the
    design's ``geometry`` (a bladder, the haptic chamber) the gate includes the printability
    rule (:mod:`spsc.cad.printability`) that sweeps and the design search apply."""
    import dataclasses

    from spsc.cad.check import check_mesh

    t0 = time.perf_counter()
    report = check_mesh(stl, design=design, process=process)
    if extra:
        report = dataclasses.replace(report, checks=tuple(report.checks) + tuple(extra))
    report.to_json(outdir / "check.json")
    print(report.summary())
    for c in extra:
        print(c.message)
    print(f"  check in {time.perf_counter() - t0:.1f} s -> {outdir / 'check.json'}")
    if not report.passed:
        print(f"FAILED: {', '.join(report.failed)}")
        return 1
    return 0
