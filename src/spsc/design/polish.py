"""Polishing a near miss: Gauss–Newton on the targets from a finite-difference Jacobian.

TPE finds the region of a single-objective goal quickly and then wanders in it: on the
issue-26 problem (``stiffness_high=6``, ``sensitivity_high>=5``, wall model, two workers) its
printable trials missed by less than 30 % from trial 2 (seed 0) and 1 (seed 1) on, and it met
the goal (1 %) at trials 75 and 66; with the polish at trials 13 and 8. The metrics are smooth
functions of the intervals (the models converge to 1e-8), so once a printable trial misses by
less than :data:`START`, the loop spends trials on it:

1. its Jacobian, one trial per interval moved by :data:`FD_STEP` of the interval's width
   (these run side by side on the workers);
2. Gauss–Newton steps: the least-norm change of the intervals (scaled to their widths) that
   zeroes the linearised misses of the equality targets and of the inequality targets that are
   missed or within the tolerance of it, at most ``trust`` of each width (:data:`TRUST` at
   first). A step that lowers the miss and is printable is the new base, and the trust
   region grows back; one that does not halves it. The Jacobian follows each step
   (Broyden's update). After :data:`GIVE_UP` steps without a better design the polish leaves
   that base to TPE.

Choices (type, material) stay the base's. Proposals are Optuna trials like any other
(``study.enqueue_trial``; user attribute ``proposer``: ``jacobian`` or ``gauss-newton``, TPE's
own have none): TPE learns from them, and the study's journal holds them. The polish decides
only on told trials, which the loop tells in the order they were asked, so the study still
depends only on the seed and the worker count.
"""

from __future__ import annotations

import math
from decimal import Decimal

import numpy as np

__all__ = ["Polish", "START", "FD_STEP", "TRUST", "GIVE_UP"]

#: a feasible trial missing by less than this (relative) is polished
START = 0.3
#: the finite-difference step, a fraction of each interval's width
FD_STEP = 0.02
#: the largest Gauss–Newton step, a fraction of each interval's width
TRUST = 0.25
#: steps without a better design before the polish gives the base back to TPE
GIVE_UP = 3


class Polish:
    """The polish of a single-objective design study (:func:`~.loop.run_design`): call
    :meth:`ask` for the next trial (None: let the sampler propose) and :meth:`tell` with each
    told trial."""

    def __init__(self, problem):
        goal = problem.goal
        self.goal = goal
        self.dims = [d for d in problem.space.searched if d.kind == "interval"]
        self.enabled = not goal.multi and bool(goal.targets) and bool(self.dims)
        self.tried: set[int] = set()  # bases given back to TPE
        self.queue: list = []  # (params, kind, column) not asked yet
        self.pending: dict = {}  # trial number -> (kind, column, base's number, params)
        self.state = "idle"
        self.base = self.J = None
        self.columns: dict = {}  # the Jacobian's columns told so far
        self.trust, self.failures = TRUST, 0

    # -- the loop's side ---------------------------------------------------------------------
    def ask(self, study):
        """The next trial, proposed by the polish (enqueued, then asked), or None."""
        if not self.enabled:
            return None
        if not self.queue:
            self._plan(study)
        if not self.queue:
            return None
        params, kind, column = self.queue.pop(0)
        study.enqueue_trial(params, user_attrs={"proposer": kind})
        trial = study.ask()
        self.pending[trial.number] = (kind, column, self.base["number"], params)
        return trial

    def tell(self, trial, metrics: dict | None, miss: float | None, feasible: bool) -> None:
        """A told trial: its metrics (None when it failed), miss and feasibility."""
        job = self.pending.pop(trial.number, None)
        if job is None or self.base is None or job[2] != self.base["number"] \
                or any(trial.params.get(k) != v for k, v in job[3].items()):
            return  # TPE's, proposed for a base given up since, or (the ask took a proposal
            # a killed run left waiting in the journal) not the design proposed
        kind, column = job[:2]
        x = self._scaled(trial.params)
        ratios = self._ratios(metrics)
        if kind == "jacobian":
            if ratios is None:  # the neighbourhood cannot be evaluated: back to TPE
                self._give_up()
                return
            dx = x[column] - self.base["x"][column]
            self.columns[column] = (ratios - self.base["r"]) / dx
            if len(self.columns) == len(self.dims):
                self.J = np.column_stack([self.columns[i] for i in range(len(self.dims))])
                self.state = "ready"
            return
        # a Gauss–Newton step: the Jacobian learns from it (Broyden) whatever its outcome
        if ratios is not None:
            ds = x - self.base["x"]
            self.J = self.J + np.outer(ratios - self.base["r"] - self.J @ ds, ds) / (ds @ ds)
        if ratios is not None and feasible and miss is not None and miss < self.base["miss"]:
            self.base = {"x": x, "r": ratios, "miss": miss, "params": dict(trial.params),
                         "number": self.base["number"]}
            self.trust, self.failures = min(2 * self.trust, TRUST), 0
        else:
            self.trust, self.failures = self.trust / 2, self.failures + 1
        if self.failures >= GIVE_UP:
            self._give_up()
        else:
            self.state = "ready"

    # -- planning ----------------------------------------------------------------------------
    def _plan(self, study) -> None:
        if self.state == "idle":
            self._start(study)
        elif self.state == "ready":
            step = self._step()
            if step is None:
                self._give_up()
            else:
                self.queue.append((step, "gauss-newton", None))
                self.state = "stepping"

    def _start(self, study) -> None:
        """Begin on the best feasible trial under :data:`START` not polished yet: queue its
        Jacobian's trials."""
        best = None
        for t in study.get_trials(deepcopy=False):
            miss = t.user_attrs.get("miss")
            if t.state.name != "COMPLETE" or t.number in self.tried or miss is None \
                    or not all(v <= 0 for v in t.constraints.values()):
                continue
            if miss < START and miss > self.goal.tol and (best is None or miss < best[0]):
                best = (miss, t)
        if best is None:
            return
        miss, t = best
        ratios = self._ratios(t.user_attrs.get("metrics"))
        if ratios is None:
            self.tried.add(t.number)
            return
        x = self._scaled(t.params)
        self.base = {"x": x, "r": ratios, "miss": miss, "params": dict(t.params),
                     "number": t.number}
        self.columns, self.trust, self.failures = {}, TRUST, 0
        for i in range(len(self.dims)):
            s = x.copy()
            s[i] += FD_STEP if x[i] + FD_STEP <= 1.0 else -FD_STEP
            self.queue.append((self._params(s), "jacobian", i))
        self.state = "jacobian"

    def _step(self) -> dict | None:
        """The next Gauss–Newton design, or None when the step rounds to nothing."""
        rows, want = [], []
        tol = self.goal.tol
        for k, t in enumerate(self.goal.targets):
            r = self.base["r"][k]
            if t.relation == "=":
                rows.append(k), want.append(1.0)
            elif t.relation == ">=" and r < 1.0 + tol:
                rows.append(k), want.append(1.0 + tol / 2)
            elif t.relation == "<=" and r > 1.0 - tol:
                rows.append(k), want.append(1.0 - tol / 2)
        if not rows:
            return None
        J = self.J[rows]
        d = np.asarray(want) - self.base["r"][rows]
        ds = np.linalg.lstsq(J, d, rcond=None)[0]  # the least-norm step
        big = np.max(np.abs(ds))
        if not np.isfinite(big) or big == 0.0:
            return None
        if big > self.trust:
            ds *= self.trust / big
        params = self._params(np.clip(self.base["x"] + ds, 0.0, 1.0))
        if all(params[d.name] == self.base["params"][d.name] for d in self.dims):
            return None
        return params

    def _give_up(self) -> None:
        self.tried.add(self.base["number"])
        self.state, self.base, self.queue = "idle", None, []

    # -- coordinates -------------------------------------------------------------------------
    def _ratios(self, metrics) -> np.ndarray | None:
        """Each target's metric over its value, or None if one is undefined."""
        if not metrics:
            return None
        out = []
        for t in self.goal.targets:
            m = metrics.get(t.metric)
            if m is None or not math.isfinite(float(m)):
                return None
            out.append(float(m) / t.value)
        return np.asarray(out)

    def _scaled(self, params: dict) -> np.ndarray:
        """The intervals of ``params`` scaled to [0, 1] over their widths."""
        return np.array([(float(params[d.name]) - d.values[0]) / (d.values[1] - d.values[0])
                         for d in self.dims])

    def _params(self, s: np.ndarray) -> dict:
        """The base's parameters with the intervals at the scaled ``s``, on each one's
        quantum grid."""
        params = dict(self.base["params"])
        for d, v in zip(self.dims, s):
            lo, hi = d.values
            q = Decimal(d.quantum)
            k = round((lo + v * (hi - lo) - lo) / float(q))
            value = float(Decimal(repr(lo)) + k * q)
            params[d.name] = min(max(value, lo), hi)
        return params
