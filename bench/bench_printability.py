"""The printability verdicts of the gate (``spsc bladder``) and of the sweep (``spsc sweep``'s
``printable`` column) on the same random designs (issue 30): they must be equal.

Run: ``.venv/bin/python bench/bench_printability.py --designs 200 --seed 30 --jsonl FILE``;
appends one JSON line per design to FILE as it goes (``--part K/N`` judges every N-th design
from the K-th, so N processes share the work; a re-run skips the designs FILE already holds),
prints a line per design the two judge differently (none expected), then, over every design of
the seed in FILE (or in the files given with ``--summarize``), the counts: equal, printable,
not printable and why, refused as invalid, and the time. About 5 s of CPU a design (the gate
on a ~90,000-triangle mesh).
"""

from __future__ import annotations

import argparse
import collections
import json
import time
from pathlib import Path

import numpy as np

from spsc_support.printability_agreement import compare, random_chamber


def summarize(rows: list[dict], seed: int) -> bool:
    """Print the counts over ``rows``; True when every judged design has equal verdicts."""
    judged = [r for r in rows if "invalid" not in r]
    equal = sum(r["gate"] == r["sweep"] for r in judged)
    printable = sum(bool(r["sweep"]) for r in judged)
    why = collections.Counter(k.split(" ")[0] for r in judged if not r["sweep"]
                              for k in r["reason"].split("; "))
    by = collections.Counter((r["process"], bool(r["sweep"])) for r in judged)
    seconds = sum(r.get("seconds", 0.0) for r in judged)
    print(f"{len(rows)} designs (seed {seed}): {len(judged)} judged, {len(rows) - len(judged)} "
          f"refused as invalid by both; verdicts equal on {equal} of {len(judged)}; printable "
          f"{printable}, not printable {len(judged) - printable} (failed checks: {dict(why)}; "
          f"by process and verdict: {dict(sorted(by.items()))}); {seconds:.0f} s of wall clock "
          f"in compare ({seconds / max(1, len(judged)):.1f} s a design)")
    return equal == len(judged)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", type=int, default=200)
    ap.add_argument("--seed", type=int, default=30)
    ap.add_argument("--jsonl", default="build/bench-printability.jsonl")
    ap.add_argument("--part", default="0/1", help="K/N: judge designs K, K+N, K+2N, ...")
    ap.add_argument("--summarize", nargs="*", help="only print the counts of these JSONL files")
    args = ap.parse_args()
    if args.summarize is not None:
        rows = [json.loads(line) for f in args.summarize
                for line in Path(f).read_text(encoding="utf-8").splitlines() if line]
        rows = list({r["index"]: r for r in rows if r["seed"] == args.seed}.values())
        return 0 if summarize(rows, args.seed) else 1
    k, n = (int(x) for x in args.part.split("/"))
    rng = np.random.default_rng(args.seed)
    designs = [random_chamber(rng) for _ in range(args.designs)]
    out = Path(args.jsonl)
    out.parent.mkdir(parents=True, exist_ok=True)
    done = {json.loads(line)["index"] for line in out.read_text(encoding="utf-8").splitlines()
            if line} if out.is_file() else set()
    t0 = time.perf_counter()
    for i in range(k, args.designs, n):
        if i in done:
            continue
        r = compare(designs[i]) | {"design": designs[i], "index": i, "seed": args.seed}
        with out.open("a", encoding="utf-8") as fh:
            fh.write(json.dumps(r) + "\n")
        if "invalid" not in r and r["gate"] != r["sweep"]:
            print(f"DIFFER #{i}: gate {r['gate']} ({r['failed']}), sweep {r['sweep']} "
                  f"({r['reason']}): {designs[i]}", flush=True)
    print(f"part {k}/{n}: {time.perf_counter() - t0:.0f} s")
    rows = [json.loads(line) for line in out.read_text(encoding="utf-8").splitlines() if line]
    return 0 if summarize([r for r in rows if r["seed"] == args.seed], args.seed) else 1


if __name__ == "__main__":
    raise SystemExit(main())
