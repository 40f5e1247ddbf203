"""Tasks for the sweep tests that must run on Dask's worker processes (importable there: they
are part of the installed package). Each has :func:`spsc.sweep.evaluate.evaluate`'s
signature."""

from __future__ import annotations

import os
import time
from pathlib import Path

from spsc.sweep.evaluate import evaluate

#: A design whose ``w`` is this kills its worker every time it runs.
POISON_W = 9.75


def slow_evaluate(design, **settings):
    """evaluate, after marking ``$SPSC_TEST_RUNNING/<pid>`` (so a test can kill a worker that is
    in the middle of a design) and sleeping a little (so a sweep lasts long enough to be
    interrupted)."""
    marks = Path(os.environ["SPSC_TEST_RUNNING"])
    mark = marks / str(os.getpid())
    mark.write_text(str(design.get("w")), encoding="utf-8")
    time.sleep(0.4)
    row = evaluate(design, **settings)
    mark.unlink(missing_ok=True)
    return row


def poison_evaluate(design, **settings):
    """evaluate, except that the poisoned design kills its worker process (as a segfault in
    compiled code or the kernel's OOM killer would)."""
    if design.get("w") == POISON_W:
        os._exit(13)
    return evaluate(design, **settings)


def config_evaluate(design, **settings):
    """evaluate, with the worker's profiler setting as the row's message."""
    import dask

    row = evaluate(design, **settings)
    row["message"] = f"profile {dask.config.get('distributed.worker.profile.enabled')}"
    return row
