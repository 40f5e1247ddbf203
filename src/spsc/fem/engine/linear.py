"""The constrained Newton step: the free unknowns' system factorised by the discretisation's
solver, the prescribed unknowns moved by their jumps, the tie's slaves aliased onto their
master, and the gas's rank-one term by Sherman–Morrison:

    PᵀKP Δy = −Pᵀ(r + K s) − c Pᵀg (gᵀs),   (K + c g gᵀ)⁻¹ by one factorisation of K,

with s the constrained part of the step and P the aliasing. The factor's inertia gives the
displacement problem's negative eigenvalues (the discretisation counts them).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constraints import Constraints
from .linsolve import Factor, factorize, solve_rank_one

__all__ = ["Step", "linear_step", "inertia", "gas_vector"]


@dataclass(frozen=True, eq=False)
class Step:
    """A Newton step: ``dx`` of all n unknowns, the negative eigenvalues of the displacement
    problem on the factorised constraint set (None: unknown or not recomputed), the linearised
    reactions of the active contact unknowns (N, None unless asked for), that set's key and
    the factorisation it was solved with."""

    dx: np.ndarray
    unstable_modes: int | None
    multipliers: np.ndarray | None
    key: bytes
    factor: Factor | None = None


def gas_vector(model, ev, m) -> np.ndarray:
    """g over the Newton system's m unknowns (zero beyond the displacements)."""
    gs = np.zeros(m)
    gs[: model.n_u] = ev.g
    return gs


def _gas_shift(gs, s, con: Constraints, how: str) -> float:
    """gᵀs: over every unknown, or over the constrained ones only (settings.gas_shift)."""
    if how == "full":
        return gs @ s
    out = gs[con.presc] @ con.jump
    if con.lean.size:
        out += gs[con.lean] @ con.ljump
    return out + gs[con.slaves] @ con.sjump if con.slaves.size else out


def inertia(model, restriction, ev, gc, settings) -> tuple[int | None, Factor]:
    """The displacement problem's negative eigenvalues on a restriction of ev's tangent, and
    the factorisation they were read from."""
    factor = factorize(restriction.matrix(ev.K), settings.solver, upper=restriction.upper)
    return model.unstable_modes(factor, ev.c, gc), factor


def linear_step(model, ev, restriction, free, con: Constraints, settings, *,
                multipliers: bool = False, factor: Factor | None = None) -> Step:
    """The Newton step of ev's system on the ``free`` unknowns under ``con``; with
    ``multipliers`` also the active contact unknowns' linearised reactions
    λ = −(r + K Δx + c g gᵀΔx)_active. Given ``factor`` (a factorisation of an earlier
    tangent on the same constraint set: modified Newton) ev.K is not factorised and the
    inertia is not recomputed."""
    K, c, m = ev.K, ev.c, con.n
    fresh = factor is None
    if fresh:
        factor = factorize(restriction.matrix(K), settings.solver, upper=restriction.upper)
    rs = model.system_residual(ev)
    s = con.shift()
    moved = bool(np.any(s))
    rhs = -rs - K @ s if moved else -rs
    rhs = restriction.take(con.condense(rhs))
    gs = gas_vector(model, ev, m)
    gc = restriction.take(con.condense(gs))
    if c > 0.0:
        if moved:
            rhs -= c * gc * _gas_shift(gs, s, con, settings.gas_shift)
        dx = solve_rank_one(factor, c, gc, rhs)
    else:
        dx = factor(rhs)
    modes = model.unstable_modes(factor, c, gc) if fresh else None
    step = s
    restriction.put(step, dx)
    if con.slaves.size and not getattr(restriction, "aliases", False):
        step[con.slaves] += step[con.master]
    lam = None
    if multipliers and con.reacting.size:
        r_lin = rs + K @ step + (c * gs * (gs @ step) if c > 0.0 else 0.0)
        lam = -r_lin[con.reacting]
    return Step(model.expand(ev, step), modes, lam, restriction.key, factor)
