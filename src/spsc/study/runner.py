"""Run a study's runs through the cache: cad → membrane / simplified / wall / FEM, here or on
a Dask cluster (:mod:`.executor`).

Each run is computed once per (inputs, code version) and stored by :class:`~.cache.Cache`; a
re-run with nothing changed only reads JSON (and starts no cluster). A run that raises is
recorded as failed (its reason kept for the report) and the others go on; failures are not
cached, so the next run retries them. A solver that returns a non-converged result is not a
failure: its curve (NaN where not reached) and message are stored like any other. On a
cluster the runs are independent tasks, the longest first, each storing its own result in the
cache; the client only reads hits and collects outcomes.
"""

from __future__ import annotations

import functools
import math
import sys
import time
import traceback
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from spsc.core.curve import Curve, SolveInfo

from spsc.study.cache import Cache
from spsc.study.runs import Run, model

__all__ = ["Outcome", "compute", "estimated_seconds", "run_all"]


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


def _membrane_files(run: Run, out, directory: Path) -> dict:
    """The membrane's meridians (nominal, inflated, last pressed) for the report's figures."""
    r = out.state
    last = max((i for i, s in enumerate(r.shapes) if s is not None), default=None)
    return {"meridians": {"nominal": {"x": r.inflated.x, "y": r.inflated.y}
                          if r.inflated is not None else None,
                          "inflated": _meridian(r.inflated),
                          "pressed": _meridian(r.shapes[last]) if last else None,
                          "pressed_y_mm": float(r.curve.y_mm[last]) if last else None}}


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


def _fem_files(run: Run, out, directory: Path) -> dict:
    """The FEM's VTUs (inflated and last pressed state) and the deformed cavity section of
    each, and the solve's facts the curve's protocol may not carry yet."""
    from spsc.fem.solid.chamber import write_vtu

    model, result = out.state
    curve = out.curve
    infl, presses = result.of("inflate"), result.of("press")
    keep = {"inflated": infl[-1] if infl else result.records[0]}
    if presses:
        keep["pressed"] = presses[-1]
    paths = write_vtu(model, replace(result, records=list(keep.values())), directory)
    info = curve.solver
    info = replace(info, instability=info.instability or result.instability,
                   iterations=info.iterations or sum(r.iterations for r in result.records),
                   details={"dofs": model.disc.n, "tetrahedra": model.mesh.n_tets,
                            **info.details})
    return {"curve": curve.replace(solver=info).to_dict(),
            "vtu": {name: p.name for name, p in zip(keep, paths)},
            "pressed_y_mm": float(curve.y_mm[len(presses)]) if presses else None,
            "sections": {name: _section(model, rec.x, run.geometry().z_widest)
                         for name, rec in keep.items()}}


#: model name -> files(run, outcome, directory) -> payload additions: what the report shows
#: of a model beyond its curve (a model without an entry stores its curve only)
_FILES = {"membrane": _membrane_files, "fem": _fem_files}


def _compute(run: Run, directory: Path, progress, mesh_dir) -> dict:
    from spsc.core.loadcase import LoadCase
    from spsc.core.setup import Setup
    from spsc.materials import material

    m = model(run.model)
    options = m.Options(**({"mesh_size": run.mesh_mm, "layers": run.layers} if m.meshed
                           else {}))
    load = LoadCase(run.pressure_kPa, run.reservoir_mm3, run.stroke_mm, run.points, 1.0)
    out = m.curve(Setup(run.geometry(), material(run.material), load), options,
                  progress=progress, cache_dir=mesh_dir)
    files = _FILES.get(run.model)
    return {"curve": out.curve.to_dict(), **(files(run, out, directory) if files else {})}


def compute(run: Run, directory: Path, progress=None, *, mesh_dir=None) -> dict:
    """Compute ``run`` (files into ``directory``; FEM meshes cached in ``mesh_dir``) →
    JSON-able payload with ``seconds``."""
    t0 = time.perf_counter()
    out = _compute(run, directory, progress, mesh_dir)
    out["seconds"] = round(time.perf_counter() - t0, 3)
    return out


def estimated_seconds(run: Run) -> float:
    """A rough compute time of ``run`` (s), used only to start the longest runs first: per
    plate position by model, scaled by the mesh's unknowns (∝ layers / size², a wall meshed
    through its thickness) and doubled for the open FEM chamber (more Newton steps)."""
    s = model(run.model).seconds_per_point * run.points
    if run.mesh_mm:
        s *= run.layers / 2 / run.mesh_mm**2
    if run.model == "fem" and run.mode == "open":
        s *= 2
    return s


def run_all(runs, cache: Cache, *, compute=compute, progress: bool = True, stream=None,
            cluster=None) -> dict[Run, Outcome]:
    """Every run through the cache with a tqdm bar; failures are isolated and reported on
    ``stream`` (stderr). Returns {run: Outcome} in the order given.

    Cache hits are read here. ``cluster`` None: the misses are computed here, in order;
    else a zero-argument factory returning a context manager that yields a
    ``distributed.Client`` (``functools.partial(executor.dask_client, workers=2)``), entered
    only if something is missing: the misses go to its workers longest first (FEM, then the
    wall, then the membrane models, so the workers stay busy to the end), each worker stores
    its run in the cache (which must be at the same path on every worker) and the outcomes
    are collected as they complete."""
    from spsc.core.progress import progress_bar

    stream = stream or sys.stderr
    runs = list(dict.fromkeys(runs))
    out: dict[Run, Outcome] = {}
    bar = progress_bar(total=len(runs), desc="spsc report", unit="run", disable=not progress,
                       file=stream, dynamic_ncols=True)

    def record(oc: Outcome) -> None:
        out[oc.run] = oc
        bar.set_postfix_str(oc.run.label, refresh=False)
        if not oc.ok:
            bar.write(f"spsc report: run {oc.run.label} failed: {oc.error}", file=stream)
        bar.update(1)

    try:
        misses = []
        for run in runs:
            hit = _lookup(run, cache)
            if hit is None:
                misses.append(run)
            else:
                record(hit)
        if cluster is None:
            for run in misses:
                record(_attempt(run, cache, compute, _step(bar, run)))
        elif misses:
            _on_cluster(misses, cache, compute, cluster, record)
    finally:
        bar.close()
    return {run: out[run] for run in runs}


def _step(bar, run: Run):
    """The progress callback of one run computed here: its label and load point on the bar."""
    bar.set_postfix_str(run.label, refresh=True)

    def step(done, total):
        bar.set_postfix_str(f"{run.label} [{done}/{total}]", refresh=True)

    return step


def _lookup(run: Run, cache: Cache) -> Outcome | None:
    """The cached outcome of ``run``, None if it is not cached, a failure if reading fails
    (e.g. its inputs do not resolve)."""
    t0 = time.perf_counter()
    try:
        hit = cache.get(run)
    except Exception as exc:  # noqa: BLE001 — isolate any failure of one run
        return _failure(run, exc, time.perf_counter() - t0)
    if hit is None:
        return None
    return Outcome(run, True, hit, cached=True, seconds=float(hit.get("seconds", math.nan)))


def _attempt(run: Run, cache: Cache, compute, progress=None) -> Outcome:
    """Compute ``run`` into ``cache``; its outcome, a failure if anything raises."""
    t0 = time.perf_counter()
    try:
        payload = cache.put(run, lambda d: compute(run, d, progress, mesh_dir=cache.mesh_dir))
    except Exception as exc:  # noqa: BLE001 — isolate any failure of one run
        return _failure(run, exc, time.perf_counter() - t0)
    return Outcome(run, True, payload,
                   seconds=float(payload.get("seconds", time.perf_counter() - t0)))


def _failure(run: Run, exc: BaseException, seconds: float) -> Outcome:
    """A failed outcome saying why: the exception and where it was raised."""
    why = f"{type(exc).__name__}: {exc}"
    tb = traceback.extract_tb(exc.__traceback__)
    if tb:
        why += f" (at {Path(tb[-1].filename).name}:{tb[-1].lineno})"
    return Outcome(run, False, None, error=why, seconds=seconds)


def _remote_attempt(run: Run, key: str, root: str, compute) -> Outcome:
    """A worker's task: :func:`_attempt` into the cache at ``root``, unless this worker's code
    gives the run another key than the client's (other sources: its result would be stored
    under a key the client never reads)."""
    if run.key() != key:
        return _failure(run, RuntimeError(
            f"the worker's code differs from the client's (cache key {run.key()[:16]}, "
            f"expected {key[:16]}): run the workers on this checkout"), 0.0)
    return _attempt(run, Cache(root), compute)


def _on_cluster(misses, cache: Cache, compute, cluster, record) -> None:
    """Compute ``misses`` on the cluster ``cluster()`` opens, longest first; ``record`` each
    outcome as it completes. A lost worker fails the run it had (after Dask's retries on
    others); a cluster that fails fails only the runs not finished."""
    root = str(cache.root.resolve())
    pending = dict.fromkeys(sorted(misses, key=estimated_seconds, reverse=True))
    try:
        with cluster() as client:
            for oc in _longest_first(client, list(pending), root, compute):
                pending.pop(oc.run)
                record(oc)
    except Exception as exc:  # noqa: BLE001 — the cluster itself: fail what is left
        for run in list(pending):
            record(_failure(run, RuntimeError(f"Dask cluster: {type(exc).__name__}: {exc}"),
                            math.nan))


def _longest_first(client, order, root: str, compute):
    """Outcomes of ``order``'s runs as they complete, with one run in flight per worker
    thread: the next (longest remaining) run goes to the first free worker. (Dask's own
    queueing holds tasks back only for large groups; a few misses would be spread over the
    workers at once, and one worker could end with two long runs while the other idles.)"""
    from distributed import as_completed

    todo = list(order)
    futures = {}
    done = as_completed()

    def top_up():
        while todo and len(futures) < max(1, sum(client.nthreads().values())):
            run = todo.pop(0)
            future = client.submit(_remote_attempt, run, run.key(), root, compute, pure=False)
            futures[future] = run
            done.add(future)

    top_up()
    for future in done:
        run = futures.pop(future)
        try:
            oc = future.result()
        except Exception as exc:  # noqa: BLE001 — a lost worker, a task not unpickled
            oc = _failure(run, exc, math.nan)
        future.release()
        top_up()
        yield oc
