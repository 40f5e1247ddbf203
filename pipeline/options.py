"""Shared command-line options: the chamber is ``--type`` (a preset, any of the seven parameters
overriding it) or all seven parameters."""

from __future__ import annotations

import argparse

from spsc.core.errors import ParameterError
from spsc.cad.geometry import SPSCGeometry, preset

__all__ = ["PARAMS", "add_geometry_options", "add_setup_options", "geometry_from_args",
           "geometry_given"]

PARAMS = ("w", "h", "l", "t0", "n1", "n2", "cy")
_HELP = {"w": "cavity semi-width at the base, mm", "h": "cavity height, mm",
         "l": "length of the extruded middle, mm (0: pure dome)", "t0": "wall thickness, mm",
         "n1": "super-ellipse exponent n1 >= 1", "n2": "super-ellipse exponent n2 >= 1",
         "cy": "bulge shift c_y >= 0"}


def add_geometry_options(parser: argparse.ArgumentParser) -> None:
    g = parser.add_argument_group("chamber geometry: --type, or all seven parameters")
    g.add_argument("--type", default=None, help="preset A, B, C or D (Table 1); any of the "
                   "seven parameters below overrides the preset's value")
    g.add_argument("--size", default="table1", help="preset footprint: table1 (w=11, h=13, "
                   "l=3, t0=1 mm, default) or GS1 (w=h=l=10, t0=1 mm)")
    for name in PARAMS:
        g.add_argument(f"--{name}", type=str, default=None, help=_HELP[name])


def geometry_given(args: argparse.Namespace) -> bool:
    return bool(args.type) or any(getattr(args, k, None) not in (None, "") for k in PARAMS)


def geometry_from_args(args: argparse.Namespace) -> SPSCGeometry:
    """The preset named by ``--type``/``--size`` with any of the seven parameters replaced, or
    the seven parameters alone. Values are validated by SPSCGeometry (one-line ParameterError
    naming the parameter, its value and the allowed range)."""
    given = {k: getattr(args, k) for k in PARAMS if getattr(args, k, None) not in (None, "")}
    if args.type:
        return preset(args.type, size=args.size, **given)
    missing = [k for k in PARAMS if k not in given]
    if missing:
        raise ParameterError("geometry", "incomplete", "--type A-D, or all seven parameters "
                             "(missing: --" + ", --".join(missing) + ")")
    return SPSCGeometry(**given)


def add_setup_options(parser: argparse.ArgumentParser, *, stroke: float, points: int) -> None:
    """The setup shared by the models: material, setup pressure, reservoir (mode), stroke,
    plate positions and polytropic index (same names and units in every verb)."""
    parser.add_argument("--material", default="tpu60a",
                        help="catalogue material (default tpu60a)")
    parser.add_argument("--pressure", type=float, default=40.0,
                        help="setup pressure, kPa gauge")
    parser.add_argument("--reservoir", type=float, default=0.0,
                        help="reservoir volume, mm³ (0: high stiffness; 40000: the paper's low "
                        "mode)")
    parser.add_argument("--stroke", type=float, default=stroke,
                        help=f"plate travel from first contact, mm (default {stroke:g})")
    parser.add_argument("--points", type=int, default=points,
                        help=f"plate positions including y = 0 (default {points})")
    parser.add_argument("--polytropic-n", type=float, default=1.0,
                        help="polytropic index n (eq. 2; 1: isothermal)")
