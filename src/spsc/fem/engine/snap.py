"""Snap-through under the plate's displacement control: from an unstable equilibrium (its
tangent on the active constraints has a negative eigenvalue) to the stable one the wall jumps
to at the same plate position, and what the jump released.

Under displacement control a wall that snaps leaves its branch at the plate position where
the branch loses stability (the bifurcation or limit point y*): the plate stands still, the
wall moves dynamically and comes to rest on another stable equilibrium. Without inertia and
damping data the path of the jump is not determined, but where it ends is: the state reached
by descending the total potential energy Π (strain energy, the gas's, the cavity pressure's
work) from the unstable state, which is what a quasi-static experiment sees.

The descent is a sequence of implicit (backward-Euler) steps of the gradient flow

    M (x_{k+1} − x_k) / τ_k = −r(x_{k+1}),   i.e.   r(x) + μ_k M (x − x_k) = 0,  μ = 1/τ,

each solved by the engine's Newton with the plate's active set and the gas (:func:`.newton.
newton` on :class:`Damped`), with M = |diag K| of the unstable state's tangent (so μ is
dimensionless) and μ shrinking as the steps grow easy, until an undamped Newton solve from the
current state converges to a stable equilibrium: tried once the flow is five pushes from the
saddle, or where it has come to rest before that (a stable state a small jump away, found on
the flow itself as μ → 0). Each implicit step lowers Π (it minimises
Π(x) + μ/2 ‖x − x_k‖²_M near x_k), so the flow cannot return to the saddle. It starts from the
unstable state pushed along its unstable mode, found by inverse iteration on the factorised
tangent (the eigenvalue nearest zero is the one that just crossed it); both directions are
followed and the one ending lower in Π is the jump (the other is usually the same state or
the branch just left).

The energy released (mJ = N·mm) is Π before less Π after, from the discretisation's
``potential(x, load)`` (the wall's stored energy less the gas's work: the plate is still, its
reactions do no work); both directions of the push end lower than the unstable state.
"""

from __future__ import annotations

import dataclasses
import logging
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from spsc.core.constants import to_kPa

from .linear import gas_vector
from .linsolve import FULL_INPUT, factorize, solve_rank_one
from .newton import _Newton, newton
from .result import NewtonFailure
from .restrict import restriction

__all__ = ["Jump", "Damped", "unstable_mode", "relax"]

_log = logging.getLogger(__name__)

#: implicit flow steps before the descent gives up
MAX_FLOW_STEPS = 80
#: the unstable mode's push (mm, largest nodal displacement)
PUSH_MM = 0.02
#: a flow step shorter than this fraction of the push, and no longer than the one before,
#: has come to rest (a stationary point; by a saddle the steps are short but grow)
STALL = 1e-3


@dataclass(frozen=True)
class Jump:
    """A snap-through at plate travel ``y_mm``: the plate force (N), cavity pressure (MPa)
    and cavity volume (mm³) before and after it, the energy it released (mJ), the flow steps
    and Newton iterations it took."""

    y_mm: float
    force_before_N: float
    force_after_N: float
    pressure_before: float
    pressure_after: float
    volume_before: float
    volume_after: float
    energy_released_mJ: float
    flow_steps: int
    iterations: int

    def as_dict(self) -> dict:
        d = dataclasses.asdict(self)
        d["pressure_before_kPa"] = to_kPa(d.pop("pressure_before"))
        d["pressure_after_kPa"] = to_kPa(d.pop("pressure_after"))
        d["volume_before_mm3"] = d.pop("volume_before")
        d["volume_after_mm3"] = d.pop("volume_after")
        return d

    def sentence(self) -> str:
        way = "falls" if self.force_after_N < self.force_before_N else "rises"
        gas = "" if self.pressure_before == self.pressure_after == 0.0 else (
            f", the pressure from {to_kPa(self.pressure_before):.4g} to "
            f"{to_kPa(self.pressure_after):.4g} kPa")
        return (f"snap-through at y = {self.y_mm:.3g} mm: the plate force {way} from "
                f"{self.force_before_N:.4g} N to {self.force_after_N:.4g} N{gas}, "
                f"{self.energy_released_mJ:.3g} mJ released (followed to the stable branch)")


class Damped:
    """``model`` with the flow's damping on its displacement unknowns: r + μ m ⊙ (u − u_a)
    and K + μ diag(m) (m: the metric, N/mm; ``anchor`` u_a: the last flow state)."""

    def __init__(self, model, metric, anchor, mu: float):
        self.model, self.metric, self.anchor, self.mu = model, metric, anchor, mu

    def __getattr__(self, name):
        return getattr(self.model, name)

    def damping(self, x) -> np.ndarray:
        n = self.model.n_u
        return self.mu * self.metric * (x[:n] - self.anchor[:n])

    def evaluate(self, x, load, *, tangent: bool = True):
        ev = self.model.evaluate(x, load, tangent=tangent)
        r = ev.r.copy()
        r[: self.model.n_u] += self.damping(x)
        K = ev.K
        if K is not None:
            # new values on the model's own index arrays: the restriction's pattern still hits
            rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
            diag = np.flatnonzero((rows == K.indices) & (rows < self.model.n_u))
            data = K.data.copy()
            data[diag] += self.mu * self.metric[rows[diag]]
            K = sp.csr_matrix((data, K.indices, K.indptr), shape=K.shape)
        return dataclasses.replace(ev, r=r, K=K)

    def reuse(self, ev, tangent_ev):
        return self.model.reuse(ev, tangent_ev)


def _settled(model, x, load) -> np.ndarray:
    """x with the discretisation's other unknowns (the wall's element pressures) at rest on
    its displacements: there Π's gradient is r_u."""
    ev = model.evaluate(x, load)
    return x + model.expand(ev, np.zeros(len(model.fixed)))


def unstable_mode(model, sol, load, settings, iterations: int = 8) -> np.ndarray:
    """The eigenvector of the converged ``sol``'s constrained tangent (gas included) whose
    eigenvalue is nearest zero, by inverse iteration on its factorisation, scaled to a largest
    nodal displacement of 1 (full numbering, zero on constrained unknowns)."""
    nw = _Newton(model, load, settings, sol.x, sol.sets)
    con, free = nw.constrain()
    ev = sol.with_tangent(model, load).evaluation
    red = restriction(ev.K, free, con, settings.solver in FULL_INPUT,
                      model.system_residual(ev))
    factor = factorize(red.matrix(ev.K), settings.solver, upper=red.upper)
    gc = red.take(con.condense(gas_vector(model, ev, con.n)))
    v = red.take(np.random.default_rng(0).standard_normal(con.n))
    for _ in range(iterations):
        v = solve_rank_one(factor, ev.c, gc, v) if ev.c > 0 else factor(v)
        v /= np.linalg.norm(v)
    mode = np.zeros(con.n)
    red.put(mode, v)
    return mode / np.max(np.abs(mode[: model.n_u]))


def relax(model, x_u, load, sets, settings, push: np.ndarray, metric):
    """Descend Π from ``x_u + push`` at the fixed ``load`` (``model`` has ``potential``;
    ``sets``: where its bodies stand, :class:`~.bodies.Sets`):
    (stable converged state, Π(x_u) − Π(it) in mJ, flow steps, Newton iterations). Raises
    NewtonFailure if no stable state is reached."""
    x = _settled(model, x_u + push, load)
    mu, iterations, k, last = 1.0, 0, 0, np.inf
    n = model.n_u
    for k in range(1, MAX_FLOW_STEPS + 1):
        try:
            sol = newton(Damped(model, metric, x, mu), x, load, settings, sets)
        except model.recoverable as exc:
            _log.debug("flow %d mu=%.3g failed: %s", k, mu, exc)
            sol = None
        if sol is None or sol.unstable_modes:
            # μ M no longer outweighs the negative curvature: the step is no descent
            mu *= 4.0
            if mu > 1e6:
                break
            continue
        iterations += sol.iterations
        dx = sol.x - x
        x, sets = sol.x, sol.sets
        moved = np.max(np.abs(x[:n] - x_u[:n]))
        _log.debug("flow %d mu=%.3g its=%d |dx|=%.3g moved=%.3g", k, mu, sol.iterations,
                   np.max(np.abs(dx[:n])), moved)
        if sol.iterations <= 4:
            mu *= 0.5
        # by the saddle Newton would go back to it, unless the flow has come to rest there: a
        # stable state a small jump away (the damped tangent is definite as μ → 0); leaving
        # the saddle the steps grow (from it undamped Newton went back: 8 of 12 attempts on
        # Type C at 10 kPa)
        step = np.max(np.abs(dx[:n]))
        stalled, last = step < STALL * PUSH_MM and step <= last, step
        if moved < 5 * PUSH_MM and not stalled:
            continue
        try:
            end = newton(model, x, load, settings, sets)
        except model.recoverable as exc:
            _log.debug("undamped from flow %d: %s", k, exc)
            continue
        _log.debug("undamped from flow %d: modes %s, %d its", k, end.unstable_modes,
                   end.iterations)
        iterations += end.iterations
        if end.unstable_modes == 0:
            released = model.potential(x_u, load) - model.potential(end.x, load)
            return end, released, k, iterations
    raise NewtonFailure(f"the snap-through's descent found no stable state in {k} flow steps")
