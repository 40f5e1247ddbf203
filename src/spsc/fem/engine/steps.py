"""The load path as data: the steps a solve walks and the load of one equilibrium.

:class:`Inflate` ramps a prescribed cavity pressure, :class:`CloseValve` traps the gas (from
then on the pressure follows the cavity volume, P·(V + V_r)ⁿ = const, eqs. 2, 6–7 of the
paper) and :class:`Press` lowers a rigid frictionless plate from first contact. A
:class:`Load` is what one Newton solve holds fixed: the pressure (or the gas law) and the
plate's height.

A step is any object with ``increments`` (its recorded points), ``begin(load, volume)`` (the
load it starts from) and ``path(load, contact_height, settings)`` (a :class:`Path`, or None
for a step that records nothing): the walk asks nothing else of it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Protocol

import numpy as np

from spsc.core.constants import P_AMB, to_MPa
from spsc.core.errors import ParameterError
from spsc.core.gaslaw import GasLaw

from .coulomb import Coulomb
from .load import Load
from .spring import Spring

__all__ = ["Inflate", "CloseValve", "SwitchValve", "Press", "Cycle", "Load", "Path",
           "IncrementSolver", "load_steps"]


@dataclass(frozen=True)
class Path:
    """How a step loads the model from the walk's state: what the walk needs to ramp it.

    ``load_at(t)``: the load at the step's parameter t; ``targets``: the recorded t;
    ``kind``: ``"inflate"`` or ``"press"`` (the records' kind); ``travel_at(t)``: the plate's
    travel (mm from first contact; None for an inflation); ``at_travel(y)``: the load with the
    indenter at travel y; ``solver``: how an increment is solved when one Newton solve is not
    enough (:class:`IncrementSolver`: the compliant object's balance, :class:`~.spring.Spring`;
    the Coulomb return mapping, :class:`~.coulomb.Coulomb`; None: one Newton solve);
    ``span``: the largest increment of t (None: the targets' own spacing)."""

    load_at: Callable
    kind: str
    targets: list
    travel_at: Callable | None = None
    at_travel: Callable | None = None
    solver: "IncrementSolver | None" = None
    span: float | None = None

    @property
    def follows_snaps(self) -> bool:
        """A press followed through its snap-throughs: one whose increments are Newton solves
        or whose solver follows them (the spring's balance and the Coulomb loop do not)."""
        return self.kind == "press" and (self.solver is None or self.solver.follows_snaps)


class IncrementSolver(Protocol):
    """How one increment of a :class:`Path` is solved where one Newton solve is not enough:
    an outer loop around :func:`~.newton.newton` (the compliant object's balance, the Coulomb
    return mapping). The walk asks nothing else of it, so a new loop is one class."""

    #: the walk follows a snap-through of this path (:meth:`~.walk._Walk.snap`)
    follows_snaps: bool

    def solve(self, walk, path: "Path", trial: Load, t: float, history: list):
        """(converged solution, its load) of the ``trial`` load at the path's parameter
        ``t``, from ``walk``'s state (its ``model``, settings ``s``, state ``x`` and the
        bodies' ``sets``, :class:`~.bodies.Sets`); ``history``: the (t, x) solved since the
        last jump."""

    def accept(self) -> None:
        """The walk took the last solution: the solver's own state moves on."""

    def annotate(self, record):
        """A recorded point with what the solver adds to it (:class:`~.result.Record`)."""


class _Ramp:
    """A step that ramps a load from the current one: it begins where the last ended."""

    def begin(self, load: Load, volume: Callable) -> Load:
        return load


@dataclass(frozen=True)
class Inflate(_Ramp):
    """Ramp the cavity gauge pressure to ``pressure`` (MPa) in ``increments``."""

    pressure: float
    increments: int = 4

    @classmethod
    def kPa(cls, pressure_kPa: float, increments: int = 4) -> "Inflate":
        """Inflate to a load case's gauge pressure ``pressure_kPa`` (kPa)."""
        return cls(to_MPa(pressure_kPa), increments)

    def targets(self) -> list:
        """The recorded load parameters t ∈ (0, 1] (fractions of the ramp)."""
        nominal = 1.0 / self.increments
        return [(i + 1) * nominal for i in range(self.increments)]

    def path(self, load: Load, contact_height: Callable, settings) -> Path:
        """The pressure ramped from the current one to this step's, the plate kept."""
        start, end = load.pressure, float(self.pressure)
        return Path(lambda t: Load(pressure=start + t * (end - start), plate=load.plate,
                                   indenter=load.indenter), "inflate", self.targets())


@dataclass(frozen=True)
class CloseValve:
    """Close the valve: the cavity plus ``reservoir`` (mm³) holds its gas, P·Vⁿ = const."""

    reservoir: float = 0.0
    polytropic_n: float = 1.0
    increments = 0  # no recorded point: the walk only changes its load

    def begin(self, load: Load, volume: Callable) -> Load:
        """The load from here on: the gas at the current pressure and cavity volume
        (``volume()``, mm³) trapped with the reservoir."""
        gas = GasLaw(load.pressure, volume(), self.reservoir, self.polytropic_n)
        return Load(gas=gas, plate=load.plate, indenter=load.indenter)

    def path(self, load: Load, contact_height: Callable, settings) -> None:
        return None


@dataclass(frozen=True)
class SwitchValve:
    """Switch the valve mid-walk (the wall stepped in time, :mod:`spsc.dynamics.wall_time`).
    ``opened``: the cavity's gas and the reservoir's (``reservoir`` mm³ at the gauge pressure
    ``state["pressure"]``, MPa) pooled at once and mixed isothermally, (P_c + Pₐ) V_c +
    (P_r + Pₐ) V_r = (P + Pₐ)(V_c + V_r), then P·Vⁿ = const of the pool — the valve's
    milliseconds are below the walk's steps; closed: the cavity's gas alone from its current
    pressure, the reservoir keeping it (written to ``state``)."""

    opened: bool
    reservoir: float
    polytropic_n: float = 1.0
    state: dict = field(default_factory=dict, compare=False)
    increments = 0  # no recorded point: the walk only changes its load

    def begin(self, load: Load, volume: Callable) -> Load:
        v = volume()
        p = load.cavity_pressure(v)[0]
        pa = load.gas.p_amb if load.gas is not None else P_AMB
        if self.opened:
            pr = float(self.state.get("pressure", p))
            p = ((p + pa) * v + (pr + pa) * self.reservoir) / (v + self.reservoir) - pa
            gas = GasLaw(p, v, self.reservoir, self.polytropic_n)
        else:
            self.state["pressure"] = p
            gas = GasLaw(p, v, 0.0, self.polytropic_n)
        return Load(gas=gas, plate=load.plate, indenter=load.indenter)

    def path(self, load: Load, contact_height: Callable, settings) -> None:
        return None


@dataclass(frozen=True)
class Press(_Ramp):
    """Lower the plate from first contact by ``stroke`` (mm) in ``increments`` recorded points
    (the load parameter t is the fraction of the stroke); or, when ``travel`` is given (see
    :meth:`through`), through those plate travels (mm from first contact, increasing; t is the
    travel itself)."""

    stroke: float
    increments: int = 10
    travel: tuple | None = None
    #: the plate holds every node it touches from sliding (:mod:`.friction`); else frictionless
    stick: bool = False
    #: the indenter's spring (N/mm, :mod:`.spring`): the travel is the spring's far end; None:
    #: the indenter itself follows the travel
    spring: float | None = None
    #: a sticking plate's Coulomb coefficient (:mod:`.coulomb`); None: no slip
    mu: float | None = None
    #: the curved body that presses (:class:`~spsc.core.indenter.Indenter`; frictionless or
    #: sticking); None: the plate
    indenter: object | None = None

    def __post_init__(self):
        if self.indenter is not None and not self.indenter.curved:
            object.__setattr__(self, "indenter", None)
        if self.indenter is not None and self.mu is not None:
            raise ParameterError("friction", self.mu,
                                 f"0 or stick with the indenter {self.indenter.spec} (Coulomb "
                                 "friction on a curved body is not built yet)")

    @classmethod
    def through(cls, travel, *, stick: bool = False, spring: float | None = None,
                mu: float | None = None, indenter=None) -> "Press":
        """Press through the plate travels ``travel`` (mm from first contact, increasing)."""
        travel = tuple(float(v) for v in travel)
        return cls(travel[-1], len(travel), travel, stick, spring, mu, indenter)

    def targets(self) -> list:
        """The recorded load parameters t: fractions of the stroke, or the travels (mm)."""
        if self.travel is not None:
            return list(self.travel)
        nominal = 1.0 / self.increments
        return [(i + 1) * nominal for i in range(self.increments)]

    def travel_at(self, t: float) -> float:
        """The plate travel (mm from first contact) at the load parameter t."""
        return t if self.travel is not None else t * self.stroke

    def parameter_span(self, travel_mm: float) -> float:
        """The load parameter's change over a plate travel of ``travel_mm``."""
        return travel_mm if self.travel is not None else travel_mm / self.stroke

    def path(self, load: Load, contact_height: Callable, settings) -> Path:
        """The indenter lowered from first contact (``contact_height(indenter)``: its tip's
        height there, mm; the plate's height if it already touches) by the step's travel;
        a sticking plate's increments at most ``settings.stick_increment`` of travel (its
        touch-downs are interpolated per increment)."""
        z0 = contact_height(self.indenter) if load.plate is None else load.plate
        if not np.isfinite(z0):
            raise ParameterError("indenter", self.indenter.spec, "a body that meets the "
                                 "model's outer surface (no contact node lies under it: "
                                 "place it with --plate-at, or a larger body)")

        def at_travel(y):
            return Load(load.pressure, load.gas, z0 - y, stick=self.stick,
                        indenter=self.indenter)

        solver = Spring(self.spring) if self.spring else \
            Coulomb(self.mu) if self.mu is not None else None
        return Path(lambda t: at_travel(self.travel_at(t)), "press", self.targets(),
                    self.travel_at, at_travel, solver,
                    self.parameter_span(settings.stick_increment) if self.stick else None)


@dataclass(frozen=True)
class Cycle(_Ramp):
    """Move the plate in time: travel ``travels`` (mm from first contact, any order: down and
    back up) at the instants ``times`` (s, increasing from 0), piecewise linear between them;
    each instant after the first is a recorded point (the load parameter t is the time). For a
    wall with a rate-dependent material (:mod:`spsc.fem.viscous`) the time is the load's.
    ``stick``: the plate holds what it touches; with ``mu`` a Coulomb coefficient, what it
    touches sticks or slips (:mod:`.coulomb`), on the way down and back up."""

    times: tuple
    travels: tuple
    stick: bool = False
    mu: float | None = None
    #: the time (s) of this step's t = 0 on the walk's clock (a cycle cut by valve events)
    start_s: float = 0.0

    def __post_init__(self):
        t = tuple(float(v) for v in self.times)
        if len(t) < 2 or len(t) != len(self.travels) or t[0] != 0.0 or \
                any(b <= a for a, b in zip(t, t[1:])):
            raise ParameterError("cycle times", t, "two or more, from 0, increasing (s), one "
                                 "per travel")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "travels", tuple(float(v) for v in self.travels))
        if self.mu is not None:
            object.__setattr__(self, "stick", True)  # Coulomb starts from a sticking trial

    @property
    def increments(self) -> int:
        return len(self.times) - 1

    def targets(self) -> list:
        return list(self.times[1:])

    def travel_at(self, t: float) -> float:
        return float(np.interp(t, self.times, self.travels))

    def path(self, load: Load, contact_height: Callable, settings) -> Path:
        """The plate moved in time from first contact (the plate's height if it touches)."""
        z0 = contact_height(None) if load.plate is None else load.plate
        span = None
        if self.stick:  # touch-downs interpolated per increment: at most stick_increment
            speed = max(abs(b - a) / (tb - ta) for a, b, ta, tb in
                        zip(self.travels, self.travels[1:], self.times, self.times[1:]))
            span = settings.stick_increment / speed if speed > 0 else None
        return Path(lambda t: Load(load.pressure, load.gas, z0 - self.travel_at(t),
                                   self.start_s + t, self.stick), "press", self.targets(),
                    self.travel_at, solver=None if self.mu is None else Coulomb(self.mu),
                    span=span)


def load_steps(load, inflate_increments: int = 4, *, stick: bool = False,
               spring: float | None = None, mu: float | None = None, indenter=None) -> list:
    """The steps of a load case (:class:`~spsc.core.loadcase.LoadCase`: kPa gauge, mm³, mm):
    inflate to the setup pressure in ``inflate_increments``, close the valve onto the
    reservoir, press the stroke in ``points − 1`` increments (``stick``: with a sticking
    plate, with Coulomb friction ``mu`` if given; ``spring``: the indenter on a spring of that
    stiffness, N/mm; ``indenter``: a curved body instead of the plate); the open chamber
    (p = 0) is pressed alone."""
    out = []
    if load.pressure_kPa > 0:
        out += [Inflate.kPa(load.pressure_kPa, inflate_increments),
                CloseValve(load.reservoir_mm3, load.polytropic_n)]
    return out + [Press(load.stroke_mm, int(load.points) - 1, stick=stick, spring=spring,
                        mu=mu, indenter=indenter)]
