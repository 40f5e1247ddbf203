"""A curve with its band: the nominal setup's spread under a tolerance (issue 49), propagated
through a model by SALib's Sobol sequence (Saltelli's scheme: N (D + 2) samples for D uncertain
inputs), with the P5, P50, P95 of every column on the curve's own travels and of its mean
stiffness and sensitivity, and the Sobol first-order and total indices of each of those two
metrics to each input (Saltelli 2010; Jansen's estimator, SALib), with their 95 % bootstrap
intervals.

Every sample is a whole setup checked as the command line checks one: a draw that makes no
chamber (a wall thicker than the base allows, a stroke past a chamber drawn too short) or that
the model refuses (outside the surrogate's domain) is counted and left out; the quantiles are
then over the rest and the indices are not computed (they need every sample), which the record
says. A model that answers many setups at once (the surrogate's ``curves_many``) takes them in
one call, any other on the Dask workers (:func:`~spsc.study.executor.dask_client`).

Units: mm, N, kPa, mm², mm³; stiffness N/mm, sensitivity kPa/mm.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from spsc.cad.geometry import LENGTHS
from spsc.core.errors import ParameterError
from spsc.study.tolerance import salib_seed

__all__ = ["COLUMNS", "QUANTILES", "sample_setups", "band", "curve_of", "DEFAULT_SAMPLES"]

COLUMNS = ("force_N", "pressure_kPa", "contact_area_mm2", "volume_change_mm3")
QUANTILES = (5, 50, 95)
#: Saltelli's base samples N (the model runs N (D + 2) setups)
DEFAULT_SAMPLES = 256


def _nominal(setup) -> dict:
    g = setup.body
    return {"t0": g.t0, "w": g.w, "h": g.h, "l": g.l, "pressure": setup.load.pressure_kPa}


def sample_setups(setup, tolerance, n: int, seed: int):
    """(SALib's problem, the draws X (samples × inputs), the setups: a checked
    :class:`~spsc.core.setup.Setup` per draw, or the one-line reason it is none)."""
    from SALib.sample import sobol

    from spsc.core.loadcase import check_load

    nominal = _nominal(setup)
    tolerance.check(nominal)
    problem = tolerance.problem(nominal)
    X = sobol.sample(problem, n, calc_second_order=False, seed=seed)
    lc = setup.load
    out = []
    for row in X:
        draw = dict(zip(tolerance.names, row.tolist()))
        try:
            geometry = setup.body.replace(**{k: draw[k] for k in LENGTHS if k in draw})
            scale = draw.get("material", 1.0)
            if not scale > 0:
                raise ParameterError("material scale", f"{scale:.3g}", "> 0")
            load = check_load(geometry, pressure_kPa=draw.get("pressure", lc.pressure_kPa),
                              reservoir_mm3=lc.reservoir_mm3, stroke_mm=lc.stroke_mm,
                              points=lc.points, polytropic_n=lc.polytropic_n)
            mat = setup.material if scale == 1.0 else replace(
                setup.material.scaled(scale), name=setup.material.name)
            contact = setup.contact
            if "friction" in draw:
                from spsc.core.setup import Contact
                from spsc.study.tolerance import friction_of

                spread = next(s for s in tolerance.spreads if s.name == "friction")
                c = setup.contact
                contact = Contact.of(c.indenter, friction_of(draw["friction"], spread),
                                     c.object_stiffness)
            out.append(replace(setup, body=geometry, material=mat, load=load,
                               contact=contact))
        except ParameterError as exc:
            out.append(str(exc))
    return problem, X, out


def band(setup, options, model: str, tolerance, *, n: int = DEFAULT_SAMPLES, seed: int = 0,
         workers=None, scheduler=None, progress=None) -> dict:
    """The band record of ``setup`` with ``model`` (its ``options``) under ``tolerance``
    (module docstring). ``progress(done, total)`` after each sample a worker returns."""
    from spsc.models import get

    t0 = time.perf_counter()
    entry = get(model)
    problem, X, setups = sample_setups(setup, tolerance, n, seed)
    refused = {i: s for i, s in enumerate(setups) if isinstance(s, str)}
    for i, s in enumerate(setups):
        if i in refused:
            continue
        try:
            entry.check(s, options, verb="curve", quiet=True)
        except ParameterError as exc:
            refused[i] = str(exc)
    run = [i for i in range(len(setups)) if i not in refused]
    curves = _curves(entry, [setups[i] for i in run], options, workers, scheduler, progress)
    y = np.linspace(0.0, setup.load.stroke_mm, setup.load.points)
    Y = {c: np.full((len(setups), y.size), np.nan) for c in COLUMNS}
    metrics = {"stiffness": np.full(len(setups), np.nan),
               "sensitivity": np.full(len(setups), np.nan)}
    for i, c in zip(run, curves):
        for col in COLUMNS:
            Y[col][i] = np.where(c.converged, getattr(c, col), np.nan)
        metrics["stiffness"][i] = c.mean_stiffness(reached=True)
        metrics["sensitivity"][i] = c.mean_sensitivity(reached=True)
    record = {"model": model, "tolerance": tolerance.to_dict(), "base_samples": n,
              "seed": seed, "samples": len(setups), "computed": len(run),
              "refused": len(refused), "first_refusal": next(iter(refused.values()), ""),
              "y_mm": y.tolist(), "quantiles": list(QUANTILES)}
    for col in COLUMNS:
        record[col] = _quantiles(Y[col], axis=0)
    for name, unit in (("stiffness", "N_per_mm"), ("sensitivity", "kPa_per_mm")):
        record[f"{name}_{unit}"] = _quantiles(metrics[name], axis=0)
    record["sobol"] = _sobol(problem, metrics, seed)
    record["seconds"] = time.perf_counter() - t0
    return record


def _curves(entry, setups, options, workers, scheduler, progress) -> list:
    if not setups:
        return []
    if hasattr(entry, "curves_many"):  # one batched call (the surrogate)
        out = entry.curves_many(setups, options)
        if progress:
            progress(len(setups), len(setups))
        return out
    from distributed import as_completed

    from spsc.study.executor import dask_client

    with dask_client(workers, scheduler) as client:
        futures = client.map(curve_of, setups, options=options, model=entry.name, pure=False)
        index = {f.key: k for k, f in enumerate(futures)}
        out = [None] * len(setups)
        for done, f in enumerate(as_completed(futures), 1):
            out[index[f.key]] = f.result()
            if progress:
                progress(done, len(setups))
    return out


def curve_of(setup, *, options, model: str):
    """The curve of one setup with ``model`` (a Dask task)."""
    from spsc.models import get

    return get(model).curve(setup, options).curve


def _quantiles(a, axis: int) -> dict:
    with np.errstate(all="ignore"):
        import warnings

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # a travel no sample reached
            q = np.nanpercentile(a, QUANTILES, axis=axis)
    return {f"p{p}": (v.tolist() if np.ndim(v) else float(v)) for p, v in zip(QUANTILES, q)}


def _sobol(problem, metrics: dict, seed: int) -> dict:
    """Per metric: S1, S1_conf, ST, ST_conf per input (SALib), or why they are not
    computed."""
    from SALib.analyze import sobol

    out = {}
    for name, values in metrics.items():
        if not np.all(np.isfinite(values)):
            out[name] = {"not_computed": f"{int(np.sum(~np.isfinite(values)))} of "
                         f"{values.size} samples have no {name} (refused or not converged)"}
            continue
        if np.ptp(values) <= 1e-12 * max(np.abs(values).max(), 1e-300):
            out[name] = {"not_computed": f"the {name} does not vary over the samples"}
            continue
        si = sobol.analyze(problem, values, calc_second_order=False,
                             seed=salib_seed(seed))
        out[name] = {k: dict(zip(problem["names"], np.asarray(si[k], float).tolist()))
                     for k in ("S1", "S1_conf", "ST", "ST_conf")}
    return out
