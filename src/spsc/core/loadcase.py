"""The load case every model shares — setup pressure, reservoir, stroke, plate positions and
polytropic index — validated in one place, with the same limits for every model.

``spsc curve`` checks it for every ``--model`` before any work, and the models' own entry points
(:func:`spsc.membrane.solver.solve`, :func:`spsc.membrane.simplified.simplified_curve`,
:class:`spsc.fem.solid.chamber.ChamberRun`) call the same function, so the CLI and the Python API refuse
the same inputs with the same one-line :class:`~spsc.core.errors.ParameterError`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .constants import to_MPa
from .errors import ParameterError, require

__all__ = ["LoadCase", "WithLoadCase", "check_load", "PRESSURE_MAX_KPA", "POLYTROPIC_RANGE", "POINTS_MAX"]

#: Highest setup pressure (kPa gauge): the catalogue's hyperelastic fits cover strains an
#: order of magnitude below what 1 MPa does to a 1 mm wall (Type D at 500 kPa already fails to
#: inflate); the paper's bench uses 10–40 kPa.
PRESSURE_MAX_KPA = 1000.0
#: The polytropic index of air, eq. 2: 1 (isothermal) to 1.4 (adiabatic, diatomic gas).
POLYTROPIC_RANGE = (1.0, 1.4)
#: Most plate positions of one curve.
POINTS_MAX = 10001


@dataclass(frozen=True)
class LoadCase:
    """A validated load case: setup pressure p_i (kPa gauge), reservoir V_r (mm³), plate
    travel from first contact (mm), number of plate positions including y = 0, polytropic
    index n (eq. 2)."""

    pressure_kPa: float
    reservoir_mm3: float
    stroke_mm: float
    points: int
    polytropic_n: float

    @property
    def pressure_MPa(self) -> float:
        """The setup pressure in the solvers' unit (MPa gauge): the one conversion."""
        return to_MPa(self.pressure_kPa)

    def as_dict(self) -> dict:
        """The fields by name (the keywords of :func:`check_load`)."""
        return {"pressure_kPa": self.pressure_kPa, "reservoir_mm3": self.reservoir_mm3,
                "stroke_mm": self.stroke_mm, "points": self.points,
                "polytropic_n": self.polytropic_n}


class WithLoadCase:
    """For a run that holds its :class:`LoadCase` as ``load``: its quantities read through it."""

    pressure_kPa = property(lambda self: self.load.pressure_kPa, doc="setup pressure, kPa")
    reservoir_mm3 = property(lambda self: self.load.reservoir_mm3, doc="reservoir, mm³")
    stroke_mm = property(lambda self: self.load.stroke_mm, doc="plate travel, mm")
    points = property(lambda self: self.load.points, doc="plate positions")
    polytropic_n = property(lambda self: self.load.polytropic_n, doc="polytropic index")


def check_load(geometry, *, pressure_kPa, reservoir_mm3, stroke_mm, points, polytropic_n,
               allow_zero_stroke: bool = False) -> LoadCase:
    """Validate a load case on ``geometry`` (an SPSCGeometry, or None for a part, whose own
    room for the plate is checked where its plate is placed); ParameterError naming the first
    parameter out of range.

    The stroke must stay below the chamber height h: the plate starts at the inflated apex,
    at least h above the base plane, and the floor under the cavity is not modelled by any of
    the models. ``allow_zero_stroke``: a stroke of 0 with one point (inflation only).
    """
    p = require("pressure", pressure_kPa, ge=0, le=PRESSURE_MAX_KPA, unit="kPa gauge")
    v_r = require("reservoir", reservoir_mm3, ge=0, unit="mm³")
    lo, hi = POLYTROPIC_RANGE
    n = require("polytropic_n", polytropic_n, ge=lo, le=hi,
                unit="1 isothermal to 1.4 adiabatic, eq. 2")
    if geometry is None:
        stroke = require("stroke", stroke_mm, ge=0 if allow_zero_stroke else None,
                         gt=None if allow_zero_stroke else 0, unit="mm")
    else:
        stroke = require("stroke", stroke_mm, ge=0 if allow_zero_stroke else None,
                         gt=None if allow_zero_stroke else 0, lt=geometry.h,
                         unit=f"mm, below the chamber height h = {geometry.h:g} mm: the plate "
                         "would reach the base plane")
    npts = _integer("points", points, 1 if allow_zero_stroke and stroke == 0 else 2, POINTS_MAX)
    if stroke == 0:
        npts = 1
    return LoadCase(p, v_r, stroke, npts, n)


def _integer(name: str, value, lo: int, hi: int) -> int:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not (math.isfinite(v) and v == int(v) and lo <= v <= hi):
        raise ParameterError(name, value, f"an integer from {lo} to {hi}")
    return int(v)
