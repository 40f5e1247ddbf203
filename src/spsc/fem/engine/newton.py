"""One load solved by Newton's method: r(x) = 0 with the plate's active set and the tie's
engaged set, one line search and the stability check of the converged state.

Each iteration: the constraints of the current sets (the plate's jumps, the tie's aliasing),
the residual and its force scale, the active-set update (``settings.active_set``), the
convergence test — the free displacements' residual below rtol × scale with every constraint
holding (and the discretisation's other equations, :meth:`pressure_error`) — and otherwise the
constrained step (:mod:`.linear`) and its line search (:mod:`.search`). The converged state
carries the number of negative eigenvalues of its tangent on its own constraint set (the last
factorisation's, or a fresh one with ``settings.fresh_inertia``): > 0 is an unstable
equilibrium.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .bodies import Sets, bodies
from .constraints import Constraints, Masked, constraint_key
from .restrict import restriction
from .friction import Grip
from .linear import gas_vector, inertia, linear_step
from .linsolve import FULL_INPUT
from .lowrank import updated
from .result import NewtonFailure
from .search import line_search
from .settings import Settings
from .load import Load

__all__ = ["Converged", "Warm", "newton"]

_NONE = np.zeros(0, int)

#: the semi-smooth strategy takes the linearised reactions until the set changed this often
_MULTIPLIER_CHANGES = 10

#: modified Newton goes on while each step shrinks the residual at least this much
_CONTRACTION = 0.25

#: returns to a set met before, without progress, that end a load (:meth:`_Newton.cycles`)
_RETURNS = 2

#: iterations on one constraint set without halving the residual that end a load
#: (:meth:`_Newton.stuck`)
_STUCK = 10

#: the incompressibility's error (J − 1 − p/κ, an element's mean) accepted once Newton is
#: stuck with the forces and the constraints already met: its round-off floor in elements
#: stretched eightfold and thinned sixtyfold (a membrane pinched under a sharp probe, 2e-12
#: there) lies above the 1e-3 rtol asked of it otherwise
_VOLUME_FLOOR = 1e-9


@dataclass(frozen=True, eq=False)
class Converged:
    """A converged load: the state x, where its bodies stand (:class:`~.bodies.Sets`: the
    plate's active contact unknowns and, on a sticking plate, the anchors of its stuck
    lateral unknowns; the tie's engaged nodes), Newton iterations, the evaluation at x (with
    tangent), the negative eigenvalues of the displacement problem there (None: unknown) and
    the factorisation the next load may start from."""

    x: np.ndarray
    sets: Sets
    iterations: int
    evaluation: object
    unstable_modes: int | None
    warm: "Warm | None" = None

    @property
    def active(self) -> np.ndarray:
        """The plate's active contact unknowns (none without a plate)."""
        return self.sets.get("active", _NONE)

    @property
    def engaged(self) -> np.ndarray:
        """The tie's engaged nodes (none without a tie)."""
        return self.sets.get("engaged", _NONE)

    @property
    def grip(self) -> Grip | None:
        """A sticking plate's anchors (None: frictionless)."""
        return self.sets.get("grip")

    def with_tangent(self, model, load: Load) -> "Converged":
        """This state with an evaluation that carries its tangent (a modified Newton
        iteration converges on the residual alone)."""
        if self.evaluation.K is not None:
            return self
        return dataclasses.replace(self, evaluation=model.evaluate(self.x, load))


@dataclass(frozen=True, eq=False)
class Warm:
    """The last factorisation of a converged load, on its constraint set: the next load's
    first step (``settings.warm_start``). ``evaluation`` carries the tangent it factorised,
    ``restriction`` that set's restriction of it, ``sets`` the bodies' sets."""

    factor: object
    evaluation: object
    restriction: object
    sets: Sets

    def fits(self, sets: Sets) -> bool:
        """Whether a load starting from ``sets`` can take it (and it can still solve)."""
        return self.factor.current() and self.sets.same(sets)


class _Newton:
    """The state of one Newton solve between iterations."""

    def __init__(self, model, load: Load, settings: Settings, x0, sets: Sets | None = None,
                 warm: Warm | None = None):
        self.model, self.load, self.s = model, load, settings
        self.x = x0.copy()
        sets = sets or Sets()
        warm = warm if settings.warm_start and load.plate is not None and warm is not None \
            and warm.fits(sets) else None
        #: the bodies that constrain this solve (:mod:`.bodies`), each with its own set; on
        #: a warm start they start on the factorised set
        self.bodies = bodies(model, load, self.x, sets, settings,
                             None if warm is None else warm.sets)
        if warm is not None and not all(b.warm for b in self.bodies):
            warm = None  # a sticking plate or a curved body: afresh
            self.bodies = bodies(model, load, self.x, sets, settings)
        self.scale, self.res, self.changes = 0.0, np.inf, 0
        #: the sets entered after the multipliers' changes, with the least residual there,
        #: and the returns to one of them without progress (:meth:`cycles`)
        self.visits, self.returns = {}, 0
        #: (sets, residual) of each iteration (:meth:`stuck`)
        self.trail = []
        self.lam = self.lam_dofs = self.carried = self.restriction = self.factored = \
            self.modes = None
        #: modified Newton: the last factorisation, the evaluation it was made from, and
        #: whether the next iteration reuses it (``settings.modified_newton``)
        self.factor = self.tangent_ev = None
        self.cheap = False
        if warm is not None:  # the first step on the last load's set and factorisation
            self.factor, self.tangent_ev, self.restriction = warm.factor, warm.evaluation, \
                warm.restriction
            self.cheap = True
        #: the last tangent factorised had negative eigenvalues: the next one skips
        #: ``pardiso-spd``'s Cholesky attempt, which would fail (10 of 14 ms, stop 44)
        self.indefinite = False

    def sets(self) -> Sets:
        """Where the bodies stand now."""
        out = {}
        for body in self.bodies:
            out.update(body.state())
        return Sets(out)

    def linear(self) -> Settings:
        """The settings of the next factorisation: LDLᵀ at once after an indefinite one."""
        if self.indefinite and self.s.solver == "pardiso-spd":
            return dataclasses.replace(self.s, solver="pardiso")
        return self.s

    def evaluate(self):
        """The evaluation at x: the line search's, the residual alone for a modified Newton
        step, or residual and tangent."""
        ev, self.carried = self.carried, None
        return ev if ev is not None else self.model.evaluate(self.x, self.load,
                                                             tangent=not self.cheap)

    def full(self, ev):
        """ev with its tangent: modified Newton ends here."""
        self.cheap = False
        return ev if ev.K is not None else self.model.evaluate(self.x, self.load)

    def refit(self, ev):
        """After the constraint set changed: ev with its tangent (a new factorisation
        follows), or, where at most ``settings.low_rank`` unknowns changed, ev alone with the
        last factorisation updated for them (:mod:`.lowrank`; a modified Newton step)."""
        if self.s.low_rank and self.factor is not None and self.tangent_ev is not None \
                and all(b.plain for b in self.bodies) and isinstance(self.restriction, Masked):
            con, free = self.constrain()
            old = self.restriction
            if np.setxor1d(np.flatnonzero(old.index)[old.held], con.presc).size \
                    > self.s.low_rank:  # decided before the new restriction is built
                return self.full(ev)
            K = self.tangent_ev.K
            new = restriction(K, free, con, self.s.solver in FULL_INPUT,
                              self.model.system_residual(self.tangent_ev))
            factor = updated(self.factor, self.restriction, new, K, self.s.low_rank)
            if factor is not None:
                self.restriction, self.factor, self.cheap = new, factor, True
                gc = new.take(con.condense(gas_vector(self.model, self.tangent_ev, con.n)))
                self.factored = new.key
                self.modes = None if factor.negative is None else \
                    self.model.unstable_modes(factor, self.tangent_ev.c, gc)
                return ev if ev.K is None else dataclasses.replace(ev, K=None)
        return self.full(ev)

    def constrain(self):
        """(Constraints, free mask) of the bodies' sets at x."""
        n = len(self.model.fixed)
        con = Constraints.join(n, [b.constraints(self.x) for b in self.bodies])
        return con, con.free(self.model.fixed)

    def measure(self, ev, rt, free) -> None:
        """The force scale (``settings.scale``) and the free displacements' residual (N)."""
        m, n_u = self.model, self.model.n_u
        self.res = float(np.linalg.norm(rt[:n_u][free[:n_u]]))
        loads = (np.linalg.norm(ev.pressure * ev.g), np.linalg.norm(ev.r[:n_u][m.fixed[:n_u]]),
                 np.linalg.norm(ev.r[self.pushing()]), m.force_floor)
        if self.s.scale == "running":
            self.scale = max(self.scale, *loads)
        elif self.scale <= m.force_floor:
            # the first iterate that carries a load; a vented press starts from none (no
            # pressure, the plate just touching): its force is the plate's reactions once the
            # state moves, and a scale left at the floor asked for a residual of 1e-14 N
            self.scale = max(*loads, self.res)

    def pushing(self) -> np.ndarray:
        """The unknowns whose reactions count in the force scale: the bodies'."""
        parts = [b.pushing() for b in self.bodies]
        return parts[0] if len(parts) == 1 else np.concatenate(parts) if parts \
            else np.zeros(0, int)

    def near(self, it, con, converged) -> bool:
        """Whether the active sets are updated in this iteration."""
        if not (con.nearly_settled(self.s.contact_tolerance) and it > 1):
            return False
        if self.s.semismooth:
            return bool(self.bodies) and (
                self.lam is not None or self.res <= self.s.active_set_update * self.scale)
        return converged or self.res <= self.s.active_set_update * self.scale

    def update(self, ev) -> bool:
        """Update each body's set (the plate's active set, the tie's engaged set); whether
        any changed."""
        s, changed = self.s, False
        tol = s.rtol * self.scale
        reaction = self.reaction(ev)
        for body in self.bodies:
            changed = body.update(self.x, ev.r, reaction, tol, s.contact_tolerance) or changed
        if changed:
            self.changes += 1
            if self.changes > s.max_active_changes:
                raise NewtonFailure("the contact active set does not settle")
            if self.cycles():
                raise NewtonFailure(f"the contact active set cycles: back to earlier sets "
                                    f"without progress (residual {self.res:.3g} N against "
                                    f"{tol:.3g} N)")
        return changed

    def reaction(self, ev):
        """``reaction(dofs)``: the constrained unknowns' reactions (N, pushing > 0): the last
        step's linearised ones under the semi-smooth strategy, else the residual's."""
        if self.s.semismooth and self.lam is not None:
            at = np.zeros(len(self.model.fixed))
            at[self.lam_dofs] = self.lam
            return lambda dofs: at[dofs]
        return lambda dofs: -ev.r[dofs]

    def keys(self) -> tuple:
        """The bodies' sets, hashable."""
        return tuple(b.key() for b in self.bodies)

    def cycles(self) -> bool:
        """Whether the sets just entered close a cycle that makes no progress: once the
        reactions are the residual's (after ``_MULTIPLIER_CHANGES``), a second return to sets
        met before in this load with a residual not below half of what it was there. The
        reactions and the next set are functions of a state that repeats: the load would
        spend its remaining iterations in the cycle and fail. Seen where the wall turns
        unstable: a node at the plate's edge pulls as active and penetrates as free (A, B, A,
        …; 20 of the 29 failed loads of the Table 1 Type C wall curve at 30 kPa with the
        reservoir), or a ring released and taken back (69, 94, 88, 81, 76, 73, 69, … nodes;
        Type B at 10 kPa with the reservoir), 25 iterations each."""
        key = self.keys()
        if self.changes > _MULTIPLIER_CHANGES:
            before = self.visits.get(key)
            if before is not None and self.res > 0.5 * before:
                self.returns += 1
            self.visits[key] = self.res if before is None else min(before, self.res)
        return self.returns >= _RETURNS

    def stuck(self) -> bool:
        """Whether the last ``_STUCK`` iterations stayed on one constraint set without halving
        the residual: Newton on a fixed set that far from a solution is not converging (the
        admissible line search takes ever shorter steps; where the wall turns unstable a load
        spent 25 iterations there at 1-10 times the force scale, and none that converged
        did)."""
        key = self.keys()
        self.trail = (self.trail + [(key, self.res)])[-(_STUCK + 1):]
        if len(self.trail) <= _STUCK:
            return False
        (k0, r0), last = self.trail[0], self.trail[1:]
        return all(k == k0 for k, _ in last) and min(r for _, r in last) > 0.5 * r0

    def step(self, ev, con, free, rt) -> None:
        """The constrained Newton step and its line search; x moves. Without ev's tangent
        (modified Newton) the last factorisation, on the same constraint set, is reused."""
        key = constraint_key(free, con.slaves, con.lean)
        wanted = self.s.semismooth and self.changes < _MULTIPLIER_CHANGES
        if ev.K is None:
            st = linear_step(self.model, self.model.reuse(ev, self.tangent_ev),
                             self.restriction, free, con, self.s, multipliers=wanted,
                             factor=self.factor)
            self.lam, self.lam_dofs = st.multipliers, con.reacting
        else:
            if self.restriction is None or self.restriction.key != key:
                self.restriction = restriction(ev.K, free, con, self.s.solver in FULL_INPUT,
                                               self.model.system_residual(ev))
            elif con.lean.size:  # the slopes move with the nodes
                self.restriction.bind(con, self.model.system_residual(ev))
            st = linear_step(self.model, ev, self.restriction, free, con, self.linear(),
                             multipliers=wanted)
            self.indefinite = bool(st.factor.negative)
            self.factored, self.modes, self.lam = st.key, st.unstable_modes, st.multipliers
            self.lam_dofs = con.reacting
            self.factor, self.tangent_ev = st.factor, ev
            # a curved indenter's slopes change every iteration: no stale factorisation
            self.cheap = con.settled and self.res <= self.s.modified_newton * self.scale \
                and not con.lean.size
        alpha, self.carried = line_search(self.model, self.x, st.dx, free, self.load, con, rt,
                                          self.s, tangent=not self.cheap)
        self.x += alpha * st.dx

    def converged(self, it, ev, con, free) -> Converged:
        """The converged state with the inertia of its tangent on its own constraint set."""
        key = constraint_key(free, con.slaves, con.lean)
        modes = self.modes if self.factored == key else None
        for body in self.bodies:
            body.close(self.x)
        sets = self.sets()
        warm = None
        if self.factored == key and self.factor is not None:
            warm = Warm(self.factor, self.tangent_ev, self.restriction, sets)
        elif self.s.fresh_inertia:
            ev = self.full(ev)
            red = restriction(ev.K, free, con, self.s.solver in FULL_INPUT,
                              self.model.system_residual(ev))
            gc = red.take(con.condense(gas_vector(self.model, ev, con.n)))
            modes, factor = inertia(self.model, red, ev, gc, self.linear())
            warm = Warm(factor, ev, red, sets)
        return Converged(self.x, sets, it, ev, modes, warm if not con.lean.size else None)


def newton(model, x0, load: Load, settings: Settings, sets: Sets | None = None,
           warm: Warm | None = None) -> Converged:
    """Solve r(x) = 0 from ``x0`` for one ``load``, its bodies starting from ``sets``
    (:class:`~.bodies.Sets`: the plate's active contact unknowns, the tie's engaged nodes, on a
    sticking plate (``load.stick``) the anchors of what touched; None: none yet); the
    converged state's sets also anchor the nodes that touched in this load
    (:mod:`.friction`). ``warm``: the last load's factorisation (:class:`Warm`), its first
    step under ``settings.warm_start``. Raises :class:`NewtonFailure` with the reason when it
    does not converge."""
    nw = _Newton(model, load, settings, x0, sets, warm)
    for it in range(1, settings.max_iterations + 1):
        con, free = nw.constrain()
        ev = nw.evaluate()
        if not np.all(np.isfinite(ev.r)):
            raise NewtonFailure("non-finite residual")
        rt = con.condense(ev.r)
        before = nw.res
        nw.measure(ev, rt, free)
        stuck = nw.stuck()
        converged = con.settled and it > 1 and nw.res <= settings.rtol * nw.scale \
            and model.pressure_error(ev) <= (_VOLUME_FLOOR if stuck else 1e-3 * settings.rtol)
        if stuck and not converged:
            off = max(np.max(np.abs(con.jump), initial=0.0),
                      np.max(np.abs(con.sjump), initial=0.0),
                      np.max(np.abs(con.ljump), initial=0.0))
            raise NewtonFailure(f"no progress in {_STUCK} iterations on one constraint set "
                                f"(residual {nw.res:.3g} N against "
                                f"{settings.rtol * nw.scale:.3g} N; constraints off by "
                                f"{off:.3g} mm against 1e-12; volume error "
                                f"{model.pressure_error(ev):.3g} against "
                                f"{1e-3 * settings.rtol:.3g})")
        if ev.K is None and not converged and nw.res > _CONTRACTION * before:
            ev = nw.full(ev)  # the old tangent no longer contracts enough
        if nw.near(it, con, converged) and nw.update(ev):
            ev = nw.refit(ev)  # a new constraint set: a new or an updated factorisation
            if not settings.semismooth:
                nw.carried = ev  # x is unchanged: its evaluation stands
                continue
            con, free = nw.constrain()  # step on the new set at once
            rt = con.condense(ev.r)
            nw.res = float(np.linalg.norm(rt[:model.n_u][free[:model.n_u]]))
        elif converged:
            return nw.converged(it, ev, con, free)
        nw.step(ev, con, free, rt)
    raise NewtonFailure(f"no convergence in {settings.max_iterations} iterations (residual "
                        f"{nw.res:.3g} N against {settings.rtol * nw.scale:.3g} N)")
