"""Inverse design: Optuna proposes chambers, Dask workers evaluate them, Optuna learns.

The loop is Optuna's ask-and-tell on this process, the evaluations (both modes with the fast
model, the metrics, the printability verdict: :func:`~.sweep_eval.evaluate`) on the Dask
workers. Up to ``workers`` trials are in flight and they are told *in the order they were
asked*: a worker that finishes early waits for the oldest, so the sequence of asks and tells,
hence the study, depends only on the seed and the worker count, never on timing.

The study lives in ``OUT/study.journal`` (:mod:`.design_study`); a run on a folder that holds
a study of the same problem continues it, up to ``trials`` trials in all. A design that the printability verdict refuses is infeasible (an Optuna constraint), so
it is never the best; an evaluation that fails, is refused by the model, stops short of the
stroke or leaves a metric of the goal undefined is a FAIL trial with its reason.
"""

from __future__ import annotations

import math
import sys
import time
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path

from spsc.core.errors import ParameterError

from spsc.design.goal import METRIC_NAMES, Goal
from spsc.design.polish import Polish
from spsc.design.problem import Problem
from spsc.design.space import INPUTS
from spsc.design.journal import (INTERRUPTED, JOURNAL, STUDY_NAME, Lock, check_resumable, open_study,
                           optuna_module)

__all__ = ["Problem", "DesignRun", "STUDY_NAME", "JOURNAL", "INTERRUPTED", "open_study",
           "check_resumable", "run_design", "trial_rows", "select", "full_params"]



@dataclass
class DesignRun:
    """The outcome of :func:`run_design`: the study, every trial as a row (:func:`trial_rows`),
    the best row (None when no feasible trial), the Pareto rows (feasible, non-dominated; the
    best alone for the single objective), whether the goal is met, and the run's facts."""

    study: object
    rows: list
    best: dict | None
    pareto: list
    met: bool
    facts: dict = field(default_factory=dict)


# -- the loop ----------------------------------------------------------------------------------
def _evaluator(problem: Problem):
    """The trial's evaluation: a sweep row, or with a robust problem the row with its
    samples' quantile miss (:func:`~.robust.robust_row`); with a life to reach, the row with
    its life (:func:`~.life.life_row`)."""
    import functools

    from spsc.sweep.evaluate import evaluate

    base = evaluate
    if problem.robust is not None:
        from spsc.design.robust import robust_row

        r = problem.robust
        base = functools.partial(robust_row, tolerance=r["tolerance"], goal=problem.goal,
                                 confidence=r["confidence"], n=r["samples"])
    if problem.life is None:
        return base
    from spsc.design.life import life_row

    return functools.partial(life_row, base=base, life_stroke_mm=problem.life["stroke_mm"],
                             exponent=problem.life["exponent"])


def run_design(problem: Problem, out, *, trials: int, seed: int, sampler: str | None = None,
               workers: int | None = None, scheduler: str | None = None, client=None,
               progress=True, evaluate=None) -> DesignRun:
    """Run (or continue) the study of ``problem`` in folder ``out`` until it has ``trials``
    trials or, with a single objective, a feasible trial meets the goal. Trials in flight:
    ``workers`` on a local cluster of that many workers, or as many as ``scheduler``'s cluster
    (or ``client``'s, when given) has. ``evaluate``: (design, model, process, points,
    stroke_mm) → row, default :func:`~.sweep_eval.evaluate`."""
    import contextlib

    from spsc.study.executor import dask_client

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    sampler = sampler or ("nsga2" if problem.goal.multi else "tpe")
    evaluate = evaluate or _evaluator(problem)
    t_start = time.perf_counter()
    with Lock(out):
        study, before = open_study(problem, out, sampler=sampler, seed=seed, trials=trials)
        with (contextlib.nullcontext(client) if client is not None
              else dask_client(workers, scheduler)) as client:
            inflight = max(1, len(client.scheduler_info()["workers"]))
            t_loop = time.perf_counter()
            evaluated = _loop(study, problem, client, evaluate, trials, inflight, progress)
            loop_s = time.perf_counter() - t_loop
    rows = trial_rows(study)
    best, pareto = select(rows, problem.goal)
    met = best is not None and (problem.goal.multi or best["miss"] <= problem.goal.tol + 1e-12)
    facts = {"sampler": sampler, "seed": seed, "workers": inflight, "trials_before": before,
             "evaluated": evaluated, "loop_seconds": loop_s,
             "seconds": time.perf_counter() - t_start, "scheduler": scheduler}
    return DesignRun(study, rows, best, pareto, met, facts)


def _counted(study) -> int:
    """Trials that count against the budget: all but those a killed run left behind."""
    return sum(1 for t in study.get_trials(deepcopy=False)
               if t.user_attrs.get("reason") != INTERRUPTED)


def stop_tol(problem: Problem) -> float:
    """The miss that ends a single-objective search: the goal's tolerance, or a share of it
    (:data:`~.confirm.SCREEN_TOL`) for a screening model whose best designs are confirmed by
    another (the surrogate's own error would otherwise spend the margin)."""
    from spsc.design.confirm import CONFIRMED_BY, SCREEN_TOL

    return problem.goal.tol * (SCREEN_TOL if problem.model in CONFIRMED_BY else 1.0)


def _goal_met_already(study, problem: Problem) -> bool:
    if problem.goal.multi:
        return False
    tol = stop_tol(problem)
    return any(t.state.name == "COMPLETE" and _feasible(t) and t.values[0] <= tol + 1e-12
               for t in study.get_trials(deepcopy=False))


def _loop(study, problem: Problem, client, evaluate, trials: int, inflight: int,
          progress) -> int:
    from spsc.core.progress import progress_bar

    optuna = optuna_module()
    polish = Polish(problem)
    done = _counted(study)
    stop = _goal_met_already(study, problem)
    pending: deque = deque()
    # the trials are a budget the search stops short of when the goal is met: no total, no
    # time left that would be wrong (issue 53: 100 trials and 2 h promised, 10 run)
    bar = progress_bar(total=None, initial=min(done, trials), unit="trial",
                       desc=f"spsc design (at most {trials} trials)", file=sys.stderr,
                       disable=not progress, dynamic_ncols=True)
    evaluated = 0
    try:
        while True:
            while not stop and len(pending) < inflight and done + len(pending) < trials:
                trial = polish.ask(study) or study.ask()
                design = problem.space.suggest(trial)
                trial.set_user_attr("design", design)
                fut = client.submit(evaluate, design, problem.model, problem.process,
                                    problem.points, problem.stroke_mm, pure=False)
                pending.append((trial, design, fut))
            if not pending:
                break
            trial, design, fut = pending[0]
            row = _result(fut)
            pending.popleft()
            feasible_met = _tell(study, problem, trial, design, row)
            told = trial.user_attrs
            ok = "reason" not in told
            polish.tell(trial, told.get("metrics") if ok else None, told.get("miss"),
                        ok and bool(told.get("printable")))
            done += 1
            evaluated += 1
            bar.set_postfix_str(_postfix(study, problem.goal), refresh=False)
            bar.update(1)
            stop = stop or feasible_met
    finally:
        bar.close()
        for trial, _, fut in pending:  # interrupted: nothing stays RUNNING
            fut.cancel()
            trial.set_user_attr("reason", INTERRUPTED)
            study.tell(trial, state=optuna.trial.TrialState.FAIL)
    return evaluated


def _result(fut) -> dict:
    try:
        return fut.result()
    except Exception as exc:  # the worker died or the task could not run
        text = str(exc).strip().splitlines()
        return {"status": "failed", "message": f"{type(exc).__name__}: "
                f"{text[0] if text else ''}".rstrip(": ")}


def _finite(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _printable(row: dict, design: dict, process: str) -> tuple[bool, str]:
    """The row's printability verdict; where the evaluation never returned one (its worker
    died), the sweep's columns of the same rule on the design's geometry, and not printable
    when that geometry is itself invalid."""
    if row.get("printable") is not None:
        return bool(row["printable"]), str(row.get("printability") or "")
    from spsc.cad.geometry import PARAMS, SPSCGeometry
    from spsc.sweep.evaluate import printability_columns

    try:
        params = full_params(design)
        return printability_columns(SPSCGeometry(**{k: params[k] for k in PARAMS}), process)
    except ParameterError as exc:
        return False, str(exc)


def _tell(study, problem: Problem, trial, design: dict, row: dict) -> bool:
    """Record ``row`` on ``trial`` and tell it; True when it is feasible and meets a
    single-objective goal (the loop then stops asking)."""
    optuna = optuna_module()
    goal = problem.goal
    metrics = {m: (float(row[m]) if _finite(row.get(m)) else None) for m in METRIC_NAMES}
    status = str(row.get("status") or "failed")
    trial.set_user_attr("metrics", metrics)
    trial.set_user_attr("status", status)
    trial.set_user_attr("message", str(row.get("message") or ""))
    trial.set_user_attr("seconds", float(row["seconds"]) if _finite(row.get("seconds")) else None)
    reason = None
    if status != "ok":
        reason = f"{status}: {row.get('message') or 'no message'}"
    else:
        undefined = [m for m in goal.needed if metrics[m] is None]
        if undefined:
            reason = (f"{', '.join(undefined)} not defined for this design"
                      + (" (the modes never differ enough over the stroke)"
                         if "jnd_mm" in undefined else ""))
    printable, verdict = _printable(row, design, problem.process)
    trial.set_user_attr("printable", printable)
    trial.set_user_attr("printability", verdict)
    if reason is not None:
        trial.set_user_attr("reason", reason)
        study.tell(trial, state=optuna.trial.TrialState.FAIL)
        return False
    trial.set_constraint("printability", 0.0 if printable else 1.0)
    if problem.life is not None:
        from spsc.design.life import LIFE_COLUMNS, life_constraint

        for key in LIFE_COLUMNS:
            trial.set_user_attr(key, row.get(key))
        trial.set_constraint("life", life_constraint(row, problem.life["cycles"]))
    for key, value in goal.constraints(metrics).items():
        trial.set_constraint(key, value)
    miss = goal.miss(metrics)
    values = goal.values(metrics)
    if "robust_miss" in row:  # judged by its prints: the miss they stay under
        trial.set_user_attr("nominal_miss", miss)
        trial.set_user_attr("p_met", row["p_met"])
        miss = row["robust_miss"]
        values = [miss]
    trial.set_user_attr("miss", miss)
    study.tell(trial, values)
    return (not goal.multi) and printable and miss <= stop_tol(problem) + 1e-12


def _feasible(t) -> bool:
    return all(v <= 0 for v in t.constraints.values())


def _postfix(study, goal: Goal) -> str:
    done = [t for t in study.get_trials(deepcopy=False) if t.state.name == "COMPLETE"]
    feas = [t for t in done if _feasible(t)]
    if goal.multi:
        return f"feasible {len(feas)}/{len(done)}"
    if not feas:
        return "no printable design yet"
    return f"best miss {100 * min(t.values[0] for t in feas):.2f} %"


# -- the trials as rows ------------------------------------------------------------------------
def full_params(design: dict) -> dict:
    """A design's inputs with the seven parameters resolved (the type's preset where the
    design leaves n1, n2, c_y out), under the CLI's names: what ``spsc curve`` takes."""
    from spsc.cad.geometry import PARAMS, SPSCGeometry, preset

    given = {k: design[k] for k in PARAMS
             if design.get(k) is not None}
    geom = preset(design["type"], **given) if design.get("type") else SPSCGeometry(**given)
    out = {k: design.get(k) for k in INPUTS}
    out.update(geom.as_dict())
    return out


def trial_rows(study) -> list[dict]:
    """One dict per trial, in trial order: number, state, the design's inputs (CLI names, the
    preset's n1, n2, c_y filled in when valid), the metrics, miss, objective values, feasible,
    printable, printability, status, reason, seconds and who proposed it (``sampler``, or the
    polish's ``jacobian`` / ``gauss-newton``: :mod:`.polish`)."""
    rows = []
    for t in study.get_trials(deepcopy=False):
        a = t.user_attrs
        design = a.get("design") or {}
        try:
            params = full_params(design)
        except (ParameterError, KeyError, TypeError):
            params = {k: design.get(k) for k in INPUTS}
        complete = t.state.name == "COMPLETE"
        row = {"trial": t.number, "state": t.state.name}
        row.update(params)
        metrics = a.get("metrics") or {}
        row.update({m: metrics.get(m) for m in METRIC_NAMES})
        row.update({"miss": a.get("miss"),
                    "values": list(t.values) if complete and t.values else None,
                    "feasible": complete and _feasible(t),
                    "printable": a.get("printable"), "printability": a.get("printability", ""),
                    "status": a.get("status", ""), "reason": a.get("reason", ""),
                    "message": a.get("message", ""), "seconds": a.get("seconds"),
                    "proposer": a.get("proposer", "sampler"),
                    "nominal_miss": a.get("nominal_miss"), "p_met": a.get("p_met"),
                    "life_cycles": a.get("life_cycles"), "peak_stretch": a.get("peak_stretch"),
                    "energy_amplitude_MPa": a.get("energy_amplitude_MPa"),
                    "life_message": a.get("life_message")})
        rows.append(row)
    return rows


def select(rows: list[dict], goal: Goal) -> tuple[dict | None, list[dict]]:
    """(best, Pareto rows) among the feasible complete trials. One objective: the smallest
    miss (the earliest of equals). Several: the non-dominated set, and as the best its
    compromise — the design nearest the ideal point once each objective is scaled to [0, 1]
    over the front."""
    feas = [r for r in rows if r["feasible"]]
    if not feas:
        return None, []
    if not goal.multi:
        best = min(feas, key=lambda r: (r["values"][0], r["trial"]))
        return best, [best]
    signs = [1.0 if d == "minimize" else -1.0 for d in goal.directions]
    pts = [[s * v for s, v in zip(signs, r["values"])] for r in feas]
    front = [r for r, p in zip(feas, pts)
             if not any(_dominates(q, p) for q in pts if q is not p)]
    fpts = [[s * v for s, v in zip(signs, r["values"])] for r in front]
    lo = [min(c) for c in zip(*fpts)]
    hi = [max(c) for c in zip(*fpts)]

    def distance(p):
        return math.fsum(((v - a) / (b - a) if b > a else 0.0) ** 2
                         for v, a, b in zip(p, lo, hi))

    best = min(zip(front, fpts), key=lambda rp: (distance(rp[1]), rp[0]["trial"]))[0]
    return best, front


def _dominates(q, p) -> bool:
    return all(a <= b for a, b in zip(q, p)) and any(a < b for a, b in zip(q, p))
