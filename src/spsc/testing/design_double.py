"""A stand-in for :func:`spsc.sweep.evaluate.evaluate` in the design loop's tests: smooth
closed-form "metrics" of the parameters (milliseconds, no model), the printability of the wall
against the process's minimum, and a refused design where w > 13.5 mm. Importable by the
Dask workers (it is part of the installed package)."""

from __future__ import annotations

import math

from spsc.cad.process import process as get_process


def evaluate(design, model, process, points=None, stroke_mm=None):
    w, h, l, t0 = (float(design[k]) for k in ("w", "h", "l", "t0"))
    shape = {"A": 1.0, "B": 1.1, "C": 1.3, "D": 0.9, None: 1.0}[design.get("type")]
    row = {k: design.get(k) for k in design}
    metrics = {"stiffness_high": shape * 0.4 * w * (1 + 0.1 * l) * t0 ** 0.5,
               "stiffness_low": shape * 0.1 * w * (1 + 0.1 * l),
               "sensitivity_high": shape * 60.0 / h,
               "sensitivity_low": shape * 15.0 / h,
               "jnd_mm": 0.2 * h,
               "cavity_mm3": 2.0 / 3.0 * math.pi * w * w * h + 2 * w * h * l}
    row.update(metrics)
    limit = get_process(process).min_wall_mm
    row.update(printable=t0 >= limit, printability=f"t0 {t0:g} vs {limit:g} mm",
               status="ok", message="", seconds=0.001, key="")
    if w > 13.5:
        row.update(dict.fromkeys(metrics, math.nan))
        row.update(status="invalid", message="w = %g is invalid: allowed <= 13.5 mm" % w)
    return row
