"""One solver entry point, :func:`solve`, walking a load path given as data.

Steps (:mod:`.steps`): :class:`Inflate` (prescribed cavity pressure ramp), :class:`CloseValve`
(from here on the cavity is a closed gas volume with a reservoir, P·(V + V_r)ⁿ = const) and
:class:`Press` (a rigid frictionless plate, displacement controlled, from first contact down by
the stroke). Each step carries its own path (``begin`` changes the load between steps, ``path``
says how the load moves with the step's parameter, :class:`~.steps.Path`): the walk knows no
step by its class, so a new kind of step is one class. Each increment is solved by Newton's
method (:func:`.newton.newton`) or by the path's own increment solver around it (a compliant
object's balance, Coulomb's return mapping: :class:`~.steps.IncrementSolver`); a failed
increment is cut in half until ``min_fraction`` of the nominal one, and a recorded equilibrium
whose tangent has a negative eigenvalue stops the walk (it is unstable: no point past it is a
result). With ``settings.snap_through`` a press follows the jump instead: from an unstable state
(:meth:`_Walk.snap`), or, where Newton finds no equilibrium past the last stable state at the
smallest increment (the branch ends at a fold, or Newton cycles), by descending the potential
from that state (:meth:`_Walk.cross`). A failure returns everything converged so far with the
reason.
"""

from __future__ import annotations

import logging
import math
import time

import numpy as np

from .active_set import first_contact, plate_force
from .bodies import Sets, reported
from .friction import tractions
from .newton import Converged, newton
from .result import NewtonFailure, Record, Result, Stop
from .snap import PUSH_MM, Jump, relax, unstable_mode
from .load import Load

__all__ = ["solve", "record"]

_log = logging.getLogger(__name__)

#: snap-throughs followed in one press before the walk stops at the next one
_MAX_JUMPS = 8


def record(model, step, kind, load, sol) -> Record:
    """The record of a converged load ``sol`` (:class:`~.newton.Converged`) of step
    ``step``: pressure, gas volume, plate force, contact area and force per named surface,
    the tie's force, a sticking plate's tangential reactions."""
    ev, active, x = sol.evaluation, sol.active, sol.x
    force, area = 0.0, 0.0
    on = model.surface
    groups = on.groups(ev.r, active[:0])
    if load.plate is not None and active.size:
        force = plate_force(model, ev.r, active)
        area = on.area(x, load.plate, load.indenter)
        groups = on.groups(ev.r, active)
    held = model.tie.force(ev.r, sol.engaged) * model.symmetry if model.tie is not None \
        else None
    shear = float(tractions(model, ev.r, active, x, load.indenter).sum()) * model.symmetry \
        if sol.grip is not None and active.size else 0.0
    return Record(step, kind, x.copy(), ev.pressure, ev.volume, load.plate, force, area,
                  sol.iterations, sol.unstable_modes, groups, held, shear,
                  bodies=reported(model, sol.sets, ev.r))


class _Walk:
    """The walk so far: the state, the load, the contact sets and the records."""

    def __init__(self, model, steps, settings, progress):
        self.model, self.s, self.progress = model, settings, progress
        self.t_start = time.perf_counter()
        self.x = model.zero_state()
        ev = model.evaluate(self.x, Load(), tangent=False)
        self.records = [Record(-1, "start", self.x.copy(), 0.0, ev.volume, None, 0.0, 0.0, 0,
                               insert_force=0.0 if model.tie is not None else None)]
        self.load = Load()
        #: where the bodies stand (:class:`~.bodies.Sets`: the plate's active set and
        #: anchors, the tie's engaged nodes)
        self.sets = Sets()
        self.warm = None  # the last load's factorisation (:class:`~.newton.Warm`)
        self.total = sum(s.increments for s in steps)
        self.done, self.last_force, self.instability, self.iterations = 0, 0.0, "", 0
        self.jumps: list[Jump] = []

    def resume(self, start: Result) -> None:
        """Go on from the last state of ``start``, an earlier walk of this model that ended
        converged with no plate (an inflation): its records, iterations and time are this
        walk's first. Two presses from one inflation (the low and high modes) share it."""
        last = start.records[-1]
        if not start.converged or start.load is None or start.load.plate is not None \
                or self.model.tie is not None \
                or self.model.viscous is not None:  # its history is its own
            raise ValueError("start: a converged walk that ended with no plate, of a model "
                             "without a tie or a rate-dependent material")
        self.x, self.load = last.x.copy(), start.load
        self.records, self.iterations = list(start.records), start.newton_iterations
        self.jumps, self.instability = list(start.jumps), start.instability
        self.t_start -= start.seconds

    def contact_height(self, indenter=None) -> float:
        """The indenter's tip height at first contact with the current state (mm)."""
        return first_contact(self.model, self.x, indenter)

    def solve_one(self, trial, t_new, history):
        """Newton for the trial load from the secant prediction (``settings.predictor``,
        retried from the last state if it fails) or from the last state."""
        model, x = self.model, self.x
        guess = x
        if self.s.predictor and len(history) >= 2:
            (t0, x0), (t1, x1) = history[-2], history[-1]
            guess = x1 + (x1 - x0) * (t_new - t1) / (t1 - t0)
        try:
            return newton(model, guess, trial, self.s, self.sets, self.warm)
        except model.recoverable:
            if guess is x:
                raise
            return newton(model, x, trial, self.s, self.sets)

    def solve(self, path, trial, t_new, history):
        """(solution, its load) of the trial load ``trial`` at ``t_new`` of a step's
        ``path``: one Newton solve, or the path's own increment solver's
        (:class:`~.steps.IncrementSolver`)."""
        if path.solver is not None:
            return path.solver.solve(self, path, trial, t_new, history)
        return self.solve_one(trial, t_new, history), trial

    def ramp(self, k, step) -> Stop | None:
        """Walk one Inflate or Press step through its targets with step halving; the
        :class:`Stop` where it failed or met an unstable equilibrium, else None."""
        path = step.path(self.load, self.contact_height, self.s)
        load_at, kind, targets = path.load_at, path.kind, path.targets
        onset = kind == "press" and self.load.plate is None  # first contact
        nominal = targets[0] if path.span is None else min(targets[0], path.span)
        t, dt, ti, history = 0.0, nominal * (self.s.onset_fraction if onset else 1.0), 0, []
        calm = self.s.regrow_after  # increments solved since the last cut
        while ti < len(targets):
            t_new = min(t + dt, targets[ti])
            trial = load_at(t_new)
            follow = path.follows_snaps and self.s.snap_through \
                and len(self.jumps) < _MAX_JUMPS
            try:
                sol, trial = self.solve(path, trial, t_new, history)
            except self.model.recoverable as exc:
                _log.debug("cut %s t=%.4g dt=%.3g: %s", kind, t_new, dt, exc)
                dt, calm = 0.5 * dt, 0
                if dt >= self.s.min_fraction * nominal:
                    continue
                sol = self.cross(path, t, t_new) if follow else None
                if sol is None:
                    return Stop(k, kind, t_new, step, trial, str(exc))
                history = []  # no secant across the jump
            if sol.unstable_modes and follow:
                jumped = self.snap(path, t, t_new, sol)
                if jumped is not None:
                    t_new, sol = jumped
                    trial, history = load_at(t_new), []  # no secant across the jump
            self.x, self.sets, t, self.load = sol.x, sol.sets, t_new, trial
            self.warm = sol.warm
            if path.solver is not None:
                path.solver.accept()
            self.model.commit(sol.x, trial)
            self.iterations += sol.iterations
            history.append((t, sol.x))
            calm += 1
            if calm >= self.s.regrow_after:
                dt = min(nominal, 2 * dt)
            if math.isclose(t, targets[ti], rel_tol=1e-12, abs_tol=1e-14):
                rec = record(self.model, k, kind, self.load, sol)
                if path.solver is not None:
                    rec = path.solver.annotate(rec)
                if rec.unstable_modes:
                    return Stop(k, kind, t, step, trial, "", rec)
                self.keep(rec, path, t)
                ti += 1
        return None

    def snap(self, path, t0, t1, sol1):
        """Follow a snap-through found between the stable state at ``t0`` (the walk's) and
        the unstable converged ``sol1`` at ``t1``: its onset located by halving, then the
        descent to the stable state at the same plate (:mod:`.snap`). (t, stable solution)
        at the jump, or None if no stable state was found (the walk then stops there)."""
        m, s, load_at = self.model, self.s, path.load_at
        x0, sets0 = self.x, self.sets
        for _ in range(s.snap_bisections):
            tm = 0.5 * (t0 + t1)
            try:
                solm = newton(m, x0, load_at(tm), s, sets0)
            except m.recoverable:
                break
            if solm.unstable_modes:
                t1, sol1 = tm, solm
            else:
                t0, x0, sets0 = tm, solm.x, solm.sets
        load = load_at(t1)
        sol1 = sol1.with_tangent(m, load)
        mode = unstable_mode(m, sol1, load, s)
        diag = np.abs(sol1.evaluation.K.diagonal()[: m.n_u])
        metric = np.maximum(diag, 1e-6 * diag.max())
        best = None
        for sign in (1.0, -1.0):
            push = np.zeros_like(sol1.x)
            push[: mode.size] = sign * PUSH_MM * mode
            try:
                end, released, steps, its = relax(m, sol1.x, load, sol1.sets, s, push,
                                                  metric)
            except NewtonFailure as exc:
                _log.debug("snap descent %+g failed: %s", sign, exc)
                continue
            if best is None or released > best[1]:
                best = (end, released, steps, its)
        if best is None:  # from the stable side of a narrowed bracket
            t0, state, t1 = self.narrow(load_at, t0, t1, (x0, sets0))
            end = self.cross(path, t0, t1, state)
            return None if end is None else (t1, end)
        end, released, steps, its = best
        before, after = record(m, -1, "press", load, sol1), record(m, -1, "press", load, end)
        self.jump(path.travel_at(t1), before, after, released, steps, its)
        return t1, end

    def jump(self, y, before, after, released, steps, its) -> None:
        """Record a jump at travel ``y`` (mm) between the records ``before`` and ``after``."""
        self.jumps.append(Jump(y, before.force, after.force, before.pressure, after.pressure,
                               before.volume, after.volume, released, steps, its))
        self.iterations += its
        self.instability = self.instability or self.jumps[-1].sentence()

    def narrow(self, load_at, t0, t1, state):
        """(t0, its stable state, t1) with [t0, t1] halved ``snap_bisections`` times: at t1
        Newton from the state at t0 fails or lands on an unstable state. ``state``: (x, the
        bodies' sets) at t0."""
        m, s = self.model, self.s
        for _ in range(s.snap_bisections):
            tm = 0.5 * (t0 + t1)
            try:
                solm = newton(m, state[0], load_at(tm), s, state[1])
            except m.recoverable:
                t1 = tm
                continue
            if solm.unstable_modes:
                t1 = tm
            else:
                t0, state = tm, (solm.x, solm.sets)
        return t0, state, t1

    def cross(self, path, t0, t1, state=None):
        """A stable state at ``t1`` where Newton finds none from the stable one at ``t0``
        however short the increment: the branch ends there (a fold: no equilibrium near it
        past t0), or Newton cycles between contact sets; or where the descent from an
        unstable state at t1 found none. Π is descended from the state at t0 (``state``:
        (x, the bodies' sets), the walk's by default) with the plate at t1
        (:func:`.snap.relax`, no push) and the jump recorded like a snap-through's; None if
        this descent finds no stable state either."""
        m, s, load_at = self.model, self.s, path.load_at
        x, sets = state or (self.x, self.sets)
        load = load_at(t1)
        try:
            ev = m.evaluate(x, load_at(t0))
            diag = np.abs(ev.K.diagonal()[: m.n_u])
            end, released, steps, its = relax(m, x, load, sets, s, np.zeros_like(x),
                                              np.maximum(diag, 1e-6 * diag.max()))
        except m.recoverable as exc:  # NewtonFailure among them
            _log.debug("crossing at t=%.4g failed: %s", t1, exc)
            return None
        start = Converged(x, sets, 0, ev, 0)
        before, after = record(m, -1, "press", load_at(t0), start), \
            record(m, -1, "press", load, end)
        # Π holds no plate: the plate's work over the last short travel, F Δy, is added
        released += before.force * (path.travel_at(t1) - path.travel_at(t0))
        self.jump(path.travel_at(t1), before, after, released, steps, its)
        return end

    def keep(self, rec, path, t) -> None:
        """Record a stable point; a plate force falling between points is reported."""
        kind = path.kind
        if kind == "press" and rec.force < (1 - self.s.softening) * self.last_force:
            self.instability = self.instability or (
                f"plate force falls from {self.last_force:.4g} N to {rec.force:.4g} N near "
                f"y = {path.travel_at(t):.3g} mm: negative stiffness (the wall buckles "
                "or snaps; the points stay valid under displacement control)")
        self.last_force = rec.force if kind == "press" else self.last_force
        self.records.append(rec)
        self.done += 1
        if self.progress is not None:
            self.progress(self.done, self.total)

    def result(self, stop: Stop | None) -> Result:
        seconds = time.perf_counter() - self.t_start
        if stop is None:
            return Result(self.records, True, "converged", self.instability, seconds,
                          None, self.iterations, tuple(self.jumps), self.load)
        if stop.record is not None:
            # an unstable equilibrium is not a result: stop before it (docs/design.md)
            message, instability = f"step {stop.index} ({stop.kind}) stopped: {stop.unstable}", \
                stop.unstable
        else:
            message, instability = stop.failure, self.instability or stop.stall
        return Result(self.records, False, message, instability, seconds, stop,
                      self.iterations, tuple(self.jumps), self.load)


def solve(model, steps, *, settings=None, progress=None, start: Result | None = None) -> Result:
    """Walk ``steps`` (Inflate / CloseValve / Press) from the undeformed state of ``model``
    (a :class:`~.protocol.Discretisation`) with ``settings`` (default: the model's), or from
    the end of ``start``, an earlier converged walk of the same model that ended with no plate
    (:meth:`_Walk.resume`: its records come first, its iterations and seconds are counted).

    ``progress(done, total)`` is called after each recorded point. Returns a :class:`Result`
    whose ``records`` hold every converged point (the undeformed state first).
    """
    walk = _Walk(model, steps, settings or model.default_settings(), progress)
    if start is not None:
        walk.resume(start)
    for k, step in enumerate(steps):
        walk.load = step.begin(walk.load, lambda: model.volume(walk.x))
        if not step.increments:
            continue
        stop = walk.ramp(k, step)
        if stop is not None:
            return walk.result(stop)
    return walk.result(None)
