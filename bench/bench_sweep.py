"""Benchmark of ``spsc sweep`` on Dask: speed with 1 and 2 workers and memory as the sweep grows.

    .venv/bin/python bench/bench_sweep.py [--membrane 1000] [--wall 200] [--workers 1,2]
                                          [--points N] [--out build/bench-sweep]

Each sweep is a Latin hypercube over Types A–D (crossed) × w 8–14 mm × t0 0.8–1.5 mm ×
p_i 10–40 kPa (Table 1 footprint otherwise, tpu60a, low mode 40 000 mm³), run from scratch (no
resume) once per worker count through :func:`spsc.sweep.run.run_sweep`, the code behind
``spsc sweep``. A sampler thread records every 0.25 s the resident memory (RSS) of the client
process and of each worker process (psutil) with the rows written so far. Printed per run:
designs/s over the evaluation (cluster start excluded, shown apart), speed-up over the first
worker count, peak RSS of the client and of the largest worker, and both at 25, 50 and 100 % of
the sweep: flat columns mean memory does not grow with the sweep.

``--every K[,K]`` runs every K-th design of the same hypercube for a worker count: the speed-up
of a subset is then a rate ratio over comparable designs (all types, the same spread), not over
the same ones.

Full run (the issue's figures): 1000 membrane + 200 wall designs, 1 and 2 workers. On an idle
2-core machine a membrane design takes about 1 s (two curves of 41 positions) and a wall design
(Table 1 stadium, two curves of 25 positions) about 40 s: roughly 25 min for the membrane runs
and 3 h for the wall runs. A check that it works: ``--membrane 100 --wall 8``.
"""

from __future__ import annotations

import argparse
import os
import shutil
import threading
import time
from pathlib import Path

MB = 1024.0 ** 2
SPACE = {"type": "A,B,C,D", "w": "8:14", "t0": "0.8:1.5", "pressure": "10:40"}


class MemorySampler(threading.Thread):
    """RSS of this process and of its worker processes every ``every`` s, with the journal's
    row count at that moment."""

    def __init__(self, journal: Path, every: float = 0.25):
        super().__init__(daemon=True)
        import psutil

        self.me, self.journal, self.every = psutil.Process(), journal, every
        self.samples, self._halt = [], threading.Event()

    def _workers(self):
        for p in self.me.children(recursive=True):
            try:
                if any("spawn_main" in part for part in p.cmdline()):
                    yield p.memory_info().rss
            except Exception:  # a worker that just died or is being replaced
                continue

    def _rows(self) -> int:
        try:
            return self.journal.read_bytes().count(b"\n")
        except OSError:
            return 0

    def run(self):
        while not self._halt.is_set():
            workers = list(self._workers())
            self.samples.append((self._rows(), self.me.memory_info().rss,
                                 max(workers, default=0), len(workers)))
            self._halt.wait(self.every)

    def stop(self):
        self._halt.set()
        self.join()
        self.run_once()

    def run_once(self):
        workers = list(self._workers())
        self.samples.append((self._rows(), self.me.memory_info().rss, max(workers, default=0),
                             len(workers)))

    def at(self, fraction: float, total: int):
        """(client, largest worker) RSS in MB at the first sample with ``fraction`` of the rows
        written."""
        need = fraction * total
        for rows, client, worker, _ in self.samples:
            if rows >= need and worker > 0:
                return client / MB, worker / MB
        return float("nan"), float("nan")

    def peak(self):
        return (max(s[1] for s in self.samples) / MB, max(s[2] for s in self.samples) / MB)


def one_run(model: str, designs: int, workers: int, points, out_dir: Path,
            every: int = 1) -> dict:
    from spsc.sweep.run import run_sweep
    from spsc.sweep.space import build_space
    from spsc.sweep.store import journal_path

    space = build_space(SPACE, samples=max(1, designs // 4), seed=0, force=True)
    if every > 1:  # every k-th design of the same hypercube (all types, the same spread)
        space = list(space)[::every]
    out = out_dir / f"{model}-{len(space)}-w{workers}.parquet"
    for p in (out, journal_path(out)):
        p.unlink(missing_ok=True)
    sampler = MemorySampler(journal_path(out))
    sampler.start()
    t0 = time.perf_counter()
    try:
        df = run_sweep(space, model=model, process="fdm", points=points, stroke_mm=6.0,
                       out=out, workers=workers, progress=True)
    finally:
        sampler.stop()
    stats = df.attrs["sweep"]
    n = len(space)
    return {"model": model, "designs": n, "workers": workers,
            "wall_s": time.perf_counter() - t0, "start_s": stats["start_s"],
            "compute_s": stats["compute_s"], "rate": stats["evaluated"] / stats["compute_s"],
            "status": df["status"].value_counts().to_dict(), "peak": sampler.peak(),
            "at": [sampler.at(f, n) for f in (0.25, 0.5, 1.0)], "samples": len(sampler.samples)}


HEADER = (f"{'model':10} {'designs':>7} {'wk':>2} {'eval s':>8} {'start s':>7} {'designs/s':>9} "
          f"{'speed-up':>8} {'client peak':>11} {'worker peak':>11}   "
          f"{'client MB @25/50/100 %':>22}   {'worker MB @25/50/100 %':>22}   status")


def line(r: dict, base: float) -> str:
    """One run as a table row; ``base``: designs/s of the first worker count (speed-up 1)."""
    client = "/".join(f"{c:.0f}" for c, _ in r["at"])
    worker = "/".join(f"{w:.0f}" for _, w in r["at"])
    status = ", ".join(f"{v} {k}" for k, v in sorted(r["status"].items()))
    return (f"{r['model']:10} {r['designs']:7d} {r['workers']:2d} {r['compute_s']:8.1f} "
            f"{r['start_s']:7.1f} {r['rate']:9.3f} {r['rate'] / base:7.2f}x "
            f"{r['peak'][0]:8.0f} MB {r['peak'][1]:8.0f} MB   {client:>22}   {worker:>22}   "
            f"{status}")


def table(results: list[dict]) -> None:
    print()
    print(HEADER)
    base = {}
    for r in results:
        print(line(r, base.setdefault(r["model"], r["rate"])))
    print("(designs/s over the evaluation, cluster start apart; RSS sampled every 0.25 s; "
          "worker = the largest worker process)")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--membrane", type=int, default=1000, help="membrane designs (0: none)")
    ap.add_argument("--wall", type=int, default=200, help="wall-model designs (0: none)")
    ap.add_argument("--workers", default="1,2", help="worker counts, comma-separated")
    ap.add_argument("--points", type=int, default=None,
                    help="plate positions per curve (default: the model's, 41 / 25)")
    ap.add_argument("--every", default="1", metavar="K[,K]",
                    help="run every K-th design of the hypercube, per worker count (e.g. 4,1 "
                    "with --workers 1,2: one worker on a quarter of the designs)")
    ap.add_argument("--out", default="build/bench-sweep", help="folder of the tables")
    args = ap.parse_args(argv)
    out_dir = Path(args.out)
    shutil.rmtree(out_dir, ignore_errors=True)
    out_dir.mkdir(parents=True)
    counts = [int(w) for w in args.workers.split(",")]
    every = [int(k) for k in args.every.split(",")]
    every = dict(zip(counts, every if len(every) == len(counts) else every[:1] * len(counts)))
    print(f"bench_sweep: {os.cpu_count()} cores, load average "
          + " ".join(f"{x:.2f}" for x in os.getloadavg()))
    results = []
    for model, n in (("membrane", args.membrane), ("wall", args.wall)):
        for w in counts if n else ():
            print(f"== {model}: {n} designs" + (f", every {every[w]}th" if every[w] > 1 else "")
                  + f", {w} worker(s)", flush=True)
            results.append(one_run(model, n, w, args.points, out_dir, every[w]))
            first = next(r for r in results if r["model"] == model)
            print(HEADER + "\n" + line(results[-1], first["rate"]), flush=True)
    table(results)
    print("load average after: " + " ".join(f"{x:.2f}" for x in os.getloadavg()))


if __name__ == "__main__":  # the worker processes are spawned: they must not run this
    main()
