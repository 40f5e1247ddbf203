"""The load path as data: the steps a solve walks and the load of one equilibrium.

:class:`Inflate` ramps a prescribed cavity pressure, :class:`CloseValve` traps the gas (from
then on the pressure follows the cavity volume, P·(V + V_r)ⁿ = const, eqs. 2, 6–7 of the
paper) and :class:`Press` lowers a rigid frictionless plate from first contact. A
:class:`Load` is what one Newton solve holds fixed: the pressure (or the gas law) and the
plate's height.
"""

from __future__ import annotations

from spsc.core.constants import to_MPa
from dataclasses import dataclass

from spsc.core.gaslaw import GasLaw

__all__ = ["Inflate", "CloseValve", "Press", "Cycle", "Load", "load_steps"]


@dataclass(frozen=True)
class Inflate:
    """Ramp the cavity gauge pressure to ``pressure`` (MPa) in ``increments``."""

    pressure: float
    increments: int = 4

    def targets(self) -> list:
        """The recorded load parameters t ∈ (0, 1] (fractions of the ramp)."""
        nominal = 1.0 / self.increments
        return [(i + 1) * nominal for i in range(self.increments)]


@dataclass(frozen=True)
class CloseValve:
    """Close the valve: the cavity plus ``reservoir`` (mm³) holds its gas, P·Vⁿ = const."""

    reservoir: float = 0.0
    polytropic_n: float = 1.0


@dataclass(frozen=True)
class Press:
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
    #: the curved body that presses (:class:`~spsc.core.indenter.Indenter`, frictionless);
    #: None: the plate
    indenter: object | None = None

    def __post_init__(self):
        if self.indenter is not None and not self.indenter.curved:
            object.__setattr__(self, "indenter", None)
        if self.indenter is not None and (self.stick or self.mu is not None):
            from spsc.core.errors import ParameterError

            raise ParameterError("friction", "stick" if self.mu is None else self.mu,
                                 f"0 with the indenter {self.indenter.spec} (friction on a "
                                 "curved body is not built yet)")

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


@dataclass(frozen=True)
class Cycle:
    """Move the plate in time: travel ``travels`` (mm from first contact, any order: down and
    back up) at the instants ``times`` (s, increasing from 0), piecewise linear between them;
    each instant after the first is a recorded point (the load parameter t is the time). For a
    wall with a rate-dependent material (:mod:`spsc.fem.viscous`) the time is the load's."""

    times: tuple
    travels: tuple
    stick: bool = False

    def __post_init__(self):
        from spsc.core.errors import ParameterError

        t = tuple(float(v) for v in self.times)
        if len(t) < 2 or len(t) != len(self.travels) or t[0] != 0.0 or \
                any(b <= a for a, b in zip(t, t[1:])):
            raise ParameterError("cycle times", t, "two or more, from 0, increasing (s), one "
                                 "per travel")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "travels", tuple(float(v) for v in self.travels))

    @property
    def increments(self) -> int:
        return len(self.times) - 1

    def targets(self) -> list:
        return list(self.times[1:])

    def travel_at(self, t: float) -> float:
        import numpy as np

        return float(np.interp(t, self.times, self.travels))


@dataclass(frozen=True)
class Load:
    """Cavity gauge pressure ``pressure`` (MPa) unless ``gas`` is given; rigid plate at height
    ``plate`` (mm, None: no plate); ``time`` (s) of a :class:`Cycle`'s load, None for a load
    at rest (a rate-dependent material is then relaxed); ``stick``: the plate holds what it
    touches from sliding (else it is frictionless); ``indenter``: a curved body whose tip is
    at ``plate`` (:class:`~spsc.core.indenter.Indenter`; None: the plate)."""

    pressure: float = 0.0
    gas: GasLaw | None = None
    plate: float | None = None
    time: float | None = None
    stick: bool = False
    indenter: object | None = None


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
        out += [Inflate(to_MPa(load.pressure_kPa), inflate_increments),
                CloseValve(load.reservoir_mm3, load.polytropic_n)]
    return out + [Press(load.stroke_mm, int(load.points) - 1, stick=stick, spring=spring,
                        mu=mu, indenter=indenter)]
