"""``spsc bench-gap``: how much of the gap between the models and the paper's bench each factor
accounts for — the wall model's Table 1 means with the plate's friction, the wall thickness,
the stroke of the means or the material (``--material-row``) changed one at a time
(:mod:`spsc.studies.bench_gap`).

    spsc bench-gap [--out build/bench-gap] [--material tpu60a] [--types ABCD]
                   [--material-row FIT.json ...] [--factors NAME,...]
                   [--workers N | --scheduler ADDRESS] [--quiet]

Writes ``summary.json`` and ``bench-gap.png`` where ``spsc report`` finds them (about 90 min
on two cores, 75 of them the Coulomb rows; ``--factors`` picks rows). Exit 0 when every curve
reached its stroke's end, 1 when some stopped early (their points reached count; the table
says how many).
"""

from __future__ import annotations

import sys

from spsc.studies.bench_gap import FACTORS


def register(sub) -> None:
    p = sub.add_parser("bench-gap", help="the wall model's Table 1 means with one factor "
                       "changed at a time, against the paper's bench",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default="build/bench-gap",
                   help="output folder (default build/bench-gap, where spsc report looks)")
    p.add_argument("--material", default="tpu60a", metavar="NAME|FILE",
                   help="the material (default tpu60a, the paper's)")
    p.add_argument("--types", default="ABCD", help="the Table 1 types (default ABCD)")
    p.add_argument("--material-row", action="append", default=[], metavar="FIT.json",
                   help="a row with this material file (spsc fit-material --out), alone and "
                        "with the stiffening factors; repeatable")
    p.add_argument("--factors", default=None, metavar="NAME,...",
                   help="the built-in rows to run (default all: " + ", ".join(
                       f.name for f in FACTORS) + "; the baseline always)")
    p.add_argument("--workers", default=None, metavar="N",
                   help="local worker processes (default: one per core)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="an existing Dask scheduler instead of local workers")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    from spsc.core.progress import progress_bar

    from spsc.cad.geometry import TYPES
    from spsc.cli.options import check_output_dir
    from spsc.core.errors import ParameterError
    from spsc.materials import material
    from spsc.report.gap import QUANTITIES
    from spsc.report.paper import paper_bench
    from spsc.study.executor import check_cluster, dask_client
    from spsc.studies.bench_gap import run_gap, select

    types = "".join(dict.fromkeys(str(args.types).upper()))
    if not types or any(t not in TYPES for t in types):
        raise ParameterError("types", args.types, "letters of " + "".join(TYPES))
    material(args.material)
    for path in args.material_row:
        if not str(path).lower().endswith(".json"):
            raise ParameterError("material-row", path, "a material file (.json) from spsc "
                                 "fit-material --out")
        try:
            material(path)
        except ParameterError as e:
            raise ParameterError("material-row", path, e.allowed) from None
    factors = select(None if args.factors is None else
                     [n.strip() for n in str(args.factors).split(",") if n.strip()])
    workers, scheduler = check_cluster(args.workers, args.scheduler)
    out = check_output_dir("--out", args.out)
    bar = progress_bar(desc="spsc bench-gap", unit="curve", disable=bool(args.quiet),
                       file=sys.stderr)

    def progress(done, total):
        bar.total = total
        bar.update(done - bar.n)

    paper = paper_bench()
    bench = {q: paper.get(q).value for q in QUANTITIES}
    with dask_client(workers, scheduler) as client:
        summary = run_gap(out, bench, bench_source=paper.source, material_name=args.material,
                          types=types, factors=factors, materials=args.material_row,
                          client=client, progress=progress)
    bar.close()
    bench = summary["bench"]
    print(f"{'factor':56s} " + " ".join(f"{q:>16s}" for q in QUANTITIES) + "  partial")
    print(f"{'the paper bench':56s} " + " ".join(f"{bench[q]:16.2f}" for q in QUANTITIES))
    for r in summary["rows"]:
        print(f"{r['label']:56s} " + " ".join(f"{r[q]:16.2f}" for q in QUANTITIES)
              + f"  {len(r['partial'])}")
    print(f"{summary['curves']} curves in {summary['seconds']:.0f} s; written: "
          f"{out / 'summary.json'}, {out / 'bench-gap.png'}")
    return 1 if any(r["partial"] for r in summary["rows"]) else 0
