"""``spsc report``: run the validation study (cached) and write the HTML report.

    spsc report [--quick] [--out DIR] [--cache DIR] [--no-fem] [--no-sweep] [--types ABCD]
                [--quiet] [--workers N | --scheduler ADDRESS] [--allow-dirty]
                [--fingertip DIR] [--haptic DIR] [--time DIR] [--bench-gap DIR]
                [--surrogate-check DIR] [--durability DIR]

Default: the full study into ``reports/validation/``; ``--quick`` (coarse FEM mesh, fewer
points and pressures; CI) into ``build/report-quick/``. Runs are cached under
``build/cache/runs`` by a hash of their inputs and of the code that computes them, so a second
call with nothing changed takes seconds. A failed run is listed in the report and the others
go on. Exit 0 when every run succeeded, 1 when some failed (the report is still written).

The report also sweeps the design space of its types with the membrane model
(:mod:`.report_sweep`: w and t0 grids, 112 designs, 24 with ``--quick``) and links the sweep's
own page (``OUT/sweep/index.html``); ``--no-sweep`` leaves it out.

The runs are independent and run in parallel on Dask (:mod:`.executor`): by default on an
in-process LocalCluster with one single-threaded worker process per core, ``--workers N`` for
another count (1: in this process, one run after another), ``--scheduler ADDRESS`` on an
existing cluster (its workers must see the cache folder at the same path and run this code).
No cluster is started when every run is in the cache.

Provenance: the report names the commit it was built from. Into the committed
``reports/validation/`` it is built only from a clean tree (exit 2 otherwise) unless
``--allow-dirty``; a report from a dirty tree (allowed anywhere else) says in big letters that
it is NOT REPRODUCIBLE.
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import sys
import time
from pathlib import Path

from spsc.core.errors import ParameterError

from spsc.study.executor import check_cluster, default_workers
from spsc.cli.options import check_output_dir, number, typed_command

DEFAULT_OUT = {False: Path("reports/validation"), True: Path("build/report-quick")}


def register(subparsers) -> None:
    p = subparsers.add_parser("report", help="validation study and HTML report (cached runs)",
                              description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true",
                   help="coarse meshes, fewer points and pressures (CI); writes "
                        "build/report-quick/ unless --out")
    p.add_argument("--out", help="output directory (default reports/validation, or "
                                 "build/report-quick with --quick)")
    p.add_argument("--cache", default="build/cache", help="cache directory (default build/cache)")
    p.add_argument("--no-fem", action="store_true",
                   help="no 3D FEM: the membrane, simplified and wall models only")
    p.add_argument("--no-sweep", action="store_true",
                   help="no design-space sweep (its section and page)")
    _add_band_options(p)
    p.add_argument("--fingertip", metavar="DIR", default=None,
                   help="the fingertip FEM study to show (spsc fingertip --fem's OUT/fem; "
                   "default build/fingertip/fem when it exists)")
    p.add_argument("--haptic", metavar="DIR", default=None,
                   help="the haptic chamber's study to show (make haptic-fem's "
                   "build/haptic-fem, the default when it exists)")
    p.add_argument("--time", metavar="DIR", default=None,
                   help="the time-domain study to show (make time-study's build/time-study, "
                   "the default when it exists)")
    p.add_argument("--bench-gap", metavar="DIR", default=None,
                   help="the bench-gap study to show (make bench-gap's build/bench-gap, the "
                   "default when it exists)")
    p.add_argument("--durability", metavar="DIR", default=None,
                   help="the durability study to show (make durability-study's "
                   "build/durability, the default when it exists)")
    p.add_argument("--surrogate-check", metavar="DIR", default=None,
                   help="the surrogate's check to show (make surrogate-check's "
                   "build/surrogate-check, the default when it exists)")
    p.add_argument("--types", help="subset of the types, e.g. BD (default ABCD)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    d = p.add_argument_group("where the runs are computed (Dask; no cluster is started when "
                             "every run is cached)")
    d.add_argument("--workers", metavar="N",
                   help=f"local worker processes, one run each at a time (default: one per "
                        f"core, here {default_workers()}; 1: in this process, no cluster)")
    d.add_argument("--scheduler", metavar="ADDRESS",
                   help="an existing Dask scheduler, e.g. tcp://10.0.0.5:8786, instead of "
                        "local workers; its workers must see --cache at the same path")
    b = p.add_argument_group("your bench test (optional): calibrate the material on it and "
                             "compare with the paper's identification")
    b.add_argument("--bench", metavar="CSV", help="bench CSV: y_mm, force_N[, pressure_kPa]")
    b.add_argument("--bench-type", metavar="TYPE", help="the tested chamber: A, B, C or D "
                   "(Table 1 preset)")
    b.add_argument("--bench-pressure", type=number("bench_pressure", "kPa gauge"), metavar="KPA",
                   help="setup pressure of the test, kPa gauge (0: open chamber)")
    b.add_argument("--bench-reservoir", type=number("bench_reservoir", "mm³"), default=0.0,
                   metavar="MM3", help="reservoir of the test, mm³ (default 0)")
    b.add_argument("--bench-material", default="tpu60a", metavar="NAME|FILE",
                   help="the law to calibrate (default tpu60a)")
    p.add_argument("--allow-dirty", action="store_true",
                   help="build the committed report from uncommitted changes (it is then "
                        "marked NOT REPRODUCIBLE)")
    p.set_defaults(func=run)


def _add_band_options(p) -> None:
    p.add_argument("--band", action=argparse.BooleanOptionalAction, default=None,
                   help="the headline's band under a tolerance set: the wall model on a grid "
                   "of it, 25-30 x 32 curves (default: on, off with --quick)")
    p.add_argument("--band-tolerance", metavar="FILE.toml", default=None,
                   help="the band's tolerance set (at most two inputs, no [friction]; default "
                   "the report's declared one: t0 0.9-1.1 mm, the material between the two "
                   "readings of the FilaFlex 60A tests)")


def run(args) -> int:
    from spsc.study.cache import Cache
    from spsc.study.provenance import committed_report_dir, provenance
    from spsc.report.build import build_report
    from spsc.study.runner import run_all
    from spsc.study.runs import full_study, quick_study

    t0 = time.perf_counter()
    cluster, executor, where = _cluster(args)
    types = _types(args.types)
    out = check_output_dir("--out", args.out if args.out is not None
                           else DEFAULT_OUT[bool(args.quick)])
    check_output_dir("--cache", args.cache)
    _check_studies(args)
    study = quick_study() if args.quick else full_study()
    if args.no_fem:
        study = study.replace(fem=False)
    if types:
        study = study.replace(types=types)
    bench = _bench(args)
    band_tolerance = _band_tolerance(args)
    committed = _same_dir(out, committed_report_dir())
    if committed and not args.allow_dirty and not _clean_or_say_why(provenance()):
        return 2
    cache = Cache(args.cache)
    outcomes = run_all(study.runs(), cache, progress=not args.quiet, cluster=cluster)
    sweep = None
    if not args.no_sweep:
        from spsc.report.sweep import run_report_sweep

        sweep = run_report_sweep(study, cache.root, progress=not args.quiet, **where)
    band = None
    if band_tolerance is not None:
        from spsc.study.headline_band import run_headline_band

        band = run_headline_band(study, cache.root, band_tolerance, progress=not args.quiet,
                                 **where)
    source = provenance()  # as it is when the report is written: the tree may have changed
    if committed and not args.allow_dirty and not _clean_or_say_why(source):
        return 2
    out.mkdir(parents=True, exist_ok=True)
    path = build_report(study, outcomes, out, command=_command(args),
                        fig_cache=cache.root / "figures", source=source,
                        wall_seconds=time.perf_counter() - t0, bench=bench,
                        executor=executor, sweep=sweep, fingertip=_fingertip(args),
                        molds=tuple(study.types), haptic=_haptic(args),
                        time_study=_time(args), gap=_gap(args),
                        surrogate=_surrogate(args), durability=_durability(args),
                        band=band)
    failed = [r.label for r, o in outcomes.items() if not o.ok]
    cached = sum(o.cached for o in outcomes.values())
    print(f"spsc report: {path} ({len(outcomes)} runs, {cached} from the cache, "
          f"{len(failed)} failed) in {time.perf_counter() - t0:.1f} s")
    if not source.clean:
        print(f"spsc report: warning: NOT REPRODUCIBLE, built from {source.describe()}",
              file=sys.stderr)
    if failed:
        print(f"spsc report: failed runs: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


#: the studies a report shows: (the option's name, what its folder holds and what writes it)
_STUDIES = (("fingertip", "a fingertip study's summary.json (spsc fingertip --fem "
             "--out DIR writes DIR/fem)"),
            ("haptic", "the haptic chamber's study summary.json (make haptic-fem "
             "writes build/haptic-fem)"),
            ("time", "the time-domain study's summary.json (make time-study writes "
             "build/time-study)"),
            ("bench_gap", "the bench-gap study's summary.json (make bench-gap "
             "writes build/bench-gap)"),
            ("surrogate_check", "the surrogate check's summary.json (make surrogate-check "
             "writes build/surrogate-check)"),
            ("durability", "the durability study's summary.json (make durability-study "
             "writes build/durability)"))


def _band_tolerance(args):
    """The band's tolerance (None: no band), read and checked before any work."""
    on = (not args.quick) if args.band is None else args.band
    if not on:
        if args.band_tolerance is not None:
            raise ParameterError("band-tolerance", args.band_tolerance,
                                 "only with the band (not with --no-band; with --quick add "
                                 "--band)")
        return None
    from spsc.study.headline_band import check_band_tolerance, declared_tolerance
    from spsc.study.tolerance import read_tolerance

    tol = (declared_tolerance() if args.band_tolerance is None
           else read_tolerance(args.band_tolerance))
    check_band_tolerance(tol)
    return tol


def _check_studies(args) -> None:
    """Each study folder given holds its summary.json."""
    for name, what in _STUDIES:
        value = getattr(args, name)
        if value is not None and not (Path(value) / "summary.json").is_file():
            raise ParameterError(name, value, f"a folder holding {what}")


def _haptic(args):
    from spsc.report.haptic import DEFAULT_DIR

    return DEFAULT_DIR if args.haptic is None else args.haptic


def _time(args):
    from spsc.report.time import DEFAULT_DIR

    return DEFAULT_DIR if args.time is None else args.time


def _gap(args):
    from spsc.report.gap import DEFAULT_DIR

    return DEFAULT_DIR if args.bench_gap is None else args.bench_gap


def _durability(args):
    from spsc.report.durability import DEFAULT_DIR

    return DEFAULT_DIR if args.durability is None else args.durability


def _surrogate(args):
    from spsc.report.surrogate import DEFAULT_DIR

    return DEFAULT_DIR if args.surrogate_check is None else args.surrogate_check


def _fingertip(args):
    from spsc.report.fingertip import DEFAULT_DIR

    return DEFAULT_DIR if args.fingertip is None else args.fingertip


def _cluster(args):
    """``--workers`` / ``--scheduler`` checked → (the runner's cluster factory or None for
    this process, how the runs are computed, for the report, the sweep's ``workers`` and
    ``scheduler``)."""
    import functools

    from spsc.study.executor import dask_client

    workers, scheduler = check_cluster(args.workers, args.scheduler)
    where = {"workers": workers, "scheduler": scheduler}
    if scheduler is not None:
        return (functools.partial(dask_client, scheduler=scheduler),
                f"on the Dask scheduler at {scheduler}", where)
    if workers == 1:
        return None, "in one process", where
    return (functools.partial(dask_client, workers=workers),
            f"on {workers} local Dask worker processes", where)


def _bench(args):
    """The bench test's spec, checked before the study runs (None without --bench)."""
    from spsc.report.bench import BenchSpec

    given = [o for o in ("bench_type", "bench_pressure") if getattr(args, o) is not None]
    if args.bench is None:
        if given:
            raise ParameterError("--" + given[0].replace("_", "-"), getattr(args, given[0]),
                                 "only with --bench CSV")
        return None
    for opt in ("bench_type", "bench_pressure"):
        if getattr(args, opt) is None:
            raise ParameterError("--" + opt.replace("_", "-"), None, "a value with --bench")
    spec = BenchSpec(args.bench, str(args.bench_type).strip().upper(), args.bench_pressure,
                     args.bench_reservoir, args.bench_material)
    spec.check()
    return spec


def _types(text: str | None) -> tuple[str, ...] | None:
    """``--types``: letters among A–D (spaces and commas ignored), e.g. ``BD`` or ``B,D``."""
    if text is None:
        return None
    letters = re.sub(r"[\s,]", "", text).upper()
    if not letters or any(c not in "ABCD" for c in letters):
        raise ParameterError("types", text, "letters among A, B, C, D, e.g. BD")
    return tuple(dict.fromkeys(letters))


def _clean_or_say_why(source) -> bool:
    if source.clean:
        return True
    print(f"spsc report: error: the committed report is built from a clean tree only; this is "
          f"{source.describe()} (commit first, or pass --allow-dirty)", file=sys.stderr)
    return False


def _same_dir(a: Path, b: Path | None) -> bool:
    return b is not None and a.resolve() == b.resolve()


def _command(args) -> str:
    command = typed_command() or "spsc " + _reconstruct(args)
    if os.environ.get("MAKELEVEL"):  # started by make: say so, the way the user typed it
        command = f"make report{' QUICK=1' if args.quick else ''}  ({command})"
    return command


def _reconstruct(args) -> str:
    parts = ["report"]
    if args.quick:
        parts.append("--quick")
    for opt in ("out", "types"):
        if getattr(args, opt):
            parts += [f"--{opt}", str(getattr(args, opt))]
    if args.cache != "build/cache":
        parts += ["--cache", args.cache]
    if args.no_fem:
        parts.append("--no-fem")
    if args.no_sweep:
        parts.append("--no-sweep")
    if args.band is not None:
        parts.append("--band" if args.band else "--no-band")
    if args.band_tolerance is not None:
        parts += ["--band-tolerance", str(args.band_tolerance)]
    for opt in ("workers", "scheduler"):
        if getattr(args, opt) is not None:
            parts += [f"--{opt}", str(getattr(args, opt))]
    if args.bench is not None:
        parts += ["--bench", str(args.bench), "--bench-type", str(args.bench_type),
                  "--bench-pressure", f"{args.bench_pressure:g}"]
        if args.bench_reservoir:
            parts += ["--bench-reservoir", f"{args.bench_reservoir:g}"]
        if args.bench_material != "tpu60a":
            parts += ["--bench-material", str(args.bench_material)]
    if args.allow_dirty:
        parts.append("--allow-dirty")
    return shlex.join(parts)
