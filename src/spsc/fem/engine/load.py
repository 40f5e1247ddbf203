"""What one Newton solve holds fixed: the :class:`Load`."""

from __future__ import annotations

from dataclasses import dataclass

from spsc.core.gaslaw import GasLaw

__all__ = ["Load"]


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

    def cavity_pressure(self, volume: float) -> tuple[float, float]:
        """(gauge pressure p, MPa; its slope dp/dV, MPa/mm³) on the cavity at the gas volume
        ``volume`` (mm³): the prescribed pressure with slope 0, or the closed gas's P·Vⁿ law
        (paper eqs. 6–7). The one place every discretisation reads the gas from."""
        if self.gas is None:
            return float(self.pressure), 0.0
        return float(self.gas.pressure(volume)), float(self.gas.dpressure(volume))
