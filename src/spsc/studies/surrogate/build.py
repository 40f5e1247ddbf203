"""A surrogate file from a training study: the fit (:mod:`.fit`), the error scale calibrated
on held-out wall curves (:mod:`.check`), the file written with what made it.

The error a surrogate states for a point is the spread of its posterior samples times one
scale, chosen on calibration cases (fresh designs, not the training's nor the check's) as the
92nd percentile of |error| / spread over their points past first contact: the stated error then
covers about nine points in ten of designs it never saw, which the check measures on others.
"""

from __future__ import annotations

import datetime
import json
import time
from pathlib import Path

import numpy as np

__all__ = ["calibrate", "write", "COVER"]

#: The share of calibration points the stated error must cover.
COVER = 0.92


def calibrate(surrogate, results: list[dict], *, draws: int = 32, seed: int = 0) -> dict:
    """The error scales ``{"force": …, "pressure": …}``: for each, the :data:`COVER` quantile
    of |error| / posterior spread over the points past first contact of the wall ``results``
    (:func:`.check.wall_cases`)."""
    from .check import MODES, beside

    old, surrogate.error_scale = surrogate.error_scale, {"force": 1.0, "pressure": 1.0}
    ratios = {"force": [], "pressure": []}
    try:
        for res, s in beside(surrogate, results, draws=draws, seed=seed):
            for j, (mode, _) in enumerate(MODES):
                w = res[mode]
                for name, key, err, true in (("force", "force_N", "force_err_N", w["F"]),
                                             ("pressure", "pressure_kPa", "pressure_err_kPa",
                                              w["P"])):
                    e = np.abs(s[key][j] - true)[1:]
                    ratios[name].append(e / np.maximum(s[err][j][1:], 1e-12))
    finally:
        surrogate.error_scale = old
    return {k: float(np.quantile(np.concatenate(v), COVER)) if v else 1.0
            for k, v in ratios.items()}


def write(path, arrays: dict, meta: dict) -> Path:
    """The surrogate file: the fitted ``arrays`` (float64 as float32 where a factor of the
    variance, else as fitted) and ``meta`` as JSON, compressed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    meta = {"trained": datetime.date.today().isoformat(), **meta}
    tmp = path.with_suffix(".tmp.npz")
    np.savez_compressed(tmp, meta=np.array(json.dumps(meta)), **arrays)
    tmp.replace(path)
    return path


def build(study_dir, out, *, calibration: list[dict], free, fixed: dict, name: str,
          progress=None) -> tuple[Path, dict]:
    """Fit the study in ``study_dir``, calibrate on ``calibration`` (wall results), write
    ``out``; (path, meta)."""
    from spsc.models.surrogate.predict import Surrogate
    from spsc.core.provenance import code_provenance

    from .fit import fit_study
    from .train import load_runs

    t = time.perf_counter()
    runs = load_runs(study_dir)
    arrays = fit_study(runs, free=list(free))
    study = json.loads((Path(study_dir) / "study.json").read_text())
    meta = {"name": name, "fixed": fixed, "study": study,
            "designs": len(runs), "excluded": int(arrays["excluded"]),
            "worker_seconds": float(sum(float(r.get("seconds", 0.0)) for r in runs)),
            "fit_seconds": time.perf_counter() - t, "commit": code_provenance().commit, "changes": len(code_provenance().changes)}
    sur = Surrogate(arrays, meta)
    meta["error_scale"] = calibrate(sur, calibration)
    meta["calibration_cases"] = len(calibration)
    return write(out, arrays, meta), meta
