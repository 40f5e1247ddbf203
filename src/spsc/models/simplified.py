"""The simplified intersection model (the nominal chamber cut by the plate, with the air
spring) as a :class:`~spsc.models.base.CurveModel`."""

from __future__ import annotations

from dataclasses import dataclass

from .base import ModelBase, Outcome
from .membrane import check_membrane_load

__all__ = ["SimplifiedModel", "SimplifiedOptions"]


@dataclass(frozen=True)
class SimplifiedOptions:
    """The simplified model has no options of its own."""


@dataclass(frozen=True)
class SimplifiedModel(ModelBase):
    """The nominal cavity cut by the plate: contact area and volume change from the geometry
    alone, the pressure from the gas law (eqs. 1–9)."""

    name: str = "simplified"
    help: str = "the nominal chamber cut by the plate, with the air spring"
    module: str = "spsc.models.simplified"
    Options = SimplifiedOptions
    stroke_mm: float = 6.0
    points: int = 41
    color: str = "C2"
    style: str = "--"
    seconds_per_point: float = 0.004

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        self.check_contact(setup)
        check_membrane_load(setup.load)

    def curve(self, setup, options, *, progress=None, cache_dir=None):
        from spsc.membrane.simplified import simplified_curve

        load = setup.load
        return Outcome(simplified_curve(setup.body, pressure_kPa=load.pressure_kPa,
                                        reservoir_mm3=load.reservoir_mm3,
                                        stroke_mm=load.stroke_mm, points=load.points,
                                        polytropic_n=load.polytropic_n,
                                        material=setup.material.name))
