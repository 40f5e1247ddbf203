"""Where parallel work runs: a Dask client on an in-process LocalCluster (the default, nothing to
set up) or on an existing scheduler given by address (a cluster started by hand, or by
dask-jobqueue on a SLURM machine; see docs/guides/sweeps.md).

Workers are processes with one thread each: the models are numpy/scipy code that holds the GIL
between small kernels, and their BLAS is kept single-threaded (multi-threaded OpenBLAS spins on
the wall model's batched small matrix products), so one process per core is the fast layout.
"""

from __future__ import annotations

import contextlib
import logging
import os
import socket
import time
import warnings
from urllib.parse import urlparse

from spsc.core.errors import ParameterError

__all__ = ["dask_client", "check_cluster", "check_workers", "check_scheduler",
           "default_workers"]

#: Environment of every local worker process: single-threaded BLAS/OpenMP (see module docstring;
#: distributed's default ``nanny.pre-spawn-environ`` does the same, this keeps it if a user's Dask
#: config changes that).
WORKER_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
              "PYTHONUTF8": "1"}
_MAX_LOCAL_WORKERS = 256
#: the scheduler always serves HTTP (health checks); without a dashboard it would still take
#: port 8787 or warn "Port 8787 is already in use" on stderr: a free port on loopback instead
_NO_DASHBOARD = {"dashboard": False, "dashboard_address": "127.0.0.1:0"}
#: Dask starts workers with MALLOC_TRIM_THRESHOLD_=65536 (to hand freed memory back to the OS);
#: setting it also fixes glibc's mmap threshold at 128 kB, so every numpy temporary above that
#: is a fresh mmap, page-faulted and zeroed: measured, a wall-model run took 2x the CPU (513k
#: page faults, 2.0 s system time, against 12k and 0.1 s). Our workers keep glibc's default.
_KEEP_MALLOC = {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}
#: Dask's statistical profiler samples every worker's stack every 10 ms, its event-loop watchdog
#: ticks every 20 ms and its system monitor polls every 0.5 s: on a 2-core machine that is CPU
#: taken from the models (measured: an idle 2-worker cluster used 3.6 CPU-s per 30 s with them,
#: 1.0 without). Nobody reads the profile of a batch run without a dashboard, so it is off and
#: the watchdog and monitor are slower.
_QUIET_WORKERS = {"distributed.worker.profile.enabled": False,
                  "distributed.admin.system-monitor.interval": "2s",
                  "distributed.admin.system-monitor.gil.enabled": False,
                  "distributed.admin.tick.interval": "200ms"}


def default_workers() -> int:
    """Local workers when none are asked for: one per core this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def check_workers(workers) -> int:
    """``workers`` as a positive int (None → :func:`default_workers`); ParameterError otherwise."""
    if workers is None:
        return default_workers()
    allowed = f"an integer from 1 to {_MAX_LOCAL_WORKERS}"
    if isinstance(workers, bool):
        raise ParameterError("workers", workers, allowed)
    try:
        n = int(str(workers).strip()) if isinstance(workers, str) else int(workers)
    except (TypeError, ValueError):
        raise ParameterError("workers", workers, allowed) from None
    if (not isinstance(workers, str) and n != workers) or not 1 <= n <= _MAX_LOCAL_WORKERS:
        raise ParameterError("workers", workers, allowed)
    return n


def check_scheduler(address: str, timeout: float = 3.0) -> str:
    """``address`` (``tcp://host:port`` or ``host:port``) if a Dask scheduler answers there
    within ``timeout`` seconds; ParameterError naming the address otherwise.

    First a plain TCP connect (a wrong address fails in seconds with one line instead of Dask's
    retry loop and traceback), then Dask's handshake and an ``identity`` request, each bounded
    by ``timeout``: the reply must come from a scheduler. A port where something else listens
    (a web server, a silent socket, a Dask worker) is refused instead of waiting forever.
    """
    text = str(address).strip()
    allowed = "the address of a running Dask scheduler, e.g. tcp://10.0.0.5:8786"
    url = urlparse(text if "://" in text else "tcp://" + text)
    if url.scheme not in ("tcp", "tls") or not url.hostname:
        raise ParameterError("scheduler", address, allowed)
    try:
        port = url.port
    except ValueError:
        port = None
    if port is None:
        raise ParameterError("scheduler", address, allowed + " (with its port)")
    try:
        with socket.create_connection((url.hostname, port), timeout=timeout):
            pass
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise ParameterError("scheduler", address,
                             f"{allowed}; nothing answered there ({reason})") from None
    canonical = f"{url.scheme}://{url.hostname}:{port}"
    who = _identity(canonical, timeout)
    if who != "Scheduler":
        raise ParameterError("scheduler", address, f"{allowed}; something listens there but "
                             f"it is not a Dask scheduler ({who})")
    return canonical


def _identity(address: str, timeout: float) -> str:
    """What answers Dask's handshake and ``identity`` request at ``address`` within
    ``timeout`` seconds each: ``Scheduler``, another Dask server's type, or why not."""
    import asyncio

    async def ask():
        from distributed.comm import connect

        comm = await asyncio.wait_for(connect(address, timeout=timeout), timeout)
        try:
            await asyncio.wait_for(comm.write({"op": "identity", "reply": True}), timeout)
            return await asyncio.wait_for(comm.read(), timeout)
        finally:
            comm.abort()

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            reply = asyncio.run(ask())
    except (asyncio.TimeoutError, TimeoutError):
        return f"no Dask handshake within {timeout:g} s"
    except Exception:  # whatever a foreign protocol makes of Dask's frames
        return "no Dask handshake: the answer is not Dask's protocol"
    if isinstance(reply, dict) and isinstance(reply.get("type"), str):
        return reply["type"]
    return "an answer that is not Dask's identity"


def check_cluster(workers=None, scheduler=None) -> tuple[int | None, str | None]:
    """A verb's ``--workers`` and ``--scheduler`` checked together, before any work:
    ``(n, None)`` for a local cluster of ``n`` workers (``workers`` None: one per core),
    ``(None, address)`` for a scheduler that answers now. Both at once is refused: the
    scheduler's cluster has its own workers."""
    if scheduler is None:
        return check_workers(workers), None
    if workers is not None:
        raise ParameterError("workers", workers, "only without a scheduler (its cluster has "
                             "its own workers)")
    return None, check_scheduler(scheduler)


@contextlib.contextmanager
def dask_client(workers: int | None = None, scheduler: str | None = None):
    """A ``distributed.Client``: on ``scheduler`` if given (``workers`` is then ignored: the
    cluster has its own), else on a new in-process LocalCluster of ``workers`` single-threaded
    worker processes, closed on exit.

    The dashboard is off (it needs bokeh and a free port, neither of which a batch run wants);
    Dask's own log lines are kept to errors so the progress bar stays readable.
    """
    import dask
    from distributed import Client, LocalCluster

    if scheduler:
        address = check_scheduler(scheduler)
        with Client(address, timeout="10s") as client:
            yield client
        return
    n = check_workers(workers)
    with dask.config.set({**_KEEP_MALLOC, **_QUIET_WORKERS}):
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR,
                               env=dict(WORKER_ENV), scheduler_kwargs=_NO_DASHBOARD)
    try:
        with Client(cluster) as client:
            yield client
    finally:
        try:
            _close_workers_first(cluster)
        finally:
            cluster.close()


def _close_workers_first(cluster, timeout_s: float = 10.0) -> None:
    """Stop the workers while the scheduler still answers: closed together, a worker's
    heartbeat in flight met the closed scheduler and logged a traceback (one close in 25)."""
    cluster.scale(0)
    deadline = time.monotonic() + timeout_s
    while cluster.scheduler_info.get("workers") and time.monotonic() < deadline:
        time.sleep(0.02)
