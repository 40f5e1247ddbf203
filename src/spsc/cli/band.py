"""``spsc curve --tolerance``: the options of a curve's band (issue 49), checked before any
work, the band computed after the nominal curve (:mod:`spsc.study.band`) and its summary."""

from __future__ import annotations

import sys

from spsc.core.errors import ParameterError
from spsc.cli.options import integer

__all__ = ["add_tolerance_options", "check_tolerance", "run_band", "band_summary"]


def add_tolerance_options(p) -> None:
    t = p.add_argument_group("a band under print and material scatter (issue 49)")
    t.add_argument("--tolerance", metavar="FILE.toml", default=None,
                   help="a tolerance file ([t0], [w], [h], [l], [pressure], [material], "
                   "[friction] with the wall model or the FEM: "
                   "docs/guides/tolerance.md): the curve's P5/P50/P95 band, its metrics' "
                   "quantiles and their Sobol indices, in --json and --png")
    t.add_argument("--samples", type=integer("samples"), default=None, metavar="N",
                   help="Saltelli's base samples N (N (D + 2) setups for D inputs; default "
                   "256)")
    t.add_argument("--seed", type=integer("seed"), default=None, metavar="S",
                   help="the samples' seed (default 0)")
    t.add_argument("--workers", default=None, metavar="N",
                   help="local worker processes for a model without a batched path "
                   "(default: one per core)")


def check_tolerance(args, setup) -> None:
    """The tolerance options, and the file read and checked against the setup (before any
    work); ``args.tolerance`` becomes the :class:`~spsc.study.tolerance.Tolerance`."""
    given = [o for o in ("samples", "seed", "workers") if getattr(args, o, None) is not None]
    if getattr(args, "tolerance", None) is None:
        if given:
            raise ParameterError(given[0], getattr(args, given[0]), "only with --tolerance")
        return
    from spsc.core.errors import require_integer
    from spsc.study.band import DEFAULT_SAMPLES
    from spsc.study.executor import check_workers
    from spsc.study.tolerance import read_tolerance

    args.samples = require_integer("samples", DEFAULT_SAMPLES if args.samples is None
                                   else args.samples, ge=8, le=100_000)
    args.seed = require_integer("seed", 0 if args.seed is None else args.seed, ge=0,
                                le=2**32 - 1)
    args.workers = check_workers(args.workers)
    args.tolerance = read_tolerance(args.tolerance)
    if "friction" in args.tolerance.names:
        model = getattr(args, "model", None)
        if model not in ("wall", "fem"):
            raise ParameterError("tolerance [friction]", model, "with --model wall or fem "
                                 "(the models that press with friction)")
        from spsc.core.setup import Contact

        c = setup.contact  # both frictions on this contact (a curved body takes no Coulomb)
        Contact.of(c.indenter, "stick", c.object_stiffness)
        Contact.of(c.indenter, "0.3", c.object_stiffness)
    b = setup.body
    args.tolerance.check({"t0": b.t0, "w": b.w, "h": b.h, "l": b.l,
                          "pressure": setup.load.pressure_kPa})


def run_band(args, job) -> dict:
    from spsc.core.progress import progress_bar
    from spsc.study.band import band

    total = args.samples * (len(args.tolerance.spreads) + 2)
    bar = progress_bar(total=total, desc="spsc curve: band", unit="setup",
                       disable=bool(args.quiet), file=sys.stderr)
    try:
        return band(job.setup, job.options, job.model.name, args.tolerance, n=args.samples,
                    seed=args.seed, workers=args.workers,
                    progress=lambda done, _: bar.update(done - bar.n))
    finally:
        bar.close()


def band_summary(r: dict) -> None:
    """The band's lines on stdout: what ran, the metrics' quantiles, the Sobol indices."""
    print(f"band ({r['model']}, {r['samples']} setups of {len(r['tolerance']['inputs'])} "
          f"uncertain inputs, seed {r['seed']}, {r['seconds']:.1f} s; {r['refused']} refused"
          + (f": {r['first_refusal']}" if r["refused"] else "") + ")")
    for key, label, unit in (("stiffness_N_per_mm", "mean stiffness", "N/mm"),
                             ("sensitivity_kPa_per_mm", "mean sensitivity", "kPa/mm")):
        q = r[key]
        print(f"  {label}: P5 {q['p5']:.4g}, P50 {q['p50']:.4g}, P95 {q['p95']:.4g} {unit}")
    for name, si in r["sobol"].items():
        if "not_computed" in si:
            print(f"  Sobol indices of the {name}: not computed ({si['not_computed']})")
            continue
        print(f"  Sobol total indices of the mean {name} (95 % interval): " + ", ".join(
            f"{k} {v:.2f} ± {si['ST_conf'][k]:.2f}" for k, v in
            sorted(si["ST"].items(), key=lambda kv: -kv[1])))
