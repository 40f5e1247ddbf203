"""The report's headline with its band (issue 49): the wall model's Table 1 means (mean
stiffness and sensitivity over the stroke, the setup pressures and the types, in each mode —
:func:`~spsc.study.metrics.headline`) under a declared tolerance set, and whether the paper's
bench means fall inside the P5–P95 band.

One headline is 4 types × 4 pressures × 2 modes = 32 wall curves, so a Monte Carlo of it on the
wall model itself (hundreds of draws) is hours. The headline is a smooth function of few inputs
(the wall t0 and the material's stiffness scale: the two that carry 97–100 % of the variance of
a chamber's metrics, ``docs/guides/tolerance.md``), so it is computed on a grid of them and
interpolated (SciPy's ``RegularGridInterpolator``, cubic with four nodes or more an input), and
the interpolant is sampled by SALib's Sobol sequence for the quantiles and the Sobol indices
(Saltelli's scheme, Jansen's estimator). The interpolant is checked against the wall model at
draws off the grid (:data:`CHECKS`), and its largest error is part of the record.

A draw moves every type and setup pressure alike (one printer, one spool made the bench's four
chambers): a length's draw is an offset from the first type's nominal value, the material a
scale on the law's stiffness (W → s W), the pressure an offset of the regulator. The band is
therefore that of a systematic print error; prints scattering independently per type would
narrow it by up to √4 in the mean over the types. Friction is not an input here (a Coulomb wall
curve is ten times slower; its effect is the bench-gap study's rows).

Units: mm, kPa gauge, N/mm (stiffness), kPa/mm (sensitivity).
"""

from __future__ import annotations

import hashlib
import json
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from spsc.cad.geometry import LENGTHS
from spsc.core.errors import ParameterError
from spsc.study.tolerance import salib_seed

__all__ = ["DECLARED", "DECLARED_SOURCES", "NODES", "CHECKS", "METRICS", "declared_tolerance",
           "check_band_tolerance", "band_setups", "headline_band", "run_headline_band",
           "repropagated"]

#: the report's declared tolerance set (a tolerance file, :mod:`spsc.study.tolerance`)
DECLARED = Path(__file__).resolve().parents[1] / "report" / "data" / "tolerance-report.toml"
#: where each declared spread comes from, in words (the report prints them)
DECLARED_SOURCES = {
    "t0": "ASSUMED: the printed wall within ±0.1 mm of its nominal 1 mm (uniform), the range "
          "of the bench-gap study's wall rows; no measured scatter of the paper's prints is "
          "published. Replace it with your own measurements.",
    "material": "the stiffness between the two readings of the same published tension tests "
                "of printed FilaFlex 60A (MacCurdy Lab, SoRoForge, 'TPU Data/allData_n20/"
                "FilaFlex 60A.txt'), neo-Hookean over stretch 1–2.3: μ0 1.60 MPa read as "
                "true stress, 2.82 MPa as nominal stress, against the catalogue's 1.667 MPa "
                "(scale 0.958–1.691, uniform)."}
#: grid nodes an input (the nominal value is added when it is not one of them)
NODES = 4
#: draws off the grid at which the interpolant is checked against the wall model
CHECKS = 3
#: SALib's base samples of the interpolant (N (D + 2) evaluations)
SAMPLES = 4096
METRICS = ("stiffness", "sensitivity")
QUANTILES = (5, 50, 95)


def declared_tolerance():
    """The report's declared tolerance set (:data:`DECLARED`)."""
    from spsc.study.tolerance import read_tolerance

    return read_tolerance(DECLARED)


def _nominal(study) -> dict:
    from spsc.cad.geometry import preset

    g = preset(study.types[0])
    return {"t0": g.t0, "w": g.w, "h": g.h, "l": g.l, "pressure": 0.0}


def _range(spread, nominal: float) -> tuple[float, float]:
    """The grid's span of one input: a uniform's own range, else ±3 standard deviations
    (the material's sd is its cv), clipped above zero for a length or a scale."""
    if spread.dist == "uniform":
        return float(spread.low), float(spread.high)
    lo, hi = nominal - 3.0 * spread.sd, nominal + 3.0 * spread.sd
    if spread.name != "pressure":
        lo = max(lo, 0.05 * nominal)
    return lo, hi


def _nodes(tolerance, nominal: dict, n: int) -> dict:
    out = {}
    for s in tolerance.spreads:
        m = 1.0 if s.name == "material" else nominal[s.name]
        lo, hi = _range(s, m)
        nodes = np.linspace(lo, hi, n)
        if lo < m < hi and not np.isclose(nodes, m, rtol=0, atol=1e-9 * max(abs(m), 1)).any():
            nodes = np.sort(np.append(nodes, m))
        out[s.name] = nodes
    return out


def check_band_tolerance(tolerance) -> None:
    """At most two inputs and no friction (one-line ParameterError)."""
    if "friction" in tolerance.names:
        raise ParameterError("band tolerance [friction]", tolerance.source or "the file",
                             "not in the report's headline band (a Coulomb wall curve is ten "
                             "times slower): t0, w, h, l, pressure, material")
    if len(tolerance.spreads) > 2:
        raise ParameterError("band tolerance", ", ".join(tolerance.names),
                             "at most two inputs in the report's headline band (its grid has "
                             f"{NODES}+ nodes an input, 32 wall curves a node)")


def band_setups(study, draw: dict) -> dict:
    """The study's wall setups under one ``draw`` ({input: value}): ``{(type, pressure,
    mode): Setup}`` (module docstring: offsets from the first type's nominal lengths, a
    scale on the material, an offset on every setup pressure)."""
    from spsc.cad.geometry import preset
    from spsc.core.loadcase import LoadCase
    from spsc.core.setup import Setup
    from spsc.materials import material

    ref = _nominal(study)
    mat = material(study.materials[0])
    s = float(draw.get("material", 1.0))
    if s != 1.0:
        mat = replace(mat.scaled(s), name=mat.name)
    out = {}
    for t in study.types:
        g = preset(t)
        g = g.replace(**{k: getattr(g, k) + draw[k] - ref[k] for k in LENGTHS if k in draw})
        for mode in study.mode_names:
            for p in study.pressures_kPa:
                load = LoadCase(p + float(draw.get("pressure", 0.0)), study.reservoir(mode),
                                study.stroke_mm, study.membrane_points, 1.0)
                out[(t, p, mode)] = Setup(g, mat, load)
    return out


def _headline_of(study, curves: dict) -> dict:
    """{metric_mode: value} of one draw's curves ({(type, pressure, mode): Curve or None})."""
    from spsc.study.metrics import headline

    out = {}
    for mode in study.mode_names:
        h = headline({t: [curves[(t, p, mode)] for p in study.pressures_kPa]
                      for t in study.types})
        for q in METRICS:
            out[f"{q}_{mode}"] = h[q] if all(v["n"] == len(study.pressures_kPa)
                                             for v in h["types"].values()) else float("nan")
    return out


def _draws(tolerance, nominal: dict, n_nodes: int, n_checks: int,
           seed: int) -> tuple[list, list]:
    """The grid's draws (nodes, C order) and ``n_checks`` draws off it (SALib's Sobol
    sequence of the tolerance, the first ones inside the grid's span)."""
    from SALib.sample import sobol

    nodes = _nodes(tolerance, nominal, n_nodes)
    names = list(nodes)
    grid = [dict(zip(names, map(float, v)))
            for v in np.array(np.meshgrid(*nodes.values(), indexing="ij")).reshape(
                len(names), -1).T]
    X = sobol.sample(tolerance.problem(nominal), 64, calc_second_order=False, seed=seed)
    lo = np.array([v[0] for v in nodes.values()])
    hi = np.array([v[-1] for v in nodes.values()])
    inside = X[np.all((X > lo) & (X < hi), axis=1)]
    checks = [dict(zip(names, map(float, row))) for row in inside[1:n_checks + 1]]
    return grid, checks


def headline_band(study, tolerance, *, workers=None, scheduler=None, progress=None,
                  seed: int = 0, n_nodes: int = NODES, n_checks: int = CHECKS) -> dict:
    """The headline band record (module docstring) of ``study`` (its types, pressures, modes,
    stroke and first material) under ``tolerance``, on ``n_nodes`` grid nodes an input (and
    the nominal value) with ``n_checks`` draws off the grid; ``progress(done, total)`` per
    curve."""
    check_band_tolerance(tolerance)
    nominal = _nominal(study)
    tolerance.check(nominal)
    t0 = time.perf_counter()
    grid, checks = _draws(tolerance, nominal, n_nodes, n_checks, seed)
    draws = grid + checks
    jobs = [(k, key, s) for k, d in enumerate(draws)
            for key, s in band_setups(study, d).items()]
    curves = _compute([s for _, _, s in jobs], study, workers, scheduler, progress)
    per_draw: list[dict] = [{} for _ in draws]
    failed = []
    for (k, key, _), c in zip(jobs, curves):
        if isinstance(c, str):
            failed.append(f"{key}: {c}")
            c = None
        per_draw[k][key] = c
    values = [_headline_of(study, d) for d in per_draw]
    record = {"model": "wall", "tolerance": tolerance.to_dict(), "seed": seed,
              "nodes": {k: v.tolist() for k, v in _nodes(tolerance, nominal, n_nodes).items()},
              "grid": [{**d, **v} for d, v in zip(grid, values[:len(grid)])],
              "curves": len(jobs), "failed": len(failed), "first_failure": next(iter(failed), ""),
              "stopped_short": _stopped_short(per_draw),
              "compute_seconds": round(time.perf_counter() - t0, 1)}
    record.update(_propagate(tolerance, nominal, record["nodes"], values[:len(grid)],
                             checks, values[len(grid):], seed))
    return record


def _stopped_short(per_draw: list[dict]) -> list[dict]:
    """The curves that did not reach the stroke, by setup: type, pressure (kPa), mode, the
    draws they stopped in and the shortest stroke reached (mm). Their means are over the
    stroke reached, as the headline's are, so the band names them."""
    out: dict = {}
    for k, curves in enumerate(per_draw):
        for (t, p, mode), c in curves.items():
            if c is None or (c.solver.converged and c.all_converged):
                continue
            reached = float(np.max(c.y_mm[np.asarray(c.converged, bool)], initial=0.0))
            row = out.setdefault((t, p, mode), {"type": t, "pressure_kPa": float(p),
                                                "mode": mode, "draws": [],
                                                "reached_mm": reached})
            row["draws"].append(k)
            row["reached_mm"] = min(row["reached_mm"], reached)
    return list(out.values())


def _compute(setups, study, workers, scheduler, progress) -> list:
    """Each setup's wall curve on Dask (the study's wall mesh); a failure is its message."""
    from distributed import as_completed

    from spsc.study.executor import dask_client

    from spsc.models import get

    wall = get("wall")
    options = wall.Options(mesh_size=float(study.wall_mesh[0]), layers=int(study.wall_mesh[1]))
    out: list = [None] * len(setups)
    with dask_client(workers, scheduler) as client:
        futures = client.map(_curve, setups, options=options, pure=False)
        index = {f.key: k for k, f in enumerate(futures)}
        for done, f in enumerate(as_completed(futures), 1):
            out[index[f.key]] = f.result()
            if progress:
                progress(done, len(setups))
    return out


def _curve(setup, *, options):
    """One wall curve (a Dask task), or why it failed (one line)."""
    from spsc.models import get

    try:
        return get("wall").curve(setup, options).curve
    except (ParameterError, ArithmeticError, RuntimeError, np.linalg.LinAlgError) as exc:
        return f"{type(exc).__name__}: {exc}"


def _propagate(tolerance, nominal, nodes: dict, grid_values: list, checks: list,
               check_values: list, seed: int) -> dict:
    """The interpolant's check, quantiles and Sobol indices (module docstring)."""
    from SALib.analyze import sobol as sobol_analyze
    from SALib.sample import sobol
    from scipy.interpolate import RegularGridInterpolator

    axes = [np.asarray(v) for v in nodes.values()]
    shape = tuple(a.size for a in axes)
    method = "cubic" if min(shape) >= 4 else "linear"
    lo, hi = np.array([a[0] for a in axes]), np.array([a[-1] for a in axes])
    problem = tolerance.problem(nominal)
    X = sobol.sample(problem, SAMPLES, calc_second_order=False, seed=seed)
    clipped = float(np.mean(np.any((X < lo) | (X > hi), axis=1)))
    Xc = np.clip(X, lo, hi)
    out = {"method": f"RegularGridInterpolator ({method}) on {' × '.join(map(str, shape))} "
                     "nodes", "samples": int(X.shape[0]), "clipped_share": clipped,
           "checks": [], "quantiles": {}, "sobol": {}}
    keys = list(grid_values[0])
    if any(not np.isfinite(v[k]) for v in grid_values for k in keys):
        out["not_computed"] = "a grid node has no headline (a wall curve failed or stopped)"
        return out
    interp = {k: RegularGridInterpolator(axes, np.array([v[k] for v in grid_values])
                                         .reshape(shape), method=method) for k in keys}
    for d, v in zip(checks, check_values):
        x = np.array([[d[n] for n in nodes]])
        out["checks"].append({"draw": d, **{k: {"wall": v[k], "interpolated":
                                                float(interp[k](x)[0])} for k in keys}})
    errs = [abs(c[k]["interpolated"] / c[k]["wall"] - 1.0) for c in out["checks"] for k in keys
            if np.isfinite(c[k]["wall"])]
    out["check_error_max"] = max(errs) if errs else float("nan")
    for k in keys:
        y = interp[k](Xc)
        out["quantiles"][k] = dict(zip((f"p{q}" for q in QUANTILES),
                                       np.percentile(y, QUANTILES).tolist()))
        si = sobol_analyze.analyze(problem, y, calc_second_order=False,
                                   seed=salib_seed(seed))
        out["sobol"][k] = {s: dict(zip(problem["names"], np.asarray(si[s], float).tolist()))
                           for s in ("S1", "S1_conf", "ST", "ST_conf")}
    return out


def repropagated(record: dict, study, tolerance) -> dict:
    """``record`` with its interpolation, quantiles and Sobol indices computed again from its
    own grid and check values (seconds, no wall curve): a change of the propagation reaches a
    cached band."""
    keys = [k for k in record["grid"][0] if k not in record["nodes"]]
    grid_values = [{k: g[k] for k in keys} for g in record["grid"]]
    checks = [c["draw"] for c in record.get("checks", [])]
    check_values = [{k: c[k]["wall"] for k in keys} for c in record.get("checks", [])]
    out = dict(record)
    for stale in ("not_computed", "check_error_max"):
        out.pop(stale, None)
    out.update(_propagate(tolerance, _nominal(study), record["nodes"], grid_values, checks,
                          check_values, record["seed"]))
    return out


def _key(study, tolerance) -> str:
    from spsc.study.runs import code_version

    spec = json.dumps({"tolerance": tolerance.to_dict()["inputs"], "types": study.types,
                       "pressures": study.pressures_kPa, "modes": study.modes,
                       "stroke": study.stroke_mm, "points": study.membrane_points,
                       "mesh": study.wall_mesh, "material": study.materials[0],
                       "nodes": NODES, "checks": CHECKS, "samples": SAMPLES},
                      sort_keys=True, default=str)
    return hashlib.sha256((spec + code_version("wall")).encode()).hexdigest()[:16]


def run_headline_band(study, cache_root, tolerance=None, *, workers=None, scheduler=None,
                      progress: bool = True) -> dict:
    """The record of :func:`headline_band` for ``study`` under ``tolerance`` (default
    :func:`declared_tolerance`), read back from ``CACHE/bands/`` when nothing changed (keyed by
    the study's setups, the tolerance and the wall model's code version)."""
    import sys

    from spsc.core.progress import progress_bar

    tolerance = declared_tolerance() if tolerance is None else tolerance
    check_band_tolerance(tolerance)
    path = Path(cache_root) / "bands" / f"headline-{study.name}-{_key(study, tolerance)}.json"
    if path.exists():
        record = json.loads(path.read_text(encoding="utf-8"))
        record["tolerance"]["source"] = tolerance.source  # the same inputs, maybe another file
        return repropagated(record, study, tolerance)
    bar = progress_bar(desc="spsc report: headline band", unit="curve", disable=not progress,
                       file=sys.stderr)
    try:
        record = headline_band(study, tolerance, workers=workers, scheduler=scheduler,
                               progress=lambda done, total: _tick(bar, done, total))
    finally:
        bar.close()
    if record["failed"] == 0:  # a failure may be the machine's: computed again next time
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(record, indent=1), encoding="utf-8")
    return record


def _tick(bar, done: int, total: int) -> None:
    bar.total = total
    bar.update(done - bar.n)
