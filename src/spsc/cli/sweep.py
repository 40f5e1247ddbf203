"""``spsc sweep``: evaluate a grid or a Latin hypercube of chambers on Dask, one table row per
design (inputs, metrics, printability, status).

    spsc sweep [--type A,B,C,D] [--w 8:14:7] [--h ...] [--l ...] [--t0 0.8:1.5:4] [--n1 ...]
               [--n2 ...] [--cy ...] [--material tpu60a,elastic50a] [--pressure 10,40]
               [--reservoir 0,40000] [--samples N --seed S]
               [--model membrane|wall|simplified|surrogate] [--process fdm|sla|molding] [--points N] [--stroke MM] --out FILE.parquet
               [--csv FILE] [--html DIR [--front M:max|min,M:max|min]]
               [--workers N | --scheduler ADDR] [--force] [--quiet]

Each input takes a value X, a list a,b,c, a grid lo:hi:n or, with --samples, a range lo:hi.
A re-run with the same --out skips what is done and retries what failed. Exit 0 when every
design is ok, 1 when some are not (every row is still written), 2 on invalid input.
"""

from __future__ import annotations

import argparse
import sys

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import POINTS_MAX

from spsc.models import MODELS
from spsc.cli.options import (_HELP, PARAMS, Once, _RenamedSize, add_quiet_option,
                      check_output_dir, check_output_file, integer, number, typed_command)
from spsc.sweep.evaluate import INPUTS, STATUSES

__all__ = ["register", "run", "SWEEP_MODELS"]

#: The models a sweep runs (the 3D FEM is for checking one design: spsc curve --model fem).
SWEEP_MODELS = tuple(m.name for m in MODELS.values() if m.fast)
_FORMS = "X, a,b,c, lo:hi:n or (with --samples) lo:hi"


def register(subparsers) -> None:
    p = subparsers.add_parser("sweep", help="evaluate a grid or Latin hypercube of chambers "
                              "on Dask: metrics, printability, one Parquet row per design",
                              description=__doc__.split("\n\n")[0])
    g = p.add_argument_group(f"the design space: each input {_FORMS}")
    g.add_argument("--type", default=None, action=Once, metavar="A,B,C,D",
                   help="preset types (Table 1); "
                   "a parameter left out is the type's preset value")
    g.add_argument("--footprint", default="table1", metavar="table1|GS1",
                   help="the presets' footprint (default table1: w=11, h=13, l=3, t0=1 mm)")
    g.add_argument("--size", action=_RenamedSize, help=argparse.SUPPRESS)
    for name in PARAMS:
        g.add_argument(f"--{name}", default=None, action=Once, metavar="SPEC", help=_HELP[name])
    g.add_argument("--material", default=None, action=Once, metavar="NAME,...",
                   help="catalogue names or material files (default tpu60a)")
    g.add_argument("--pressure", default=None, action=Once, metavar="KPA",
                   help="setup pressure, kPa gauge (default 40)")
    g.add_argument("--reservoir", default=None, action=Once, metavar="MM3",
                   help="reservoir of the low "
                   "mode, mm³ (default 40000, the paper's; 0: both modes closed)")
    g.add_argument("--samples", type=integer("samples"), default=None, metavar="N",
                   help="Latin hypercube of N samples over the ranges lo:hi")
    g.add_argument("--seed", type=integer("seed"), default=0, metavar="S",
                   help="seed of the Latin hypercube (default 0: a re-run resumes)")
    g.add_argument("--force", action="store_true",
                   help="run a sweep of more than 10,000 designs (1,000,000 with --model "
                   "surrogate)")
    m = p.add_argument_group("evaluation")
    m.add_argument("--model", choices=SWEEP_MODELS, default="membrane",
                   help="the model of both modes (default membrane)")
    m.add_argument("--process", default="fdm", metavar="fdm|sla|molding",
                   help="process whose printability limits are judged (default fdm)")
    m.add_argument("--points", type=integer("points"), default=None, metavar="N",
                   help="plate positions per curve (default the model's: membrane, simplified "
                   "41; wall, surrogate 25)")
    m.add_argument("--life", action="store_true",
                   help="each design's life too: squeezed in the wall model to --stroke at its "
                   "setup, cycles by its material's fatigue law calibrated on Table 2 "
                   "(docs/guides/durability.md; one wall solve a design: 0.3 s a dome, 3 s a "
                   "stadium): life_cycles, peak_stretch, energy_amplitude_MPa")
    _band_options(m)
    m.add_argument("--stroke", type=number("stroke", "mm"), default=6.0, metavar="MM",
                   help="plate travel of the metrics, mm (default 6, the paper's)")
    o = p.add_argument_group("outputs and where it runs (checked before any work)")
    o.add_argument("--out", required=True, metavar="FILE.parquet",
                   help="the table (its journal FILE.journal.jsonl beside it; a re-run resumes)")
    o.add_argument("--csv", default=None, metavar="FILE.csv", help="the table as CSV too")
    o.add_argument("--html", default=None, metavar="DIR", help="an HTML page of the sweep "
                   "in DIR (both modes, a Pareto front, each metric against each input, "
                   "parallel coordinates, the best designs; DIR/index.html)")
    o.add_argument("--front", default=None, metavar="M:max|min,M:max|min",
                   help="the page's Pareto front: two metrics and their senses (default "
                   "sensitivity_high:max,cavity_mm3:min)")
    o.add_argument("--workers", default=None, metavar="N",
                   help="local worker processes (default: one per core)")
    o.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of a running Dask scheduler (tcp://host:8786) instead")
    add_quiet_option(p)
    p.set_defaults(func=run)


def prepare(args):
    """Every check before any work: outputs, where it runs, the model's settings and the
    space. Returns the :class:`~.sweep_space.SweepSpace`; ParameterError on a problem."""
    from spsc.cad.process import process
    from spsc.membrane.solver import check_membrane_pressure

    from spsc.study.executor import check_scheduler, check_workers
    from spsc.sweep.space import build_space

    from spsc.report.sweep_figures import Front
    from spsc.report.sweep_page import DEFAULT_FRONT

    check_output_file("--out", args.out, (".parquet",))
    if args.csv is not None:
        check_output_file("--csv", args.csv, (".csv",))
    if args.html is not None:
        check_output_dir("--html", args.html)
    elif args.front is not None:
        raise ParameterError("front", args.front, "only with --html (it shapes the page)")
    args.front = Front.parse(DEFAULT_FRONT if args.front is None else args.front)
    if args.scheduler is not None and args.workers is not None:
        raise ParameterError("workers", args.workers, "only without --scheduler (the "
                             "cluster has its own workers)")
    args.workers = check_workers(args.workers) if args.scheduler is None else None
    args.process = process(args.process).name
    if args.points is not None and not 2 <= args.points <= POINTS_MAX:
        raise ParameterError("points", args.points, f"an integer from 2 to {POINTS_MAX}")
    require("stroke", args.stroke, gt=0, unit="mm")
    from spsc.sweep.evaluate import batched
    from spsc.sweep.space import MAX_BATCHED_DESIGNS, MAX_DESIGNS

    limit = MAX_BATCHED_DESIGNS if batched(args.model) else MAX_DESIGNS
    space = build_space({k: getattr(args, k) for k in INPUTS}, samples=args.samples,
                        seed=args.seed, footprint=args.footprint, force=args.force,
                        limit=limit)
    # a stroke no design of the space can take refuses the sweep (read from the axes: the
    # space is not walked twice)
    tallest = space.tallest_h
    require("stroke", args.stroke, gt=0, lt=tallest, unit=f"mm, below the tallest "
            f"chamber's height in the space, h = {tallest:g} mm: no design could take it")
    if args.model in ("membrane", "simplified"):
        for a in space.axes:
            if a.name == "pressure" and a.kind != "range":
                for v in a.values:
                    check_membrane_pressure(v, args.stroke)
    if args.life:
        from spsc.sweep.life import check_life_materials

        check_life_materials([m for a in space.axes if a.name == "material" for m in a.values]
                             or ["tpu60a"])
    args.band = _band(args)
    if args.scheduler is not None:
        args.scheduler = check_scheduler(args.scheduler)
    return space


def _band_options(group) -> None:
    group.add_argument("--tolerance", default=None, metavar="FILE.toml",
                       help="each design's band too, under this tolerance file "
                       "(docs/guides/tolerance.md; --model surrogate): the P5, P50, P95 of its "
                       "stiffness and sensitivity in both modes (stiffness_high_p5, ...)")
    group.add_argument("--band-samples", type=integer("band samples"), default=32,
                       metavar="N", help="Saltelli's base samples N of each design's band "
                       "(N (D + 2) setups a mode; default 32)")


def _band(args):
    """The tolerance of each design's band (None without --tolerance), checked."""
    if args.tolerance is None:
        if args.band_samples != 32:
            raise ParameterError("band-samples", args.band_samples, "only with --tolerance")
        return None
    from spsc.study.tolerance import read_tolerance
    from spsc.sweep.band import check_band_model

    check_band_model(args.model)
    require("band-samples", args.band_samples, ge=4, le=4096)
    return read_tolerance(args.tolerance)


def run(args) -> int:
    from spsc.sweep import run as sweep

    space = prepare(args)
    where = args.scheduler or f"{args.workers} local worker{'s' * (args.workers > 1)}"
    points = args.points or MODELS[args.model].points
    print(f"spsc sweep: {len(space):,} designs, {args.model} model ({points} points over "
          f"{args.stroke:g} mm), printability for {args.process}, on {where}")
    df = sweep.run_sweep(space, model=args.model, process=args.process, points=args.points,
                         stroke_mm=args.stroke, out=args.out, workers=args.workers,
                         scheduler=args.scheduler, progress=not args.quiet, csv=args.csv,
                         life_stroke_mm=args.stroke if args.life else None,
                         tolerance=args.band, band_samples=args.band_samples)
    code = summary(df, args)
    if args.html is not None:
        from spsc.report.sweep_page import write_page

        page = write_page(df, args.html, model=args.model, process=args.process,
                          stroke_mm=args.stroke, points=args.points, front=args.front,
                          command=typed_command() or "", table=str(args.out),
                          searched=[a.name for a in space.axes])
        print(f"page: {page}")
    return code



def summary(df, args) -> int:
    """Counts by status, printability, speed and where it was written (stdout); the first
    message of each status that is not ok (stderr). Exit code 0 if every row is ok, else 1."""
    stats = df.attrs.get("sweep", {})
    counts = df["status"].value_counts()
    by_status = ", ".join(f"{int(counts.get(s, 0))} {s}" for s in STATUSES)
    judged = df["printable"].dropna()
    printable = (f"; printable ({args.process}): {int(judged.sum())} of {len(df)}"
                 + (f" ({len(df) - len(judged)} not judged)" if len(judged) < len(df) else ""))
    print(f"{len(df):,} designs: {by_status}{printable}")
    n, t = stats.get("evaluated", 0), stats.get("compute_s", 0.0)
    skipped = stats.get("skipped", 0)
    earlier = f"{skipped:,} done earlier and skipped"
    if n:
        w = stats.get("workers", 0)
        print(f"evaluated {n:,} in {t:.1f} s on {w} worker{'s' * (w != 1)} "
              f"({n / t:.3g} designs/s; cluster start {stats.get('start_s', 0.0):.1f} s); "
              + earlier)
    else:
        print(f"nothing to evaluate: {earlier}")
    print(f"written: {args.out} (journal {stats.get('journal', '')})"
          + (f", {args.csv}" if args.csv else ""))
    for s in STATUSES[1:]:
        rows = df[df["status"] == s]
        if len(rows):
            again = "; a re-run with the same --out retries them" if s == "failed" else ""
            print(f"spsc sweep: {len(rows)} {s} (rows kept{again}); first: "
                  f"{rows['message'].iloc[0]}", file=sys.stderr)
    return 0 if len(df) and (df["status"] == "ok").all() else 1
