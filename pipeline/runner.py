"""Run a study's runs through the cache: cad → membrane / simplified / FEM.

Each run is computed once per (inputs, code version) and stored by :class:`~.cache.Cache`; a
re-run with nothing changed only reads JSON. A run that raises is recorded as failed (its
reason kept for the report) and the others go on; failures are not cached, so the next run
retries them. A solver that returns a non-converged result is not a failure: its curve (NaN
where not reached) and message are stored like any other.
"""

from __future__ import annotations

import functools
import importlib
import math
import sys
import time
import traceback
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from spsc.core.curve import Curve, SolveInfo

from .cache import Cache
from .study import Run

__all__ = ["Outcome", "compute", "curve_model", "run_all"]


@dataclass(frozen=True, eq=False)
class Outcome:
    """What became of a run: ``ok`` (a payload exists), ``cached`` (read, not computed),
    ``error`` (why it failed), ``seconds`` (compute time of the payload, or of the failure).
    The payload holds the model's curve JSON (``Curve.to_dict()``, with its ``solver`` block)
    under ``curve`` and model-specific files and shapes beside it."""

    run: Run
    ok: bool
    payload: dict | None
    error: str = ""
    seconds: float = 0.0
    cached: bool = False

    @functools.cached_property
    def curve(self) -> Curve | None:
        return Curve.from_dict(self.payload["curve"]) if self.ok else None

    @property
    def solver(self) -> SolveInfo | None:
        """How the solve went (converged, message, instability, iterations, details)."""
        return self.curve.solver if self.ok else None

    @property
    def dir(self) -> Path | None:
        return Path(self.payload["dir"]) if self.ok else None


def _meridian(shape) -> dict | None:
    if shape is None:
        return None
    x, rho, eta = shape.meridian()
    return {"x": np.round(x, 6), "rho": np.round(rho, 6), "eta": np.round(eta, 6)}


def _membrane(run: Run, directory: Path, progress, mesh_dir) -> dict:
    from spsc.membrane.solver import solve

    r = solve(run.geometry(), run.material, pressure_kPa=run.pressure_kPa,
              reservoir_mm3=run.reservoir_mm3, stroke_mm=run.stroke_mm, points=run.points)
    last = max((i for i, s in enumerate(r.shapes) if s is not None), default=None)
    return {"curve": r.curve.to_dict(),
            "meridians": {"nominal": {"x": r.inflated.x, "y": r.inflated.y}
                          if r.inflated is not None else None,
                          "inflated": _meridian(r.inflated),
                          "pressed": _meridian(r.shapes[last]) if last else None,
                          "pressed_y_mm": float(r.curve.y_mm[last]) if last else None}}


def curve_model(module: str, function: str, *, material_object: bool = False,
                meshed: bool = False):
    """The compute entry of a model that is a function returning a :class:`Curve` from a
    geometry and the membrane's setup arguments (``material``, ``pressure_kPa``,
    ``reservoir_mm3``, ``stroke_mm``, ``points``): the simplified model, the wall model.
    ``material_object``: pass the catalogue :class:`~spsc.membrane.materials.Material`, not its
    name. ``meshed``: the run's mesh size and layers go in as the model's ``settings``
    (``<module>.WallSettings``-like: ``mesh_size_mm``, ``layers``)."""

    def compute(run: Run, directory: Path, progress, mesh_dir) -> dict:
        from spsc.membrane.materials import material

        mod = importlib.import_module(module)
        fn = getattr(mod, function)
        mat = material(run.material) if material_object else run.material
        kw = {}
        if meshed:
            kw["settings"] = mod.WallSettings(mesh_size_mm=run.mesh_mm, layers=run.layers)
        c = fn(run.geometry(), material=mat, pressure_kPa=run.pressure_kPa,
               reservoir_mm3=run.reservoir_mm3, stroke_mm=run.stroke_mm, points=run.points,
               **kw)
        return {"curve": c.to_dict()}

    return compute


def _section(model, x, z_centre: float) -> dict:
    """The deformed cavity profile in the plane y = 0 (the middle section), x ≥ 0, ordered
    from the base to the apex: the FEM counterpart of the membrane meridian (mm)."""
    X = model.disc.X
    cav = model.mesh.nodes_on("cavity")
    sel = cav[np.abs(X[cav, 1]) < 1e-9]
    u = model.displacement(x)[sel]
    order = np.argsort(np.arctan2(X[sel, 2] - z_centre, X[sel, 0]))
    sel, u = sel[order], u[order]
    return {"x": np.round(X[sel, 0], 6), "z": np.round(X[sel, 2], 6),
            "rho": np.round(X[sel, 0] + u[:, 0], 6), "eta": np.round(X[sel, 2] + u[:, 2], 6)}


def _fem(run: Run, directory: Path, progress, mesh_dir) -> dict:
    from spsc.fem.run import ChamberRun, run_chamber, write_vtu
    from spsc.membrane.materials import material

    spec = ChamberRun(run.geometry(), material(run.material), pressure_kPa=run.pressure_kPa,
                      reservoir_mm3=run.reservoir_mm3, stroke_mm=run.stroke_mm,
                      points=run.points, mesh_size_mm=run.mesh_mm, layers=run.layers)
    curve, result, model = run_chamber(spec, progress=progress, cache_dir=mesh_dir)
    infl, presses = result.of("inflate"), result.of("press")
    keep = {"inflated": infl[-1] if infl else result.records[0]}
    if presses:
        keep["pressed"] = presses[-1]
    paths = write_vtu(model, replace(result, records=list(keep.values())), directory)
    info = curve.solver  # the run's facts the curve's protocol may not carry yet
    info = replace(info, instability=info.instability or result.instability,
                   iterations=info.iterations or sum(r.iterations for r in result.records),
                   details={"dofs": model.disc.n, "tetrahedra": model.mesh.n_tets,
                            **info.details})
    return {"curve": curve.replace(solver=info).to_dict(),
            "vtu": {name: p.name for name, p in zip(keep, paths)},
            "pressed_y_mm": float(curve.y_mm[len(presses)]) if presses else None,
            "sections": {name: _section(model, rec.x, run.geometry().z_widest)
                         for name, rec in keep.items()}}


#: model name -> compute(run, directory, progress, mesh_dir) -> payload; one entry per model
#: of :data:`~.study.MODELS` (the wall model: ``"wall": curve_model("spsc.fem.wall",
#: "wall_curve", material_object=True)`` with ``Model("wall", "spsc.fem.wall", bending=True)``)
_COMPUTE = {
    "membrane": _membrane,
    "simplified": curve_model("spsc.membrane.simplified", "simplified_curve"),
    "wall": curve_model("spsc.fem.wall", "wall_curve", material_object=True, meshed=True),
    "fem": _fem,
}


def compute(run: Run, directory: Path, progress=None, *, mesh_dir=None) -> dict:
    """Compute ``run`` (files into ``directory``; FEM meshes cached in ``mesh_dir``) →
    JSON-able payload with ``seconds``."""
    t0 = time.perf_counter()
    out = _COMPUTE[run.model](run, directory, progress, mesh_dir)
    out["seconds"] = round(time.perf_counter() - t0, 3)
    return out


def run_all(runs, cache: Cache, *, compute=compute, progress: bool = True,
            stream=None) -> dict[Run, Outcome]:
    """Every run through the cache, in order, with a tqdm bar; failures are isolated and
    reported on ``stream`` (stderr). Returns {run: Outcome} in the order given."""
    from tqdm import tqdm

    stream = stream or sys.stderr
    runs = list(dict.fromkeys(runs))
    out: dict[Run, Outcome] = {}
    bar = tqdm(total=len(runs), desc="spsc report", unit="run", disable=not progress,
               file=stream, dynamic_ncols=True)
    try:
        for run in runs:
            bar.set_postfix_str(run.label, refresh=True)

            def step(done, total, _run=run):
                bar.set_postfix_str(f"{_run.label} [{done}/{total}]", refresh=True)

            t0 = time.perf_counter()
            try:
                hit = cache.get(run)
                if hit is not None:
                    out[run] = Outcome(run, True, hit, cached=True,
                                       seconds=float(hit.get("seconds", math.nan)))
                    bar.update(1)
                    continue
                payload = cache.put(run, lambda d, _run=run: compute(
                    _run, d, step, mesh_dir=cache.mesh_dir))
                out[run] = Outcome(run, True, payload,
                                   seconds=float(payload.get("seconds", time.perf_counter() - t0)))
            except Exception as exc:  # noqa: BLE001 — isolate any failure of one run
                why = f"{type(exc).__name__}: {exc}"
                tb = traceback.extract_tb(exc.__traceback__)
                if tb:
                    why += f" (at {Path(tb[-1].filename).name}:{tb[-1].lineno})"
                out[run] = Outcome(run, False, None, error=why,
                                   seconds=time.perf_counter() - t0)
                bar.write(f"spsc report: run {run.label} failed: {why}", file=stream)
            bar.update(1)
    finally:
        bar.close()
    return out

