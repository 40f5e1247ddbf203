"""Each design's band in a sweep (issue 49): the spread of its prints under a tolerance file
(:mod:`spsc.study.tolerance`), propagated through the sweep's model in both modes
(:func:`spsc.study.band.band`: Saltelli's N (D + 2) samples), the P5, P50 and P95 of its mean
stiffness and sensitivity as columns of its row. With the surrogate one design's band is two
batched calls (about 0.05 s with N = 32); any other model would run N (D + 2) curves a design,
which :func:`check_band_model` refuses.
"""

from __future__ import annotations

import hashlib
import json

from spsc.core.errors import ParameterError
from spsc.sweep.evaluate import BAND_COLUMNS

__all__ = ["BAND_COLUMNS", "band_columns", "band_row", "band_digest", "check_band_model",
           "DEFAULT_BAND_SAMPLES"]

#: Saltelli's base samples N of a sweep row's band (the model runs N (D + 2) setups a mode)
DEFAULT_BAND_SAMPLES = 32
_METRICS = (("stiffness", "N_per_mm"), ("sensitivity", "kPa_per_mm"))


def check_band_model(model: str) -> None:
    """A sweep's band needs a batched model (the surrogate); one line otherwise."""
    from spsc.models import get

    if not hasattr(get(model), "curves_many"):
        raise ParameterError("tolerance", model, "with --model surrogate (a design's band is "
                             "N (D + 2) curves a mode: the surrogate answers them in one call)")


def band_digest(tolerance, samples: int) -> str:
    """What a band depends on beyond the design: the tolerance's distributions and N."""
    text = json.dumps({"tolerance": tolerance.to_dict(), "samples": int(samples)},
                      sort_keys=True, default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


def band_columns(design: dict, model: str, points=None, stroke_mm=None, *, tolerance,
                 samples: int = DEFAULT_BAND_SAMPLES) -> dict:
    """The band columns of ``design`` (:data:`BAND_COLUMNS`), both modes."""
    from dataclasses import replace

    from spsc.core.loadcase import check_load
    from spsc.models import get
    from spsc.study.band import band
    from spsc.sweep.evaluate import design_setup, resolve_design

    entry = get(model)
    low = design_setup(entry, *resolve_design(design), points, stroke_mm)
    out, n_run, n_refused = {}, 0, 0
    for mode in ("high", "low"):
        setup = low
        if mode == "high":
            lc = low.load
            setup = replace(low, load=check_load(
                low.body, pressure_kPa=lc.pressure_kPa, reservoir_mm3=0.0,
                stroke_mm=lc.stroke_mm, points=lc.points, polytropic_n=lc.polytropic_n))
        rec = band(setup, entry.Options(), model, tolerance, n=samples, seed=0)
        n_run, n_refused = n_run + rec["computed"], n_refused + rec["refused"]
        for m, unit in _METRICS:
            for q in (5, 50, 95):
                out[f"{m}_{mode}_p{q}"] = rec[f"{m}_{unit}"][f"p{q}"]
    out.update(band_samples=n_run, band_refused=n_refused)
    return out


def band_row(design: dict, model: str, process: str, points=None, stroke_mm=None, *, base,
             tolerance, samples: int = DEFAULT_BAND_SAMPLES, key_of=None) -> dict:
    """``base``'s row of the design with its band columns (a row the base refused keeps
    none; a band the model could not compute says why in the row's message), keyed by
    ``key_of`` (the sweep's key with the band's digest)."""
    row = base(design, model, process, points, stroke_mm)
    if row.get("key") and key_of is not None:
        row["key"] = key_of(design, model, process, points, stroke_mm)
    if row.get("status") in ("ok", "partial"):
        try:
            row.update(band_columns(design, model, points, stroke_mm, tolerance=tolerance,
                                    samples=samples))
        except (ParameterError, RuntimeError, ValueError, ArithmeticError) as exc:
            row["message"] = (row.get("message") or "") + \
                f"; no band: {str(exc).splitlines()[0][:160]}"
    return row
