"""What a solve returns: one :class:`Record` per converged load point, the :class:`Result` of
the whole walk, and the one failure of a Newton solve, :class:`NewtonFailure`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["Record", "Result", "NewtonFailure"]


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


@dataclass(frozen=True, eq=False)
class Result:
    """All converged records, whether every step converged (``converged``), why and where
    the run stopped (``message``, "converged" if it did not), a detected instability, and
    the wall-clock time of the solve (s)."""

    records: list
    converged: bool
    message: str
    instability: str = ""
    seconds: float = float("nan")

    def of(self, kind: str) -> list:
        return [r for r in self.records if r.kind == kind]

    @property
    def iterations(self) -> int:
        """Newton iterations over the converged load points."""
        return sum(r.iterations for r in self.records)
