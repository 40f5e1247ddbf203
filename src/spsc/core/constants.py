"""Physical constants shared by every model (internal units: mm, N, MPa)."""

from __future__ import annotations

__all__ = ["P_AMB", "KPA_PER_MPA"]

#: Ambient (atmospheric) pressure, MPa absolute: the reference of every gauge pressure.
P_AMB = 0.101325

#: Unit conversion at the edges (CLI, files): kPa per MPa.
KPA_PER_MPA = 1000.0
