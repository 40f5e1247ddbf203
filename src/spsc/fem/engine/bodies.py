"""The bodies that constrain one Newton solve, each a term with its own set.

A body met unilaterally is a :class:`Body`: it holds its set (the plate's active contact
unknowns, the tie's engaged nodes), gives the constraints that set puts on the state x
(:class:`~.constraints.Constraints`: prescribed, aliased or leaning unknowns), updates its set
from the residual's reactions (a primal–dual active set) and closes it at convergence. Newton
(:mod:`.newton`) asks nothing else of a body: it joins their constraints, solves, and updates
each set until none changes, so a new body (a second plate, a floor under the cavity) is one
class here and one line in :func:`bodies`.

- :class:`Plate`: the rigid plate or a curved indenter (:mod:`.active_set`, :mod:`.leaning`)
  and, on a sticking plate, its anchors (:mod:`.friction`);
- :class:`Tied`: a rigid body inside the model (the 3D solid's insert, the discretisation's
  :class:`~.protocol.Tie`).
"""

from __future__ import annotations

from typing import Callable, Protocol

import numpy as np

from .active_set import curved, jumps, start, surface, update
from .constraints import Constraints
from .friction import Grip, hold, release, stuck
from .load import Load
from .result import NewtonFailure

__all__ = ["Body", "Plate", "Tied", "bodies"]

_NONE = np.zeros(0, int)


class Body(Protocol):
    """One body's part in a Newton solve; its set is its own state."""

    #: its constraints only prescribe unknowns (no aliasing, no leaning): a changed set can
    #: update the last factorisation by a low-rank correction (:mod:`.lowrank`)
    plain: bool
    #: the next load of a press may start from this solve's last factorisation on this set
    warm: bool

    def constraints(self, x) -> Constraints:
        """The constraints of its set at the state x."""

    def pushing(self) -> np.ndarray:
        """The unknowns whose reactions count in the convergence test's force scale."""

    def update(self, x, r, reaction: Callable, force_tol: float, gap_tol: float) -> bool:
        """Update its set from the residual ``r`` (or ``reaction(dofs)``, the linearised
        reactions where the solve has them); whether it changed."""

    def key(self) -> bytes:
        """Its set, hashable (the solve's cycle and stall checks)."""

    def close(self, x) -> None:
        """The solve converged at x: keep what the next load starts from."""


class Plate:
    """The rigid plate at ``load.plate`` (a curved ``load.indenter`` whose tip is there) on the
    model's :class:`~.surface.ContactSurface`: its active set ``active``, each active height
    prescribed (the plate) or leaning on its lateral unknowns (a curved body); on a sticking
    plate (``load.stick``) the anchors ``grip`` of what touched hold it from sliding."""

    def __init__(self, model, load: Load, x, active, grip: Grip | None, settings,
                 warm_active=None):
        self.model, self.load = model, load
        self.curved = curved(load.indenter)
        self.active = start(model, x, load.plate, active, settings, load.indenter) \
            if warm_active is None else warm_active
        #: the sticking plate's anchors (None: frictionless)
        self.grip = None if not load.stick else grip if grip is not None \
            else Grip.empty(model)
        self.plain = not self.curved
        self.warm = not (load.stick or self.curved)

    def constraints(self, x) -> Constraints:
        m, n = self.model, len(self.model.fixed)
        presc = np.asarray(self.active, int)
        if self.curved and presc.size:
            return self.lean(x, presc)
        jump = jumps(m, x, self.load.plate, presc)
        if self.grip is not None:  # the anchored nodes still on the plate do not slide
            self.grip = release(m, self.grip, presc)
            held, moved = stuck(self.grip, x)
            presc, jump = np.concatenate([presc, held]), np.concatenate([jump, moved])
        return Constraints(n, presc, jump, _NONE, np.zeros(0), -1)

    def lean(self, x, active) -> Constraints:
        """Under a curved indenter the active heights lean on their lateral unknowns
        (:mod:`.leaning`)."""
        m = self.model
        S, dS, d2S, lat = surface(m, x, active, self.load.indenter)
        if not np.all(np.isfinite(S)):
            raise NewtonFailure("a node on the indenter passed beyond its equator (the body "
                                "has no lower surface there)")
        ljump = jumps(m, x, self.load.plate, active, self.load.indenter)
        return Constraints(len(m.fixed), _NONE, np.zeros(0), _NONE, np.zeros(0), -1, active,
                           ljump, lat, dS, d2S)

    def pushing(self) -> np.ndarray:
        return self.active

    def update(self, x, r, reaction, force_tol, gap_tol) -> bool:
        new = update(self.model, x, reaction(self.active), self.load.plate, self.active,
                     force_tol, gap_tol, self.load.indenter)
        if new is None:
            return False
        self.active = new
        return True

    def key(self) -> bytes:
        return self.active.tobytes()

    def close(self, x) -> None:
        if self.grip is not None:
            self.grip = hold(self.model, self.grip, x, self.active)


class Tied:
    """The discretisation's tie (:class:`~.protocol.Tie`, the 3D solid's insert) with its
    engaged nodes ``engaged``: their unknowns aliased onto its master (``n``: the Newton
    system's unknowns)."""

    plain = False
    warm = True

    def __init__(self, tie, engaged, n: int):
        self.tie, self.n = tie, n
        self.engaged = _NONE if engaged is None else np.asarray(engaged)

    def constraints(self, x) -> Constraints:
        slaves, sjump = self.tie.constraints(x, self.engaged)
        return Constraints(self.n, _NONE, np.zeros(0), slaves, sjump,
                           self.tie.master)

    def pushing(self) -> np.ndarray:
        return _NONE

    def update(self, x, r, reaction, force_tol, gap_tol) -> bool:
        new = self.tie.update(x, r, self.engaged, force_tol, gap_tol)
        if new is None:
            return False
        self.engaged = new
        return True

    def key(self) -> bytes:
        return self.engaged.tobytes()

    def close(self, x) -> None:
        """The engaged set is all the next load starts from."""


def bodies(model, load: Load, x, active, engaged, grip, settings, warm_active=None):
    """(the plate or None, the tie or None) of one solve of ``load`` from the sets given."""
    plate = Plate(model, load, x, active, grip, settings, warm_active) \
        if load.plate is not None else None
    tied = Tied(model.tie, engaged, len(model.fixed)) if model.tie is not None else None
    return plate, tied
