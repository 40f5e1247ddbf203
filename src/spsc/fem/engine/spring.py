"""A compliant object (``--object-stiffness K``): the rigid indenter on a linear spring of
stiffness k (N/mm) whose far end follows the prescribed travel y.

The indenter stands where the spring's force balances the chamber's. Its own travel y_p (mm
from first contact) solves

    g(y_p) = k (y − y_p) − F(y_p) = 0,

with F(y_p) the plate force of the chamber held at y_p: a converged load of the engine. So the
curve F(y) with the spring is the rigid curve at the indenter's travel, F(y) = F_rigid(y − F/k),
which is what makes objects of different stiffness (the paper's Fig. 10a) one option.

g is k Δy > 0 at the last indenter position and decreases with y_p while the chamber is stable
against the spring (dF/dy_p > −k). The root is found by secant steps from the last position,
the first with F's slope from the last increment, kept inside the bracket once one is found
(bisection otherwise), and never past the far end. Each trial solves the chamber from the last
trial's state.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import ClassVar

from .active_set import plate_force
from .newton import newton
from .result import NewtonFailure

__all__ = ["Spring", "balance", "solver"]

#: trials of one balance before the increment fails (and is cut)
MAX_TRIALS = 30


def balance(solve_at, y: float, k: float, y_prev: float, f_prev: float, slope: float,
            tol: float):
    """(converged solution, y_p, F(y_p)) with |k (y − y_p) − F(y_p)| ≤ ``tol`` (N).

    ``solve_at(y_p)`` → (solution, F) solves the chamber with the indenter at y_p; ``y_prev``,
    ``f_prev``: the last converged indenter travel and force; ``slope``: dF/dy_p there (N/mm,
    an estimate). Raises :class:`NewtonFailure` if no balance is found."""
    lo, g_lo, hi = y_prev, k * (y - y_prev), None
    a, g_a = lo, g_lo
    yp = min(y, lo + g_lo / (k + max(slope, 0.0)))
    for _ in range(MAX_TRIALS):
        sol, force = solve_at(yp)
        g = k * (y - yp) - force
        if abs(g) <= tol:
            return sol, yp, force
        if g > 0:
            lo, g_lo = yp, g
        else:
            hi = yp
        nxt = yp - g * (yp - a) / (g - g_a) if g != g_a else yp
        a, g_a = yp, g
        if hi is None:
            nxt = min(max(nxt, lo), y)
        elif not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        yp = nxt
    raise NewtonFailure(f"the object's spring does not balance the chamber at y = {y:.4g} mm "
                        f"in {MAX_TRIALS} trials (indenter between {lo:.6g} and "
                        f"{hi if hi is not None else y:.6g} mm)")


def solver(model, settings, load_at_travel, x, sets):
    """``solve_at(y_p)`` for :func:`balance`: Newton from the last trial's state and sets (the
    walk's ``x`` and ``sets`` first), always with the walk's anchors (a sticking plate's
    nodes touch at the indenter's final position only)."""
    state = {"x": x, "sets": sets, "iterations": 0}
    grip = sets.get("grip")

    def solve_at(y_p):
        load = load_at_travel(y_p)
        sol = newton(model, state["x"], load, settings, state["sets"].replace(grip=grip))
        state.update(x=sol.x, sets=sol.sets, iterations=state["iterations"] + sol.iterations)
        sol = dataclasses.replace(sol, iterations=state["iterations"])  # every trial's
        return sol, plate_force(model, sol.evaluation.r, sol.active) if sol.active.size \
            else 0.0

    return solve_at


@dataclass(eq=False)
class Spring:
    """The increment solver (:class:`~.steps.IncrementSolver`) of a press on an object of
    stiffness ``k`` (N/mm): each increment's far-end travel balanced by :func:`balance`, its
    secant from the last two balanced (indenter travel mm, force N) of this press."""

    k: float
    follows_snaps: ClassVar[bool] = False

    def __post_init__(self):
        self.points = [(0.0, 0.0)]  # the last two accepted balances
        self.trial = None  # the balance of the solution the walk has not taken yet

    def solve(self, walk, path, trial, t, history):
        """(solution, its load) with the indenter where the spring balances the chamber at
        the far-end travel of ``t``."""
        (y0, f0), (y1, f1) = self.points[-2:] if len(self.points) > 1 else self.points * 2
        slope = (f1 - f0) / (y1 - y0) if y1 > y0 else 0.0
        solve_at = solver(walk.model, walk.s, path.at_travel, walk.x, walk.sets)
        tol = walk.s.rtol * 10 * max(f1, self.k * path.travel_at(t), walk.model.force_floor)
        sol, y_p, force = balance(solve_at, path.travel_at(t), self.k, y1, f1, slope, tol)
        self.trial = (y_p, force)
        return sol, path.at_travel(y_p)

    def accept(self) -> None:
        if self.trial is not None:  # a balance is accepted as found
            self.points, self.trial = self.points[-1:] + [self.trial], None

    def annotate(self, record):
        """The record with the indenter's own travel (mm from first contact)."""
        return dataclasses.replace(record, indenter=self.points[-1][0])
