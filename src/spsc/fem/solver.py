"""One solver entry point, :func:`solve`, walking a load path given as data.

Steps: :class:`Inflate` (prescribed cavity pressure ramp), :class:`CloseValve` (from here on the
cavity is a closed gas volume with a reservoir, P·(V + V_r)ⁿ = const) and :class:`Press` (a
rigid frictionless plate, displacement controlled, from first contact with the chamber down by
the stroke). Each increment is solved by Newton's method with a backtracking line search;
frictionless contact is a primal–dual active set on the outer-surface nodes (an active node's
height is prescribed at the plate, and it is released when its reaction pulls); a rigid insert
in the cavity (:mod:`spsc.fem.insert`) is met the same way, its constraints eliminated by
aliasing the constrained unknowns onto its own; a failed
increment is cut in half until ``min_fraction``. A failure returns everything converged so far
with the reason.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass

import numpy as np

from .assembly import InvertedElement
from .contact import contact_area, group_forces, plate_force, update_active_set
from spsc.core.gaslaw import GasLaw
from .insert import insert_constraints, insert_force, update_engaged
from .newton_step import Constraints as _Constraints, Reduction as _Reduction
from .newton_step import constraint_key as _key, linear_step as _linear_step
from .engine.result import NewtonFailure, Record, Result
from .engine.steps import CloseValve, Inflate, Load, Press
from .model import FEMModel

__all__ = ["Inflate", "CloseValve", "Press", "Settings", "Record", "Result", "solve", "newton"]


@dataclass(frozen=True)
class Settings:
    """Newton and step control. ``rtol``: residual reduction against the load's force scale;
    ``solver``: sparse solver name (:func:`spsc.fem.linsolve.factorize`)."""

    rtol: float = 1e-8
    max_iterations: int = 25
    min_fraction: float = 1.0 / 64
    line_search: bool = True
    solver: str = "auto"
    contact_tolerance: float = 1e-6  # mm: penetration that activates a node
    #: the active set is updated once the residual is below this fraction of the force scale
    #: (1e-1 took fewer iterations than 1e-3 on Type B; earlier updates chatter)
    active_set_update: float = 1e-1
    #: a plate-force drop between recorded points larger than this fraction is reported as
    #: negative stiffness (smaller dips are contact discretisation wiggles)
    softening: float = 1e-2


_log = logging.getLogger(__name__)


def newton(model: FEMModel, x0, load: Load, settings: Settings, active=None, engaged=None):
    """Solve r(x) = 0 from x0 for one load.

    Returns (x, active plate nodes, iterations, evaluation, negative pivots of the last tangent
    or None, engaged top nodes of the model's insert). Raises :class:`NewtonFailure` with the
    reason when it does not converge.
    """
    x = x0.copy()
    X = model.disc.X
    active = np.zeros(0, int) if active is None or load.plate is None else np.asarray(active)
    insert = model.insert
    engaged = np.zeros(0, int) if engaged is None or insert is None else np.asarray(engaged)
    n_u, n = model.disc.n_u, model.disc.n
    fscale, negative, changes, reduction, factored = None, None, 0, None, None
    carried = None  # the full step's evaluation, tangent included, from the line search
    for it in range(1, settings.max_iterations + 1):
        # active nodes are prescribed at the plate; a pending jump to it enters the linear
        # solve (K_ff Δx_f = −r_f − K_fc δ_c) instead of moving those nodes alone, which
        # would invert the elements under them; the insert's constraints likewise
        presc = 3 * active + 2
        jump = (load.plate - model.gap[active] - X[active, 2] - x[presc]) \
            if load.plate is not None else np.zeros(0)
        slaves, sjump = insert_constraints(insert, X, x, engaged) if insert is not None \
            else (np.zeros(0, int), np.zeros(0))
        con = _Constraints(n, presc, jump, slaves, sjump,
                           insert.master if insert is not None else -1)
        free = ~model.fixed
        free[presc] = False
        free[slaves] = False
        ev = carried if carried is not None else model.evaluate(x, load)
        carried = None
        r = ev.r
        if not np.all(np.isfinite(r)):
            raise NewtonFailure("non-finite residual")
        rc = con.condense(r)
        fscale = fscale or max(np.linalg.norm(ev.pressure * ev.g), 1e-6 * model.law.mu,
                               np.linalg.norm(r[:n_u][model.fixed[:n_u]]),
                               np.linalg.norm(rc[:n_u][free[:n_u]]))
        res = np.linalg.norm(rc[:n_u][free[:n_u]])
        settled = con.settled
        converged = res <= settings.rtol * fscale and it > 1 and settled
        near = converged or res <= settings.active_set_update * fscale
        if settled and it > 1 and near:
            changed = False
            if load.plate is not None:
                new_active = update_active_set(model, x, r, load.plate, active,
                                               settings.rtol * fscale,
                                               settings.contact_tolerance)
                if new_active is not None:
                    active, changed = new_active, True
            if insert is not None:
                new_engaged = update_engaged(insert, X, x, r, engaged, settings.rtol * fscale,
                                             settings.contact_tolerance)
                if new_engaged is not None:
                    engaged, changed = new_engaged, True
            if changed:
                changes += 1
                if changes > 30:
                    raise NewtonFailure("contact active set does not settle")
                carried = ev  # x is unchanged: its evaluation stands
                continue
        key = _key(free, slaves)
        if converged:
            # the inertia of the last factorised tangent: unknown if the active set changed since
            return (x, active, it, ev, negative if factored == key else None, engaged)
        reduction = reduction if reduction is not None and reduction.key == key \
            else _Reduction(ev.K, free, slaves, con.master)
        step, negative = _linear_step(model, ev, reduction, free, con, settings)
        factored = reduction.key
        # with a pending jump the residual of the unconstrained state is no merit to descend
        # on: take the largest admissible step (no inverted element) instead
        base = np.linalg.norm(rc[free]) if settled else np.inf
        alpha, carried = _line_search(model, x, step, free, load, base, con) \
            if settings.line_search else (1.0, None)
        x += alpha * step
    raise NewtonFailure(f"no convergence in {settings.max_iterations} iterations "
                        f"(residual {res:.3g} N against {settings.rtol * fscale:.3g} N)")


def _line_search(model, x, step, free, load, base, con, trials=5):
    """Backtracking on the residual norm: the first α = 1, ½, … that reduces it (Armijo-like),
    else the α with the smallest residual among admissible trials (1 if none is).

    The full step is evaluated with its tangent: it is accepted nearly always, and then that
    evaluation is the next Newton iteration's (returned with α, else None).
    """
    best, best_alpha, alpha = np.inf, 1.0, 1.0
    for _ in range(trials):
        xt = x + alpha * step
        try:
            ev = model.evaluate(xt, load, tangent=alpha == 1.0)
            rt = np.linalg.norm(con.condense(ev.r)[free])
        except (np.linalg.LinAlgError, InvertedElement):
            ev, rt = None, np.inf
        if rt <= base * (1 - 1e-4 * alpha) or (np.isinf(base) and np.isfinite(rt)):
            return alpha, ev if alpha == 1.0 else None
        if rt < best:
            best, best_alpha = rt, alpha
        alpha *= 0.5
    return best_alpha, None


def _unstable_modes(model, negative, load) -> int | None:
    """Negative eigenvalues of the displacement problem: the LDLᵀ inertia minus the pressure
    unknowns (the mixed form's pressure block is negative definite). With a closed gas volume
    the factorised matrix lacks the positive rank-one gas term, which can remove one."""
    if negative is None:
        return None
    extra = negative - model.disc.n_p - (1 if load.gas is not None else 0)
    return max(extra, 0)


def _record(model, step, kind, x, ev, load, active, it, settings, negative=None,
            engaged=()) -> Record:
    force, area = 0.0, 0.0
    groups = dict.fromkeys(model.groups, 0.0)
    if load.plate is not None and active.size:
        force = plate_force(model, ev.r, active)
        area = contact_area(model, x, load.plate)
        groups = group_forces(model, ev.r, active)
    held = insert_force(model.insert, ev.r, engaged) * model.symmetry \
        if model.insert is not None else None
    return Record(step, kind, x.copy(), ev.pressure, ev.volume, load.plate, force, area, it,
                  _unstable_modes(model, negative, load), groups, held)


def _load_path(model, x, load, step):
    """(t ∈ [0, 1] -> Load, kind) of an Inflate or Press step starting from ``load`` at the
    state ``x``: the pressure ramp, or the plate lowered from first contact (the highest
    contact node, mm) by the stroke."""
    if isinstance(step, Inflate):
        start, end = load.pressure, float(step.pressure)
        return (lambda t: Load(pressure=start + t * (end - start), plate=load.plate)), "inflate"
    if isinstance(step, Press):
        pos = model.disc.X + model.displacement(x)
        z0 = float((pos[model.contact_nodes, 2] + model.gap[model.contact_nodes]).max()) \
            if load.plate is None else load.plate
        stroke = float(step.stroke)
        return (lambda t: Load(load.pressure, load.gas, z0 - t * stroke)), "press"
    raise TypeError(f"unknown step {step!r}")


def _failed(k, kind, t, step, trial, exc) -> tuple[str, str]:
    """(message, instability) of an increment that failed under every step cut: a press that
    stalls may be a snap-through or buckling."""
    where = (f"press at y = {t * step.stroke:.4g} mm" if kind == "press"
             else f"inflate at p = {trial.pressure * 1e3:.4g} kPa")
    stall = ("Newton stalls under step cuts: possible snap-through or buckling at "
             f"y ≈ {t * step.stroke:.3g} mm") if kind == "press" else ""
    return f"step {k} ({kind}) failed at {where}: {exc}", stall


def _unstable(rec, kind, t, step) -> str:
    """The instability message of an unstable recorded equilibrium ('' if stable)."""
    if not rec.unstable_modes:
        return ""
    where = (f"y = {t * step.stroke:.3g} mm" if kind == "press"
             else f"p = {rec.pressure * 1e3:.3g} kPa")
    return (f"the tangent has {rec.unstable_modes} negative eigenvalue(s) at {where}: "
            "unstable equilibrium (buckling or snap-through)")


def solve(model: FEMModel, steps, *, settings: Settings | None = None, progress=None) -> Result:
    """Walk ``steps`` (Inflate / CloseValve / Press) from the undeformed state.

    ``progress(done, total)`` is called after each recorded point. Returns a :class:`Result`
    whose ``records`` hold every converged point (the undeformed state first).
    """
    settings = settings or Settings()
    t_start = time.perf_counter()
    x = model.zero_state()
    ev = model.evaluate(x, Load(), tangent=False)
    records = [Record(-1, "start", x.copy(), 0.0, ev.volume, None, 0.0, 0.0, 0,
                      insert_force=0.0 if model.insert is not None else None)]
    load = Load()
    active, engaged = np.zeros(0, int), np.zeros(0, int)
    total = sum(s.increments for s in steps if not isinstance(s, CloseValve))
    done, last_force, instability = 0, 0.0, ""
    for k, step in enumerate(steps):
        if isinstance(step, CloseValve):
            gas = GasLaw(load.pressure, model.volume(x), step.reservoir,
                         step.polytropic_index)
            load = Load(gas=gas, plate=load.plate)
            continue
        load_at, kind = _load_path(model, x, load, step)
        nominal = 1.0 / step.increments
        t, dt, ti = 0.0, nominal, 0
        targets = [(i + 1) * nominal for i in range(step.increments)]
        while ti < len(targets):
            t_new = min(t + dt, targets[ti])
            trial = load_at(t_new)
            try:
                x_new, act_new, it, ev, negative, eng_new = newton(model, x, trial, settings,
                                                                   active, engaged)
            except (NewtonFailure, np.linalg.LinAlgError, ValueError) as exc:
                _log.debug("cut %s t=%.4g dt=%.3g: %s", kind, t_new, dt, exc)
                dt *= 0.5
                if dt < settings.min_fraction * nominal:
                    msg, stall = _failed(k, kind, t_new, step, trial, exc)
                    return Result(records, False, msg, instability or stall,
                                  time.perf_counter() - t_start)
                continue
            x, active, engaged, t, load = x_new, act_new, eng_new, t_new, trial
            dt = min(nominal, 2 * dt)
            if math.isclose(t, targets[ti], rel_tol=1e-12, abs_tol=1e-14):
                rec = _record(model, k, kind, x, ev, load, active, it, settings, negative,
                              engaged)
                if _unstable(rec, kind, t, step):
                    # an unstable equilibrium is not a result: stop before it (DESIGN.md)
                    instability = _unstable(rec, kind, t, step)
                    return Result(records, False, f"step {k} ({kind}) stopped: {instability}",
                                  instability, time.perf_counter() - t_start)
                if kind == "press" and rec.force < (1 - settings.softening) * last_force:
                    instability = instability or (
                        f"plate force falls from {last_force:.4g} N to {rec.force:.4g} N near "
                        f"y = {t * step.stroke:.3g} mm: negative stiffness (the wall buckles "
                        "or snaps; the points stay valid under displacement control)")
                last_force = rec.force if kind == "press" else last_force
                records.append(rec)
                ti += 1
                done += 1
                if progress is not None:
                    progress(done, total)
    return Result(records, True, "converged", instability, time.perf_counter() - t_start)
