"""The bodies that constrain one Newton solve, each a term with its own set.

A body met unilaterally is a :class:`Body`: it holds its set (the plate's active contact
unknowns, the tie's engaged nodes), gives the constraints that set puts on the state x
(:class:`~.constraints.Constraints`: prescribed, aliased or leaning unknowns), updates its set
from the residual's reactions (a primal–dual active set) and closes it at convergence. Newton
(:mod:`.newton`) asks nothing else of a body: it joins their constraints, solves, and updates
each set until none changes. What each body keeps from one load to the next travels in one
value, :class:`Sets`, so a new body (a second plate, a floor under the cavity) is one class
and one line in :data:`BODIES`.

- :class:`Plate`: the rigid plate or a curved indenter (:mod:`.active_set`, :mod:`.leaning`)
  and, on a sticking plate, its anchors (:mod:`.friction`);
- :class:`Tied`: a rigid body inside the model (the 3D solid's insert, the discretisation's
  :class:`~.protocol.Tie`);
- :class:`Floor`: the base under the cavity, which the cavity's wall comes down onto when it
  is pressed through its height (the membrane pinched between a probe and the base: the
  paper's puncture test, sec. 3.2), where the discretisation names that surface (its
  ``floor``).

A body class also says what it adds to a recorded point (:meth:`Body.report`: forces by name,
N of the whole part).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Protocol

import numpy as np

from .active_set import curved, jumps, start, started, stepped, surface, update
from .constraints import Constraints
from .friction import Grip, hold, lateral, release, stuck
from .load import Load
from .result import NewtonFailure

__all__ = ["BODIES", "Body", "Floor", "Plate", "Sets", "Tied", "bodies", "reported"]

_NONE = np.zeros(0, int)


@dataclass(frozen=True, eq=False)
class Sets:
    """What the bodies keep from one converged load to the next, by name: the plate's
    ``active`` contact unknowns and its ``grip`` anchors, the tie's ``engaged`` nodes, a new
    body's own entries. A name not there: nothing yet (the body starts afresh)."""

    states: dict = field(default_factory=dict)

    def get(self, name: str, default=None):
        return self.states.get(name, default)

    def replace(self, **states) -> "Sets":
        """These sets with ``states`` in place of their entries."""
        return Sets({**self.states, **states})

    def same(self, other: "Sets") -> bool:
        """Whether every set of ``self`` and ``other`` is the same (arrays element by element;
        an absent array is an empty one)."""
        for name in self.states.keys() | other.states.keys():
            a, b = self.states.get(name), other.states.get(name)
            if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
                if not np.array_equal(_NONE if a is None else a, _NONE if b is None else b):
                    return False
            elif a is not b:
                return False
        return True


class Body(Protocol):
    """One body's part in a Newton solve; its set is its own state. A body class is built by
    ``of(model, load, x, sets, settings, warm)`` (None where the load or the model has no such
    body; ``warm``: the sets of a factorisation the solve starts from, or None)."""

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
        """Update its set from the residual ``r``, or from ``reaction(dofs)``: −r at those
        unknowns, or its linearisation where the solve has one (so a push down, the plate's,
        is > 0; a push up, the floor's, < 0); whether it changed."""

    def key(self) -> bytes:
        """Its set, hashable (the solve's cycle and stall checks)."""

    def close(self, x) -> None:
        """The solve converged at x: keep what the next load starts from."""

    def state(self) -> dict:
        """Its entries of :class:`Sets`."""

    @classmethod
    def report(cls, model, sets: Sets, r) -> dict:
        """What a recorded point shows of this body from the sets and the residual ``r``:
        forces by name (N, whole part); the plate's and the tie's are the record's own."""


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

    @classmethod
    def of(cls, model, load: Load, x, sets: Sets, settings, warm: Sets | None):
        if load.plate is None:
            return None
        return cls(model, load, x, sets.get("active"), sets.get("grip"), settings,
                   None if warm is None else warm.get("active"))

    def state(self) -> dict:
        return {"active": self.active, "grip": self.grip}

    @classmethod
    def report(cls, model, sets: Sets, r) -> dict:
        return {}  # the record's force, area and shear

    def constraints(self, x) -> Constraints:
        m, n = self.model, len(self.model.fixed)
        presc = np.asarray(self.active, int)
        if self.curved and presc.size:
            return self.lean(x, presc)
        if self.curved and self.grip is not None:
            self.grip = release(m, self.grip, presc)
        jump = jumps(m, x, self.load.plate, presc)
        if self.grip is not None:  # the anchored nodes still on the plate do not slide
            self.grip = release(m, self.grip, presc)
            held, moved = stuck(self.grip, x)
            presc, jump = np.concatenate([presc, held]), np.concatenate([jump, moved])
        return Constraints(n, presc, jump, _NONE, np.zeros(0), -1)

    def lean(self, x, active) -> Constraints:
        """Under a curved indenter the active heights lean on their lateral unknowns
        (:mod:`.leaning`); on a sticking one (``load.stick``) a node anchored at an earlier
        load is carried with the body instead: its lateral unknowns held at their anchors
        and its height prescribed onto the body's surface over them (the body only
        translates, so a stuck point keeps its place on it)."""
        m, n = self.model, len(self.model.fixed)
        held, moved, carried = _NONE, np.zeros(0), np.zeros(len(active), bool)
        if self.grip is not None:
            self.grip = release(m, self.grip, active)
            held, moved = stuck(self.grip, x)
            lat = lateral(m, active)
            anchored = np.where(lat >= 0, ~np.isnan(self.grip.anchor[np.maximum(lat, 0)]),
                                True)
            carried = np.all(anchored, axis=0) & np.any(lat >= 0, axis=0)
        parts = []
        if np.any(carried):
            at = x.copy()
            at[held] = self.grip.anchor[held]
            on = active[carried]
            if not np.all(np.isfinite(surface(m, at, on, self.load.indenter)[0])):
                raise NewtonFailure("a stuck node lies beyond the indenter's equator")
            parts.append(Constraints(n, np.concatenate([on, held]), np.concatenate(
                [jumps(m, at, self.load.plate, on, self.load.indenter), moved]),
                _NONE, np.zeros(0), -1))
        free = active[~carried]
        if free.size:
            S, dS, d2S, lat = surface(m, x, free, self.load.indenter)
            if not np.all(np.isfinite(S)):
                raise NewtonFailure("a node on the indenter passed beyond its equator (the "
                                    "body has no lower surface there)")
            ljump = jumps(m, x, self.load.plate, free, self.load.indenter)
            parts.append(Constraints(n, _NONE, np.zeros(0), _NONE, np.zeros(0), -1, free,
                                     ljump, lat, dS, d2S))
        return Constraints.join(n, parts)

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

    @classmethod
    def of(cls, model, load: Load, x, sets: Sets, settings, warm: Sets | None):
        if model.tie is None:
            return None
        return cls(model.tie, sets.get("engaged"), len(model.fixed))

    def state(self) -> dict:
        return {"engaged": self.engaged}

    @classmethod
    def report(cls, model, sets: Sets, r) -> dict:
        return {}  # the record's insert force

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


class Floor:
    """The rigid base under the cavity, frictionless: the discretisation's ``floor`` surface
    (a :class:`~.surface.ContactSurface` of the cavity wall's vertical unknowns, its
    ``height`` measured from the base) stays at or above it. Exact like the plate: an active
    unknown's height is prescribed at the base, its reaction r_a ≥ 0 pushes up, and it is
    released when that pulls; an inactive one below the base by more than the contact
    tolerance is taken in."""

    plain = True
    warm = True

    def __init__(self, model, x, active, settings, warm_active=None):
        self.model, self.on = model, model.floor
        self.active = warm_active if warm_active is not None else started(
            self.on.dofs, active, lambda d: self.heights(x, d) < -settings.contact_tolerance,
            settings)

    @classmethod
    def of(cls, model, load: Load, x, sets: Sets, settings, warm: Sets | None):
        if model.floor is None:
            return None
        return cls(model, x, sets.get("floor"), settings,
                   None if warm is None else warm.get("floor"))

    def heights(self, x, dofs) -> np.ndarray:
        """Each unknown's height above the base at the state x (mm)."""
        return self.on.height[dofs] + x[dofs]

    def constraints(self, x) -> Constraints:
        return Constraints(len(self.model.fixed), self.active, -self.heights(x, self.active),
                           _NONE, np.zeros(0), -1)

    def pushing(self) -> np.ndarray:
        return self.active

    def update(self, x, r, reaction, force_tol, gap_tol) -> bool:
        # ``reaction`` is the plate's, down > 0: the base pushes up
        new = stepped(self.on.dofs, self.active, -reaction(self.active),
                      lambda d: self.heights(x, d) < -gap_tol, force_tol)
        if new is None:
            return False
        self.active = new
        return True

    def key(self) -> bytes:
        return self.active.tobytes()

    def close(self, x) -> None:
        """The active set is all the next load starts from."""

    def state(self) -> dict:
        return {"floor": self.active}

    @classmethod
    def report(cls, model, sets: Sets, r) -> dict:
        """The base's force on the cavity wall (N, whole part; 0 where nothing touches)."""
        if model.floor is None:
            return {}
        active = sets.get("floor", _NONE)
        return {"floor": float(np.asarray(r)[active].sum()) * model.symmetry}


#: the bodies a Newton solve may hold, in the order their constraints are joined
BODIES = (Plate, Tied, Floor)


def reported(model, sets: Sets, r) -> dict:
    """What the bodies add to a recorded point (:meth:`Body.report`)."""
    out = {}
    for kind in BODIES:
        out.update(kind.report(model, sets, r))
    return out


def bodies(model, load: Load, x, sets: Sets, settings, warm: Sets | None = None) -> list:
    """The bodies of one solve of ``load`` from the state x and the ``sets`` given."""
    out = (kind.of(model, load, x, sets, settings, warm) for kind in BODIES)
    return [b for b in out if b is not None]
