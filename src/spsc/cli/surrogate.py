"""``spsc surrogate``: train the wall model's surrogate, and check one against the wall model
on designs it never saw.

    spsc surrogate train --out DIR [--designs N] [--family F] [--calibration N] [--seed S]
                         [--workers N | --scheduler ADDR] [--quiet]
    spsc surrogate check [FILE] --samples N [--seed S] [--out DIR]
                         [--workers N | --scheduler ADDR] [--quiet]

``train`` samples the domain (a scrambled Sobol sequence), computes the wall maps of each
design on Dask (one file per design in DIR/runs: a re-run resumes, and a study of fewer
pressure levels than this version's computes only those it lacks), fits them and calibrates
the stated error on fresh wall curves: DIR/surrogate.npz, for ``spsc curve --model surrogate
--surrogate DIR/surrogate.npz``. ``check`` runs fresh designs (another seed) through the wall
model and the surrogate (FILE, or a shipped one by its family: dome, the default, or table1)
and prints the error table; with
--out, the table (CSV), the summary (JSON) and a figure.
"""

from __future__ import annotations

import json
import sys

from spsc.core.errors import ParameterError
from spsc.cli.options import add_quiet_option, check_output_dir, integer

__all__ = ["register", "run"]

#: seeds of the calibration and check cases, apart from training's
_CALIBRATION_SEED, _CHECK_SEED = 1000, 2000


def _cluster(p) -> None:
    p.add_argument("--workers", default=None, metavar="N",
                   help="local worker processes (default: one per core)")
    p.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of a running Dask scheduler (tcp://host:8786) instead")
    add_quiet_option(p)


def register(subparsers) -> None:
    p = subparsers.add_parser("surrogate", help="train the wall model's surrogate or check "
                              "one against the wall model", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="action", metavar="train|check", required=True)
    t = sub.add_parser("train", help="wall maps of sampled designs on Dask, the fit, the "
                       "calibrated error: DIR/surrogate.npz")
    t.add_argument("--out", required=True, metavar="DIR", help="the study folder (a re-run "
                   "resumes; one of fewer pressure levels is extended)")
    t.add_argument("--designs", type=integer("designs"), default=1024, metavar="N",
                   help="designs sampled (default 1024)")
    t.add_argument("--family", default="dome", metavar="dome|table1|stadium",
                   help="the design family: dome (l = 0), table1 (the stadiums of Table 1's "
                   "proportions h/w 13/11, l/w 3/11, t0/w 1/11, their shape free) or "
                   "stadium (every ratio free); default dome")
    t.add_argument("--calibration", type=integer("calibration"), default=100, metavar="N",
                   help="fresh wall cases the stated error is calibrated on (default 100)")
    t.add_argument("--seed", type=integer("seed"), default=0, metavar="S",
                   help="the sampling's seed (default 0)")
    _cluster(t)
    c = sub.add_parser("check", help="fresh designs through the wall model and the "
                       "surrogate: the error table")
    c.add_argument("file", nargs="?", default=None, metavar="FILE",
                   help="a surrogate file, or a shipped one by its family (dome, table1; "
                   "default dome)")
    c.add_argument("--samples", type=integer("samples"), default=200, metavar="N",
                   help="fresh designs (default 200; two curves each: both modes)")
    c.add_argument("--seed", type=integer("seed"), default=0, metavar="S",
                   help="the cases' seed (default 0)")
    c.add_argument("--out", default=None, metavar="DIR",
                   help="write the table, the summary and a figure in DIR")
    _cluster(c)
    p.set_defaults(func=run)


def _count(name: str, v: int, lo: int, hi: int) -> int:
    if not lo <= v <= hi:
        raise ParameterError(name, v, f"an integer from {lo} to {hi:,}")
    return v


def _bar(desc: str, quiet: bool):
    from spsc.core.progress import progress_bar

    bar = progress_bar(desc=desc, total=None, unit="design", disable=quiet, file=sys.stderr)

    def tick(done, total):
        bar.total = total
        bar.update(done - bar.n)
    return bar, tick


def _prepare(args):
    from spsc.study.executor import check_cluster

    args.workers, args.scheduler = check_cluster(
        None if args.workers is None else integer("workers")(args.workers), args.scheduler)
    if args.action == "train":
        from spsc.studies.surrogate.train import FAMILIES

        if args.family not in FAMILIES:
            raise ParameterError("family", args.family, "one of " + ", ".join(FAMILIES))
        _count("designs", args.designs, 16, 1_000_000)
        _count("calibration", args.calibration, 10, 10_000)
        check_output_dir("--out", args.out)
    else:
        from spsc.models.surrogate.predict import load

        _count("samples", args.samples, 1, 100_000)
        load(_file(args.file))
        if args.out is not None:
            check_output_dir("--out", args.out)


def _file(text):
    """A surrogate file: ``text`` itself, or the shipped one of the family it names."""
    from spsc.models.surrogate.predict import SHIPPED_FILES

    return str(SHIPPED_FILES[text]) if text in SHIPPED_FILES else text


def _wall(cases, args, desc):
    from spsc.studies.surrogate.check import wall_cases

    bar, tick = _bar(desc, bool(args.quiet))
    try:
        return wall_cases(cases, workers=args.workers, scheduler=args.scheduler,
                          progress=tick)
    finally:
        bar.close()


def _train(args) -> int:
    from pathlib import Path

    from spsc.studies.surrogate.build import build
    from spsc.studies.surrogate.check import check_cases
    from spsc.models.surrogate.domain import RATIOS
    from spsc.studies.surrogate.train import FAMILIES, train_maps

    bar, tick = _bar("spsc surrogate train: wall maps", bool(args.quiet))
    try:
        train_maps(args.out, count=args.designs, seed=args.seed, family=args.family,
                   workers=args.workers, scheduler=args.scheduler, progress=tick)
    finally:
        bar.close()
    fixed = FAMILIES[args.family]
    cases = check_cases(args.calibration, _CALIBRATION_SEED + args.seed, fixed)
    calibration = _wall(cases, args, "spsc surrogate train: calibration")
    path, meta = build(args.out, Path(args.out) / "surrogate.npz", calibration=calibration,
                       free=[r for r in RATIOS if r not in fixed], fixed=fixed,
                       name=f"wall-{args.family}")
    size = path.stat().st_size / 1e6
    print(f"spsc surrogate train: {path} ({size:.1f} MB): {meta['designs']} designs "
          f"({meta['excluded']} left out: the wall model could not mesh or press them), "
          f"{meta['worker_seconds'] / 3600:.2f} worker-hours of wall maps, fit "
          f"{meta['fit_seconds']:.0f} s, error scales "
          + ", ".join(f"{k} {v:.3g}" for k, v in meta["error_scale"].items()))
    return 0


def _check(args) -> int:
    from spsc.models.surrogate.predict import load
    from spsc.studies.surrogate.check import check_cases, compare, summary

    sur = load(_file(args.file))
    cases = check_cases(args.samples, _CHECK_SEED + args.seed, sur.fixed)
    results = _wall(cases, args, "spsc surrogate check: wall curves")
    result = compare(sur, results)
    s = summary(result)
    print(f"spsc surrogate check: {s['curves']} curves of {args.samples} fresh designs "
          f"(both modes; {s['skipped_cases']} cases the wall model did not finish left out)")
    print(f"{'error, relative to the curve max':34s} {'median':>8s} {'p95':>8s} {'max':>8s}")
    for key, label in (("force", "force (per point)"), ("pressure", "pressure rise (per point)"),
                       ("stiffness", "mean stiffness (per curve)"),
                       ("sensitivity", "mean sensitivity (per curve)")):
        q = s[key]
        print(f"{label:34s} {100 * q['median']:7.2f}% {100 * q['p95']:7.2f}% "
              f"{100 * q['max']:7.2f}%")
    print(f"stated error covers the true error: force {100 * s['coverage_force']:.1f} %, "
          f"pressure {100 * s['coverage_pressure']:.1f} % of points; "
          f"{s['unanswered_points']} points past the surrogate's map (not answered, not scored)")
    print(f"flagged (near designs that snap through): {s['flagged']} of {s['curves']} curves, "
          f"{s['snapping_flagged']} of the {s['snapping']} whose wall solve snapped")
    if "unflagged" in s:
        u = s["unflagged"]
        print("the unflagged curves' largest errors (median / p95 / max of the curves): "
              + "; ".join(f"{k} {100 * u[k]['median']:.2f} / {100 * u[k]['p95']:.2f} / "
                          f"{100 * u[k]['max']:.2f} %" for k in u))
    if args.out is not None:
        from spsc.report.surrogate_figures import check_figure, worst_figure

        import pandas as pd
        from pathlib import Path

        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        pd.DataFrame(result["rows"]).to_csv(out / "check.csv", index=False)
        check_figure(result, out / "check.png")
        worst = worst_figure(sur, results, result["rows"], out / "worst.png")
        s.update(samples=args.samples, seed=args.seed, worst=worst,
                 surrogate={k: sur.meta.get(k) for k in ("name", "trained", "designs",
                                                         "excluded", "worker_seconds",
                                                         "commit", "error_scale")})
        (out / "summary.json").write_text(json.dumps(s, indent=1))
    return 0


def run(args) -> int:
    _prepare(args)
    return _train(args) if args.action == "train" else _check(args)
