"""A squeeze–release cycle of the wall model in time: the plate down by the stroke and back
at a constant speed, the wall rate-dependent (a Prony series, :mod:`spsc.fem.viscous`) — the
paper's hysteresis test of the vented chamber (sec. 3.1: 8.1, 3.8, 4.0 and 4.5 N for Types A–D).

Before the cycle the chamber rests at its setup (inflated with the valve open, relaxed); the
cycle then runs with the valve closed (``pressure_kPa`` > 0, the gas with ``reservoir_mm3``) or
vented (0). The hysteresis is the largest loading-minus-unloading force at one travel; the loop's
area is the energy the wall dissipated (mJ).
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from spsc.core.errors import require

from ..engine import CloseValve, Cycle, Inflate, solve
from .model import WallModel, WallSettings

__all__ = ["CycleResult", "wall_cycle"]


@dataclass(frozen=True)
class CycleResult:
    """Travels ``y_mm`` (0 … stroke, n + 1) with the loading and unloading plate forces and
    cavity pressures at them (NaN where not reached), the largest hysteresis (N) and the
    travel it is at, the dissipated energy (mJ), whether the cycle completed and why not."""

    y_mm: np.ndarray
    force_load_N: np.ndarray
    force_unload_N: np.ndarray
    pressure_load_kPa: np.ndarray
    pressure_unload_kPa: np.ndarray
    hysteresis_N: float
    hysteresis_at_mm: float
    dissipated_mJ: float
    complete: bool
    message: str
    seconds: float
    #: the snap-throughs followed (``snaps``): (travel mm, force before, after N, energy
    #: released mJ) each, on the way down and back up; their energy is dissipated too
    jumps: tuple = ()

    @property
    def jump_energy_mJ(self) -> float:
        """The energy the snap-throughs released (mJ): dissipated between recorded points,
        where the loop's area over the recorded travels does not see it."""
        return float(sum(j[3] for j in self.jumps))


def wall_cycle(geometry, material, prony, *, stroke_mm: float = 6.0, speed_mm_s: float = 1.0,
               points: int = 25, pressure_kPa: float = 0.0, reservoir_mm3: float = 0.0,
               settings: WallSettings | None = None, friction=None,
               snaps: bool = False, mullins=None, cycles: int = 1) -> CycleResult:
    """Squeeze by ``stroke_mm`` and release at ``speed_mm_s``, ``points`` travels each way
    (0 and the stroke included), with the ``prony`` terms (None: the relaxed law, which
    retraces itself unless something else dissipates). ``friction``: None (frictionless),
    ``"stick"`` or a Coulomb coefficient μ on the plate, both ways; ``snaps``: follow the
    snap-throughs on the way down and back up (:mod:`spsc.fem.engine.snap`: a jump's energy
    is dissipated, a hysteresis without any viscosity; an elastic, frictionless wall only —
    the descent needs the wall's potential). ``mullins``: the first loading's softening
    (:class:`~spsc.fem.mullins.MullinsParams`); ``cycles``: squeeze–release repeated, the
    result the last one's (the first of a Mullins wall dissipates, later ones less)."""
    require("stroke", stroke_mm, gt=0, le=12, unit="mm")
    require("speed", speed_mm_s, gt=0, le=1e4, unit="mm/s")
    require("points", points, ge=3, le=500)
    if friction not in (None, "stick"):
        friction = require("friction", friction, ge=0, le=1e6) or None  # 0: frictionless
    require("cycles", cycles, ge=1, le=20)
    if snaps and (prony is not None or friction is not None or mullins is not None):
        from spsc.core.errors import ParameterError

        raise ParameterError("snaps", True, "with an elastic, frictionless wall only (a jump "
                             "is found by descending the wall's potential, which a viscous "
                             "or softening wall or a sliding plate has not)")
    from threadpoolctl import threadpool_limits

    # one BLAS thread, as wall_curve: on small blocks threads spin (10-20x slower under load)
    with threadpool_limits(limits=1, user_api="blas"):
        return _cycle(geometry, material, prony, stroke_mm, speed_mm_s, int(points),
                      pressure_kPa, reservoir_mm3, settings, friction, snaps, mullins,
                      int(cycles))


def _cycle(geometry, material, prony, stroke_mm, speed_mm_s, points, pressure_kPa,
           reservoir_mm3, settings, friction=None, snaps=False, mullins=None,
           cycles=1) -> CycleResult:
    t0 = time.perf_counter()
    model = WallModel(geometry, material, settings, prony=prony, mullins=mullins)
    s = dataclasses.replace(model.default_settings(), snap_through=bool(snaps))
    y = np.linspace(0.0, stroke_mm, int(points))
    travels = np.concatenate([y] + [np.concatenate([y[-2::-1], y[1:]])] * (cycles - 1)
                             + [y[-2::-1]])
    times = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(travels)))]) / speed_mm_s
    steps = []
    if pressure_kPa > 0:
        steps = [Inflate.kPa(pressure_kPa, model.settings.inflate_increments),
                 CloseValve(reservoir_mm3)]
    mu = None if friction in (None, "stick") else float(friction)
    cycle = Cycle(tuple(times), tuple(travels), stick=friction is not None, mu=mu)
    res = solve(model, steps + [cycle], settings=s)
    pressed = [r for r in res.records if r.kind == "press"]
    pressed = pressed[2 * (len(y) - 1) * (cycles - 1):]  # the last cycle's
    n = len(y)
    F = np.full(2 * n - 1, np.nan)
    P = np.full(2 * n - 1, np.nan)
    F[0], P[0] = 0.0, pressure_kPa
    for k, r in enumerate(pressed, start=1):
        F[k], P[k] = r.force, r.pressure_kPa
    load, unload = F[:n], F[n - 1:][::-1]
    p_load, p_unload = P[:n], P[n - 1:][::-1]
    gap = load - unload
    k = int(np.nanargmax(gap)) if np.isfinite(gap).any() else 0
    area = float(np.trapezoid(gap, y)) if np.all(np.isfinite(gap)) else float("nan")
    return CycleResult(y, load, unload, p_load, p_unload, float(np.nanmax(gap))
                       if np.isfinite(gap).any() else float("nan"), float(y[k]), area,
                       bool(res.converged), res.message, time.perf_counter() - t0,
                       tuple((j.y_mm, j.force_before_N, j.force_after_N, j.energy_released_mJ)
                             for j in res.jumps))
