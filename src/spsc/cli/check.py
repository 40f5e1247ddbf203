"""``spsc check FILE [--min-wall MM] [--process fdm|sla|molding] [--design JSON] [--json OUT]``.

Prints the printability summary and writes the full report (default ``check.json`` beside FILE).
The design sidecar ``<stem>.design.json`` beside FILE is used when present, unless ``--design``
names another. Exit 0 if every gating check passed, 1 with the failed checks named on one line,
2 on bad input (missing or unreadable file, bad option).
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

from spsc.cad.check import check_mesh, design_path_for, load_design
from spsc.cad.meshload import load_mesh
from spsc.core.errors import ParameterError, require
from spsc.cad.process import PROCESSES, process

from spsc.cli.options import check_output_file

__all__ = ["register", "run"]


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "check", help="printability report of an STL/3MF mesh",
        description="Printability gate: watertight, 2-manifold, no self-intersections, one part, "
                    "genus, minimum wall, cavity volume, bounding box, overhang area (report "
                    "only); with the design's geometry, the printability rule (wall, chamber "
                    "overhang).")
    p.add_argument("file", metavar="FILE", help="mesh to check (.stl or .3mf, mm)")
    p.add_argument("--min-wall", metavar="MM", default=None,
                   help="minimum wall thickness in mm (default: the process minimum)")
    p.add_argument("--process", default="fdm", metavar="|".join(PROCESSES),
                   help="manufacturing process whose limits apply (default fdm)")
    p.add_argument("--design", metavar="JSON", default=None,
                   help="design sidecar (default: FILE's <stem>.design.json if it exists)")
    p.add_argument("--json", metavar="OUT", default=None,
                   help="where to write the report (default: check.json beside FILE)")
    p.set_defaults(func=run)


def run(args) -> int:
    min_wall = None if args.min_wall is None else require("--min-wall", args.min_wall, gt=0,
                                                          unit="mm")
    process(args.process)
    mesh = Path(args.file)
    if not str(args.file).strip():
        raise ParameterError("FILE", args.file, "a mesh file (.stl or .3mf)")
    if mesh.is_dir():
        raise ParameterError("FILE", args.file, "a mesh file (this is a folder)")
    if not mesh.is_file():
        raise FileNotFoundError(2, "no such file", str(mesh))
    if args.design is not None:
        design = load_design(args.design)
    else:
        sidecar = design_path_for(mesh)
        design = load_design(sidecar) if sidecar.is_file() else None
    out = check_output_file("--json", args.json if args.json is not None
                            else mesh.with_name("check.json"))
    arrays = load_mesh(mesh)  # an unreadable mesh is bad input, refused before the checks
    report = dataclasses.replace(check_mesh(arrays, design=design, process=args.process,
                                            min_wall=min_wall), source=str(mesh))
    report.to_json(out)
    print(report.summary())
    if report.passed:
        return 0
    print(f"spsc check: FAILED: {', '.join(report.failed)}", file=sys.stderr)
    return 1
