"""Robust design (issue 49): a design judged by how its prints land, not by its nominal curve.

Each trial's design is evaluated as usual (:func:`~spsc.sweep.evaluate.evaluate`: the nominal
metrics, the printability verdict) and then under the tolerance: ``n`` base samples of SALib's
Sobol sequence (:func:`~spsc.study.band.sample_setups`, N (D + 2) setups), both modes of every
sample in one batched call of the model (the surrogate), the goal's miss of every sample. The
trial's objective is the miss its prints stay under with the asked ``confidence`` — the
``confidence`` quantile of the samples' misses (a sample that makes no chamber or that the
model refuses counts as missing everything) — so the search's own stopping rule (that miss
within the tolerance) is "at least ``confidence`` of the prints meet the targets", and the row
says the share that does (``p_met``).

The chosen design is then confirmed by the wall model's samples on Dask
(:func:`confirm_robust`).
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict

import numpy as np

__all__ = ["robust_row", "sample_misses", "confirm_robust", "chosen_band", "ROBUST_SAMPLES"]

#: base samples per trial (N (D + 2) setups, both modes of each)
ROBUST_SAMPLES = 32
#: the robust miss of a design whose quantile sample made no chamber (1000 %)
MISS_CAP = 10.0


def sample_misses(low_setup, model: str, options, goal, tolerance, n: int, seed: int,
                  curves=None) -> np.ndarray:
    """The goal's miss of every sample of the design whose low-mode setup is ``low_setup``
    (inf where the sample makes no chamber, the model refuses it or a metric is undefined).
    ``curves(setups) -> [Curve]``: how the model computes them (default: its
    ``curves_many``)."""
    from spsc.core.errors import ParameterError
    from spsc.models import get
    from spsc.study.band import sample_setups
    from spsc.study.metrics import design_metrics

    entry = get(model)
    _, _, setups = sample_setups(low_setup, tolerance, n, seed)
    ok = []
    for k, s in enumerate(setups):
        if isinstance(s, str):
            continue
        try:
            entry.check(s, options, verb="design", quiet=True)
            ok.append(k)
        except ParameterError:
            pass
    pairs = [x for k in ok for x in (setups[k].with_load(reservoir_mm3=0.0), setups[k])]
    solved = (curves or (lambda ss: entry.curves_many(ss, options)))(pairs) if pairs else []
    misses = np.full(len(setups), np.inf)
    for j, k in enumerate(ok):
        m = asdict(design_metrics([solved[2 * j]], [solved[2 * j + 1]]))
        miss = goal.miss(m)
        misses[k] = miss if math.isfinite(miss) else np.inf
    return misses


def robust_row(design: dict, model: str, process: str, points=None, stroke_mm=None, *,
               tolerance, goal, confidence: float, n: int = ROBUST_SAMPLES,
               seed: int = 0) -> dict:
    """The row of :func:`~spsc.sweep.evaluate.evaluate` with ``robust_miss`` (the
    ``confidence`` quantile of the samples' misses), ``p_met`` (the share of samples within
    the goal's tolerance) and ``robust_samples``. Never raises (a failure is the row's)."""
    from spsc.models import get
    from spsc.sweep.evaluate import design_setup, evaluate, resolve_design

    t0 = time.perf_counter()
    row = evaluate(design, model, process, points, stroke_mm)
    if row["status"] != "ok":
        return row
    try:
        entry = get(model)
        low = design_setup(entry, *resolve_design(design), points, stroke_mm)
        misses = sample_misses(low, model, entry.Options(), goal, tolerance, n, seed)
    except Exception as exc:  # a row that says so, as evaluate's
        row["status"], row["message"] = "failed", f"{type(exc).__name__}: {exc}"
        return row
    # a quantile past the chambers that were made is "misses everything": a finite cap
    # (1000 %) that Optuna's samplers can rank
    q = min(float(np.quantile(misses, confidence, method="higher")), MISS_CAP)
    row.update(robust_miss=q, p_met=float(np.mean(misses <= goal.tol + 1e-12)),
               robust_samples=int(misses.size))
    row["seconds"] = time.perf_counter() - t0
    return row


def confirm_robust(client, problem, params: dict, *, model: str = "wall",
                   n: int | None = None, seed: int = 1) -> dict:
    """The chosen design's samples (``n`` base samples, default the search's; a seed the
    search did not use) run by ``model`` on the Dask workers: ``p_met``, the ``confidence``
    quantile of the misses, the samples and the time."""
    from spsc.models import get
    from spsc.study.band import curve_of

    n = problem.robust["samples"] if n is None else n
    t0 = time.perf_counter()
    entry = get(model)
    low = _low_setup(entry, params, problem)
    options = entry.Options()

    def curves(setups):
        return client.gather(client.map(curve_of, setups, model=model, options=options,
                                        pure=False))

    r = problem.robust
    misses = sample_misses(low, model, options, problem.goal, r["tolerance"], n, seed,
                           curves=curves)
    return {"model": model, "samples": int(misses.size), "seed": seed,
            "p_met": float(np.mean(misses <= problem.goal.tol + 1e-12)),
            "quantile_miss": min(float(np.quantile(misses, r["confidence"], method="higher")),
                                 MISS_CAP),
            "seconds": time.perf_counter() - t0}


def _low_setup(entry, params: dict, problem):
    """The low-mode setup of a study's design ``params`` for ``entry`` (the search's stroke,
    the model's points)."""
    from spsc.sweep.evaluate import design_setup, resolve_design

    return design_setup(entry, *resolve_design(params), None, problem.stroke_mm)


def chosen_band(problem, params: dict, *, n: int = 256, seed: int = 2) -> dict:
    """The chosen design's band in both modes by the search's model
    (:func:`spsc.study.band.band`) and, per goal metric of a mode (stiffness and sensitivity,
    high and low), its Sobol total indices and the input to tighten first (the largest)."""
    from spsc.models import get
    from spsc.study.band import band

    entry = get(problem.model)
    low = _low_setup(entry, params, problem)
    out = {"modes": {}, "tighten": {}}
    for mode, setup in (("high", low.with_load(reservoir_mm3=0.0)), ("low", low)):
        r = band(setup, entry.Options(), problem.model, problem.robust["tolerance"], n=n,
                 seed=seed)
        out["modes"][mode] = {k: r[k] for k in ("samples", "refused", "stiffness_N_per_mm",
                                                "sensitivity_kPa_per_mm", "sobol")}
    for metric in problem.goal.needed:
        name, _, mode = metric.partition("_")
        si = out["modes"].get(mode, {}).get("sobol", {}).get(name, {})
        if "ST" in si:
            order = sorted(si["ST"], key=lambda k: -si["ST"][k])
            out["tighten"][metric] = [(k, si["ST"][k]) for k in order]
    return out
