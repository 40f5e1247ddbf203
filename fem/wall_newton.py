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

from .linsolve import solve_rank_one
from .wall_model import WallModel, WallSettings

__all__ = ["WallFailure", "WallState", "newton"]


class WallFailure(RuntimeError):
    """Newton did not converge for one increment (the reason is the message)."""


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


def newton(model: WallModel, x0, *, pressure=0.0, gas: GasLaw | None = None, plate=None,
            active=None, settings: WallSettings):
    """Solve one load (prescribed gauge ``pressure`` MPa, or the closed ``gas``; plate height
    ``plate`` mm or None) from ``x0``. Returns a :class:`WallState`."""
    x = x0.copy()
    n_u = model.n_u
    active = np.zeros(0, int) if active is None or plate is None else np.asarray(active, int)
    if plate is not None:  # start from every node the plate has passed
        z = model.reference[model.contact_dofs] + x[model.contact_dofs]
        active = np.union1d(active, model.contact_dofs[z > plate + settings.contact_tolerance])
    scale, changes, negative, factored, res, lam = None, 0, None, None, np.inf, None
    for it in range(1, settings.max_iterations + 1):
        V = model.volume(x)
        p = float(gas.pressure(V)) if gas is not None else float(pressure)
        c = -float(gas.dpressure(V)) if gas is not None else 0.0
        ev = model.evaluate(x, p)
        r = ev.r
        if not np.all(np.isfinite(r)):
            raise WallFailure("non-finite residual")
        jump = (plate - model.reference[active] - x[active]) if plate is not None \
            else np.zeros(0)
        free = ~model.fixed
        free[active] = False
        res = float(np.linalg.norm(r[free]))
        # the load's force scale: pressure load, support and plate reactions (displacement
        # control of a vented chamber has no other)
        scale = max(scale or 0.0, np.linalg.norm(p * ev.g), np.linalg.norm(r[model.fixed]),
                    np.linalg.norm(r[active]), 1e-9 * model.mu * model.geometry.t0 ** 2)
        settled = jump.size == 0 or float(np.max(np.abs(jump))) <= 1e-12
        small = settled and it > 1 and model.pressure_error(ev) <= 1e-3 * settings.rtol
        # semi-smooth Newton on the contact: the active set is updated after every linear
        # step from its linearised reactions (the multipliers of that step) and the gaps;
        # if it keeps changing, only at near-equilibrium from the true reactions (plain PDAS)
        changed = False
        if plate is not None and settled and it > 1 and (lam is not None
                                                          or res <= 1e-2 * scale):
            reaction = lam if lam is not None else -r[active]
            new = _update_active(model, x, reaction, plate, active, settings.rtol * scale,
                                 settings.contact_tolerance)
            if new is not None:
                changes += 1
                if changes > 40:
                    raise WallFailure("the contact active set does not settle")
                active, changed = new, True
                jump = plate - model.reference[active] - x[active]
                free = ~model.fixed
                free[active] = False
                res = float(np.linalg.norm(r[free]))
        lam = None
        if not changed and small and res <= settings.rtol * scale:
            if factored != free.tobytes():  # the inertia must be that of this free set
                negative = _inertia(ev.K[free][:, free], c, ev.g[free])
            force = float(-np.sum(r[active])) if plate is not None else 0.0
            area = model.contact_area(x, plate) if plate is not None and active.size else 0.0
            return WallState(x, p, V, plate, force, area, active, it, negative)
        K = ev.K
        solve, negative = _factor(K[free][:, free])
        factored = free.tobytes()
        rc = model.condensed(ev)
        rhs = -rc[free]
        g = ev.g
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
        if jump.size:
            du[active] = jump
        if active.size and changes < 10:
            r_lin = rc + K @ du + (c * g * (g @ du) if c > 0.0 else 0.0)
            lam = -r_lin[active]
        step = np.concatenate([du, model.recover(ev, du)])
        x = _admissible(model, x, step)
    raise WallFailure(f"no convergence in {settings.max_iterations} iterations (residual "
                      f"{res:.3g} N against {settings.rtol * scale:.3g} N)")


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

