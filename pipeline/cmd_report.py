"""``spsc report``: run the validation study (cached) and write the HTML report.

    spsc report [--quick] [--out DIR] [--cache DIR] [--no-fem] [--types ABCD] [--quiet]
                [--allow-dirty]

Default: the full study into ``reports/validation/``; ``--quick`` (coarse FEM mesh, fewer
points and pressures; CI) into ``build/report-quick/``. Runs are cached under
``build/cache/runs`` by a hash of their inputs and of the code that computes them, so a second
call with nothing changed takes seconds. A failed run is listed in the report and the others
go on. Exit 0 when every run succeeded, 1 when some failed (the report is still written).

Provenance: the report names the commit it was built from. Into the committed
``reports/validation/`` it is built only from a clean tree (exit 2 otherwise) unless
``--allow-dirty``; a report from a dirty tree (allowed anywhere else) says in big letters that
it is NOT REPRODUCIBLE.
"""

from __future__ import annotations

import os
import re
import shlex
import sys
import time
from pathlib import Path

from spsc.core.errors import ParameterError

from .options import check_output_dir

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
    p.add_argument("--types", help="subset of the types, e.g. BD (default ABCD)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--allow-dirty", action="store_true",
                   help="build the committed report from uncommitted changes (it is then "
                        "marked NOT REPRODUCIBLE)")
    p.set_defaults(func=run)


def run(args) -> int:
    from .cache import Cache
    from .provenance import committed_report_dir, provenance
    from .report import build_report
    from .runner import run_all
    from .study import full_study, quick_study

    t0 = time.perf_counter()
    types = _types(args.types)
    out = check_output_dir("--out", args.out if args.out is not None
                           else DEFAULT_OUT[bool(args.quick)])
    check_output_dir("--cache", args.cache)
    study = quick_study() if args.quick else full_study()
    if args.no_fem:
        study = study.replace(fem=False)
    if types:
        study = study.replace(types=types)
    committed = _same_dir(out, committed_report_dir())
    if committed and not args.allow_dirty and not _clean_or_say_why(provenance()):
        return 2
    cache = Cache(args.cache)
    outcomes = run_all(study.runs(), cache, progress=not args.quiet)
    source = provenance()  # as it is when the report is written: the tree may have changed
    if committed and not args.allow_dirty and not _clean_or_say_why(source):
        return 2
    out.mkdir(parents=True, exist_ok=True)
    path = build_report(study, outcomes, out, command=_command(args),
                        fig_cache=cache.root / "figures", source=source,
                        wall_seconds=time.perf_counter() - t0)
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
    argv = sys.argv[1:] if sys.argv and Path(sys.argv[0]).name == "spsc" else None
    command = "spsc " + (shlex.join(argv) if argv else _reconstruct(args))
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
    if args.allow_dirty:
        parts.append("--allow-dirty")
    return shlex.join(parts)
