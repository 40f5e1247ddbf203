"""``spsc report``: run the validation study (cached) and write the HTML report.

    spsc report [--quick] [--out DIR] [--cache DIR] [--no-fem] [--types ABCD] [--quiet]

Default: the full study into ``reports/validation/``; ``--quick`` (coarse FEM mesh, fewer
points and pressures; CI) into ``build/report-quick/``. Runs are cached under
``build/cache/runs`` by a hash of their inputs and of the code that computes them, so a second
call with nothing changed takes seconds. A failed run is listed in the report and the others
go on. Exit 0 when every run succeeded, 1 when some failed (the report is still written).
"""

from __future__ import annotations

import os
import shlex
import sys
import time
from pathlib import Path

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
    p.add_argument("--no-fem", action="store_true", help="membrane and simplified models only")
    p.add_argument("--types", help="subset of the types, e.g. BD (default ABCD)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    from .cache import Cache
    from .report import build_report
    from .runner import run_all
    from .study import full_study, quick_study

    t0 = time.perf_counter()
    study = quick_study() if args.quick else full_study()
    if args.no_fem:
        study = study.replace(fem=False)
    if args.types:
        study = study.replace(types=tuple(args.types.upper()))
    out = Path(args.out) if args.out else DEFAULT_OUT[bool(args.quick)]
    argv = sys.argv[1:] if sys.argv and Path(sys.argv[0]).name == "spsc" else None
    command = "spsc " + (shlex.join(argv) if argv else _reconstruct(args))
    if os.environ.get("MAKELEVEL"):  # started by make: say so, the way the user typed it
        command = f"make report{' QUICK=1' if args.quick else ''}  ({command})"
    cache = Cache(args.cache)
    outcomes = run_all(study.runs(), cache, progress=not args.quiet)
    out.mkdir(parents=True, exist_ok=True)
    path = build_report(study, outcomes, out, command=command, fig_cache=cache.root / "figures",
                        wall_seconds=time.perf_counter() - t0)
    failed = [r.label for r, o in outcomes.items() if not o.ok]
    cached = sum(o.cached for o in outcomes.values())
    print(f"spsc report: {path} ({len(outcomes)} runs, {cached} from the cache, "
          f"{len(failed)} failed) in {time.perf_counter() - t0:.1f} s")
    if failed:
        print(f"spsc report: failed runs: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


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
    return shlex.join(parts)
