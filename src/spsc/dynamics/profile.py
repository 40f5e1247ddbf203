"""The press: the plate travel y(t) (:class:`PressProfile`), the plate force F(t)
(:class:`ForceProfile`), or a compliant object — the plate on a spring whose far end follows
x(t) (:class:`SpringProfile`) — as a piecewise-linear profile of knots."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from spsc.core.errors import ParameterError

__all__ = ["PressProfile", "ForceProfile", "SpringProfile"]


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
        _check_times("press profile t_s", t)

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

    def travel(self, t: float, chamber, m_kg: float, t_K: float) -> float:
        """The plate travel (mm) at ``t``: the profile's (the gas does not move it)."""
        return float(self.y(t))


def _check_times(name: str, t: np.ndarray) -> None:
    if t[0] != 0.0 or np.any(np.diff(t) <= 0):
        raise ParameterError(name, list(map(float, t)), "starting at 0 and strictly "
                             "increasing (s)")


@dataclass(frozen=True)
class ForceProfile:
    """A force-controlled press: knots ``t_s`` (s, from 0, strictly increasing) and the plate
    force ``force_N`` (N, ≥ 0; the plate rests on the chamber with at least
    :data:`~.chamber.FORCE_FLOOR_N`); the plate goes where the chamber carries the force,
    at most ``max_travel_mm`` deep (the extent of the chamber's map)."""

    t_s: tuple
    force_N: tuple
    max_travel_mm: float = 4.0

    def __post_init__(self):
        t, f = np.asarray(self.t_s, float), np.asarray(self.force_N, float)
        if t.size < 2 or t.size != f.size:
            raise ParameterError("press force", f"{t.size} knots",
                                 "at least two [t_s, force_N] pairs")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(f))):
            raise ParameterError("press force", "non-finite value", "finite t_s and force_N")
        _check_times("press force t_s", t)
        if np.any(f < 0):
            raise ParameterError("press force force_N", float(f.min()), ">= 0 N (the plate "
                                 "only pushes)")
        if not (0 < self.max_travel_mm <= 50):
            raise ParameterError("press.max_travel_mm", self.max_travel_mm, "in (0, 50] mm")

    @classmethod
    def of(cls, pairs, max_travel_mm: float = 4.0) -> "ForceProfile":
        try:
            t, f = zip(*[(float(a), float(b)) for a, b in pairs])
        except (TypeError, ValueError):
            raise ParameterError("press force", pairs, "a list of [t_s, force_N] pairs") \
                from None
        return cls(t, f, float(max_travel_mm))

    @property
    def duration(self) -> float:
        return float(self.t_s[-1])

    def force(self, t):
        return np.interp(t, self.t_s, self.force_N)

    def rate(self, t0: float, t1: float) -> float:
        """Ḟ (N/s) on a segment [t0, t1] between knots."""
        return float((self.force(t1) - self.force(t0)) / (t1 - t0))

    @property
    def extent(self) -> tuple[float, float]:
        """The travels the chamber's map must cover (mm)."""
        return 0.0, float(self.max_travel_mm)

    def travel(self, t: float, chamber, m_kg: float, t_K: float) -> float:
        """The plate travel (mm) at which the gas (``m_kg`` at ``t_K``) carries the force."""
        return chamber.travel(m_kg, t_K, float(self.force(t)))


@dataclass(frozen=True)
class SpringProfile:
    """A compliant object: the plate on a linear spring of ``stiffness_N_per_mm`` k whose far
    end follows ``path`` (a :class:`PressProfile`: its travel x from first contact, mm; < 0
    above the chamber — a finger closing on a soft object). The plate goes where the chamber
    carries the spring's force, F(y, P) = k (x − y)
    (:meth:`~.chamber.Chamber.travel_on_spring`); off the chamber y = x. Differentiated,
    F_P Ṗ + (F_y + k) ẏ = k ẋ: the force-controlled press's third equation with
    Ḟ = k (ẋ − ẏ)."""

    path: PressProfile
    stiffness_N_per_mm: float

    def __post_init__(self):
        k = self.stiffness_N_per_mm
        if not (np.isfinite(k) and 0 < k <= 1e5):
            raise ParameterError("object stiffness", k, "in (0, 1e5] N/mm")

    @classmethod
    def of(cls, pairs, stiffness_N_per_mm: float) -> "SpringProfile":
        return cls(PressProfile.of(pairs), float(stiffness_N_per_mm))

    @property
    def t_s(self) -> tuple:
        """The knots' times (s): the pieces the circuit integrates."""
        return self.path.t_s

    @property
    def duration(self) -> float:
        return self.path.duration

    def x(self, t):
        return self.path.y(t)

    def rate(self, t0: float, t1: float) -> float:
        """ẋ (mm/s) of the spring's far end on a segment [t0, t1] between knots."""
        return self.path.rate(t0, t1)

    @property
    def extent(self) -> tuple[float, float]:
        return self.path.extent

    def travel(self, t: float, chamber, m_kg: float, t_K: float) -> float:
        """The plate travel (mm) where the gas (``m_kg`` at ``t_K``) carries the spring."""
        return chamber.travel_on_spring(m_kg, t_K, float(self.x(t)), self.stiffness_N_per_mm)
