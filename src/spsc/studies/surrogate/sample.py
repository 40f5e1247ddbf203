"""One training sample of the surrogate: the wall model's map of one dimensionless design.

The chamber is built at the reference size (w = :data:`~spsc.models.surrogate.domain.W_REF_MM`)
in the reference material (neo-Hookean, μ = μ_ref); at every pressure level q of
:data:`~spsc.models.surrogate.domain.Q_LEVELS` it is inflated with the pressure held (the valve
open onto an infinite reservoir: the wall's equilibrium r(u; P) = 0 of eq. 37 without the gas)
and pressed by the frictionless plate through the travels of
:data:`~spsc.models.surrogate.domain.TRAVELS` × h from that level's first contact. The gas law
is left to the surrogate, which applies it exactly (eqs. 2, 6–7).

What a level could not reach (a chamber that balloons before q, a press that stops) is NaN,
with the reason kept; a snap-through on the way is counted and located.
"""

from __future__ import annotations

import time

import numpy as np

from spsc.models.surrogate.domain import MU_REF_MPA, Q_LEVELS, TRAVELS, W_REF_MM, \
    pressure_unit_kPa

__all__ = ["geometry_of", "run_design", "extend_run", "levels_of", "level_index"]

#: a run's arrays over its levels (the last axis)
_MAP_KEYS = ("top_mm", "free_volume_mm3", "volume_mm3", "force_N", "area_mm2")


def geometry_of(ratios):
    """The reference-size :class:`~spsc.cad.geometry.SPSCGeometry` of six ratios
    (h/w, l/w, t0/w, n1, n2, c_y)."""
    from spsc.cad.geometry import SPSCGeometry

    hw, lw, tw, n1, n2, cy = (float(v) for v in ratios)
    w = W_REF_MM
    return SPSCGeometry(w=w, h=round(hw * w, 6), l=round(lw * w, 6), t0=round(tw * w, 6),
                        n1=n1, n2=n2, cy=cy)


def _reference_material():
    from spsc.materials.law import neo_hookean

    return neo_hookean(MU_REF_MPA, name="surrogate-reference", provenance="datasheet",
                       source="the catalogue's tpu60a law (mu = E/3, E = 5 MPa)")


def _press_level(model, p_MPa, travels, settings):
    """(top mm, free volume mm³, V, F, A at the travels, jumps (y, ΔF), message) of one
    level; NaN where it did not reach."""
    from spsc.fem.engine import Inflate, Press, solve

    steps = [Inflate(p_MPa, settings.inflate_increments)] if p_MPa > 0 else []
    res = solve(model, steps + [Press.through(travels)], settings=settings.newton_settings())
    free = [r for r in res.records if r.kind != "press"]
    pressed = [r for r in res.records if r.kind == "press"]
    inflated = p_MPa == 0 or (free and len(free) > 1 and not
                              (res.stop is not None and res.stop.kind != "press"))
    top, v0 = (model.top(free[-1].x), free[-1].volume) if inflated else (np.nan, np.nan)
    V, F, A = (np.full(len(travels), np.nan) for _ in range(3))
    n = len(pressed) if inflated else 0
    if n and res.stop is not None and res.stop.record is not None \
            and pressed[-1] is res.stop.record:
        n -= 1  # the unstable state it stopped at is not an answer
    V[:n] = [r.volume for r in pressed[:n]]
    F[:n] = [r.force for r in pressed[:n]]
    A[:n] = [r.contact_area for r in pressed[:n]]
    jumps = [(j.y_mm, j.force_after_N - j.force_before_N) for j in res.jumps]
    return top, v0, V, F, A, jumps, res.message


def run_design(ratios, settings=None, levels=None) -> dict:
    """The wall map of the design ``ratios`` at the reference size and material: arrays
    ``top_mm``, ``free_volume_mm3`` (levels), ``volume_mm3``, ``force_N``, ``area_mm2``
    (travels × levels), ``q_levels`` and ``pressure_kPa`` (levels), ``travel_mm`` (travels), the
    snap-throughs (``jumps``: level, y mm, force change N), ``messages`` and ``seconds``, at the
    dimensionless pressures ``levels`` (increasing; None: :data:`~spsc.models.surrogate.domain.
    Q_LEVELS`). One BLAS thread."""
    from threadpoolctl import threadpool_limits

    from spsc.fem.wall.model import WallModel, WallSettings

    t_start = time.perf_counter()
    levels = Q_LEVELS if levels is None else np.asarray(levels, float)
    g = geometry_of(ratios)
    settings = settings or WallSettings()
    model = WallModel(g, _reference_material(), settings)
    unit = pressure_unit_kPa(g.w, g.t0, MU_REF_MPA)
    travels = TRAVELS[1:] * g.h
    nq, nt = len(levels), len(TRAVELS)
    out = {k: np.full((nt, nq), np.nan) for k in ("volume_mm3", "force_N", "area_mm2")}
    top, v0 = np.full(nq, np.nan), np.full(nq, np.nan)
    jumps, messages = [], []
    with threadpool_limits(limits=1, user_api="blas"):
        for j, q in enumerate(levels):
            t, v, V, F, A, jj, msg = _press_level(model, q * unit / 1000.0, travels, settings)
            messages.append(msg)
            if not np.isfinite(t):
                break  # it balloons (or fails) below this level: so it does above
            top[j], v0[j] = t, v
            out["volume_mm3"][:, j] = np.concatenate([[v], V])
            out["force_N"][:, j] = np.concatenate([[0.0], F])
            out["area_mm2"][:, j] = np.concatenate([[0.0], A])
            jumps += [(j, y, df) for y, df in jj]
    return {"ratios": np.asarray(ratios, float), "q_levels": np.asarray(levels, float),
            "pressure_kPa": levels * unit, "travel_mm": TRAVELS * g.h, "top_mm": top,
            "free_volume_mm3": v0, **out, "jumps": np.array(jumps, float).reshape(-1, 3),
            "messages": np.array(messages), "seconds": time.perf_counter() - t_start}


def levels_of(run: dict) -> np.ndarray:
    """The dimensionless pressure levels of a run (``q_levels``; a run of a study before they
    were stored: its pressures over the reference wall's unit)."""
    if "q_levels" in run:
        return np.asarray(run["q_levels"], float)
    g = geometry_of(run["ratios"])
    return np.asarray(run["pressure_kPa"], float) / pressure_unit_kPa(g.w, g.t0, MU_REF_MPA)


def level_index(old, levels) -> list[int]:
    """For each of ``levels``, the index of the same level (within 1e-9) among ``old``, or
    -1 where ``old`` lacks it."""
    old = np.asarray(old, float)
    return [int(np.argmin(np.abs(old - q))) if old.size and np.min(np.abs(old - q)) <= 1e-9
            else -1 for q in levels]


def extend_run(run: dict, levels=None, settings=None) -> dict:
    """The run on the grid ``levels`` (None: :data:`~spsc.models.surrogate.domain.Q_LEVELS`)
    whose old levels (within 1e-9) are kept from ``run`` and the others computed by
    :func:`run_design` (a level above one the chamber ballooned at is not: NaN, as there).
    ``seconds`` adds the new levels' time to the old; ``messages`` follow the new grid."""
    levels = Q_LEVELS if levels is None else np.asarray(levels, float)
    old = levels_of(run)
    where = level_index(old, levels)
    new = [q for q, k in zip(levels, where) if k < 0]
    ballooned = old[~np.isfinite(run["top_mm"])]
    new = [q for q in new if not (ballooned.size and q > ballooned.min())]
    extra = run_design(run["ratios"], settings, new) if new else None
    merged = dict(run)
    g = geometry_of(run["ratios"])
    merged["q_levels"] = levels
    merged["pressure_kPa"] = levels * pressure_unit_kPa(g.w, g.t0, MU_REF_MPA)
    msgs, jumps = [], []
    for key in _MAP_KEYS:
        a = np.asarray(run[key])
        merged[key] = np.full(a.shape[:-1] + (len(levels),), np.nan)
    for j, (q, k) in enumerate(zip(levels, where)):
        src, col = (run, k) if k >= 0 else (extra, new.index(q) if q in new else -1)
        if col < 0:
            msgs.append("not computed: it balloons at a lower level")
            continue
        for key in _MAP_KEYS:
            merged[key][..., j] = np.asarray(src[key])[..., col]
        msgs.append(str(src["messages"][col]) if col < len(src["messages"]) else "")
        jumps += [(j, y, df) for lv, y, df in np.asarray(src["jumps"]).reshape(-1, 3)
                  if int(lv) == col]
    merged["messages"] = np.array(msgs)
    merged["jumps"] = np.array(jumps, float).reshape(-1, 3)
    merged["seconds"] = float(run.get("seconds", 0.0)) + (extra["seconds"] if extra else 0.0)
    return merged
