"""``spsc design``: inverse design — from targets on stiffness, sensitivity, JND or cavity to a
printable chamber, with Optuna on Dask.

    spsc design --target stiffness_high=6 --target "sensitivity_high>=5" [--minimize M]
                [--maximize M] [--tol PCT] [--type A,B,C,D] [--w 8:14] [--h ...] [--l ...]
                [--t0 ...] [--n1 ...] [--n2 ...] [--cy ...] [--material tpu60a]
                [--pressure 40] [--reservoir 40000] [--model wall|membrane|simplified]
                [--process fdm|sla|molding] [--trials N] [--seed S] [--sampler tpe|nsga2]
                [--verify fem|none] [--mesh-size MM] [--no-build] [--points N] [--stroke MM]
                --out DIR [--json FILE] [--csv FILE] [--workers N | --scheduler ADDR] [--quiet]

Writes DIR/design.json, DIR/trials.parquet, DIR/index.html (figures in DIR/figures), the FEM
check's curves in DIR/verify and the part in DIR/part; a re-run with the same --out continues
the study. Exit 0 when the goal is met and the part passes the printability gate, 1 otherwise
(everything is still written), 2 on invalid input.
"""

from __future__ import annotations

import math
import secrets
import shlex
import sys
import time
from pathlib import Path

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import POINTS_MAX
from spsc.models import MODELS

from spsc.design.goal import METRIC_NAMES
from spsc.cli.options import (_HELP, PARAMS, Once, add_quiet_option, check_output_dir,
                      check_output_file, integer, number, typed_command)

__all__ = ["register", "run", "prepare", "DESIGN_MODELS"]

#: The fast models a design searches with (the FEM checks the best: --verify fem).
DESIGN_MODELS = tuple(m.name for m in MODELS.values() if m.fast)
_MAX_TRIALS = 100_000
_FORMS = "X, a,b or lo:hi"


def register(subparsers) -> None:
    p = subparsers.add_parser("design", help="inverse design with Optuna on Dask: targets on "
                              "the metrics in, a printable chamber out",
                              description=__doc__.split("\n\n")[0])
    _goal_options(p.add_argument_group("the goal (metrics: " + ", ".join(METRIC_NAMES) + ")"))
    _space_options(p.add_argument_group(f"the search space: each input {_FORMS}"))
    _search_options(p.add_argument_group("evaluation and search"))
    r = p.add_argument_group("a robust design (issue 49): targets met by the prints, not the "
                             "nominal chamber")
    r.add_argument("--tolerance", default=None, metavar="FILE.toml",
                   help="a tolerance file (docs/guides/tolerance.md): each trial judged by its "
                   "prints' misses; with --model surrogate and targets")
    r.add_argument("--confidence", type=number("confidence"), default=None, metavar="P",
                   help="the share of prints that must meet the targets (default 0.9 with "
                   "--tolerance)")
    d = p.add_argument_group("a life to reach (issue 51): the squeeze cycle in the wall model, "
                             "the fatigue law calibrated on Table 2 (docs/guides/durability.md)")
    d.add_argument("--min-life", type=number("min-life", "cycles"), default=None, metavar="N",
                   help="each trial's chamber must last N squeeze cycles at its own setup "
                   "(one wall solve a trial: 0.3 s a dome, 3 s a stadium)")
    d.add_argument("--life-stroke", type=number("life-stroke", "mm"), default=None,
                   metavar="MM", help="the squeeze of the life, mm from first contact "
                   "(default --stroke)")
    v = p.add_argument_group("the best design")
    v.add_argument("--verify", choices=("fem", "none"), default="fem",
                   help="re-run the best with the 3D FEM and compare (default fem)")
    v.add_argument("--mesh-size", type=number("mesh size", "mm"), default=1.0, metavar="MM",
                   help="the FEM check's element size, mm (default 1.0)")
    v.add_argument("--no-build", action="store_true",
                   help="do not build the part (STEP/STL/3MF) nor run the printability gate")
    o = p.add_argument_group("outputs and where it runs (checked before any work)")
    o.add_argument("--out", required=True, metavar="DIR",
                   help="design.json, trials.parquet, index.html, the study's journal (a "
                   "re-run continues it), the part")
    o.add_argument("--json", default=None, metavar="FILE", help="design.json here too")
    o.add_argument("--csv", default=None, metavar="FILE", help="the trials as CSV too")
    o.add_argument("--workers", default=None, metavar="N",
                   help="local worker processes, also the trials in flight (default: one per "
                   "core)")
    o.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of a running Dask scheduler (tcp://host:8786) instead")
    add_quiet_option(p)
    p.set_defaults(func=run)


def _goal_options(g) -> None:
    g.add_argument("--target", action="append", default=[], metavar="M=V|M>=V|M<=V",
                   help="a target on a metric (repeat for several); the miss is relative")
    g.add_argument("--minimize", action="append", default=[], metavar="M",
                   help="a metric to minimise (targets become constraints; NSGA-II)")
    g.add_argument("--maximize", action="append", default=[], metavar="M",
                   help="a metric to maximise")
    g.add_argument("--tol", default="1", metavar="PCT",
                   help="a target is met within this relative miss, %% (default 1)")


def _space_options(s) -> None:
    s.add_argument("--type", default=None, action=Once, metavar="A,B,C,D",
                   help="preset types (default all four); n1, n2, cy are the type's unless given")
    for name in PARAMS:
        default = {"w": "8:14", "h": "8:16", "l": "0:6; 0 with --model surrogate",
                   "t0": "the process's wall:2"}.get(
            name, "the type's")
        s.add_argument(f"--{name}", default=None, action=Once, metavar="SPEC",
                       help=f"{_HELP[name]} (default {default})")
    s.add_argument("--material", default=None, action=Once, metavar="NAME|FILE.json",
                   help="catalogue material or material file (default tpu60a)")
    s.add_argument("--pressure", default=None, action=Once, metavar="KPA",
                   help="setup pressure, kPa gauge (default 40)")
    s.add_argument("--reservoir", default=None, action=Once, metavar="MM3",
                   help="reservoir of the low mode, mm³ (default 40000; an interval lo:hi "
                   "searches it as a continuous variable)")


def _search_options(e) -> None:
    e.add_argument("--model", choices=DESIGN_MODELS, default="wall",
                   help="fast model of both modes (default wall)")
    e.add_argument("--process", default="fdm", metavar="fdm|sla|molding",
                   help="printing process: its printability is a constraint, its gate is run "
                   "on the part (default fdm)")
    e.add_argument("--points", type=integer("points"), default=None, metavar="N",
                   help="plate positions per curve (default the model's: wall 25, membrane "
                   "and simplified 41)")
    e.add_argument("--stroke", type=number("stroke", "mm"), default=6.0, metavar="MM",
                   help="plate travel of the metrics, mm (default 6)")
    e.add_argument("--trials", type=integer("trials"), default=None, metavar="N",
                   help="trials in the study, those of an earlier run included (default 100; "
                   "400 with the surrogate)")
    e.add_argument("--seed", type=integer("seed"), default=None, metavar="S",
                   help="sampler seed (default: drawn and recorded); with the worker count, "
                   "it reproduces the study")
    e.add_argument("--sampler", choices=("tpe", "nsga2"), default=None,
                   help="default tpe for targets only (a printable trial within 30 %% of them is then "
                        "polished by Gauss-Newton steps), nsga2 with --minimize/--maximize")


def prepare(args):
    """Every check before any work; returns the :class:`~spsc.design.problem.Problem`. ParameterError
    (one line) on the first problem."""
    from spsc.cad.process import process

    from spsc.design.loop import Problem, check_resumable, full_params
    from spsc.design.goal import parse_goal, parse_tol
    from spsc.design.space import INPUTS, parse_space
    from spsc.design.verify import check_mode, fem_points
    from spsc.study.executor import check_scheduler, check_workers

    out = check_output_dir("--out", args.out)
    if args.json is not None:
        check_output_file("--json", args.json, (".json",))
    if args.csv is not None:
        check_output_file("--csv", args.csv, (".csv",))
    if args.scheduler is not None and args.workers is not None:
        raise ParameterError("workers", args.workers, "only without --scheduler (the "
                             "cluster has its own workers)")
    args.workers = check_workers(args.workers) if args.scheduler is None else None
    args.process = process(args.process).name
    goal = check_targets(parse_goal(args.target, args.minimize, args.maximize,
                                    parse_tol(args.tol)))
    if args.model == "surrogate" and args.l is None:
        args.l = "0"  # the surrogate's domain: the domes (a stadium is refused by it)
    space = parse_space({k: getattr(args, k) for k in INPUTS}, args.process)
    if args.points is not None and not 2 <= args.points <= POINTS_MAX:
        raise ParameterError("points", args.points, f"an integer from 2 to {POINTS_MAX}")
    lowest_h = space["h"].low
    require("stroke", args.stroke, gt=0, lt=lowest_h,
            unit=f"mm, below the smallest h of the search space ({lowest_h:g} mm)")
    if args.trials is None:
        args.trials = 400 if args.model == "surrogate" else 100
    if not 1 <= args.trials <= _MAX_TRIALS:
        raise ParameterError("trials", args.trials, f"an integer from 1 to {_MAX_TRIALS:,}")
    if args.seed is not None and not 0 <= args.seed < 2**32:
        raise ParameterError("seed", args.seed, "an integer from 0 to 2**32 - 1")
    if args.verify == "fem":
        require("mesh size", args.mesh_size, gt=0, unit="mm")
    for design in space.representatives():  # the models' own limits, on a design of each type
        params = full_params(design)
        check_mode(params, args.model, "low", points=args.points, stroke_mm=args.stroke)
        if args.verify == "fem":
            check_mode(params, "fem", "low", points=fem_points(args.stroke),
                       stroke_mm=args.stroke, options={"mesh_size": args.mesh_size})
    problem = Problem(goal, space, args.model, args.process, args.points, args.stroke,
                      robust=_robust(args, goal), life=_life(args, space))
    check_resumable(out, problem)
    if args.scheduler is not None:
        args.scheduler = check_scheduler(args.scheduler)
    return problem


def _life(args, space):
    """The life to reach (None without --min-life), checked."""
    if args.min_life is None:
        if args.life_stroke is not None:
            raise ParameterError("life-stroke", args.life_stroke, "only with --min-life")
        return None
    from spsc.design.life import check_life

    materials = space["material"].values  # one material (fixed) a search
    return check_life(args.min_life, args.stroke if args.life_stroke is None
                      else args.life_stroke, None, materials, space["h"].low)


def _robust(args, goal):
    """The robust search's settings (None without --tolerance), checked."""
    if args.tolerance is None:
        if args.confidence is not None:
            raise ParameterError("confidence", args.confidence, "only with --tolerance")
        return None
    from spsc.design.robust import ROBUST_SAMPLES
    from spsc.study.tolerance import read_tolerance

    if args.model != "surrogate":
        raise ParameterError("tolerance", args.tolerance, "with --model surrogate (each trial "
                             f"is {ROBUST_SAMPLES} x (D + 2) samples of both modes)")
    if goal.multi:
        raise ParameterError("tolerance", args.tolerance, "with targets only (no --minimize "
                             "or --maximize)")
    confidence = require("confidence", 0.9 if args.confidence is None else args.confidence,
                         gt=0, lt=1, unit="a share of the prints")
    return {"tolerance": read_tolerance(args.tolerance), "confidence": confidence,
            "samples": ROBUST_SAMPLES}


def check_targets(goal):
    """``goal`` if its targets can be met together: each target once, and per metric the
    values asked for (``=``), the lower bounds (``>=``) and the upper bounds (``<=``) leave a
    value (two different ``=``, or ``>=`` above ``<=``, cannot). ParameterError naming
    ``target`` otherwise."""
    seen = set()
    for t in goal.targets:
        if str(t) in seen:
            raise ParameterError("target", str(t), "each target once (it is given twice)")
        seen.add(str(t))
    for metric in dict.fromkeys(t.metric for t in goal.targets):
        ts = [t for t in goal.targets if t.metric == metric]
        lo = max((t.value for t in ts if t.relation in ("=", ">=")), default=0.0)
        hi = min((t.value for t in ts if t.relation in ("=", "<=")), default=math.inf)
        if lo > hi:
            raise ParameterError("target", ", ".join(map(str, ts)), f"targets on {metric} "
                                 "that a value can meet together (these contradict)")
    return goal


def run(args) -> int:
    from spsc.design.confirm import confirm
    from spsc.design.loop import run_design
    from spsc.design.output import document, print_summary, write_document, write_tables
    from spsc.design.verify import build_part, mode_curve, verify_fem
    from spsc.study.executor import dask_client

    problem = prepare(args)
    out = Path(args.out)
    seed = args.seed if args.seed is not None else secrets.randbelow(2**31)
    where = args.scheduler or f"{args.workers} local worker{'s' * (args.workers > 1)}"
    print(f"spsc design: {problem.goal.describe()}; {problem.model} model, printability for "
          f"{problem.process}; up to {args.trials} trials on {where}, seed {seed}")
    print(f"  space: {problem.space.describe()}")
    t0 = time.perf_counter()
    verify = build = None
    with dask_client(args.workers, args.scheduler) as client:
        result = run_design(problem, out, trials=args.trials, seed=seed, sampler=args.sampler,
                            client=client, progress=not args.quiet)
        best = result.best
        curves = None
        # a surrogate's best designs run again with the model it learnt: what follows (the
        # FEM check, the part, the re-run commands) is built on the confirmed design
        confirmed = (confirm(client, problem, result.rows, best) if problem.robust is None
                     else None)
        robust = (_confirm_robust(client, problem, result, best)
                  if problem.robust is not None and best is not None else None)
        model, points = problem.model, problem.points
        if confirmed is not None and confirmed["chosen"] is not None:
            model, points = confirmed["model"], None
            best = dict(best, **confirmed["candidates"][confirmed["chosen"]]["params"])
        if best is not None:
            params = {k: best[k] for k in ("type",) + PARAMS + ("material", "pressure",
                                                                 "reservoir")}
            if args.verify == "fem":
                verify = verify_fem(client, params, problem.goal, fast_model=model,
                                    points=points, stroke_mm=problem.stroke_mm,
                                    mesh_size_mm=args.mesh_size, out=out / "verify")
                curves = verify["_curves"]
            else:
                curves = {"fast": {m: mode_curve(params, model, m, points=points,
                                                 stroke_mm=problem.stroke_mm)
                                   for m in ("high", "low")}, "fem": {}}
            if not args.no_build:
                build = build_part(params, problem.process, out / "part")
    result.facts["total_seconds"] = time.perf_counter() - t0
    doc = document(problem, result, verify=verify, build=build, command=_command(args),
                   confirmed=confirmed, robust=robust)
    write_document(doc, out, args.json)
    write_tables(result.rows, out, args.csv)
    page = _page(doc, result, curves, out)
    print_summary(doc, out)
    print(f"written: {out / 'design.json'}, {out / 'trials.parquet'}"
          + (f", {page}" if page else "") + (f", {args.json}" if args.json else "")
          + (f", {args.csv}" if args.csv else ""))
    return _exit(doc, args)


def _confirm_robust(client, problem, result, best) -> dict:
    """The chosen design's prints by the wall model (fresh samples) and, for comparison, the
    trial with the lowest nominal miss (the design a nominal search would pick) with its
    share of prints that met the targets."""
    from spsc.design.robust import chosen_band, confirm_robust

    params = {k: best[k] for k in ("type",) + PARAMS + ("material", "pressure", "reservoir")}
    out = {"confidence": problem.robust["confidence"],
           "chosen": {"trial": best["trial"], "p_met": best.get("p_met"),
                      "quantile_miss": best["miss"]},
           "wall": confirm_robust(client, problem, params),
           "band": chosen_band(problem, params)}
    done = [r for r in result.rows if r.get("nominal_miss") is not None
            and r.get("printable")]
    if done:
        nominal = min(done, key=lambda r: (r["nominal_miss"], r["trial"]))
        out["nominal_best"] = {"trial": nominal["trial"], "nominal_miss": nominal["nominal_miss"],
                               "p_met": nominal["p_met"]}
    return out


def _page(doc, result, curves, out):
    try:
        from spsc.report.design_page import write_page
    except ModuleNotFoundError as exc:
        if exc.name != "spsc.report.design_page":
            raise
        return None
    return write_page(doc, result.rows, curves, out)


def _exit(doc, args) -> int:
    """0 when the goal is met and the part (if built) passes the gate; 1 otherwise, saying
    why on stderr."""
    why = []
    if doc["best"] is None:
        why.append("no feasible design in the study (more --trials, or a wider space)")
    elif not doc["met"] and doc.get("robust"):
        r = doc["robust"]
        why.append(f"goal not met robustly: {100 * r['wall']['p_met']:.0f} % of the wall model's "
                   f"samples of the chosen design meet the targets ({100 * r['confidence']:g} % "
                   "asked)")
    elif not doc["met"] and doc.get("confirmed"):
        c = doc["confirmed"]
        miss = None if c["chosen"] is None else c["candidates"][c["chosen"]]["miss"]
        why.append(f"goal not met by the {c['model']} model: " + (
            f"the confirmed design's miss is {100 * miss:.2f} % (> "
            f"{100 * doc['goal']['tol']:g} %)" if miss is not None
            else f"it computed none of the {len(c['candidates'])} best designs"))
    elif not doc["met"]:
        why.append(f"goal not met: the best miss is {100 * doc['best']['miss']:.2f} % "
                   f"(> {100 * doc['goal']['tol']:g} %)")
    b = doc.get("build")
    if b is not None and not b["gate"]["passed"]:
        why.append("the part fails the printability gate: " + ", ".join(b["gate"]["failed"]))
    v = doc.get("verify")
    if v is not None and not v.get("agrees"):
        worst = v.get("max_abs_difference_pct")
        print("spsc design: warning: the FEM check " + (
            f"differs by {worst:.2f} % (more than {v['tolerance_pct']:g} %)"
            if worst is not None and worst == worst else f"failed: {v.get('message')}"),
            file=sys.stderr)
    for w in why:
        print(f"spsc design: {w}", file=sys.stderr)
    return 1 if why else 0


def _command(args) -> str:
    typed = typed_command()
    if typed:
        return typed
    parts = ["design"]
    for t in args.target:
        parts += ["--target", t]
    for opt in ("minimize", "maximize"):
        for m in getattr(args, opt):
            parts += [f"--{opt}", m]
    for opt in ("type",) + PARAMS + ("material", "pressure", "reservoir"):
        if getattr(args, opt) is not None:
            parts += [f"--{opt}", str(getattr(args, opt))]
    parts += ["--model", args.model, "--process", args.process, "--trials", str(args.trials),
              "--verify", args.verify, "--out", str(args.out)]
    if args.seed is not None:
        parts += ["--seed", str(args.seed)]
    return "spsc " + shlex.join(parts)
