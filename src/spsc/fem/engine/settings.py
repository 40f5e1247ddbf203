"""Newton and step control of the engine (:func:`~spsc.fem.engine.walk.solve`).

The defaults are the 3D solid's; a discretisation states its own through
``default_settings()``.
The fields below the first block are the choices where the two discretisations' Newton methods
differ: each keeps its own so that no curve changes (:mod:`spsc.fem.engine`).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Settings", "SEMISMOOTH_CONTACT", "PART_CONTACT"]

_CHOICES = {"search": ("residual", "admissible"), "active_set": ("equilibrium", "semismooth"),
            "scale": ("initial", "running"), "gas_shift": ("full", "constrained")}


@dataclass(frozen=True)
class Settings:
    """Newton and step control.

    rtol : residual against the load's force scale; max_iterations : Newton iterations per
    load; min_fraction : smallest increment as a fraction of the nominal one; line_search :
    damp the Newton step (else full steps); solver : sparse solver
    (:func:`spsc.fem.engine.linsolve.factorize`); contact_tolerance : penetration that
    activates a contact node (mm); active_set_update : the active set is updated once the
    residual is below this fraction of the force scale (1e-1 took fewer iterations than 1e-3
    on the 3D Type B; earlier updates chatter); softening : a plate-force drop between recorded
    points larger than this fraction is reported as negative stiffness (smaller dips are
    contact discretisation wiggles).

    The per-discretisation choices (3D solid / wall model):

    search : ``"residual"`` backtracks on the residual norm (α = 1, ½, … 5 trials, the full
    step's evaluation reused) / ``"admissible"`` takes the largest α = 1, ½, … (8 trials)
    that inverts no element (the condensed mixed form's residual is no merit function);
    active_set : ``"equilibrium"`` updates the plate's primal–dual active set near
    equilibrium from the residual's reactions and iterates again on the new set /
    ``"semismooth"`` starts from the nodes past the plate, updates from the last step's
    linearised reactions (its multipliers) at every iteration — from the residual's once it
    has changed ten times — and steps on the new set at once;
    max_active_changes : active-set changes before the load fails (30 / 40);
    scale : the force scale of the convergence test, ``"initial"`` the first iterate's load,
    support reactions and out-of-balance force / ``"running"`` the largest over the
    iterations of the load, support and plate reactions;
    fresh_inertia : when the last factorised tangent was on another constraint set than the
    converged state's, factorise that one for the stability check (the wall) instead of
    reporting the inertia unknown (the 3D solid: a factorisation costs an iteration);
    predictor : the secant predictor from the last two accepted states of a ramp (retried
    from the last state if it fails); gas_shift : gᵀs, the gas's share of a step's
    prescribed jumps s, summed over every unknown (``"full"``) or over the constrained ones
    (``"constrained"``): one number, rounded differently.

    modified_newton : after a full Newton step from a residual below this fraction of the
    force scale on a settled constraint set, the next iterations evaluate the residual alone
    and solve with the last factorisation while each shrinks the residual at least 4× (the
    tail of a load, where the tangent barely changes; 0: always full Newton). Needs the
    discretisation's ``reuse``.

    snap_through : a press that reaches an unstable equilibrium follows the wall's jump to
    the stable one at the same plate position and goes on (:mod:`.snap`) instead of stopping
    there; the onset is located between the last stable and the first unstable increment by
    ``snap_bisections`` halvings. Needs the inertia of every converged state
    (``fresh_inertia``).

    warm_start : a press's load starts on the last load's active set with a step on its last
    factorisation (a modified Newton step: the linearised response to the plate's advance), and
    the semi-smooth update takes that step's reactions and penetrations: where the secant
    prediction alone put every node past the plate into the first set and releasing the
    surplus took a factorisation each (the 3D chamber curve, Type B Table 1: 38 -> 34
    factorisations, the curve within 4e-11; the wall's stadium 64 -> 59 but 106 -> 116
    iterations, no faster: the wall keeps it off and its curves bit for bit).

    onset_fraction : the first increment of a press from first contact, as a fraction of the
    nominal one; regrow_after : increments solved after a cut before the increment doubles
    again (1: after each). A printed part meets the plate on sharp edges (the fingertip's pads
    and pockets): there the full first increment, and each doubling back to it, inverted
    elements and failed after several factorisations each (:data:`PART_CONTACT`).

    low_rank : when the plate's active set changes by at most this many unknowns, the last
    factorisation is updated for them (:mod:`.lowrank`, Sherman–Morrison–Woodbury: one
    2k-column solve, the inertia by Haynsworth's additivity) instead of a new one, and the
    step on the new set is a modified Newton step (0: never). The tail of a load's set
    changes is a few nodes (162 -> 160 -> …): on the Type B Table 1 curve 16 takes 34 -> 24
    factorisations at 56 instead of 54 iterations, the curve within 3e-9; 64 took 13 but 69
    iterations and was slower.

    stick_increment : the longest plate travel (mm) of one increment on a sticking plate
    (:mod:`.friction`): a node is held from the end of the increment it touched in, an
    error of first order in the increment (``bench/bench_friction.py``).
    """

    rtol: float = 1e-8
    max_iterations: int = 25
    min_fraction: float = 1.0 / 64
    line_search: bool = True
    solver: str = "auto"
    contact_tolerance: float = 1e-6
    active_set_update: float = 1e-1
    softening: float = 1e-2
    search: str = "residual"
    active_set: str = "equilibrium"
    max_active_changes: int = 30
    scale: str = "initial"
    fresh_inertia: bool = False
    predictor: bool = False
    gas_shift: str = "full"
    snap_through: bool = False
    snap_bisections: int = 5
    modified_newton: float = 1e-2
    stick_increment: float = 0.05
    warm_start: bool = False
    onset_fraction: float = 1.0
    low_rank: int = 0
    regrow_after: int = 1

    def __post_init__(self):
        for name, allowed in _CHOICES.items():
            if getattr(self, name) not in allowed:
                raise ValueError(f"{name} = {getattr(self, name)!r}: one of {allowed}")
        if not 0.0 < self.onset_fraction <= 1.0:
            raise ValueError(f"onset_fraction = {self.onset_fraction!r}: a fraction in (0, 1]")
        for name, least in (("regrow_after", 1), ("low_rank", 0)):
            value = getattr(self, name)
            if int(value) != value or value < least:
                raise ValueError(f"{name} = {value!r}: a whole number ≥ {least}")

    @property
    def semismooth(self) -> bool:
        return self.active_set == "semismooth"


#: the plate's contact as the wall model walks it: each increment from the secant prediction of
#: the last two states, the active set updated at every iteration from the step's linearised
#: reactions (1e-2 of the scale before the first; 40 changes); the 3D chamber curve takes it too
SEMISMOOTH_CONTACT = dict(predictor=True, active_set="semismooth", active_set_update=1e-2,
                          max_active_changes=40)

#: a printed part's press (:mod:`spsc.fem.part`): the chamber curve's semi-smooth contact from
#: the last load's factorisation, updated for small set changes; the first increment from first
#: contact an eighth of the nominal one, and an increment doubled only after two solved at its
#: length since the last cut. The fingertip's pulp at 40 kPa (169k unknowns) against the
#: engine's defaults: 74 -> 39 factorisations, 404 -> 274 s (338 s without the updates; the
#: walk had cut the onset 1 -> 1/8 after several failed factorisations, and failed at each
#: doubling back to the full increment after); the curve within 3e-9
PART_CONTACT = dict(SEMISMOOTH_CONTACT, warm_start=True, low_rank=16, onset_fraction=1 / 8,
                    regrow_after=2)
