"""``spsc fem``: the short form of ``spsc curve --model fem``: the 3D hyperelastic FEM check
of one chamber, one setup — the membrane's JSON; or, with ``--part``, of any closed part.

    spsc fem --type B --pressure 40 [--reservoir 40000] [--stroke 4] [--points 11]
             [--material tpu60a] [--mesh-size 1.0] [--layers 2] [--full] [--solver auto]
             [--json F] [--csv F] [--png F] [--vtu DIR] [--quiet]
    spsc fem --part FILE.stl|.3mf|.step [--design FILE.design.json] [--fix "z<=0"]
             [--plate-normal 0,0,-1] [--plate-at X,Y,Z|SITE] [--motor] [--cache DIR]
             [setup and outputs as above]

Chamber: quarter model of the wall (clamped on z = 0, symmetry planes x = 0, y = 0), P2/P1
mixed tetrahedra, follower cavity pressure, closed gas volume with reservoir after inflation,
rigid frictionless plate. ``--pressure 0`` is the open chamber (F_el).

Part: the whole part meshed by fTetWild (quadratic, curved boundary), its one enclosed cavity
found and loaded by the gas; the nodes the ``--fix`` selector takes are clamped (default: the
design file's mount); the plate moves along ``--plate-normal`` from where it first touches the
part (``--plate-at`` checks that point, or names a site of the design file: ``apex``, ``pulp``,
``distal``). A design file ``STEM.design.json`` beside the part is read when ``--design`` is not
given: it plugs the inlet bore, names the mount, the sites and the FSR pockets, whose forces
(the plate pressing the sensor in each pocket) are written as ``force_<pocket>_N`` columns.
``--motor`` holds the design's motor (a haptic chamber's, ``spsc bladder --haptic``) as a rigid
insert: seated on its ledge, met by the dome above it, its volume taken off the gas; its force
is the ``force_motor_N`` column. The part's mesh is cached (keyed by the file's hash, its port
and the mesh size) in ``--cache DIR``, by default ``spsc-cache/`` in the folder of the first
output named (``--json``, ``--csv``, ``--png``, ``--vtu``), else ``build/cache/fem`` under the
current folder; a run refused after meshing caches nothing.

Pressures kPa gauge, volumes mm³, lengths mm. Exit 0 when every point converged, 1 when not
(what converged is written), 2 on invalid input.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from spsc.core.errors import ParameterError
from spsc.core.setup import Contact
from spsc.models.part import refuse_contact

from spsc.cli.curve import add_curve_parser, exit_status, plot, run as run_curve, summary
from spsc.cli.options import (PARAMS, PLOT_SUFFIXES, Once, check_output_dir, check_output_file,
                              output_cache_dir,
                              number_list)

#: the options that belong to one mode only
_PART_ONLY = ("design", "fix", "plate_normal", "plate_at", "motor", "cache")
_CHAMBER_ONLY = ("type", "layers", "full") + tuple(PARAMS)


def register(subparsers) -> None:
    p = add_curve_parser(subparsers, "fem", models=("fem",),
                         help="3D hyperelastic FEM: inflation and plate contact "
                         "(= spsc curve --model fem), of a chamber or of any part (--part)",
                         description=__doc__.split("\n\n")[0])
    g = p.add_argument_group("any closed part (instead of --type)")
    g.add_argument("--part", metavar="FILE", default=None,
                   help="the part: .stl, .3mf or .step with one enclosed cavity")
    g.add_argument("--design", metavar="FILE.design.json", default=None,
                   help="its design file (default: STEM.design.json beside the part, if any): "
                   "plugs the inlet bore, names the mount, plate sites and FSR pockets")
    g.add_argument("--fix", metavar="SELECTOR", default=None,
                   help="nodes to clamp, e.g. 'z<=0' or 'y<-12 & z<1' (default: the design's "
                   "mount)")
    g.add_argument("--plate-normal", metavar="NX,NY,NZ", default=None, action=Once,
                   type=_vector("plate-normal"),
                   help="the plate's direction of travel (default 0,0,-1, or the site's)")
    g.add_argument("--motor", action="store_true", default=None,
                   help="hold the design file's motor as a rigid insert (haptic chamber: seated "
                   "on its ledge, met by the dome; its volume off the gas; force_motor_N)")
    g.add_argument("--plate-at", metavar="X,Y,Z|SITE", default=None, action=Once,
                   help="the point the plate first touches, or a site of the design file")
    g.add_argument("--cache", metavar="DIR", default=None,
                   help="the part mesh's cache folder (default: spsc-cache/ beside the first "
                   "output named, else build/cache/fem)")
    p.set_defaults(func=run)


def _vector(name: str):
    """argparse ``type``: three comma-separated numbers (:func:`number_list`)."""
    def parse(text: str):
        import argparse

        try:
            return number_list(name, text, count=3)
        except ParameterError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
    parse.__name__ = "vector"
    return parse


def run(args) -> int:
    if args.part is None:
        for dest in _PART_ONLY:
            if getattr(args, dest, None) is not None:
                raise ParameterError("--" + dest.replace("_", "-"), getattr(args, dest),
                                     "only with --part")
        return run_curve(args)
    return run_part_cli(args)


# -- part mode ------------------------------------------------------------------------------
def _design_of(args) -> tuple[dict | None, str | None]:
    from spsc.core.jsonio import read_json

    path = args.design
    if path is None:
        beside = Path(args.part).with_name(Path(args.part).stem + ".design.json")
        if not beside.is_file():
            return None, None
        path = beside
    path = Path(path)
    if not path.is_file():
        raise ParameterError("design", str(path), "an existing design file (.design.json)")
    try:
        data = read_json(path)
    except (ValueError, UnicodeDecodeError) as exc:
        raise ParameterError("design", str(path), f"a JSON design file ({exc})") from None
    from spsc.fem.part.design import check_design

    return check_design(data, path.name), str(path)


def _sites(design: dict | None) -> dict:
    return dict(((design or {}).get("fem") or {}).get("sites") or {})


def _refuse_friction(args) -> None:
    """Friction and a compliant object are not built for parts: refused in one line by the
    part model's own rule (:func:`spsc.models.part.refuse_contact`), before the part's files
    are read."""
    friction = getattr(args, "friction", None)
    refuse_contact(Contact.of(friction="0" if friction is None else friction,
                              object_stiffness=getattr(args, "object_stiffness", None)))


def _check_outputs(args) -> None:
    for opt, path in (("--json", args.json), ("--csv", args.csv)):
        if path is not None:
            check_output_file(opt, path)
    if args.png is not None:
        check_output_file("--png", args.png, PLOT_SUFFIXES)
    if args.vtu is not None:
        check_output_dir("--vtu", args.vtu)
    if args.cache is not None:
        check_output_dir("--cache", args.cache)


def _placement(args, design) -> tuple:
    """(the plate's direction or None, the point it first touches or None): ``--plate-at``
    a point or a site of the design file (whose normal is the default direction)."""
    normal, at = args.plate_normal, None
    if args.plate_at is not None:
        sites = _sites(design)
        if args.plate_at in sites:
            site = sites[args.plate_at]
            at = tuple(site["at"])
            normal = normal if normal is not None else tuple(site["normal"])
        else:
            try:
                at = number_list("plate-at", args.plate_at, count=3)
            except ParameterError:
                names = ", ".join(sites) or "none in the design file"
                raise ParameterError("plate-at", args.plate_at,
                                     f"X,Y,Z in mm or a site name ({names})") from None
    return normal, at


def part_setup_from_args(args):
    """The :class:`~spsc.core.setup.Setup` (its body a :class:`~spsc.fem.part.Part`) and the
    part model's options of an invocation, every check before any work (one-line
    ParameterError; the run's own against the part's surface are the model's ``check``)."""
    from spsc.core.loadcase import check_load
    from spsc.core.setup import Contact, Setup
    from spsc.fem.part import ContactPatch, Part
    from spsc.materials import material
    from spsc.models import MODELS

    for dest in _CHAMBER_ONLY:
        if getattr(args, dest, None) not in (None, False):
            raise ParameterError("--" + dest.replace("_", "-"), getattr(args, dest),
                                 "not with --part (the part file is the geometry; the mesh "
                                 "size is --mesh-size)")
    _refuse_friction(args)
    _check_outputs(args)
    part = Path(args.part)
    if not part.is_file():
        raise ParameterError("part", str(part), "an existing .stl, .3mf or .step file")
    design, _ = _design_of(args)
    fem = (design or {}).get("fem") or {}
    fix = args.fix if args.fix is not None else fem.get("mount")
    if fix is None:
        raise ParameterError("fix", None, "a selector of the nodes to clamp, e.g. --fix 'z<=0' "
                             "(the design file names no mount)")
    normal, at = _placement(args, design)
    contacts = tuple(ContactPatch(p["name"], tuple(p["center"]), tuple(p["normal"]),
                                  float(p["radius"]), float(p.get("insert_mm", 0.0)))
                     for p in fem.get("contacts", ()))
    model = MODELS["part"]
    load = check_load(None, pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
                      stroke_mm=args.stroke if args.stroke is not None else model.stroke_mm,
                      points=args.points if args.points is not None else model.points,
                      polytropic_n=args.polytropic_n)
    body = Part(str(part), fix, plate_normal=normal if normal is not None else (0.0, 0.0, -1.0),
                plate_at=at, design=design, contacts=contacts, motor=bool(args.motor))
    setup = Setup(body, material(args.material), load, Contact.of(args.indenter or "plate"))
    options = model.Options(mesh_size=args.mesh_size if args.mesh_size is not None else 1.0,
                            force=bool(args.force), solver=args.solver or "auto",
                            vtu=args.vtu)
    model.run_of(setup, options)  # the run's own checks (normal, selector, motor, ...)
    return setup, options


def run_part_cli(args) -> int:
    from spsc.core.progress import progress_bar
    from spsc.models import MODELS

    verb, model = "fem", MODELS["part"]
    setup, options = part_setup_from_args(args)
    model.check(setup, options, verb=verb, quiet=bool(args.quiet))
    if not args.quiet:
        from spsc.models.part import part_surface_of

        surface = part_surface_of(model.run_of(setup, options))
        print(f"spsc {verb}: meshing {Path(setup.body.path).name} (cavity "
              f"{surface.cavity_volume:.1f} mm³{', port plugged' if surface.capped else ''})",
              file=sys.stderr)
    bar = progress_bar(total=model.load_steps(setup, options), desc=f"spsc {verb}",
                       unit="step", disable=bool(args.quiet), file=sys.stderr)

    def progress(done, total):
        bar.total = total
        bar.update(done - bar.n)

    try:
        out = model.curve(setup, options, progress=progress, cache_dir=output_cache_dir(args))
    finally:
        bar.close()
    curve = out.curve
    if args.json:
        curve.to_json(args.json, extra=out.extra or None)
    if args.csv:
        curve.to_csv(args.csv)
    if args.png:
        plot(curve, None, args.png)
    summary(curve)
    if curve.series:
        last = int(np.flatnonzero(curve.converged)[-1]) if curve.converged.any() else 0
        forces = ", ".join(f"{k[6:-2]} {v[last]:.3g}" for k, v in curve.series.items())
        print(f"contact forces at y = {curve.y_mm[last]:.3g} mm (N): {forces}")
    return exit_status(verb, curve)
