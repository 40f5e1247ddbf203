"""The quasi-static chamber map: cavity volume V(y, P), plate force F(y, P) and contact area
A(y, P) of a chamber held at the gauge pressure P and pressed to the plate travel y, from the
wall model (:mod:`spsc.fem.wall`).

The time-domain circuit needs the chamber at any pressure the gas reaches, not only along one
closed-valve curve: each pressure level is one wall solve with the pressure *prescribed*
(inflate to P, press with the valve open onto an infinite reservoir), which is the wall
model's own equilibrium r(u; P) = 0 (eq. 37's follower pressure) with the gas law left out.
The gas law is then the circuit's (:mod:`.circuit`): at every instant P V(y, P) = m R T.

y is the plate travel from first contact with the chamber inflated at the setup pressure (the
y of ``spsc curve``); a chamber at a higher P is taller and meets the plate at y < 0. Between
the grid points V and F are interpolated piecewise-cubically and monotonically (PCHIP) along y
at every level (no overshoot at the contact onset's kink), then by a cubic spline along P
(smooth there: its slopes are what the gas's compliance ∂V/∂P needs).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline, PchipInterpolator

from spsc.core.errors import ParameterError

__all__ = ["ChamberMap", "Slice", "build_map", "pressure_levels"]


class _Column:
    """One quantity of a :class:`Slice`: ``f(p)`` or ``f(p, nu)`` (the nu-th derivative in
    P), as a :class:`~scipy.interpolate.CubicSpline` would answer."""

    __slots__ = ("spline", "k")

    def __init__(self, spline: CubicSpline, k: int):
        self.spline, self.k = spline, k

    def __call__(self, p, nu: int = 0):
        return self.spline(p, nu)[..., self.k]


class Slice:
    """The map at one plate travel y: V, ∂V/∂y, F, A, ∂F/∂y as functions of the gauge
    pressure — one cubic spline through the five columns (built once: building five took
    a millisecond a slice, and the travel under a spring-borne object needs several)."""

    __slots__ = ("volume", "dvolume_dy", "force", "area", "dforce_dy")

    def __init__(self, p_kPa: np.ndarray, columns: np.ndarray):
        spline = CubicSpline(p_kPa, columns, axis=0)
        self.volume, self.dvolume_dy, self.force, self.area, self.dforce_dy = (
            _Column(spline, k) for k in range(5))


@dataclass(frozen=True, eq=False)
class ChamberMap:
    """V, F, A (ny, nP) on the travels ``y_mm`` (ny) and gauge pressures ``pressure_kPa`` (nP);
    ``y_max_mm`` the largest travel every level reached."""

    y_mm: np.ndarray
    pressure_kPa: np.ndarray
    volume_mm3: np.ndarray
    force_N: np.ndarray
    area_mm2: np.ndarray
    setup_kPa: float

    def __post_init__(self):
        y = self.y_mm
        object.__setattr__(self, "_v", PchipInterpolator(y, self.volume_mm3, axis=0))
        object.__setattr__(self, "_dv", self._v.derivative())
        object.__setattr__(self, "_f", PchipInterpolator(y, self.force_N, axis=0))
        object.__setattr__(self, "_df", self._f.derivative())
        object.__setattr__(self, "_a", PchipInterpolator(y, self.area_mm2, axis=0))

    @property
    def y_range(self) -> tuple[float, float]:
        return float(self.y_mm[0]), float(self.y_mm[-1])

    @property
    def pressure_range(self) -> tuple[float, float]:
        return float(self.pressure_kPa[0]), float(self.pressure_kPa[-1])

    def at(self, y: float) -> Slice:
        """The map at travel ``y`` (mm, within :attr:`y_range`)."""
        return Slice(self.pressure_kPa, np.column_stack(
            [self._v(y), self._dv(y), self._f(y), self._a(y), self._df(y)]))

    def levels_at(self, y):
        """(V mm³, F N) at the travels ``y`` (mm, an array) and every pressure level of the
        map, each (len(y), levels): the map's own interpolation along y, for a table of it."""
        return self._v(y), self._f(y)

    def as_arrays(self) -> dict:
        return {"y_mm": self.y_mm, "pressure_kPa": self.pressure_kPa,
                "volume_mm3": self.volume_mm3, "force_N": self.force_N,
                "area_mm2": self.area_mm2, "setup_kPa": np.array(self.setup_kPa)}

    @classmethod
    def from_arrays(cls, d) -> "ChamberMap":
        return cls(np.asarray(d["y_mm"]), np.asarray(d["pressure_kPa"]),
                   np.asarray(d["volume_mm3"]), np.asarray(d["force_N"]),
                   np.asarray(d["area_mm2"]), float(d["setup_kPa"]))


def pressure_levels(setup_kPa: float, top_kPa: float, count: int = 9) -> np.ndarray:
    """``count`` gauge pressures from 0 to ``top_kPa`` (kPa), the setup pressure among them."""
    levels = np.linspace(0.0, top_kPa, count)
    levels = np.union1d(levels, [setup_kPa])
    # a level closer than a tenth of the spacing to the setup's would only add ringing
    spacing = top_kPa / max(count - 1, 1)
    keep = (np.abs(levels - setup_kPa) > 0.1 * spacing) | (levels == setup_kPa)
    return levels[keep]


def travel_grid(y_lo: float, y_hi: float, step: float) -> np.ndarray:
    """Travels from ``y_lo`` ≤ 0 to ``y_hi`` (mm) with y = 0 (first contact at the setup
    pressure) on the grid, about ``step`` apart; at least one step past it (a scenario at
    rest, whose plate never goes below first contact, has a map to stand on)."""
    y_hi = max(y_hi, step)
    below = np.linspace(0.0, y_lo, max(2, math.ceil(-y_lo / step) + 1))[:0:-1] \
        if y_lo < 0 else np.zeros(0)
    above = np.linspace(0.0, y_hi, max(2, math.ceil(y_hi / step) + 1))
    return np.concatenate([below, above])


def _tops(model, levels_kPa, settings) -> dict:
    """{P: (inflated state, top height mm, cavity volume mm³)} of the chamber inflated to each
    level (one inflation walk through them)."""
    from spsc.fem.engine import Inflate, solve

    out = {0.0: (model.zero_state(), model.top(model.zero_state()),
                 model.volume(model.zero_state()))}
    for p in levels_kPa:
        if p <= 0 or p in out:
            continue
        res = solve(model, [Inflate.kPa(p, settings.inflate_increments)],
                    settings=settings.newton_settings())
        if not res.converged:
            raise ParameterError("chamber map", f"{p:g} kPa",
                                 f"a pressure the wall model inflates to ({res.message})")
        rec = res.records[-1]
        out[p] = (rec.x, model.top(rec.x), rec.volume)
    return out


def _level(model, p_kPa, travels, settings):
    """(V, F, A, travel reached) at the plate ``travels`` (mm from this level's first contact,
    increasing, > 0) of the chamber held at ``p_kPa``."""
    from spsc.fem.engine import Inflate, Press, solve

    steps = [Inflate.kPa(p_kPa, settings.inflate_increments)] if p_kPa > 0 else []
    res = solve(model, steps + [Press.through(travels)], settings=settings.newton_settings())
    pressed = [r for r in res.records if r.kind == "press"]
    n = len(pressed)
    V, F, A = (np.full(len(travels), np.nan) for _ in range(3))
    V[:n] = [r.volume for r in pressed]
    F[:n] = [r.force for r in pressed]
    A[:n] = [r.contact_area for r in pressed]
    reached = travels[n - 1] if n else 0.0
    return V, F, A, reached, res.message


def _level_job(geometry, material, settings, p_kPa, travels):
    """One level on a worker: its own wall model, one BLAS thread."""
    from threadpoolctl import threadpool_limits

    from spsc.fem.wall.model import WallModel

    with threadpool_limits(limits=1, user_api="blas"):
        return _level(WallModel(geometry, material, settings), p_kPa, travels, settings)


def _levels(model, jobs, settings, workers, scheduler, progress) -> list:
    """The (V, F, A, reached, message) of each job (p_kPa, travels), in order: here, one after
    the other (``workers`` 1), or on Dask (:func:`spsc.study.executor.dask_client`)."""
    done = [None] * len(jobs)
    if workers == 1 and not scheduler:
        for j, (p, travels) in enumerate(jobs):
            done[j] = _level(model, p, travels, settings)
            if progress is not None:
                progress(j + 1, len(jobs))
        return done
    from distributed import as_completed

    from spsc.study.executor import dask_client

    with dask_client(workers, scheduler) as client:
        futures = {client.submit(_level_job, model.geometry, model.material, settings, p, t,
                                 pure=False): j for j, (p, t) in enumerate(jobs)}
        for k, fut in enumerate(as_completed(futures), start=1):
            done[futures[fut]] = fut.result()
            if progress is not None:
                progress(k, len(jobs))
    return done


def build_map(geometry, material, *, setup_kPa: float, top_kPa: float, y_max_mm: float,
              y_step_mm: float = 0.25, levels: int = 6, settings=None, progress=None,
              workers: int | None = 1, scheduler: str | None = None) -> ChamberMap:
    """The map of the chamber for gauge pressures 0 … ``top_kPa`` (``levels`` of them, the
    setup pressure added among them) and travels from the highest level's first contact to
    ``y_max_mm``, every ``y_step_mm``. Six levels (16 kPa apart to 80 kPa) reproduce the
    Table 1 Type B's wall curves as well as nine (slow press against ``spsc curve``: pressure
    7.0e-5 / 1.6e-5, force 7.2e-4 / 8.8e-4, high mode; the force's error is the travel's
    interpolation) in 62 % of the time; five leave 1.5e-3 in pressure. The levels are pressed
    one after the other (``workers`` 1) or on Dask: ``workers`` local processes (None: one
    per core) or the cluster at ``scheduler``; the map is the same. ``progress(done, total)``
    after each level. Raises ParameterError naming the level when the wall model cannot reach
    ``y_max_mm`` there."""
    from threadpoolctl import threadpool_limits

    from spsc.fem.wall.model import WallModel, WallSettings

    settings = settings or WallSettings()
    model = WallModel(geometry, material, settings)
    ps = pressure_levels(setup_kPa, top_kPa, levels)
    with threadpool_limits(limits=1, user_api="blas"):
        tops = _tops(model, ps, settings)
    z_ref = tops[float(setup_kPa)][1] if setup_kPa > 0 else tops[0.0][1]
    y_lo = -(max(t[1] for t in tops.values()) - z_ref)
    y = travel_grid(y_lo, y_max_mm, y_step_mm)
    V, F, A = (np.zeros((y.size, len(ps))) for _ in range(3))
    touching = {}
    for j, p in enumerate(ps):
        _, top, v_free = tops[float(p)]
        touching[j] = y - (z_ref - top) > 1e-9  # from this level's first contact
        V[:, j], F[:, j], A[:, j] = v_free, 0.0, 0.0
    jobs = [(float(p), y[touching[j]] - (z_ref - tops[float(p)][1]))
            for j, p in enumerate(ps) if touching[j].any()]
    with threadpool_limits(limits=1, user_api="blas"):
        results = _levels(model, jobs, settings, workers, scheduler, progress)
    for (p, _), (v, f, a, reached, message) in zip(jobs, results):
        j = int(np.flatnonzero(ps == p)[0])
        if not np.all(np.isfinite(v)):
            top = tops[p][1]
            raise ParameterError(
                "chamber map", f"{p:g} kPa", "a pressure the wall model presses to "
                f"y = {y_max_mm:g} mm (it reached {reached + z_ref - top:.3g} mm: "
                f"{message}); lower the stroke or the pressures")
        V[touching[j], j], F[touching[j], j], A[touching[j], j] = v, f, a
    return ChamberMap(y, ps, V, F, A, float(setup_kPa))
