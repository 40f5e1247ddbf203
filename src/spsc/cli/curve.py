"""``spsc curve``: the one verb that computes a :class:`~spsc.core.curve.Curve` from a chamber
and a setup, with any model — JSON, CSV and a plot.

    spsc curve --model membrane|simplified|wall|fem --type D --pressure 40 [--reservoir 40000]
               [--stroke MM] [--points N] [--material tpu60a] [model options]
               [--json F] [--csv F] [--png F] [--quiet]

``spsc membrane`` and ``spsc fem`` are its short forms (the same code, the same JSON). The
models are :data:`spsc.models.MODELS`: each brings its default stroke and points, its checks,
and its options as a dataclass whose fields become this verb's options. Pressures kPa gauge,
volumes mm³, lengths mm. Exit 0 when every plate position converged, 1 when some did not (what was computed is
still written, the reason on stderr), 2 on invalid input (one line on stderr).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError
from spsc.models import MODELS, cli_options, options_from, parametric
from spsc.models.meshed import ContactOptions

from spsc.cli.figure import contact_words, plot, title  # noqa: F401  (spsc fem, the tests)
from spsc.cli.band import add_tolerance_options, band_summary, check_tolerance, run_band
from spsc.cli.options import (PLOT_SUFFIXES, add_geometry_options, add_output_options,
                              output_cache_dir,
                      add_quiet_option, add_setup_options, check_output_dir,
                      check_output_file, geometry_from_args, integer, number, warn)

__all__ = ["Job", "add_curve_parser", "add_model_options", "prepare", "register", "run"]


@dataclass(frozen=True)
class Job:
    """A checked invocation: the model, the setup (:class:`~spsc.core.setup.Setup`: the
    chamber, the material, the load case, the contact) and the model's options, ready to
    solve."""

    model: object
    setup: object
    options: object

    geometry = property(lambda self: self.setup.body, doc="the chamber")
    material = property(lambda self: self.setup.material, doc="the material")
    load = property(lambda self: self.setup.load, doc="the load case")


def _argument(group, name: str, meta: dict) -> None:
    kw = {"default": None, "dest": name, "help": meta["help"]}
    if meta["kind"] == "flag":
        kw["action"] = "store_true"
    elif meta["kind"] == "number":
        kw["type"] = number(meta["label"], meta["unit"])
    elif meta["kind"] == "integer":
        kw["type"] = integer(meta["label"])
    elif meta["kind"] == "choice":
        kw["choices"] = meta["choices"]
    if meta["metavar"]:
        kw["metavar"] = meta["metavar"]
    group.add_argument(meta["flag"], **kw)


def add_model_options(parser, models) -> None:
    """The options of ``models`` (names of :data:`MODELS`), from their options dataclasses:
    those of a shared group (the meshed models' ``discretisation``, the plate's ``contact``)
    once in that group, each model's own in its group; the contact's
    (:class:`~spsc.models.meshed.ContactOptions`) once for the models that take it. Every
    option defaults to None (not given), so a model can refuse another's."""
    done = set()
    takers = [m for m in models if MODELS[m].contact]
    if takers:
        g = parser.add_argument_group(f"{' and '.join(takers)} contact")
        for name, meta in cli_options(ContactOptions).items():
            _argument(g, name, meta)
            done.add(name)
    for group in ("discretisation",):
        shared = {}
        for m in models:
            for name, meta in cli_options(MODELS[m].Options).items():
                if meta["group"] == group:
                    shared.setdefault(name, meta)
        owners = [m for m in models if any(n in cli_options(MODELS[m].Options) for n in shared)]
        if shared:
            g = parser.add_argument_group(f"{' and '.join(owners)} {group}")
            for name, meta in shared.items():
                _argument(g, name, meta)
                done.add(name)
    for m in models:
        own = {n: meta for n, meta in cli_options(MODELS[m].Options).items() if n not in done}
        if own:
            g = parser.add_argument_group(f"{m} model options")
            for name, meta in own.items():
                _argument(g, name, meta)
                done.add(name)


# -- the verb and its short forms -------------------------------------------------------------
def add_curve_parser(subparsers, verb: str, *, models: tuple[str, ...], help: str,
                     description: str):
    """Register ``verb`` computing a Curve with any of ``models`` (the first is the default;
    ``--model`` only when there is a choice). ``spsc curve``, ``spsc membrane`` and
    ``spsc fem`` are all this parser."""
    p = subparsers.add_parser(verb, help=help, description=description)
    add_geometry_options(p)
    strokes = {MODELS[m].stroke_mm for m in models}
    points = {MODELS[m].points for m in models}
    note = ("the model's: " + ", ".join(f"{m} {MODELS[m].stroke_mm:g}" for m in models),
            "the model's: " + ", ".join(f"{m} {MODELS[m].points}" for m in models))
    add_setup_options(p, stroke=strokes.pop() if len(strokes) == 1 else None,
                      points=points.pop() if len(points) == 1 else None,
                      defaults_note=note)
    if len(models) > 1:
        p.add_argument("--model", choices=models, default=models[0],
                       help="; ".join(f"{m}: {MODELS[m].help}" for m in models)
                       + f" (default {models[0]})")
    else:
        p.set_defaults(model=models[0])
    add_model_options(p, models)
    if verb == "curve":
        add_tolerance_options(p)
    add_output_options(p, png="write a plot of F, p, A, dV and the stiffness here "
                       "(" + ", ".join(s.lstrip(".") for s in PLOT_SUFFIXES[:3]) + " ...)")
    add_quiet_option(p)
    p.set_defaults(func=run, models=models)
    return p


def register(subparsers) -> None:
    add_curve_parser(subparsers, "curve", models=parametric(),
                     help="the Curve F, p, A, dV(y) of a chamber with any model",
                     description=__doc__.split("\n\n")[0])


def model_options(args, model):
    """The model's options from the arguments; an option of another model is refused (the
    contact's by a model that takes none). Fills in the model's default stroke and points."""
    if not model.contact:
        for dest, meta in cli_options(ContactOptions).items():
            if getattr(args, dest, None) is not None:
                owners = [m for m in args.models if MODELS[m].contact]
                raise ParameterError(meta["flag"], getattr(args, dest),
                                     "only with --model " + " or ".join(owners))
    own = cli_options(model.Options)
    for other in args.models:
        for dest, meta in cli_options(MODELS[other].Options).items():
            if dest not in own and getattr(args, dest, None) is not None:
                owners = [m for m in args.models if dest in cli_options(MODELS[m].Options)]
                raise ParameterError(meta["flag"], getattr(args, dest),
                                     "only with --model " + " or ".join(owners))
    if args.stroke is None:
        args.stroke = model.stroke_mm
    if args.points is None:
        args.points = model.points
    return options_from(model.Options, args)


def _check_outputs(args) -> None:
    if args.json is not None:
        check_output_file("--json", args.json)
    if args.csv is not None:
        check_output_file("--csv", args.csv)
    if args.png is not None:
        check_output_file("--png", args.png, PLOT_SUFFIXES)
    if getattr(args, "vtu", None) is not None:
        check_output_dir("--vtu", args.vtu)


def prepare(args) -> Job:
    """Every check of the invocation, before any work: the model's options, the outputs, then
    the setup once (the chamber, the material, the load case with the same limits for every
    model, the contact) and the model's own limits and size. ParameterError (one line) on the
    first problem."""
    from spsc.core.setup import Setup
    from spsc.materials import material

    model = MODELS[args.model]
    options = model_options(args, model)
    _check_outputs(args)
    setup = Setup.of(geometry_from_args(args), material(args.material),
                     pressure_kPa=args.pressure, reservoir_mm3=args.reservoir,
                     stroke_mm=args.stroke, points=args.points, polytropic_n=args.polytropic_n,
                     allow_zero_stroke=model.zero_stroke,
                     **_contact(args))
    model.check(setup, options, verb=args.command, quiet=bool(args.quiet))
    check_tolerance(args, setup)
    return Job(model, setup, options)


def _contact(args) -> dict:
    """The contact's spellings given on the command line (the defaults otherwise: the
    frictionless rigid plate), for :meth:`~spsc.core.setup.Contact.of`."""
    given = {k: getattr(args, k, None) for k in cli_options(ContactOptions)}
    return {k: v for k, v in given.items() if v is not None}


def solve(job: Job, *, verb: str, quiet: bool, cache_dir=None):
    """The job's model solved, with a progress bar on stderr (unless ``quiet``) for a model
    that reports load steps; a meshed model keeps its meshes in ``cache_dir`` (None: its
    default)."""
    from spsc.core.progress import progress_bar

    total = job.model.load_steps(job.setup, job.options)
    bar = progress_bar(total=total, desc=f"spsc {verb}", unit="step",
                       disable=quiet or not total, file=sys.stderr)

    def progress(done, total):
        bar.total = total
        bar.update(done - bar.n)

    try:
        return job.model.curve(job.setup, job.options, progress=progress,
                               cache_dir=cache_dir)
    finally:
        bar.close()


def run(args) -> int:
    verb = args.command
    job = prepare(args)
    for msg in job.geometry.design_space_warnings():
        warn(verb, msg)
    out = solve(job, verb=verb, quiet=bool(args.quiet), cache_dir=output_cache_dir(args))
    curve = out.curve
    record = run_band(args, job) if getattr(args, "tolerance", None) is not None else None
    if args.json and record is None:
        curve.to_json(args.json, extra=out.extra or None)
    elif args.json:  # the band beside the nominal curve
        from spsc.core.jsonio import write_json

        write_json(args.json, dict(curve.to_dict(out.extra or None), band=record))
    if args.csv:
        curve.to_csv(args.csv)
    if args.png:
        plot(curve, out.state, args.png, band=record)
    summary(curve)
    if record is not None:
        band_summary(record)
    noted = [m for m, c in zip(curve.message, curve.converged) if c and m]
    if noted:
        warn(verb, noted[-1] + (f" (and at {len(noted) - 1} other positions)"
                                if len(noted) > 1 else ""))
    return exit_status(verb, curve)


def exit_status(verb: str, curve) -> int:
    """Say an instability and a solve that did not converge on stderr; 0 when every point
    converged, else 1."""
    info = curve.solver
    if info.instability:
        print(f"spsc {verb}: instability: {info.instability}", file=sys.stderr)
    if not (info.converged and curve.all_converged):
        first = next((m for m, c in zip(curve.message, curve.converged) if not c), "")
        print(f"spsc {verb}: not converged: {info.message if not info.converged else first}",
              file=sys.stderr)
        return 1
    return 0


def summary(curve) -> None:
    """The result on stdout: setup, volumes, the curve (at most 11 rows), means and timing."""
    s, info = curve.setup, curve.solver
    d = info.details
    size = (f" ({d.get('model_part')}, {d['dofs']} unknowns, {d.get('tetrahedra')} tetrahedra)"
            if "dofs" in d else "")
    print(f"{curve.model} model{size}, material {curve.material}, p_i = {s['p_i_kPa']:g} kPa, "
          f"V_r = {s['reservoir_mm3']:g} mm³" + "".join(f", {c}" for c in contact_words(s)))
    apex = (f", apex at {curve.inflated_height_mm:.3f} mm"
            if np.isfinite(curve.inflated_height_mm) else "")
    print(f"cavity volume {curve.nominal_volume_mm3:.1f} -> {curve.inflated_volume_mm3:.1f} mm³ "
          f"({100 * (curve.inflated_volume_mm3 / curve.nominal_volume_mm3 - 1):+.2f} %){apex}")
    print(f"{'y_mm':>7} {'force_N':>9} {'p_kPa':>8} {'A_mm2':>8} {'dV_mm3':>9}")
    step = max(1, (len(curve) - 1) // 10)
    rows = sorted(set(range(0, len(curve), step)) | {len(curve) - 1})
    for k in rows:
        print(f"{curve.y_mm[k]:7.3f} {curve.force_N[k]:9.4f} {curve.pressure_kPa[k]:8.3f} "
              f"{curve.contact_area_mm2[k]:8.2f} {curve.volume_change_mm3[k]:9.2f}")
    k, q = curve.mean_stiffness(), curve.mean_sensitivity()
    if np.isfinite(k):
        print(f"mean stiffness {k:.4g} N/mm, mean sensitivity {q:.4g} kPa/mm")
    if info.iterations:
        print(f"solved in {info.seconds:.3g} s ({info.iterations} Newton iterations)")
    else:
        print(f"computed in {info.seconds:.3g} s")
