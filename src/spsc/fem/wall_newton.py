"""One load of the wall model solved by Newton's method: prescribed pressure or closed gas
(Sherman–Morrison on its rank-one tangent), the rigid plate by an exact active set, the pressure
unknowns condensed out of each linear solve, and the inertia of the constrained tangent (the
stability check of every converged state).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as spla

from spsc.core.gaslaw import GasLaw

from .engine.result import NewtonFailure
from .linsolve import solve_rank_one
from .wall_model import WallModel, WallSettings

__all__ = ["WallFailure", "WallState", "newton"]


#: Newton did not converge for one increment: the engine's one failure
WallFailure = NewtonFailure


@dataclass(frozen=True, eq=False)
class WallState:
    """A converged state: unknowns, gauge pressure (MPa), cavity volume (mm³), plate height
    (mm or None), plate force (N), contact area (mm²), active contact unknowns, iterations,
    negative eigenvalues of the constrained tangent (None: not computed)."""

    x: np.ndarray = field(repr=False)
    pressure: float
    volume: float
    plate: float | None
    force: float
    area: float
    active: np.ndarray = field(repr=False)
    iterations: int = 0
    negative: int | None = None


def _factor(A):
    """LDLᵀ-like LU without off-diagonal pivoting (symmetric mode): its U diagonal carries the
    inertia (Sylvester). Falls back to pivoted LU (inertia unknown) if a pivot vanishes."""
    A = A.tocsc()
    try:
        lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
        d = lu.U.diagonal()
        if np.all(np.isfinite(d)) and np.min(np.abs(d)) > 1e-13 * np.max(np.abs(d)):
            return lu.solve, int(np.sum(d < 0))
    except RuntimeError:
        pass
    return spla.splu(A).solve, None


def _inertia(Kff, c, gf) -> int | None:
    """Negative eigenvalues of Kff + c g gᵀ (None if the factorisation cannot tell)."""
    solve, negative = _factor(Kff)
    if negative is not None and c > 0.0:
        negative -= int(1.0 + c * float(gf @ solve(gf)) < 0.0)
    return negative


@dataclass(frozen=True)
class _Load:
    """One load: prescribed gauge ``pressure`` (MPa) or the closed ``gas``; plate height
    ``plate`` (mm) or None."""

    pressure: float
    gas: GasLaw | None
    plate: float | None

    def at(self, volume: float) -> tuple[float, float]:
        """(gauge pressure p (MPa), c = −dp/dV (MPa/mm³)) at the cavity ``volume``."""
        if self.gas is None:
            return float(self.pressure), 0.0
        return float(self.gas.pressure(volume)), -float(self.gas.dpressure(volume))


def newton(model: WallModel, x0, *, pressure=0.0, gas: GasLaw | None = None, plate=None,
           active=None, settings: WallSettings):
    """Solve one load (prescribed gauge ``pressure`` MPa, or the closed ``gas``; plate height
    ``plate`` mm or None) from ``x0``. Returns a :class:`WallState`.

    Semi-smooth Newton on the contact: the active set is updated after every linear step from
    its linearised reactions (the multipliers of that step) and the gaps; if it keeps changing,
    only at near-equilibrium from the true reactions (plain primal–dual active set)."""
    load = _Load(pressure, gas, plate)
    x = x0.copy()
    active = _start_active(model, x, plate, active, settings)
    scale, changes, lam, res, step = 0.0, 0, None, np.inf, None
    for it in range(1, settings.max_iterations + 1):
        V = model.volume(x)
        p, c = load.at(V)
        ev = model.evaluate(x, p)
        if not np.all(np.isfinite(ev.r)):
            raise WallFailure("non-finite residual")
        # the load's force scale: pressure load, support and plate reactions (displacement
        # control of a vented chamber has no other)
        scale = max(scale, np.linalg.norm(p * ev.g), np.linalg.norm(ev.r[model.fixed]),
                    np.linalg.norm(ev.r[active]), 1e-9 * model.mu * model.geometry.t0 ** 2)
        jump = _gap(model, x, plate, active)
        settled = jump.size == 0 or float(np.max(np.abs(jump))) <= 1e-12
        res = float(np.linalg.norm(ev.r[_free(model, active)]))
        changed = False
        if plate is not None and settled and it > 1 and (lam is not None or res <= 1e-2 * scale):
            new = _update_active(model, x, lam if lam is not None else -ev.r[active], plate,
                                 active, settings.rtol * scale, settings.contact_tolerance)
            if new is not None:
                changes += 1
                if changes > 40:
                    raise WallFailure("the contact active set does not settle")
                active, changed = new, True
                res = float(np.linalg.norm(ev.r[_free(model, active)]))
        small = settled and it > 1 and model.pressure_error(ev) <= 1e-3 * settings.rtol
        if not changed and small and res <= settings.rtol * scale:
            return _converged(model, x, ev, load, V, c, active, it, step)
        step = _linear_step(model, ev, c, active, _gap(model, x, plate, active),
                            multipliers=changes < 10)
        lam = step.multipliers
        x = _admissible(model, x, np.concatenate([step.du, model.recover(ev, step.du)]))
    raise WallFailure(f"no convergence in {settings.max_iterations} iterations (residual "
                      f"{res:.3g} N against {settings.rtol * scale:.3g} N)")


def _start_active(model, x, plate, active, settings) -> np.ndarray:
    """The given active set plus every contact node the plate has passed (none without a
    plate)."""
    if plate is None:
        return np.zeros(0, int)
    active = np.zeros(0, int) if active is None else np.asarray(active, int)
    z = model.reference[model.contact_dofs] + x[model.contact_dofs]
    return np.union1d(active, model.contact_dofs[z > plate + settings.contact_tolerance])


def _free(model, active) -> np.ndarray:
    free = ~model.fixed
    free[active] = False
    return free


def _gap(model, x, plate, active) -> np.ndarray:
    """Prescribed jump of the active contact unknowns onto the plate (mm)."""
    if plate is None:
        return np.zeros(0)
    return plate - model.reference[active] - x[active]


@dataclass(frozen=True, eq=False)
class _Step:
    """A Newton step: displacement increment ``du`` (mm), the linearised contact reactions
    ``multipliers`` (N, or None), the negative eigenvalues of the factorised tangent (None:
    unknown) and the free set it was factorised on (bytes)."""

    du: np.ndarray
    multipliers: np.ndarray | None
    negative: int | None
    free: bytes


def _linear_step(model, ev, c, active, jump, *, multipliers: bool) -> _Step:
    """Solve the condensed system (K + c g gᵀ) Δu = −r on the free unknowns with the active
    contact unknowns moved by ``jump`` (Sherman–Morrison for the gas)."""
    K, g, n_u = ev.K, ev.g, model.n_u
    free = _free(model, active)
    solve, negative = _factor(K[free][:, free])
    rc = model.condensed(ev)
    rhs = -rc[free]
    if jump.size:
        dj = np.zeros(n_u)
        dj[active] = jump
        rhs -= (K @ dj)[free]
        if c > 0.0:
            rhs -= c * g[free] * (g[active] @ jump)
    if c > 0.0:
        du_f = solve_rank_one(solve, c, g[free], rhs)
        if negative is not None:
            # K + c g gᵀ loses one negative eigenvalue iff 1 + c gᵀK⁻¹g < 0
            negative -= int(1.0 + c * float(g[free] @ solve(g[free])) < 0.0)
    else:
        du_f = solve(rhs)
    du = np.zeros(n_u)
    du[free] = du_f
    du[active] = jump if jump.size else du[active]
    lam = None
    if active.size and multipliers:
        r_lin = rc + K @ du + (c * g * (g @ du) if c > 0.0 else 0.0)
        lam = -r_lin[active]
    return _Step(du, lam, negative, free.tobytes())


def _converged(model, x, ev, load, V, c, active, iterations, step) -> WallState:
    """The converged state, with the inertia of the tangent on its own free set (the last
    factorisation's when that was on the same set)."""
    free = _free(model, active)
    if step is not None and step.free == free.tobytes():
        negative = step.negative
    else:
        negative = _inertia(ev.K[free][:, free], c, ev.g[free])
    p, plate = load.at(V)[0], load.plate
    force = float(-np.sum(ev.r[active])) if plate is not None else 0.0
    area = model.contact_area(x, plate) if plate is not None and active.size else 0.0
    return WallState(x, p, V, plate, force, area, active, iterations, negative)


def _update_active(model, x, reaction, plate, active, force_tol, gap_tol):
    """The new active set (contact z-unknowns) or None if unchanged (the PDAS fixed point):
    active nodes whose ``reaction`` (N, pushing > 0) does not pull, and the nodes above the
    plate."""
    keep = reaction >= -force_tol
    inactive = np.setdiff1d(model.contact_dofs, active)
    z = model.reference[inactive] + x[inactive]
    new = inactive[z > plate + gap_tol]
    if new.size == 0 and np.all(keep):
        return None
    return np.union1d(active[keep], new)


def _admissible(model, x, step, trials=8):
    """x + α step with the largest α = 1, ½, … that inverts no element (full Newton steps
    otherwise: the mixed form's residual is no merit function to descend on)."""
    alpha = 1.0
    for _ in range(trials):
        xt = x + alpha * step
        if model.admissible(xt):
            return xt
        alpha *= 0.5
    raise WallFailure("every trial step inverts an element")

