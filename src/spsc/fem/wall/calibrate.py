"""Calibration of a material's stiffness against a bench test of the user's own chamber,
through the ``wall`` model (:mod:`spsc.fem.wall`): the physics-based counterpart of the
paper's identification (eqs. 39–40), which fits curves and not the material.

The unknown is one factor s on every constant of the starting law (μ of a neo-Hookean law;
the shape of a fitted Mooney–Rivlin or Yeoh law is kept, its stiffness scaled): printed parts
differ from their datasheet mostly in stiffness (infill, layer bonding). The bench test is

* the **open chamber** (setup pressure 0, the paper's Fig. 5b): the plate force F_el(y) (N).
  With no pressure load the wall's equilibrium under the prescribed plate travel does not depend
  on the stiffness and every force scales with it, F(y; s) = s F(y; 1) (the bulk modulus is a
  fixed multiple of μ), so s is the linear least-squares factor, from one solve;
* a **closed chamber** at setup pressure p_i (reservoir V_r): F(y) and, if measured, the gauge
  pressure P(y). The pressure load does not scale with s: s minimises the relative residuals of
  F and of the pressure rise P − p_i by Gauss–Newton on log s (scipy's least_squares), one
  wall solve per evaluation.

Units: mm, N, kPa at this edge (the models' MPa inside).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import least_squares

from spsc.cad.geometry import SPSCGeometry
from spsc.core.curve import Curve
from spsc.core.errors import ParameterError
from spsc.core.bench import BenchData
from spsc.materials import Material

from .curve import WallSettings, wall_curve

__all__ = ["Calibration", "calibrate", "scaled", "SCALE_RANGE"]

#: The stiffness factors searched (a printed part 20× softer or stiffer than its law is a
#: units error, not a calibration).
SCALE_RANGE = (0.05, 20.0)


def scaled(material: Material, s: float, *, note: str = "") -> Material:
    """``material`` with every constant multiplied by ``s`` (W → s W), its provenance
    ``user-fit`` (calibrated on the user's own test)."""
    source = f"{material.source}; stiffness x {s:.4g}" + (f" ({note})" if note else "")
    return dataclasses.replace(material.scaled(s), source=source,
                               name=f"{material.name}-calibrated", provenance="user-fit")


@dataclass(frozen=True, eq=False)
class Calibration:
    """The calibrated ``material`` (``scale`` times the starting one), the model ``curve`` at
    it, the bench's y (mm) and residuals: RMS force error (N), RMS pressure-rise error (kPa or
    None), the relative RMS over both, and the number of wall solves."""

    material: Material
    scale: float
    curve: Curve
    y_mm: np.ndarray
    force_residual_N: np.ndarray
    pressure_residual_kPa: np.ndarray | None
    relative_rms: float
    evaluations: int

    @property
    def force_rms_N(self) -> float:
        return float(np.sqrt(np.mean(self.force_residual_N ** 2)))

    @property
    def pressure_rms_kPa(self) -> float | None:
        r = self.pressure_residual_kPa
        return None if r is None else float(np.sqrt(np.mean(r ** 2)))


def _at(curve: Curve, y: np.ndarray, values: np.ndarray) -> np.ndarray:
    """A model quantity at the bench's plate positions (monotone cubic through the points)."""
    ok = curve.converged
    if not ok.all() and curve.y_mm[ok][-1] < y[-1] - 1e-9:
        raise ParameterError("bench y_mm", float(y[-1]), f"<= {curve.y_mm[ok][-1]:.4g} mm, where "
                             f"the wall model stopped: {curve.solver.message}")
    return PchipInterpolator(curve.y_mm[ok], values[ok])(y)


def _check_bench(bench: BenchData, pressure_kPa: float) -> None:
    if bench.y_mm[0] < 0:
        raise ParameterError("bench y_mm (first row)", float(bench.y_mm[0]),
                             ">= 0 mm (plate travel from first contact)")
    if not np.any(np.abs(bench.force_N) > 0):
        raise ParameterError("bench force_N", 0.0, "a non-zero force somewhere")
    if pressure_kPa > 0 and bench.pressure_kPa is not None:
        tol = max(1.0, 0.2 * pressure_kPa)
        if abs(bench.pressure_kPa[0] - pressure_kPa) > tol:
            raise ParameterError("bench pressure_kPa (first row)", float(bench.pressure_kPa[0]),
                                 f"within {tol:g} kPa of the setup pressure {pressure_kPa:g} "
                                 "kPa (kPa gauge, not Pa, bar or absolute)")


def calibrate(bench: BenchData, geometry: SPSCGeometry, material: Material, *,
              pressure_kPa: float, reservoir_mm3: float = 0.0, polytropic_n: float = 1.0,
              settings: WallSettings | None = None, points: int = 13,
              progress=None, solve=None) -> Calibration:
    """The stiffness factor s of ``material`` that reproduces ``bench`` (y mm, F N, P kPa) on
    ``geometry`` at setup ``pressure_kPa`` (kPa gauge; 0: the open chamber) with reservoir
    ``reservoir_mm3`` (mm³). The wall model runs over the bench's stroke in ``points``
    positions and is interpolated onto the bench's y. ``progress()`` after each wall solve.
    ``solve(material, stroke_mm, points)``: the curve of a scaled material on this setup, as
    the caller's model computes it (the callers above this layer pass the model registry's;
    default the wall model with ``settings``)."""
    _check_bench(bench, pressure_kPa)
    y = np.asarray(bench.y_mm, float)
    F_b = np.asarray(bench.force_N, float)
    stroke = float(y[-1])
    settings = settings or WallSettings()
    runs: dict[float, Curve] = {}

    def model(s: float) -> Curve:
        if s not in runs:  # the optimiser's last point is the answer: solve it once
            runs[s] = wall_curve(geometry, scaled(material, s), pressure_kPa=pressure_kPa,
                                 reservoir_mm3=reservoir_mm3, stroke_mm=stroke, points=points,
                                 polytropic_n=polytropic_n, settings=settings) \
                if solve is None else solve(scaled(material, s), stroke, points)
            if progress is not None:
                progress()
        return runs[s]

    use_p = pressure_kPa > 0 and bench.pressure_kPa is not None
    dP_b = np.asarray(bench.pressure_kPa, float) - pressure_kPa if use_p else None
    f_scale = float(np.max(np.abs(F_b)))
    p_scale = float(np.max(np.abs(dP_b))) if use_p and np.any(dP_b != 0) else None

    def residuals(c: Curve) -> tuple[np.ndarray, np.ndarray | None]:
        rF = _at(c, y, c.force_N) - F_b
        rP = None if dP_b is None else _at(c, y, c.pressure_kPa - pressure_kPa) - dP_b
        return rF, rP

    def relative(rF, rP) -> np.ndarray:
        parts = [rF / f_scale] + ([rP / p_scale] if rP is not None and p_scale else [])
        return np.concatenate(parts)

    if pressure_kPa == 0:
        c1 = model(1.0)
        unit = _at(c1, y, c1.force_N)
        s = float(F_b @ unit / (unit @ unit))
    else:
        fit = least_squares(lambda q: relative(*residuals(model(math.exp(q[0])))), [0.0],
                            bounds=([math.log(SCALE_RANGE[0])], [math.log(SCALE_RANGE[1])]),
                            diff_step=1e-3, x_scale=[1.0], xtol=1e-3, ftol=1e-6)
        s = float(math.exp(fit.x[0]))
    if not SCALE_RANGE[0] <= s <= SCALE_RANGE[1] * (1 + 1e-9):
        raise ParameterError("calibrated stiffness factor", round(s, 6),
                             f"within {SCALE_RANGE[0]:g}–{SCALE_RANGE[1]:g} of {material.name} "
                             "(check the bench units: mm, N, kPa gauge; and the chamber)")
    final = model(s)
    rF, rP = residuals(final)
    rel = relative(rF, rP)
    return Calibration(scaled(material, s, note=f"calibrated on {bench.source or 'bench data'}"),
                       s, final, y, rF, rP, float(np.sqrt(np.mean(rel ** 2))), len(runs))
