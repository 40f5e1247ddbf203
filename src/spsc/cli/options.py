"""Shared command-line options, defined once for every verb: the chamber (``--type`` with
``--footprint``, or the seven parameters), the setup (material, pressure, reservoir, stroke,
points, polytropic index), the output files and ``--quiet``; number parsing and output-path
checks that end in the one-line error of :mod:`spsc.cli.main`.

Names and meanings are the same in every verb: ``--footprint`` is a preset's footprint
(table1/GS1); a mesh size is ``--mesh-size`` (mm). Numbers parse as numbers, including
``-inf``, ``nan`` and ``-1e5``, and are then refused by validation naming the parameter.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

from spsc.core.errors import ParameterError
from spsc.cad.geometry import LENGTHS, PARAMS, SIZES, SPSCGeometry, preset

__all__ = ["PARAMS", "add_geometry_options", "add_setup_options", "add_gas_options",
           "add_output_options", "add_quiet_option", "check_output_file", "check_output_dir",
           "geometry_from_args", "geometry_given", "integer", "number", "number_list",
           "Once", "typed_command", "warn"]

_HELP = {"w": "cavity semi-width at the base, mm", "h": "cavity height, mm",
         "l": "length of the extruded middle, mm (0: pure dome)", "t0": "wall thickness, mm",
         "n1": "super-ellipse exponent n1 >= 1", "n2": "super-ellipse exponent n2 >= 1",
         "cy": "bulge shift c_y >= 0"}

#: Image formats ``--png`` accepts (matplotlib's savefig), by suffix.
PLOT_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff",
                 ".webp")


# -- number parsing ------------------------------------------------------------------------
def number(name: str, unit: str = ""):
    """argparse ``type`` for a real number; the error names the parameter (``name``) like
    :class:`ParameterError`. inf and nan parse: the model's validation refuses them with its
    allowed range."""
    allowed = "a number" + (f" ({unit})" if unit else "")

    def parse(text: str) -> float:
        try:
            return float(text.strip())
        except ValueError:
            raise argparse.ArgumentTypeError(str(ParameterError(name, text, allowed))) from None
    parse.__name__ = "number"
    return parse


def gas_option(name: str, text):
    """``N[,TAU]``: the :class:`~spsc.dynamics.gas.Gas` (n in [1, 1.67], τ ≥ 0 s or inf);
    one ParameterError naming ``name`` otherwise."""
    from spsc.dynamics.gas import Gas  # here: every verb imports this module at start-up

    allowed = ("N or N,TAU: n in [1, 1.67] (1: isothermal, 1.4: air) and the thermal time "
               "τ >= 0 s or inf (adiabatic), e.g. 1.4,0.5")
    parts = [x.strip() for x in str(text).split(",")]
    try:
        values = [float(x) for x in parts]
    except ValueError:
        raise ParameterError(name, text, allowed) from None
    if len(values) not in (1, 2) or any(math.isnan(v) for v in values) \
            or not 1.0 <= values[0] <= 1.67 or (len(values) == 2 and values[1] < 0):
        raise ParameterError(name, text, allowed)
    return Gas(values[0], values[1] if len(values) == 2 else math.inf)


def integer(name: str):
    """argparse ``type`` for an integer (``2.5`` and ``inf`` are refused, naming ``name``)."""
    def parse(text: str) -> int:
        try:
            return int(text.strip())
        except ValueError:
            raise argparse.ArgumentTypeError(
                str(ParameterError(name, text, "an integer"))) from None
    parse.__name__ = "integer"
    return parse


def number_list(name: str, text, *, ge: float | None = None, gt: float | None = None,
                le: float | None = None, unit: str = "", count: int | None = None,
                distinct: bool = False) -> tuple[float, ...]:
    """Comma-separated numbers (``10,20,40``), each finite and within the bounds (``ge``,
    ``gt``, ``le``, in ``unit``); exactly ``count`` of them if given; no repeated value if
    ``distinct``. One ParameterError naming ``name`` and the whole text for a list that is
    empty, has an empty item (``10,,40``, ``10,``), a non-number or a value out of range: every
    verb that takes a list of numbers parses it here."""
    from spsc.core.errors import require

    items = str(text).split(",")
    if not str(text).strip():
        raise ParameterError(name, text, "one or more comma-separated numbers")
    values = []
    for k, item in enumerate(items, 1):
        if not item.strip():
            raise ParameterError(name, text, f"comma-separated numbers (item {k} is empty)")
        try:
            v = float(item.strip())
        except ValueError:
            raise ParameterError(name, text, f"comma-separated numbers (item {k}, "
                                 f"{item.strip()!r}, is not a number)") from None
        try:
            values.append(require(name, v, ge=ge, gt=gt, le=le, unit=unit))
        except ParameterError as exc:
            raise ParameterError(name, text, f"{exc.allowed} in every item (item {k} is "
                                 f"{item.strip()})") from None
    if count is not None and len(values) != count:
        raise ParameterError(name, text, f"{count} comma-separated numbers")
    if distinct and len(set(values)) != len(values):
        raise ParameterError(name, text, "each value once")
    return tuple(values)


class Once(argparse.Action):
    """Store an option's value, refusing the option given a second time (argparse keeps the
    last, so a bad first value would pass unseen): ``action=Once``."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._given: dict[int, object] = {}

    def __call__(self, parser, namespace, values, option_string=None):
        first = self._given.get(id(namespace), _NOT_GIVEN)
        if first is not _NOT_GIVEN:
            raise argparse.ArgumentError(self, str(ParameterError(
                option_string, f"{first} and {values}", "given once")))
        self._given[id(namespace)] = values
        setattr(namespace, self.dest, values)


_NOT_GIVEN = object()


# -- the chamber ---------------------------------------------------------------------------
class _RenamedSize(argparse.Action):
    """``--size`` was both a preset footprint here and a mesh size in the FEM API: refuse it,
    pointing to the two names that replace it."""

    def __call__(self, parser, namespace, values, option_string=None):
        raise argparse.ArgumentError(self, "renamed: --footprint table1|GS1 for the preset's "
                                     "footprint, --mesh-size MM for the FEM mesh")


def add_geometry_options(parser: argparse.ArgumentParser) -> None:
    g = parser.add_argument_group("chamber geometry: --type, or all seven parameters")
    g.add_argument("--type", default=None, help="preset A, B, C or D (Table 1); any of the "
                   "seven parameters below overrides the preset's value")
    g.add_argument("--footprint", default="table1", metavar="table1|GS1",
                   help="the preset's footprint: table1 (w=11, h=13, l=3, t0=1 mm, default) or "
                   "GS1 (w=h=l=10, t0=1 mm)")
    g.add_argument("--size", action=_RenamedSize, help=argparse.SUPPRESS)
    for name in PARAMS:
        g.add_argument(f"--{name}", type=str, default=None, metavar="MM" if name in LENGTHS
                       else "X", help=_HELP[name])


def geometry_given(args: argparse.Namespace) -> bool:
    return bool(args.type) or any(getattr(args, k, None) is not None for k in PARAMS)


def geometry_from_args(args: argparse.Namespace) -> SPSCGeometry:
    """The preset named by ``--type``/``--footprint`` with any of the seven parameters replaced,
    or the seven parameters alone. Values (an empty one included) are validated by
    SPSCGeometry: one-line ParameterError naming the parameter, its value and the range."""
    given = {k: getattr(args, k) for k in PARAMS if getattr(args, k, None) is not None}
    if args.type:
        if str(args.footprint).lower() not in {k.lower() for k in SIZES}:
            raise ParameterError("footprint", args.footprint, "one of " + ", ".join(SIZES))
        return preset(args.type, size=args.footprint, **given)
    missing = [k for k in PARAMS if k not in given]
    if missing:
        raise ParameterError("geometry", "incomplete", "--type A-D, or all seven parameters "
                             "(missing: --" + ", --".join(missing) + ")")
    return SPSCGeometry(**given)


# -- the setup -----------------------------------------------------------------------------
def add_gas_options(parser, *, pressure_required: bool = False,
                    pressure_help: str = "setup pressure, kPa gauge (default 40)") -> None:
    """Setup pressure, reservoir (mode) and polytropic index: the gas of eqs. 2, 6–7."""
    parser.add_argument("--pressure", type=number("pressure", "kPa gauge"), metavar="KPA",
                        required=pressure_required, default=None if pressure_required else 40.0,
                        help=pressure_help)
    parser.add_argument("--reservoir", type=number("reservoir", "mm³"), default=0.0,
                        metavar="MM3", help="reservoir volume, mm³ (0: high stiffness, "
                        "default; 40000: the paper's low mode)")
    parser.add_argument("--polytropic-n", type=number("polytropic_n"), default=1.0,
                        metavar="N", help="polytropic index n (eq. 2; 1: isothermal, default)")


def add_setup_options(parser: argparse.ArgumentParser, *, stroke: float | None,
                      points: int | None, defaults_note=("", "")) -> None:
    """The setup shared by the models: material, setup pressure, reservoir (mode), stroke,
    plate positions and polytropic index (same names and units in every verb). ``stroke`` or
    ``points`` None: the default is the model's (``defaults_note``, the stroke's and the
    points' notes, says which)."""
    g = parser.add_argument_group("setup")
    g.add_argument("--material", default="tpu60a", metavar="NAME|FILE.json",
                   help="catalogue material (tpu60a, elastic50a, silicone40a, as40; default "
                   "tpu60a) or a material file from spsc fit-material")
    add_gas_options(g)
    stroke_note, points_note = ((defaults_note, defaults_note) if isinstance(defaults_note, str)
                                else defaults_note)
    s = f"default {stroke:g}" if stroke is not None else stroke_note
    g.add_argument("--stroke", type=number("stroke", "mm"), default=stroke, metavar="MM",
                   help=f"plate travel from first contact, mm ({s})")
    n = f"default {points}" if points is not None else points_note
    g.add_argument("--points", type=integer("points"), default=points, metavar="N",
                   help=f"plate positions including y = 0 ({n})")


# -- outputs ---------------------------------------------------------------------------------
def add_output_options(parser, *, json: str | None = "write the result JSON here",
                       csv: str | None = "write the curve CSV here",
                       png: str | None = None) -> None:
    g = parser.add_argument_group("outputs (checked before any work)")
    if json:
        g.add_argument("--json", metavar="FILE", help=json)
    if csv:
        g.add_argument("--csv", metavar="FILE", help=csv)
    if png:
        g.add_argument("--png", metavar="FILE", help=png)


def add_quiet_option(parser) -> None:
    parser.add_argument("--quiet", action="store_true",
                        help="no progress bar (warnings and errors still go to stderr)")


def check_output_file(option: str, path, suffixes: tuple[str, ...] | None = None) -> Path:
    """``path`` can be written as a file: not empty, its folder exists, it is not a folder or a
    device (except the null device), its suffix is one of ``suffixes`` (if given), and the
    system lets us open it for writing (tried: a new file is created and removed again, an
    existing one opened for appending, so nothing is changed). Else a ParameterError naming
    ``option``: cheap, so commands call it before the work."""
    text = str(path)
    p = Path(path)
    if text.strip() == "":
        raise ParameterError(option, text, "a file path")
    if suffixes and p.suffix.lower() not in suffixes:
        raise ParameterError(option, text, "a file ending in " + ", ".join(suffixes))
    if p.is_dir():
        raise ParameterError(option, text, "a file path (this is a folder)")
    if text == os.devnull:
        return p
    if p.exists() and not p.is_file():
        raise ParameterError(option, text, "a regular file (this is a device or a pipe)")
    parent = p.parent
    if not parent.is_dir():
        raise ParameterError(option, text, f"a path in an existing folder ({parent} "
                             "is not one)")
    _try_write(option, p)
    return p


def _try_write(option: str, p: Path) -> None:
    existed = p.exists()
    try:
        with open(p, "ab"):
            pass
    except OSError as exc:
        raise ParameterError(option, str(p), f"a writable path ({exc.strerror})") from None
    if not existed:
        p.unlink()


def check_output_dir(option: str, path) -> Path:
    """``path`` is, or can be created as, a writable folder (tried with a temporary file in it
    or in its nearest existing parent, removed again)."""
    import tempfile

    text = str(path)
    p = Path(path)
    if text.strip() == "":
        raise ParameterError(option, text, "a folder path")
    if p.exists() and not p.is_dir():
        raise ParameterError(option, text, "a folder (this is a file)")
    anc = p
    while not anc.exists():
        anc = anc.parent
    if not anc.is_dir():
        raise ParameterError(option, text, f"a folder that can be created ({anc} is a file)")
    try:
        with tempfile.TemporaryFile(dir=anc):
            pass
    except OSError as exc:
        raise ParameterError(option, text, f"a folder that can be written ({anc}: "
                             f"{exc.strerror})") from None
    return p


def output_cache_dir(args) -> Path | None:
    """Where a meshed model keeps its meshes: ``--cache`` if the verb has it and it is given,
    else ``spsc-cache`` in the folder of the first output named (``--json``, ``--csv``,
    ``--png``; ``--vtu`` is a folder: beside it), else None (the model's default,
    ``build/cache/fem`` under the current folder)."""
    if getattr(args, "cache", None) is not None:
        return Path(args.cache)
    for name in ("json", "csv", "png", "vtu"):
        out = getattr(args, name, None)
        if out is not None and str(out) != os.devnull:
            return Path(out).absolute().parent / "spsc-cache"
    return None


def warn(verb: str, message: str) -> None:
    """A warning: one line on stderr, ``spsc <verb>: warning: <message>``."""
    import sys

    print(f"spsc {verb}: warning: {message}", file=sys.stderr)


def typed_command() -> str | None:
    """The command line as the user typed it (``spsc ...``), or None when not run as ``spsc``
    (tests, ``python -m``): callers then rebuild it from their arguments."""
    if not (sys.argv and Path(sys.argv[0]).name == "spsc"):
        return None
    import shlex

    return "spsc " + shlex.join(sys.argv[1:])
