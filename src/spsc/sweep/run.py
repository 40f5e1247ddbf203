"""Run a sweep on Dask: every design evaluated by :func:`~.sweep_eval.evaluate` on the workers
of :func:`~.executor.dask_client`, each row stored as it arrives
(:class:`~.sweep_store.SweepStore`).

A bounded number of designs is in flight at any time (a few per worker thread), refilled as
rows come back, so the client's memory does not grow with the sweep. A worker that dies (killed,
out of memory, a crash in compiled code) is replaced by its nanny and Dask runs its task
elsewhere; a task whose workers died ``allowed-failures + 1`` times (Dask's KilledWorker, 4 by
default) may only have shared a dying worker with the real culprit (Dask blames every task a
dead worker held), so it is given one more chance once the rest of the sweep is done, alone on
the cluster, where a death can only be its own; then it is recorded as a failed row. A task that raises is retried ``retries``
times. No design is lost and none is stored twice.
"""

from __future__ import annotations

import functools
import itertools
import sys
import time
import uuid
from contextlib import ExitStack, contextmanager

from spsc.study.executor import dask_client
from spsc.sweep.evaluate import batched, design_key, evaluate, evaluate_many, failed_row
from spsc.sweep.store import SweepStore

__all__ = ["run_sweep", "RETRIES", "IN_FLIGHT_PER_THREAD", "LOCAL_CLUSTER_CONFIG"]

#: Re-runs of a task that raised (evaluate itself never raises: this covers the task not
#: arriving, e.g. a worker that cannot import it).
RETRIES = 1
#: Designs in flight per worker thread (more than two keeps Dask's scheduler queueing them, so
#: each worker holds one at a time and a dying worker takes only its own design down).
IN_FLIGHT_PER_THREAD = 4
#: Dask settings of the in-process LocalCluster (an existing cluster keeps its own): one queued
#: task per single-threaded worker, so a worker's death implicates its own design only. (The
#: executor also turns the workers' statistical profiler off: its hour of call-tree history grew
#: a worker by 40 kB a design in a sweep, measured.)
LOCAL_CLUSTER_CONFIG = {"distributed.scheduler.worker-saturation": 1.0}
#: Seconds between rewrites of the table from the journal during a sweep.
CHECKPOINT_S = 120.0
#: Designs per task of a batched model (:func:`~.evaluate.evaluate_many`): large enough that
#: the model's batch dominates a task's overhead, small enough that the bar moves and a lost
#: worker loses little.
BATCH = 2000


def run_sweep(designs, *, model: str, process: str, points: int | None,
              stroke_mm: float | None, out, workers: int | None = None,
              scheduler: str | None = None, progress: bool = True, csv=None,
              task=evaluate, checkpoint_s: float = CHECKPOINT_S, batch: int = BATCH,
              life_stroke_mm: float | None = None, tolerance=None, band_samples: int = 32):
    """Evaluate ``designs`` (an iterable of design dicts, iterated twice; see
    :mod:`.sweep_space`) with ``model`` and the printability of ``process``, ``points`` plate
    positions over ``stroke_mm`` (mm; None: the model's defaults), and write the table to
    ``out`` (Parquet; CSV to ``csv`` too). Designs already done in ``out``'s journal are
    skipped, failed ones computed again.

    ``workers``/``scheduler``: see :func:`~.executor.dask_client`. ``progress``: a bar on
    stderr. ``task``: the function run per design, ``evaluate``'s signature (tests pass one
    that kills its worker). ``batch``: designs per task of a batched model (the surrogate,
    :func:`~.evaluate.evaluate_many`). Returns the table of the sweep's designs (one row per distinct
    design, in sweep order); ``df.attrs["sweep"]`` holds the run's counts (designs, skipped:
    done earlier, evaluated, retried_killed, workers) and seconds (start_s: the cluster,
    compute_s: first submission to last row, seconds: all). ``life_stroke_mm``: each row also
    carries the design's life squeezed to that stroke (:mod:`.life`: one wall solve a design,
    its rows keyed apart from the rows without a life). ``tolerance``: each row also carries
    its band under it (:mod:`.band`, ``band_samples`` Saltelli base samples), keyed apart.
    """
    import pandas  # noqa: F401  (the table's writers, loaded now: missing, the sweep stops
    import pyarrow  # noqa: F401  before any work; present, the client's memory is set at start)

    store = SweepStore(out)
    if iter(designs) is designs:  # a one-shot iterator: it is walked twice
        designs = list(designs)
    settings = (model, process, points, stroke_mm)
    task, key_of = _task_and_key(task, life_stroke_mm, tolerance, band_samples)
    done = store.done()
    keys, todo = _keys(designs, settings, done, key_of)
    stats = {"designs": len(keys), "skipped": len(keys) - todo, "evaluated": 0,
             "retried_killed": 0, "workers": 0, "start_s": 0.0, "compute_s": 0.0,
             "seconds": 0.0, "journal": str(store.journal)}
    t0 = time.perf_counter()
    try:
        if todo and task is evaluate and batched(model):
            _run_batched(_pending(designs, settings, done, key_of), todo, store, settings, stats,
                         workers=workers, scheduler=scheduler, progress=progress,
                         checkpoint=(keys, checkpoint_s), batch=batch)
        elif todo:
            _run(_pending(designs, settings, done, key_of), todo, store, settings, stats,
                 workers=workers, scheduler=scheduler, progress=progress, task=task,
                 checkpoint=(keys, checkpoint_s))
    finally:
        store.close()
        stats["seconds"] = time.perf_counter() - t0
        df = store.write(keys, csv)
    df.attrs["sweep"] = stats
    return df


def _task_and_key(task, life_stroke_mm, tolerance, band_samples):
    """(the task a design runs, the key of its row): ``task`` with the life (:mod:`.life`)
    and the band (:mod:`.band`) columns where asked for, the key telling those rows apart."""
    key_of = design_key
    if life_stroke_mm is not None:
        from spsc.sweep.life import life_row

        task = functools.partial(life_row, base=task, life_stroke_mm=life_stroke_mm)
        key_of = functools.partial(design_key, life_stroke_mm=life_stroke_mm)
    if tolerance is not None:
        from spsc.sweep.band import band_digest, band_row

        key_of = functools.partial(key_of, band=band_digest(tolerance, band_samples))
        task = functools.partial(band_row, base=task, tolerance=tolerance,
                                 samples=band_samples, key_of=key_of)
    return task, key_of


def _keys(designs, settings, done, key_of) -> tuple[list, int]:
    """(every distinct design's key in sweep order, how many are not done)."""
    keys, seen, todo = [], set(), 0
    for d in designs:
        k = key_of(d, *settings)
        if k in seen:
            continue
        seen.add(k)
        keys.append(k)
        todo += k not in done
    return keys, todo


def _pending(designs, settings, done, key_of=design_key):
    """(key, design) of every design still to compute, each key once."""
    seen = set()
    for d in designs:
        k = key_of(d, *settings)
        if k not in done and k not in seen:
            seen.add(k)
            yield k, d


class _Flight:
    """The designs in flight: submitted in batches (one graph update each, so that Dask treats
    them as root tasks and queues them, one per free worker slot), each under its own Dask key;
    at most ``limit`` at a time."""

    def __init__(self, client, task, settings, limit: int):
        from distributed import as_completed

        model, process, points, stroke_mm = settings
        self.client, self.task, self.limit = client, task, limit
        self.kwargs = dict(model=model, process=process, points=points, stroke_mm=stroke_mm)
        self.run = uuid.uuid4().hex[:8]  # a shared cluster may still know an earlier run's keys
        self.designs, self.completed = {}, as_completed()

    def submit(self, items, attempt: int = 0) -> None:
        """Submit ``(key, design)`` pairs; ``attempt`` > 0 after their workers kept dying."""
        if not items:
            return
        tail = f"-again{attempt}" if attempt else ""
        names = [f"spsc-sweep-{key}-{self.run}{tail}" for key, _ in items]
        futures = self.client.map(self.task, [d for _, d in items], key=names,
                                  retries=RETRIES, pure=False, **self.kwargs)
        for f, (key, design) in zip(futures, items):
            self.designs[f.key] = (key, design, attempt)
            self.completed.add(f)

    def refill(self, pending) -> None:
        self.submit(list(itertools.islice(pending, max(0, self.limit - len(self.designs)))))


@contextmanager
def _cluster(total, stats, *, workers, scheduler, progress):
    """(client, progress bar, its worker threads) for a sweep's run, the start-up's time and
    the worker count in ``stats``."""
    import dask
    import distributed  # noqa: F401  (its config defaults first: a set() on a missing section
    from spsc.core.progress import progress_bar  # would delete the whole section on exit)

    t_start = time.perf_counter()
    with ExitStack() as stack:
        stack.enter_context(dask.config.set(LOCAL_CLUSTER_CONFIG))
        client = stack.enter_context(dask_client(workers=workers, scheduler=scheduler))
        bar = stack.enter_context(progress_bar(total=total, desc="spsc sweep", unit="design",
                                               disable=not progress, file=sys.stderr,
                                               dynamic_ncols=True))
        threads = sum(client.nthreads().values())
        stats.update(workers=len(client.nthreads()), start_s=time.perf_counter() - t_start)
        yield client, bar, threads
        stats["compute_s"] = time.perf_counter() - t_start - stats["start_s"]


def _run(pending, total, store, settings, stats, *, workers, scheduler, progress, task,
         checkpoint):
    keys, every = checkpoint
    with _cluster(total, stats, workers=workers, scheduler=scheduler,
                  progress=progress) as (client, bar, threads):
        flight = _Flight(client, task, settings, IN_FLIGHT_PER_THREAD * max(1, threads))
        flight.refill(pending)
        failed, last, suspects = 0, time.perf_counter(), []
        for f in flight.completed:
            key, design, attempt = flight.designs.pop(f.key)
            row = _row(f, key, design)
            if row is None and attempt == 0:  # perhaps it only shared a dying worker
                stats["retried_killed"] += 1
                suspects.append((key, design))
            elif row is None:
                row = failed_row(design, _one_line(f.exception()), key=key)
            f.release()
            if row is not None:
                store.append(row)
                stats["evaluated"] += 1
                failed += row["status"] == "failed"
                bar.set_postfix(failed=failed, refresh=False)
                bar.update(1)
            flight.refill(pending)
            if suspects and not flight.designs:  # the rest is done: each suspect alone
                flight.submit([suspects.pop(0)], attempt=1)
            if time.perf_counter() - last > every:
                store.write(keys)
                last = time.perf_counter()


def _run_batched(pending, total, store, settings, stats, *, workers, scheduler, progress,
                 checkpoint, batch: int = BATCH):
    """The sweep of a batched model: chunks of ``batch`` designs per task
    (:func:`~.evaluate.evaluate_many`), two per worker thread in flight; a chunk whose task
    did not return (its worker died twice, Dask's retries spent) is a chunk of failed rows
    naming why, computed again by a re-run."""
    from distributed import as_completed

    model, process, points, stroke_mm = settings
    keys, every = checkpoint
    with _cluster(total, stats, workers=workers, scheduler=scheduler,
                  progress=progress) as (client, bar, threads):
        run = uuid.uuid4().hex[:8]
        chunks = iter(lambda: list(itertools.islice(pending, batch)), [])
        flying, completed = {}, as_completed()

        def submit(n):
            for chunk in itertools.islice(chunks, n):
                f = client.submit(evaluate_many, [d for _, d in chunk], model, process, points,
                                  stroke_mm, key=f"spsc-sweep-batch-{chunk[0][0]}-{run}",
                                  retries=RETRIES, pure=False)
                flying[f.key] = chunk
                completed.add(f)

        submit(2 * max(1, threads))
        failed, last = 0, time.perf_counter()
        for f in completed:
            chunk = flying.pop(f.key)
            if f.status == "finished":
                rows = f.result()
                for (key, _), row in zip(chunk, rows):
                    row["key"] = key
            else:
                why = _one_line(f.exception())
                rows = [failed_row(d, why, key=key) for key, d in chunk]
            f.release()
            store.extend(rows)
            stats["evaluated"] += len(rows)
            failed += sum(r["status"] == "failed" for r in rows)
            bar.set_postfix(failed=failed, refresh=False)
            bar.update(len(rows))
            submit(1)
            if time.perf_counter() - last > every:
                store.write(keys)
                last = time.perf_counter()


def _row(future, key, design):
    """The row a finished future carries; None for a task whose workers kept dying
    (KilledWorker); a failed row for a task that raised."""
    from distributed import KilledWorker

    if future.status == "finished":
        row = future.result()
        row["key"] = key
        return row
    exc = future.exception()
    if isinstance(exc, KilledWorker):
        return None
    return failed_row(design, _one_line(exc), key=key)


def _one_line(exc) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else ''}".rstrip(": ")
