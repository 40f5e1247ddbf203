"""The axisymmetric membrane (the Yang–Feng problem of sec. 2.3, eqs. 15–38) as a
:class:`~spsc.models.base.CurveModel`."""

from __future__ import annotations

from dataclasses import dataclass

from .base import ModelBase, Outcome, option

__all__ = ["MembraneModel", "MembraneOptions", "check_membrane_load"]


@dataclass(frozen=True)
class MembraneOptions:
    """``meridians``: add the deformed meridians (x, ρ, η per position) to the JSON;
    ``wrinkling``: ``on`` the tension-field membrane, ``off`` the paper's taut law."""

    meridians: bool = option(False, "--meridians", "add the deformed meridians (x, rho, eta "
                             "per position) to the JSON", kind="flag")
    wrinkling: str = option("on", "--wrinkling", "on (default): tension-field membrane, it "
                            "wrinkles instead of carrying compression; off: the paper's taut "
                            "law (hoop compression carried; fails to converge on 13 of 24 "
                            "3D-checked cases, docs/theory/membrane.md)", kind="choice",
                            choices=("on", "off"))


def check_membrane_load(load) -> None:
    """The membrane's own limit on the load case (:func:`spsc.membrane.solver.check_membrane_pressure`)."""
    from spsc.membrane.solver import check_membrane_pressure

    check_membrane_pressure(load.pressure_kPa, load.stroke_mm)


def _meridians(result) -> list:
    return [None if sh is None else dict(zip(("x", "rho", "eta"), (
        [round(float(v), 6) for v in a] for a in sh.meridian()))) for sh in result.shapes]


@dataclass(frozen=True)
class MembraneModel(ModelBase):
    """Inflation and plate contact of the membrane on the cavity surface, with the trapped
    gas; no bending (its force is p·A)."""

    name: str = "membrane"
    help: str = "axisymmetric membrane: inflation and plate contact (fast)"
    module: str = "spsc.models.membrane"
    Options = MembraneOptions
    stroke_mm: float = 6.0
    points: int = 41
    color: str = "C0"
    style: str = "-"
    seconds_per_point: float = 0.025
    zero_stroke: bool = True

    def check(self, setup, options, *, verb: str, quiet: bool) -> None:
        self.check_contact(setup)
        check_membrane_load(setup.load)

    def curve(self, setup, options, *, progress=None, cache_dir=None):
        from spsc.membrane.solver import SolverSettings, solve

        load = setup.load
        r = solve(setup.body, setup.material, pressure_kPa=load.pressure_kPa,
                  reservoir_mm3=load.reservoir_mm3, stroke_mm=load.stroke_mm,
                  points=load.points, polytropic_n=load.polytropic_n,
                  settings=SolverSettings(wrinkling=options.wrinkling != "off"))
        extra = {"meridians_mm": _meridians(r)} if options.meridians else {}
        return Outcome(r.curve, extra, r)
