"""``spsc bench-gap``: how much of the gap between the models and the paper's bench each factor
accounts for — the wall model's Table 1 means with the plate's friction, the wall thickness or
the stroke of the means changed one at a time (:mod:`spsc.studies.bench_gap`).

    spsc bench-gap [--out build/bench-gap] [--material tpu60a] [--types ABCD]
                   [--workers N | --scheduler ADDRESS] [--quiet]

Writes ``summary.json`` and ``bench-gap.png`` where ``spsc report`` finds them (about 14 min
on two cores). Exit 0 when every curve reached its stroke's end, 1 when some stopped early
(their points reached count; the table says how many).
"""

from __future__ import annotations

import sys


def register(sub) -> None:
    p = sub.add_parser("bench-gap", help="the wall model's Table 1 means with one factor "
                       "changed at a time, against the paper's bench",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default="build/bench-gap",
                   help="output folder (default build/bench-gap, where spsc report looks)")
    p.add_argument("--material", default="tpu60a", metavar="NAME|FILE",
                   help="the material (default tpu60a, the paper's)")
    p.add_argument("--types", default="ABCD", help="the Table 1 types (default ABCD)")
    p.add_argument("--workers", default=None, metavar="N",
                   help="local worker processes (default: one per core)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="an existing Dask scheduler instead of local workers")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    from tqdm import tqdm

    from spsc.cad.geometry import TYPES
    from spsc.cli.options import check_output_dir
    from spsc.core.errors import ParameterError
    from spsc.materials import material
    from spsc.report.gap import QUANTITIES
    from spsc.report.paper import paper_bench
    from spsc.study.executor import check_cluster, dask_client
    from spsc.studies.bench_gap import run_gap

    types = "".join(dict.fromkeys(str(args.types).upper()))
    if not types or any(t not in TYPES for t in types):
        raise ParameterError("types", args.types, "letters of " + "".join(TYPES))
    material(args.material)
    workers, scheduler = check_cluster(args.workers, args.scheduler)
    out = check_output_dir("--out", args.out)
    bar = tqdm(desc="spsc bench-gap", unit="curve", disable=bool(args.quiet), file=sys.stderr)

    def progress(done, total):
        bar.total = total
        bar.update(done - bar.n)

    paper = paper_bench()
    bench = {q: paper.get(q).value for q in QUANTITIES}
    with dask_client(workers, scheduler) as client:
        summary = run_gap(out, bench, bench_source=paper.source, material_name=args.material,
                          types=types, client=client, progress=progress)
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
