"""After the search: the best design re-run with the 3D FEM and compared with the fast model,
and the part built and put through the full printability gate.

The FEM runs both modes over the fast model's stroke (plate positions every 0.5 mm), the two
modes as two tasks on the Dask workers; the fast model's curves are recomputed beside them. The
comparison is per metric, (fast − FEM)/FEM in %; the wall model is expected within 5 % of the
FEM (docs/theory/wall.md, the wall model's bench), the membrane models further (no bending). The part is
the bladder of ``spsc bladder`` (wall, floor, flange, barbed port): STEP, STL, 3MF and the
gate's ``check.json`` for the process.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

from spsc.design.goal import METRIC_NAMES, Goal
from spsc.cad.geometry import PARAMS as _PARAMS

__all__ = ["VERIFY_TOLERANCE_PCT", "FEM_STEP_MM", "mode_curve", "check_mode", "metrics_of", "verify_fem",
           "build_part", "fem_points"]

#: Expected agreement of the fast model with the 3D FEM on the goal's metrics (wall model).
VERIFY_TOLERANCE_PCT = 5.0
#: Plate travel between the FEM's positions (mm).
FEM_STEP_MM = 0.5


def fem_points(stroke_mm: float) -> int:
    """Plate positions of the FEM over ``stroke_mm`` (mm): every :data:`FEM_STEP_MM`."""
    return max(3, int(round(stroke_mm / FEM_STEP_MM)) + 1)


def mode_curve(params: dict, model: str, mode: str, *, points: int | None, stroke_mm: float,
               options: dict | None = None):
    """The Curve of a design (``params`` under the CLI's names, all seven parameters) with
    ``model`` of :data:`spsc.models.MODELS` in ``mode`` high (closed chamber) or low
    (with the design's reservoir); ``options`` override the model's defaults (e.g. the FEM's
    ``mesh_size``). The same checks and defaults as ``spsc curve``."""
    m, setup, opts = check_mode(params, model, mode, points=points, stroke_mm=stroke_mm,
                                options=options)
    return m.curve(setup, opts).curve


def check_mode(params: dict, model: str, mode: str, *, points: int | None, stroke_mm: float,
               options: dict | None = None):
    """``(model, setup, options)`` of :func:`mode_curve`, checked against the load case's and
    the model's limits (ParameterError, one line) without solving anything."""
    from spsc.cad.geometry import SPSCGeometry
    from spsc.core.setup import Setup
    from spsc.materials import material

    from spsc.models import get, options_from

    entry = get(model)
    geom = SPSCGeometry(**{k: float(params[k]) for k in _PARAMS})
    reservoir = 0.0 if mode == "high" else float(params["reservoir"])
    setup = Setup.of(geom, material(params["material"]), pressure_kPa=params["pressure"],
                     reservoir_mm3=reservoir, stroke_mm=stroke_mm,
                     points=entry.points if points is None else points)
    opts = options_from(entry.Options, options or {})
    entry.check(setup, opts, verb="design", quiet=True)
    return entry, setup, opts


def metrics_of(high, low) -> dict:
    """The design metrics of a high/low pair of curves (:func:`~.metrics.design_metrics`)."""
    from dataclasses import asdict

    from spsc.study.metrics import design_metrics

    return {k: float(v) for k, v in asdict(design_metrics([high], [low])).items()}


def _converged(curve) -> tuple[bool, str]:
    info = curve.solver
    if info.converged and curve.all_converged:
        return True, ""
    first = next((m for m, c in zip(curve.message, curve.converged) if not c), "")
    return False, info.message if not info.converged else first


def _pct(fast: float, ref: float) -> float:
    if not (math.isfinite(fast) and math.isfinite(ref)) or ref == 0:
        return math.nan
    return 100.0 * (fast - ref) / abs(ref)


def verify_fem(client, params: dict, goal: Goal, *, fast_model: str, points: int | None,
               stroke_mm: float, mesh_size_mm: float, out: Path, fast_curves=None) -> dict:
    """Run the FEM (both modes, in parallel on ``client``'s workers) and the fast model on the
    design ``params``; write the four curves under ``out`` (JSON) and return the comparison:
    both metric sets, the differences in %, the largest on the goal's metrics, whether it is
    within :data:`VERIFY_TOLERANCE_PCT`, and how the FEM solves went."""
    t0 = time.perf_counter()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    n_fem = fem_points(stroke_mm)
    futs = {m: client.submit(mode_curve, params, "fem", m, points=n_fem, stroke_mm=stroke_mm,
                             options={"mesh_size": mesh_size_mm}, pure=False)
            for m in ("high", "low")}
    fast = fast_curves or {m: mode_curve(params, fast_model, m, points=points,
                                         stroke_mm=stroke_mm) for m in ("high", "low")}
    fem, errors = {}, []
    for m, f in futs.items():
        try:
            fem[m] = f.result()
        except Exception as exc:  # a refused mesh, a worker lost: said, not raised
            errors.append(f"{m} mode: {type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}")
    files = {}
    for name, curves in ((fast_model, fast), ("fem", fem)):
        for m, c in curves.items():
            path = out / f"{name}-{m}.json"
            c.to_json(path)
            files[f"{name}_{m}"] = path.name
    result = {"model": "fem", "fast_model": fast_model, "stroke_mm": stroke_mm,
              "points": {"fast": len(fast["high"]), "fem": n_fem}, "mesh_size_mm": mesh_size_mm,
              "files": files, "tolerance_pct": VERIFY_TOLERANCE_PCT}
    fast_m = metrics_of(fast["high"], fast["low"])
    result["metrics"] = {"fast": fast_m, "fem": None}
    if errors:
        result.update(converged=False, message="; ".join(errors), agrees=False,
                      difference_pct=None, max_abs_difference_pct=None)
    else:
        fem_m = metrics_of(fem["high"], fem["low"])
        diff = {k: _pct(fast_m[k], fem_m[k]) for k in METRIC_NAMES}
        judged = [abs(diff[k]) for k in (goal.needed or METRIC_NAMES) if math.isfinite(diff[k])]
        worst = max(judged, default=math.nan)
        states = [(m, *_converged(c)) for m, c in fem.items()]
        message = "; ".join(f"{m} mode: {msg}" for m, ok, msg in states if not ok)
        result["metrics"]["fem"] = fem_m
        result.update(converged=all(ok for _, ok, _ in states), message=message,
                      difference_pct=diff, max_abs_difference_pct=worst,
                      agrees=bool(math.isfinite(worst) and worst <= VERIFY_TOLERANCE_PCT),
                      fem_met=goal.met(fem_m) if goal.targets else None,
                      fem_miss=goal.miss(fem_m) if goal.targets else None,
                      fem_seconds={m: c.solver.seconds for m, c in fem.items()})
    result["seconds"] = time.perf_counter() - t0
    result["_curves"] = {"fast": fast, "fem": fem}  # for the page; not written to JSON
    return result


def build_part(params: dict, process: str, out: Path, name: str = "bladder") -> dict:
    """Build the bladder of the design (as ``spsc bladder``), write STEP/STL/3MF and the
    design facts under ``out``, run the full printability gate for ``process`` and write its
    ``check.json``; returns the files (names relative to ``out``), the gate's verdict and the
    times (s)."""
    from spsc.cad.bladder import build_bladder
    from spsc.cad.check import check_mesh
    from spsc.cad.export import export_part
    from spsc.cad.geometry import SPSCGeometry
    from spsc.cad.meshbuild import bladder_mesh

    from spsc.cad.specs import bladder_spec

    out = Path(out)
    t0 = time.perf_counter()
    spec = bladder_spec(SPSCGeometry(**{k: float(params[k]) for k in _PARAMS}), 4, 3.0)
    bladder = build_bladder(spec)
    written = export_part(bladder.solid, bladder.design, out, name, mesh=bladder_mesh(spec))
    t_build = time.perf_counter() - t0
    report = check_mesh(written["paths"]["stl"], design=bladder.design, process=process)
    report.to_json(out / "check.json")
    return {"files": {k: p.name for k, p in written["paths"].items()} | {"check": "check.json"},
            "triangles": written["triangles"], "process": process,
            "gate": {"passed": bool(report.passed), "failed": list(report.failed),
                     "summary": report.summary()},
            "seconds": {"build_export": t_build, "gate": time.perf_counter() - t0 - t_build}}
