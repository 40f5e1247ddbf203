"""The surrogate against the wall model on designs it never saw: fresh designs sampled over
its domain (a Latin hypercube of another seed than training's), each at a random size, setup
pressure and polytropic index, in both modes (closed, and the paper's 40 cm³ reservoir), the
wall curves on Dask, the surrogate's beside them.

Errors are the issue's measures: at every point, the force's and the pressure rise's error
relative to that curve's largest value (of the wall's); per curve, the mean stiffness
(F(end) − F(0))/stroke and the mean sensitivity (P(end) − P(0))/stroke, relative; the stated
error's coverage, the share of points whose true error is within it. They are taken where the
surrogate answers, as a user gets it: a point it marks past its map (not converged, NaN in its
curve) is counted apart (``unanswered``), not scored, and a curve whose end it does not answer
has no mean stiffness or sensitivity to compare.
"""

from __future__ import annotations

import numpy as np

from spsc.models.surrogate.domain import BOUNDS, RATIOS
from spsc.models.surrogate.gp import RISK_FLAG

__all__ = ["check_cases", "wall_cases", "beside", "compare", "summary", "MODES"]

#: The modes every check case runs: (name, reservoir mm³).
MODES = (("high", 0.0), ("low", 40_000.0))


def check_cases(count: int, seed: int, fixed: dict) -> list[dict]:
    """``count`` cases: the seven parameters (w 8–14 mm, the ratios over the domain, the
    ``fixed`` ratios at their value), setup pressure 10–50 kPa, polytropic index 1–1.4 and a
    stroke of 0.4 h up to 6 mm (25 points)."""
    from scipy.stats import qmc

    free = [r for r in RATIOS if r not in fixed]
    u = qmc.LatinHypercube(len(free) + 3, seed=np.random.default_rng(seed)).random(count)
    cases = []
    for row in u:
        r = dict(fixed)
        for k, name in enumerate(free):
            lo, hi = BOUNDS[name]
            r[name] = lo + row[k] * (hi - lo)
        w = round(8.0 + 6.0 * row[-3], 3)
        # free ratios drawn to 0.001 mm, the fixed exact (h = 13/11 w, not 0.001 mm off it)
        size = lambda name: r[name] * w if name in fixed else round(r[name] * w, 3)  # noqa
        g = {"w": w, "h": size("h/w"), "l": size("l/w"), "t0": size("t0/w"),
             "n1": round(r["n1"], 3), "n2": round(r["n2"], 3), "cy": round(r["cy"], 3)}
        cases.append({"geometry": g, "pressure_kPa": round(10.0 + 40.0 * row[-2], 2),
                      "polytropic_n": round(1.0 + 0.4 * row[-1], 3),
                      "stroke_mm": round(min(6.0, 0.4 * g["h"]), 2), "points": 25})
    return cases


def _wall_job(case: dict) -> dict:
    """The wall model's curves of one case in both modes (its arrays, or its error)."""
    from spsc.cad.geometry import SPSCGeometry
    from spsc.core.setup import Setup
    from spsc.materials import material
    from spsc.models import get
    from spsc.models.wall import WallOptions

    try:
        setup = Setup.of(SPSCGeometry(**case["geometry"]), material("tpu60a"),
                         pressure_kPa=case["pressure_kPa"], stroke_mm=case["stroke_mm"],
                         points=case["points"], polytropic_n=case["polytropic_n"])
        curves = get("wall").curves(setup, [v for _, v in MODES], WallOptions())
    except Exception as exc:  # a case the wall model refuses is reported, not fatal
        return {**case, "error": repr(exc)}
    out = dict(case)
    for (mode, _), c in zip(MODES, curves):
        out[mode] = {"y": c.y_mm, "F": c.force_N, "P": c.pressure_kPa,
                     "converged": np.asarray(c.converged), "seconds": c.solver.seconds,
                     "jumps": len(c.solver.details.get("jumps", ())),
                     "instability": c.solver.instability}
    return out


def wall_cases(cases: list[dict], *, workers=None, scheduler=None, progress=None) -> list:
    """:func:`_wall_job` of every case on Dask, in order."""
    from distributed import as_completed

    from spsc.study.executor import dask_client

    done = [None] * len(cases)
    with dask_client(workers, scheduler) as client:
        futures = {client.submit(_wall_job, c, pure=False): i for i, c in enumerate(cases)}
        for k, fut in enumerate(as_completed(futures), start=1):
            done[futures[fut]] = fut.result()
            if progress is not None:
                progress(k, len(cases))
    return done


def _finished(res: dict) -> bool:
    """The wall model computed both modes of the case to the end."""
    return "error" not in res and all(np.all(res[m]["converged"]) for m, _ in MODES)


def beside(surrogate, results: list[dict], *, draws: int = 32, seed: int = 0):
    """(case, the surrogate's answer for both modes, :meth:`~spsc.models.surrogate.predict.
    Surrogate.curves`) for every case of ``results`` the wall model finished, on the wall
    curves' own travels."""
    from spsc.cad.geometry import PARAMS
    from spsc.materials import material

    mu = material("tpu60a").shear_modulus
    for res in filter(_finished, results):
        params = np.array([[res["geometry"][k] for k in PARAMS]] * len(MODES))
        y = np.array([res[m]["y"] for m, _ in MODES])
        yield res, surrogate.curves(params, mu, y, res["pressure_kPa"],
                                    [v for _, v in MODES], res["polytropic_n"], draws=draws,
                                    rng=np.random.default_rng(seed))


def compare(surrogate, results: list[dict], *, draws: int = 32, seed: int = 0) -> dict:
    """Per-point and per-curve errors of ``surrogate`` against the wall ``results`` of
    :func:`wall_cases` (cases the wall model did not finish are counted apart)."""
    rows, points = [], {"force": [], "pressure": [], "force_cov": [], "pressure_cov": []}
    finished = [r for r in results if _finished(r)]
    skipped = len(results) - len(finished)
    for res, s in beside(surrogate, finished, draws=draws, seed=seed):
        g = res["geometry"]
        for j, (mode, _) in enumerate(MODES):
            w = res[mode]
            ok = s["converged"][j] & s["inside"][j]  # what the surrogate answers
            eF, eP = (s["force_N"][j] - w["F"])[ok], (s["pressure_kPa"][j] - w["P"])[ok]
            fmax, pmax = np.abs(w["F"]).max(), np.abs(w["P"] - w["P"][0]).max()
            points["force"].append(np.abs(eF) / fmax)
            points["pressure"].append(np.abs(eP) / pmax)
            points["force_cov"].append(np.abs(eF) <= s["force_err_N"][j][ok] + 1e-12)
            points["pressure_cov"].append(np.abs(eP) <= s["pressure_err_kPa"][j][ok] + 1e-12)
            stroke = w["y"][-1]
            k_w = (w["F"][-1] - w["F"][0]) / stroke
            k_s = (s["force_N"][j][-1] - s["force_N"][j][0]) / stroke
            sen_w = (w["P"][-1] - w["P"][0]) / stroke
            sen_s = (s["pressure_kPa"][j][-1] - s["pressure_kPa"][j][0]) / stroke
            end = bool(ok[0] and ok[-1])
            rows.append({**g, "pressure_kPa": res["pressure_kPa"], "mode": mode,
                         "polytropic_n": res["polytropic_n"], "stroke_mm": stroke,
                         "unanswered": int(np.count_nonzero(~ok)),
                         "force_err": float(np.max(points["force"][-1], initial=0.0)),
                         "pressure_err": float(np.max(points["pressure"][-1], initial=0.0)),
                         "stiffness_err": abs(k_s - k_w) / abs(k_w) if end else np.nan,
                         "sensitivity_err": abs(sen_s - sen_w) / abs(sen_w) if end else np.nan,
                         "inside": bool(np.all(s["inside"][j])),
                         "snaps": int(w.get("jumps", 0)) > 0 or bool(w.get("instability")),
                         "flagged": bool(s["snap_risk"][j] >= RISK_FLAG),
                         "wall_seconds": w["seconds"]})
    return {"rows": rows, "points": {k: np.concatenate(v) for k, v in points.items()
                                     if v}, "skipped": skipped}


def summary(result: dict) -> dict:
    """The check's figures: quantiles of the per-point errors, the Table 1 metrics' errors,
    the coverage of the stated error; and the per-curve largest errors of the curves the
    surrogate flags (near designs that snap through) and of the others."""
    p, rows = result["points"], result["rows"]
    def q(a):
        a = np.asarray(a, float)
        a = a[np.isfinite(a)]  # a curve whose end the surrogate does not answer: no metric
        if a.size == 0:
            return {"median": np.nan, "p95": np.nan, "max": np.nan}
        return {"median": float(np.median(a)), "p95": float(np.percentile(a, 95)),
                "max": float(np.max(a))}

    out = {"curves": len(rows), "skipped_cases": result["skipped"],
           "unanswered_points": sum(r.get("unanswered", 0) for r in rows),
           "force": q(p["force"]), "pressure": q(p["pressure"]),
           "stiffness": q([r["stiffness_err"] for r in rows]),
           "sensitivity": q([r["sensitivity_err"] for r in rows]),
           "coverage_force": float(np.mean(p["force_cov"])),
           "coverage_pressure": float(np.mean(p["pressure_cov"])),
           "flagged": sum(r["flagged"] for r in rows),
           "snapping": sum(r["snaps"] for r in rows),
           "snapping_flagged": sum(r["snaps"] and r["flagged"] for r in rows)}
    for name, sel in (("unflagged", [r for r in rows if not r["flagged"]]),
                      ("flagged_curves", [r for r in rows if r["flagged"]])):
        if sel:
            out[name] = {k: q([r[k + "_err"] for r in sel]) for k in
                         ("force", "pressure", "stiffness", "sensitivity")}
    return out
