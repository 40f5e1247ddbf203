"""The press: the plate travel y(t) as a piecewise-linear profile of (t, y) knots."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError

__all__ = ["PressProfile"]


@dataclass(frozen=True)
class PressProfile:
    """Knots ``t_s`` (s, from 0, strictly increasing) and ``y_mm`` (plate travel from first
    contact at the setup pressure, mm; < 0 above the chamber)."""

    t_s: tuple
    y_mm: tuple

    def __post_init__(self):
        t, y = np.asarray(self.t_s, float), np.asarray(self.y_mm, float)
        if t.size < 2 or t.size != y.size:
            raise ParameterError("press profile", f"{t.size} knots",
                                 "at least two [t_s, y_mm] pairs")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
            raise ParameterError("press profile", "non-finite value", "finite t_s and y_mm")
        if t[0] != 0.0 or np.any(np.diff(t) <= 0):
            raise ParameterError("press profile t_s", list(map(float, t)),
                                 "starting at 0 and strictly increasing (s)")

    @classmethod
    def of(cls, pairs) -> "PressProfile":
        try:
            t, y = zip(*[(float(a), float(b)) for a, b in pairs])
        except (TypeError, ValueError):
            raise ParameterError("press profile", pairs, "a list of [t_s, y_mm] pairs") from None
        return cls(t, y)

    @property
    def duration(self) -> float:
        return float(self.t_s[-1])

    def y(self, t):
        return np.interp(t, self.t_s, self.y_mm)

    def rate(self, t0: float, t1: float) -> float:
        """ẏ (mm/s) on a segment [t0, t1] between knots."""
        return float((self.y(t1) - self.y(t0)) / (t1 - t0))

    @property
    def extent(self) -> tuple[float, float]:
        return float(min(self.y_mm)), float(max(self.y_mm))
