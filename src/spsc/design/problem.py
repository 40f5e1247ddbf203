"""The problem an inverse-design study answers (a study continues only with the same one)."""

from __future__ import annotations

from dataclasses import dataclass

from spsc.design.goal import Goal
from spsc.design.space import Space

__all__ = ["Problem"]


@dataclass(frozen=True)
class Problem:
    """What a study answers: the goal, the space, the fast model, the process whose
    printability is the constraint, the plate positions (None: the model's) and the stroke
    (mm). A study continues only with the same problem."""

    goal: Goal
    space: Space
    model: str
    process: str
    points: int | None
    stroke_mm: float
    #: a robust search (:mod:`spsc.design.robust`): {"tolerance": Tolerance, "confidence":
    #: float, "samples": int}; None: the nominal search
    robust: dict | None = None
    #: a life to reach (:mod:`spsc.design.life`): {"cycles": N, "stroke_mm": mm, "exponent":
    #: F or None}; None: no durability constraint
    life: dict | None = None

    def to_dict(self) -> dict:
        out = {"goal": self.goal.to_dict(), "space": self.space.to_dict(), "model": self.model,
               "process": self.process, "points": self.points, "stroke_mm": self.stroke_mm}
        if self.robust is not None:  # a robust study continues only with the same tolerance
            out["robust"] = {"tolerance": self.robust["tolerance"].to_dict()["inputs"],
                             "confidence": self.robust["confidence"],
                             "samples": self.robust["samples"]}
        if self.life is not None:  # a study continues only with the same life asked
            out["life"] = dict(self.life)
        return out
