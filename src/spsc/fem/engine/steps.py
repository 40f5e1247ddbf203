"""The load path as data: the steps a solve walks and the load of one equilibrium.

:class:`Inflate` ramps a prescribed cavity pressure, :class:`CloseValve` traps the gas (from
then on the pressure follows the cavity volume, P·(V + V_r)ⁿ = const, eqs. 2, 6–7 of the
paper) and :class:`Press` lowers a rigid frictionless plate from first contact. A
:class:`Load` is what one Newton solve holds fixed: the pressure (or the gas law) and the
plate's height.
"""

from __future__ import annotations

from dataclasses import dataclass

from spsc.core.gaslaw import GasLaw

__all__ = ["Inflate", "CloseValve", "Press", "Load"]


@dataclass(frozen=True)
class Inflate:
    """Ramp the cavity gauge pressure to ``pressure`` (MPa) in ``increments``."""

    pressure: float
    increments: int = 4


@dataclass(frozen=True)
class CloseValve:
    """Close the valve: the cavity plus ``reservoir`` (mm³) holds its gas, P·Vⁿ = const."""

    reservoir: float = 0.0
    polytropic_index: float = 1.0


@dataclass(frozen=True)
class Press:
    """Lower the plate from first contact by ``stroke`` (mm) in ``increments`` recorded points."""

    stroke: float
    increments: int = 10


@dataclass(frozen=True)
class Load:
    """Cavity gauge pressure ``pressure`` (MPa) unless ``gas`` is given; rigid plate at height
    ``plate`` (mm, None: no plate)."""

    pressure: float = 0.0
    gas: GasLaw | None = None
    plate: float | None = None
