"""Shared command-line options: the chamber given by ``--type`` and/or the seven parameters."""

from __future__ import annotations

import argparse

from spsc.cad.geometry import SPSCGeometry, preset

__all__ = ["add_geometry_options", "geometry_from_args"]

_PARAMS = ("w", "h", "l", "t0", "n1", "n2", "cy")


def add_geometry_options(parser: argparse.ArgumentParser, *, type_required: bool = False) -> None:
    g = parser.add_argument_group("chamber geometry (mm); a preset, overridden by any parameter")
    g.add_argument("--type", default="D" if not type_required else None,
                   help="preset A, B, C or D of Table 1 (default D)")
    g.add_argument("--size", default="table1", help="preset footprint: table1 (w=11, h=13, "
                   "l=3, t0=1) or GS1 (w=h=l=10, t0=1)")
    for name, text in (("w", "cavity semi-width at the base"), ("h", "cavity height"),
                       ("l", "length of the extruded middle (0: pure dome)"),
                       ("t0", "wall thickness"), ("n1", "super-ellipse exponent n1 >= 1"),
                       ("n2", "super-ellipse exponent n2 >= 1"), ("cy", "bulge shift c_y >= 0")):
        g.add_argument(f"--{name}", type=str, default=None, help=text)


def geometry_from_args(args: argparse.Namespace) -> SPSCGeometry:
    """The preset named by ``--type``/``--size`` with any of the seven parameters replaced.
    Values are validated by SPSCGeometry (one-line ParameterError naming the parameter)."""
    overrides = {k: getattr(args, k) for k in _PARAMS if getattr(args, k, None) not in (None, "")}
    return preset(args.type or "D", size=args.size, **overrides)
