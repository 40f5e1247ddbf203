"""Coulomb friction on the plate (``--friction MU``): each node on the plate sticks while the
plate's tangential force on it stays within μ times its normal force, and slides against a
friction force of exactly μ times its normal force otherwise.

Each increment is solved by a return mapping over the nodes, as plasticity is:

1. trial: every node that was on the plate sticks (:mod:`.friction`: its lateral unknowns
   held at its anchor; a node touching in this increment meets the plate frictionless);
2. a sticking node whose tangential force R_t exceeds μ λ_n (λ_n its normal force) slips: its
   lateral unknowns are freed and loaded by the friction force F = μ λ_n R_t / |R_t|, the
   direction the sticking force had;
3. the increment is solved again with those forces held (:class:`Sliding`), then each slipping
   node's force is updated: its magnitude μ λ_n from the new normal force, its direction kept
   the trial's (the radial return of plasticity: updating it from the node's slide made the
   swept wall's nodes flip between stick and slip without end); a node whose slide runs along
   its friction force (it would be pushed forward by friction) sticks again at its anchor;
4. until the set of slipping nodes is unchanged and the friction forces move by less than
   ``TOLERANCE`` of the largest.

The friction forces are held within each Newton solve, so the tangent stays symmetric (the
nonsymmetric term μ t ⊗ ∂λ_n/∂u is left to the outer loop, a fixed point). μ → ∞ is the
sticking plate and μ = 0 the frictionless one (both tested). After the increment a slipping
node is anchored where it stopped, and the next increment's trial holds it there. On the
axisymmetric dome the direction is a sign and exact; on the swept wall (two lateral unknowns)
a slipping node's force keeps the trial's direction, which may lean from the slide's within
one increment of 0.05 mm. The loop costs: 5 s against 0.4 s frictionless for a dome curve to
2 mm, 81 s against 4 s for a Type B stadium curve to 6 mm.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .friction import Grip, lateral
from .newton import newton
from .result import NewtonFailure

__all__ = ["Coulomb", "Sliding", "coulomb", "TOLERANCE", "MAX_ROUNDS"]

#: the friction forces' largest change, relative to the largest force, that ends the loop
TOLERANCE = 1e-7
#: rounds of the return mapping before the increment fails (and is cut)
MAX_ROUNDS = 60


@dataclass(frozen=True)
class Coulomb:
    """The increment solver (:class:`~.steps.IncrementSolver`) of a press with Coulomb
    friction ``mu``: each increment the return mapping :func:`coulomb`."""

    mu: float
    follows_snaps: ClassVar[bool] = False

    def solve(self, walk, path, trial, t, history):
        return coulomb(walk.model, walk.x, trial, walk.s, walk.sets, self.mu), trial

    def accept(self) -> None:
        """Nothing to carry: the anchors are the walk's."""

    def annotate(self, record):
        return record


class Sliding:
    """``model`` with the friction forces ``forces`` (N, plate on node) on its lateral unknowns
    ``dofs`` as held external loads: r − F, the tangent unchanged."""

    def __init__(self, model, dofs, forces):
        self.model, self.dofs, self.forces = model, np.asarray(dofs, int), np.asarray(forces)

    def __getattr__(self, name):
        return getattr(self.model, name)

    def evaluate(self, x, load, *, tangent: bool = True):
        ev = self.model.evaluate(x, load, tangent=tangent)
        r = ev.r.copy()
        r[self.dofs] -= self.forces
        return dataclasses.replace(ev, r=r)

    def reuse(self, ev, tangent_ev):
        return self.model.reuse(ev, tangent_ev)


def coulomb(model, x0, load, settings, sets, mu: float):
    """The converged state of one sticking ``load`` with Coulomb friction μ from the walk's
    ``x0`` and its bodies' ``sets`` (:class:`~.bodies.Sets`; their anchors: the nodes on the
    plate before the increment). Its evaluation is the model's own (the plate's forces as reactions r: normal
    −r_z, tangential r_t at every node, sticking or slipping); its grip anchors every node
    where it ended. Raises :class:`NewtonFailure` if the return mapping does not settle."""
    grip = sets.get("grip")
    grip = Grip.empty(model) if grip is None else grip
    slip = {}  # lateral dof -> friction force (N)
    x, now = x0, sets
    iterations, change = 0, np.inf
    for _ in range(MAX_ROUNDS):
        free = grip.anchor.copy()
        dofs = np.fromiter(slip, int, len(slip))
        free[dofs] = np.nan
        solved = newton(Sliding(model, dofs, [slip[d] for d in dofs]) if slip else model,
                        x, load, settings, now.replace(grip=Grip(free)))
        iterations += solved.iterations
        x, now = solved.x, solved.sets
        ev = model.evaluate(x, load, tangent=False)  # the plate's forces as reactions
        new, change = _map(model, ev.r, x, solved.active, grip, slip, mu)
        if new.keys() == slip.keys() and change <= TOLERANCE:
            return dataclasses.replace(solved, evaluation=ev, iterations=iterations)
        slip = new
    raise NewtonFailure(f"the friction's stick and slip do not settle in {MAX_ROUNDS} rounds "
                        f"(the friction forces still change by {change:.2g} of the largest)")


def _map(model, r, x, active, grip: Grip, slip: dict, mu: float) -> tuple[dict, float]:
    """The next slipping set and friction forces, and how much the forces changed (relative
    to the largest)."""
    lat = lateral(model, active)
    normal = np.maximum(-r[active], 0.0)
    new, change, scale = {}, 0.0, max(mu * float(normal.max(initial=0.0)), 1e-300)
    for k in range(len(active)):
        dofs = lat[:, k][lat[:, k] >= 0]
        if dofs.size == 0 or np.isnan(grip.anchor[dofs]).any():
            continue  # no lateral freedom, or touched in this increment: frictionless
        limit = mu * normal[k]
        if dofs[0] not in slip:
            held = r[dofs]
            if np.linalg.norm(held) > limit * (1 + 1e-9) + 1e-12 * scale:
                force = limit * held / np.linalg.norm(held)
                new.update(zip(dofs, force))
                change = max(change, 1.0)
            continue
        old = np.array([slip[d] for d in dofs])
        slid = x[dofs] - grip.anchor[dofs]
        if slid @ old > 1e-6 * np.linalg.norm(slid) * np.linalg.norm(old):
            change = max(change, 1.0)  # pushed forward by its friction: it sticks again
            continue
        force = limit * old / max(np.linalg.norm(old), 1e-300)  # the trial's direction
        new.update(zip(dofs, force))
        change = max(change, float(np.abs(force - old).max()) / scale)
    return new, change
