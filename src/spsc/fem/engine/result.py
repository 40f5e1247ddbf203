"""What a solve returns: one :class:`Record` per converged load point, the :class:`Result` of
the whole walk, and the one failure of a Newton solve, :class:`NewtonFailure`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from spsc.core.constants import to_kPa

__all__ = ["Record", "Result", "Stop", "NewtonFailure"]


class NewtonFailure(RuntimeError):
    """Newton's method did not converge for one load (the reason is the message)."""


@dataclass(frozen=True, eq=False)
class Record:
    """One converged load point: which step, its load, and the measured quantities (mm, N,
    MPa, mm³, mm²; force and area of the full part)."""

    step: int
    kind: str
    x: np.ndarray = field(repr=False)
    pressure: float
    volume: float
    plate: float | None
    force: float
    contact_area: float
    iterations: int
    unstable_modes: int | None = None  # negative eigenvalues of the displacement problem
    #: force (N) through each named contact surface of the model (e.g. an FSR pocket floor)
    group_forces: dict = field(default_factory=dict)
    #: the rigid insert's force (N, ≥ 0: the wall above it pressed onto it; None: no insert)
    insert_force: float | None = None
    #: a sticking plate's tangential reactions, Σ over the contact nodes of their norms (N,
    #: whole part; 0 on a frictionless plate): what friction must carry for no slip
    shear: float = 0.0
    #: the indenter's own travel (mm from first contact) when it rides on a spring (the
    #: press's travel is then the spring's far end); None otherwise
    indenter: float | None = None
    #: what the other bodies carry (:meth:`~.bodies.Body.report`): force by name (N, whole
    #: part), e.g. ``floor``, the base's push on the cavity wall
    bodies: dict = field(default_factory=dict)

    @property
    def pressure_kPa(self) -> float:
        """The cavity gauge pressure in the units of a :class:`~spsc.core.curve.Curve`
        (kPa)."""
        return to_kPa(self.pressure)


@dataclass(frozen=True, eq=False)
class Stop:
    """Where and why a walk stopped early: the ``index`` and ``kind`` ("inflate", "press") of
    its step (``step``, the data), the load parameter ``t`` of the trial load ``load``, and
    either the Newton failure's ``reason`` (after every step cut) or the unstable equilibrium
    ``record`` it reached (negative eigenvalues of its tangent). The properties phrase it."""

    index: int
    kind: str
    t: float
    step: object
    load: object
    reason: str
    record: Record | None = None

    def _where(self, digits: str) -> str:
        if self.kind == "press":
            return f"y = {self.step.travel_at(self.t):{digits}} mm"
        pressure = self.record.pressure if self.record is not None else self.load.pressure
        return f"p = {to_kPa(pressure):{digits}} kPa"

    @property
    def failure(self) -> str:
        """The message of a failed increment."""
        where = f"{self.kind} at {self._where('.4g')}"
        return f"step {self.index} ({self.kind}) failed at {where}: {self.reason}"

    @property
    def stall(self) -> str:
        """A press that stalls under step cuts may be a snap-through or buckling."""
        if self.kind != "press" or self.record is not None:
            return ""
        return ("Newton stalls under step cuts: possible snap-through or buckling at "
                f"y ≈ {self.step.travel_at(self.t):.3g} mm")

    @property
    def unstable(self) -> str:
        """The instability of the unstable equilibrium ('' after a failure)."""
        if self.record is None:
            return ""
        return (f"the tangent has {self.record.unstable_modes} negative eigenvalue(s) at "
                f"{self._where('.3g')}: unstable equilibrium (buckling or snap-through)")


@dataclass(frozen=True, eq=False)
class Result:
    """All converged records, whether every step converged (``converged``), why and where
    the run stopped (``message``, "converged" if it did not; ``stop`` says it as data), a
    detected instability, the wall-clock time of the solve (s), and the Newton iterations of
    every accepted increment (``newton_iterations``: also those of cut increments between
    recorded points and of an unstable point it stopped at)."""

    records: list
    converged: bool
    message: str
    instability: str = ""
    seconds: float = float("nan")
    stop: Stop | None = None
    newton_iterations: int = 0
    #: the snap-throughs followed (:class:`~spsc.fem.engine.snap.Jump`), in order
    jumps: tuple = ()
    #: the load of the last converged state (:class:`~spsc.fem.engine.steps.Load`): where
    #: another walk may go on from (``solve(..., start=result)``)
    load: object = None

    def of(self, kind: str) -> list:
        return [r for r in self.records if r.kind == kind]

    @property
    def iterations(self) -> int:
        """Newton iterations over the converged load points."""
        return sum(r.iterations for r in self.records)
