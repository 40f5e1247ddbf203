"""The printability verdicts of the gate (``spsc bladder``) and of the sweep (``spsc sweep``'s
``printable`` column) on the same random designs (issue 30): they must be equal.

Run: ``.venv/bin/python bench/bench_printability.py --designs 200 --seed 30 [--json FILE]``;
prints one line per design that the two judge differently (none expected), then the counts
(equal, printable, not printable and why, refused as invalid) and the time. About 10 s a
design (the gate on a ~90,000-triangle mesh), so 200 take about half an hour on one core.
"""

from __future__ import annotations

import argparse
import collections
import json
import time

import numpy as np

from spsc.testing.printability_agreement import compare, random_chamber


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", type=int, default=200)
    ap.add_argument("--seed", type=int, default=30)
    ap.add_argument("--json", default=None, help="write every design and its verdicts here")
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    t0 = time.perf_counter()
    rows, why = [], collections.Counter()
    for i in range(args.designs):
        d = random_chamber(rng)
        r = compare(d) | {"design": d}
        rows.append(r)
        if "invalid" in r:
            continue
        if r["gate"] != r["sweep"]:
            print(f"DIFFER #{i}: gate {r['gate']} ({r['failed']}), sweep {r['sweep']} "
                  f"({r['reason']}): {d}", flush=True)
        if not r["sweep"]:
            why.update(k.split(" ")[0] for k in r["reason"].split("; "))
    judged = [r for r in rows if "invalid" not in r]
    equal = sum(r["gate"] == r["sweep"] for r in judged)
    printable = sum(bool(r["sweep"]) for r in judged)
    seconds = time.perf_counter() - t0
    print(f"{args.designs} designs (seed {args.seed}): {len(judged)} judged, "
          f"{len(rows) - len(judged)} refused as invalid by both; verdicts equal on {equal} of "
          f"{len(judged)}; printable {printable}, not printable {len(judged) - printable} "
          f"(failed checks: {dict(why)}); {seconds:.0f} s "
          f"({seconds / max(1, len(rows)):.1f} s a design)")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump({"seed": args.seed, "seconds": seconds, "rows": rows}, fh, indent=1)
    return 0 if equal == len(judged) else 1


if __name__ == "__main__":
    raise SystemExit(main())
