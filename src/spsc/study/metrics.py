"""Metrics of the validation report and of design studies: pure functions of :class:`Curve` s.

docs/design.md defines the headline once: stroke y ∈ [0, 6] mm, setup pressures p_i = 10, 20, 30,
40 kPa; mean stiffness = mean of dF/dy over the stroke and the pressures (likewise sensitivity
dP/dy), per type and mode, then over types; JND depth = first y where
|F_high − F_low| ≥ max(0.1·F_low, 5 N). The per-curve means and the JND depth are those of
:mod:`spsc.membrane.lumped` (the lumped model of sec. 2.1 defines them); this module only
composes them, so there is one definition of each.

Units: y in mm, force N, pressure kPa gauge, stiffness N/mm, sensitivity kPa/mm, volume mm³.
Points that did not converge are NaN in a curve and drop out of every metric.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from spsc.core.curve import Curve
from spsc.membrane.lumped import jnd_depth, mean_sensitivity, mean_stiffness

__all__ = ["COLUMNS", "DesignMetrics", "HeadlineRow", "Jnd", "design_metrics", "headline",
           "headline_row", "interp", "jnd", "model_errors", "type_mean", "with_f_el"]

#: the compared columns of a curve (docs/design.md order)
COLUMNS = ("force_N", "pressure_kPa", "contact_area_mm2", "volume_change_mm3")


def interp(y, v):
    """Linear interpolant of the finite samples of v(y) (y in mm); NaN outside them."""
    y, v = np.asarray(y, float), np.asarray(v, float)
    ok = np.isfinite(v)

    def f(x):
        x = np.asarray(x, float)
        if ok.sum() < 2:
            return np.full_like(x, np.nan)
        out = np.interp(x, y[ok], v[ok])
        out[(x < y[ok][0] - 1e-12) | (x > y[ok][-1] + 1e-12)] = np.nan
        return out

    return f


def with_f_el(curve: Curve, f_el: Curve | None) -> Curve:
    """``curve`` with force p·A + F_el(y) (N): the FEM open chamber's force linearly
    interpolated on the curve's grid, NaN beyond its last converged point. For models without
    bending (membrane, simplified), as the paper's Fig. 8 adds its measured F_el."""
    if f_el is None:
        return curve
    return curve.replace(force_N=curve.force_N + interp(f_el.y_mm, f_el.force_N)(curve.y_mm),
                         model=f"{curve.model}+F_el")


def model_errors(fem: Curve, ref: Curve) -> dict:
    """Per column, ref − FEM at the FEM's plate positions where both are finite:
    ``max`` (the signed largest), ``rms``, ``rms_pct`` (RMS as % of the FEM's largest
    magnitude) and ``n`` (points compared). Units those of the column."""
    out = {}
    for col in COLUMNS:
        r = interp(ref.y_mm, getattr(ref, col))(fem.y_mm)
        f = getattr(fem, col)
        ok = np.isfinite(r) & np.isfinite(f)
        if not ok.any():
            out[col] = {"max": math.nan, "rms": math.nan, "rms_pct": math.nan, "n": 0}
            continue
        d = r[ok] - f[ok]
        scale = float(np.max(np.abs(f[ok])))
        rms = float(np.sqrt(np.mean(d**2)))
        out[col] = {"max": float(d[np.argmax(np.abs(d))]), "rms": rms,
                    "rms_pct": 100 * rms / scale if scale > 0 else math.nan, "n": int(ok.sum())}
    return out


def type_mean(curves, quantity: str) -> float:
    """Mean of ``stiffness`` (dF/dy, N/mm) or ``sensitivity`` (dP/dy, kPa/mm) over the stroke
    of each curve, then over the curves (the setup pressures of one type and mode). NaN when
    there is no curve or one curve has no finite slope: the mean over the pressures is then
    not defined."""
    curves = list(curves)
    slope = {"stiffness": Curve.stiffness, "sensitivity": Curve.sensitivity}[quantity]
    if not curves or any(not np.isfinite(slope(c)).any() for c in curves):
        return math.nan
    return (mean_stiffness if quantity == "stiffness" else mean_sensitivity)(curves)


def headline(curves_by_type: dict) -> dict:
    """``{type: [Curve per setup pressure]}`` (None for a failed run, left out) → per type
    ``stiffness`` (N/mm), ``sensitivity`` (kPa/mm) and ``n`` (curves used), and their means
    over the types (each type weighs the same)."""
    per = {}
    for t, cs in curves_by_type.items():
        cs = [c for c in cs if c is not None]
        per[t] = {"stiffness": type_mean(cs, "stiffness"),
                  "sensitivity": type_mean(cs, "sensitivity"), "n": len(cs)}
    used = [v for v in per.values() if v["n"]]

    def over_types(q):
        return float(np.mean([v[q] for v in used])) if used else math.nan

    return {"types": per, "stiffness": over_types("stiffness"),
            "sensitivity": over_types("sensitivity")}


@dataclass(frozen=True)
class HeadlineRow:
    """One row of the headline table: a model's means in both modes and their ratios
    (stiffness N/mm, sensitivity kPa/mm; ratios high / low, dimensionless)."""

    name: str
    stiffness_low: float
    stiffness_high: float
    sensitivity_low: float
    sensitivity_high: float

    @property
    def stiffness_ratio(self) -> float:
        return _ratio(self.stiffness_high, self.stiffness_low)

    @property
    def sensitivity_ratio(self) -> float:
        return _ratio(self.sensitivity_high, self.sensitivity_low)


def headline_row(name: str, by_mode: dict) -> HeadlineRow:
    """``by_mode``: ``{"high": headline(...), "low": headline(...)}`` → :class:`HeadlineRow`
    (NaN for a missing mode)."""
    def get(mode, q):
        return by_mode[mode][q] if mode in by_mode else math.nan

    return HeadlineRow(name, get("low", "stiffness"), get("high", "stiffness"),
                       get("low", "sensitivity"), get("high", "sensitivity"))


def _ratio(a: float, b: float) -> float:
    return a / b if math.isfinite(a) and math.isfinite(b) and b != 0 else math.nan


@dataclass(frozen=True)
class Jnd:
    """JND depth (mm; NaN if the modes are never distinguishable) and ``reach``, the last
    plate position where both forces are known (mm; NaN if none): "not reached by y = reach"."""

    depth_mm: float
    reach_mm: float


def jnd(high: Curve, low: Curve) -> Jnd:
    """The JND depth of a high/low pair (:func:`~spsc.membrane.lumped.jnd_depth`: 10 % of
    F_low or 5 N, sec. 3.1) and how far both curves reach."""
    ok = np.isfinite(high.force_N) & np.isfinite(low.force_N)
    return Jnd(jnd_depth(high, low), float(high.y_mm[ok][-1]) if ok.any() else math.nan)


@dataclass(frozen=True)
class DesignMetrics:
    """What a design is judged by (a design sweep optimises these; the report shows them).

    stiffness_high, stiffness_low : mean dF/dy over the stroke and setup pressures, N/mm.
    sensitivity_high, sensitivity_low : mean dP/dy likewise, kPa/mm.
    jnd_mm : JND depth at the lowest setup pressure (the paper's Fig. 5(e) uses its lowest,
        10 kPa), mm; NaN if never distinguishable.
    cavity_mm3 : nominal cavity volume (bladder only), mm³.
    """

    stiffness_high: float
    stiffness_low: float
    sensitivity_high: float
    sensitivity_low: float
    jnd_mm: float
    cavity_mm3: float


def design_metrics(high, low) -> DesignMetrics:
    """:class:`DesignMetrics` of one design from its high- and low-mode curves (one per setup
    pressure, each mode at the same pressures, on a shared y grid per pressure)."""
    high, low = list(high), list(low)
    by_p = {c.setup.get("p_i_kPa"): c for c in low}
    pairs = sorted(((h.setup.get("p_i_kPa"), h) for h in high if h.setup.get("p_i_kPa") in by_p),
                   key=lambda pc: pc[0])
    depth = jnd(pairs[0][1], by_p[pairs[0][0]]).depth_mm if pairs else math.nan
    cavity = next((c.nominal_volume_mm3 for c in high + low
                   if math.isfinite(c.nominal_volume_mm3)), math.nan)
    return DesignMetrics(type_mean(high, "stiffness"), type_mean(low, "stiffness"),
                         type_mean(high, "sensitivity"), type_mean(low, "sensitivity"),
                         depth, cavity)
