"""After a search with a surrogate: its best designs confirmed with the model it learnt.

A surrogate screens (hundreds of trials in seconds) with an error it states but cannot remove;
the designs it ranks best are run again with the model it was trained on (the wall model)
before anything is built or checked in 3D. The :data:`CONFIRM` best distinct feasible trials
(the lowest misses; with several objectives the compromise alone) are evaluated as sweep rows
(:func:`~spsc.sweep.evaluate.evaluate`) with that model on the Dask workers. The confirmed
design is the one with the lowest miss under that model, and the goal counts as met only when
that model meets it: the answer a user builds on is never the surrogate's alone.
"""

from __future__ import annotations

import math
import time

from spsc.design.goal import METRIC_NAMES
from spsc.cad.geometry import PARAMS

__all__ = ["CONFIRM", "CONFIRMED_BY", "SCREEN_TOL", "confirm"]

#: the best distinct trials run again with the confirming model
CONFIRM = 5
#: the model that confirms a screening model's best designs
CONFIRMED_BY = {"surrogate": "wall"}
#: the share of the goal's tolerance a screening model's search must reach before it stops:
#: half, so that the surrogate's own error (0.3 % of the force at the 95th percentile, more on
#: the sensitivity) leaves the confirmed design within the tolerance
SCREEN_TOL = 0.5
_DESIGN = ("type",) + PARAMS + ("material", "pressure", "reservoir")


def confirm(client, problem, rows: list[dict], best: dict | None, *, k: int = CONFIRM):
    """The confirmation of a study's best designs (module docstring), or None when
    ``problem``'s model needs none or there is no feasible design: ``model``, ``candidates``
    (per design: trial, params, the screening model's and the confirming model's metrics and
    misses, status and message of the confirming run), ``chosen`` (index of the confirmed
    design among the candidates, None if the confirming model computed none of them),
    ``met`` and ``seconds``."""
    from spsc.sweep.evaluate import evaluate

    model = CONFIRMED_BY.get(problem.model)
    if model is None or best is None:
        return None
    t0 = time.perf_counter()
    goal = problem.goal
    ranked = [best] if goal.multi else sorted(
        (r for r in rows if r["feasible"]), key=lambda r: (r["values"][0], r["trial"]))
    picked, seen = [], set()
    for r in ranked:
        key = tuple(r.get(n) for n in _DESIGN)
        if key not in seen:
            seen.add(key)
            picked.append(r)
        if len(picked) == k:
            break
    designs = [{n: r.get(n) for n in _DESIGN} for r in picked]
    futures = client.map(evaluate, designs, model=model, process=problem.process, points=None,
                         stroke_mm=problem.stroke_mm, pure=False)
    candidates = []
    for r, f in zip(picked, futures):
        try:
            row = f.result()
        except Exception as exc:  # the worker died: this candidate is not confirmed
            row = {"status": "failed", "message": f"{type(exc).__name__}: {exc}"}
        metrics = {m: _finite(row.get(m)) for m in METRIC_NAMES}
        ok = row.get("status") == "ok" and all(metrics[m] is not None for m in goal.needed)
        candidates.append({
            "trial": r["trial"], "params": designs[len(candidates)],
            "screened": {m: r.get(m) for m in METRIC_NAMES}, "screened_miss": r.get("miss"),
            "metrics": metrics, "miss": goal.miss(metrics) if ok else None,
            "status": row.get("status"), "message": row.get("message") or ""})
    done = [i for i, c in enumerate(candidates) if c["miss"] is not None]
    chosen = min(done, key=lambda i: (candidates[i]["miss"], i)) if done else None
    met = chosen is not None and (goal.multi or candidates[chosen]["miss"] <= goal.tol + 1e-12)
    return {"model": model, "candidates": candidates, "chosen": chosen, "met": bool(met),
            "seconds": time.perf_counter() - t0}


def _finite(v):
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) \
        and math.isfinite(v) else None
