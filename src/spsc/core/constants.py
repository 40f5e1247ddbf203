"""Physical constants shared by every model (internal units: mm, N, MPa)."""

from __future__ import annotations

__all__ = ["P_AMB", "P_AMB_KPA", "KPA_PER_MPA", "to_MPa", "to_kPa"]

#: Ambient (atmospheric) pressure, MPa absolute: the reference of every gauge pressure.
P_AMB = 0.101325

#: Unit conversion at the edges (CLI, files): kPa per MPa.
KPA_PER_MPA = 1000.0


def to_MPa(kPa):
    """A pressure from the edges' kPa to the solvers' MPa (a float or an array)."""
    return kPa / KPA_PER_MPA


def to_kPa(MPa):
    """A pressure from the solvers' MPa to the edges' kPa (a float or an array)."""
    return MPa * KPA_PER_MPA


#: The ambient pressure in the edges' unit, kPa absolute.
P_AMB_KPA = to_kPa(P_AMB)
