"""One entry point for the membrane model (sec. 2.3, Algorithm 1 replaced by a global Newton):
inflate at p_i, close the valve, press with a rigid frictionless plate along the stroke.

The load path: inflate at p_i (Newton from a tensioned guess, pressure continuation if that
fails), close the gas, then one Newton solve of :class:`.bvp.BoxScheme` per plate position,
warm-started by a secant predictor with step halving (:mod:`.stroke`). A point that does not
converge carries its reason and NaN values, never a number.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from spsc.core.constants import to_MPa
from spsc.core.loadcase import check_load
from spsc.core.errors import ParameterError, require
from spsc.cad.geometry import SPSCGeometry

from .bvp import BoxScheme
from spsc.core.curve import Curve, SolveInfo
from spsc.materials import Material, material as catalogue_material
from .meridian import Meridian
from .shape import Shape, make_shape
from .stroke import StrokeContinuation

__all__ = ["SolverSettings", "MembraneResult", "Inflation", "solve", "inflate"]


@dataclass(frozen=True)
class SolverSettings:
    """Discretisation and Newton controls.

    inflation_intervals : int  intervals of the inflation grid (>= 8)
    contact_intervals, free_intervals : int  intervals on [0, s_Γ] and [s_Γ, L] (>= 4, >= 8)
    rtol : float  max scaled residual for convergence (> 0); the same name as the FEM's
        :class:`spsc.fem.engine.Settings`
    max_iterations : int  Newton iterations per solve (>= 2)
    max_halvings : int  step halvings allowed between two requested plate positions (>= 0)
    wrinkling : bool  True: tension-field membrane (no compression: it wrinkles, and a slack
        core lies on the plate); False: the paper's taut law (hoop compression carried)
    """

    inflation_intervals: int = 192
    contact_intervals: int = 48
    free_intervals: int = 144
    rtol: float = 1e-9
    max_iterations: int = 25
    max_halvings: int = 6
    wrinkling: bool = True

    def __post_init__(self):
        require("inflation_intervals", self.inflation_intervals, ge=8)
        require("contact_intervals", self.contact_intervals, ge=4)
        require("free_intervals", self.free_intervals, ge=8)
        require("rtol", self.rtol, gt=0)
        require("max_iterations", self.max_iterations, ge=2)
        require("max_halvings", self.max_halvings, ge=0)

    def scaled(self, factor: float) -> "SolverSettings":
        """Same settings with every interval count multiplied by ``factor`` (refinement studies)."""
        from dataclasses import replace
        return replace(self, inflation_intervals=int(round(self.inflation_intervals * factor)),
                       contact_intervals=int(round(self.contact_intervals * factor)),
                       free_intervals=int(round(self.free_intervals * factor)))


@dataclass(frozen=True, eq=False)
class MembraneResult:
    """What :func:`solve` returns: the :class:`Curve` (whose ``solver`` is the
    :class:`~spsc.core.curve.SolveInfo` of the solve: converged, message, y reached, seconds,
    Newton iterations, notes), the inflated shape and the shape at each plate position (None
    where not converged). When the inflation failed, ``inflated`` (and ``shapes[0]``) is the
    last shape the pressure continuation reached (its ``pressure_kPa`` below the setup
    pressure), and ``curve.solver.details["inflation_path"]`` lists every converged pressure
    with its volume and apex. The protocol fields are read through from ``curve.solver``."""

    curve: Curve
    inflated: Shape | None
    shapes: tuple

    @property
    def solver(self) -> SolveInfo:
        return self.curve.solver

    @property
    def converged(self) -> bool:
        return self.curve.solver.converged

    @property
    def message(self) -> str:
        return self.curve.solver.message

    @property
    def y_reached_mm(self) -> float:
        return self.curve.solver.y_reached_mm

    @property
    def seconds(self) -> float:
        return self.curve.solver.seconds

    @property
    def iterations(self) -> int:
        return self.curve.solver.iterations

    @property
    def notes(self) -> tuple:
        return self.curve.solver.notes


@dataclass(frozen=True, eq=False)
class Inflation:
    """The inflation problem's outcome: the inflated :class:`Shape` (None if it failed),
    whether it converged, why not, the Newton iterations spent, and the states the pressure
    continuation reached: ``reached`` the last converged :class:`Shape` (the inflated one when
    it converged), ``path`` (pressure kPa, cavity volume mm³, apex height mm) per converged
    pressure."""

    shape: Shape | None
    converged: bool
    message: str
    iterations: int
    reached: Shape | None = None
    path: tuple = ()


def _material(mat) -> Material:
    return catalogue_material(mat)  # a law passes through, a name or file is looked up


def _stress_guess(bs: BoxScheme, p_mpa: float) -> np.ndarray:
    """Reference shape with the meridional stretch of the cap balance T1 = pρ/(2 sin φ) (linear
    law), so the first Newton step starts from a tensioned membrane."""
    mer = bs.mer
    s = bs.nodes()
    x, phi = mer.x(s), mer.angle(s)
    T1 = 0.5 * p_mpa * np.minimum(x / np.maximum(np.sin(phi), 1e-3), 2.0 * mer.geometry.w)
    T1[0] = T1[1]
    l1 = 1.0 + T1 / (4.0 * bs.scale_T)
    return np.column_stack([x, mer.y(s), phi, l1]).ravel()


def inflate(geometry: SPSCGeometry, material, pressure_kPa: float, *,
            settings: SolverSettings | None = None, edge: str = "clamped"):
    """Inflation problem at gauge pressure ``pressure_kPa`` (kPa) → :class:`Inflation`.
    Newton from a tensioned guess; pressure continuation if that fails. ``edge="symmetric"``
    replaces the clamped edge by a symmetry plane (φ = π/2, η = 0), for the sphere check."""
    settings = settings or SolverSettings()
    mat = _material(material)
    p = to_MPa(require("pressure", pressure_kPa, ge=0, unit="kPa gauge"))
    mer = Meridian(geometry)
    bs = BoxScheme(mer, mat, 0, settings.inflation_intervals, edge=edge,
                   wrinkling=settings.wrinkling)
    if p == 0.0:
        s = bs.nodes()
        v = np.column_stack([mer.x(s), mer.y(s), mer.angle(s), np.ones_like(s)]).ravel()
        return Inflation(make_shape(bs, v, 0.0), True, "", 0)
    r = bs.newton(_stress_guess(bs, p), p=p, tol=settings.rtol,
                  max_iter=settings.max_iterations)
    iters = r.iterations
    path = []
    if not r.converged:  # continuation in pressure from a small one
        frac, v, done = 0.125, None, 0.0
        while done < 1.0 and frac > 1e-3:
            target = min(1.0, done + frac)
            guess = _stress_guess(bs, target * p) if v is None else v
            rr = bs.newton(guess, p=target * p, tol=settings.rtol,
                           max_iter=settings.max_iterations)
            iters += rr.iterations
            if rr.converged:
                v, done, frac = rr.v, target, frac * 2.0
                path.append(make_shape(bs, v, done * p))
            else:
                frac *= 0.5
        if done < 1.0:
            return Inflation(None, False, f"inflation did not converge ({r.message}); pressure "
                             f"continuation reached {done * pressure_kPa:.4g} kPa", iters,
                             path[-1] if path else None, _path(path))
        r.v = v
    shape = make_shape(bs, r.v, p)
    return Inflation(shape, True, "", iters, shape, _path(path or [shape]))


def _path(shapes) -> tuple:
    """(pressure kPa, cavity volume mm³, apex height mm) of each converged shape."""
    return tuple((round(float(sh.pressure_kPa), 9), round(float(sh.volume_mm3), 6),
                  round(float(sh.eta[0]), 6)) for sh in shapes)


def check_membrane_pressure(pressure_kPa: float, stroke_mm: float) -> None:
    """A membrane carries no force without pressure (eq. 38: F = p·A): pressing a vented
    membrane has no equilibrium and the simplified model's force would be zero. Refused naming
    the models that compute the vented chamber's structural force F_el."""
    if float(pressure_kPa) == 0.0 and float(stroke_mm) > 0.0:
        raise ParameterError("pressure", pressure_kPa, "> 0 kPa for the membrane models: a "
                             "membrane carries no force without pressure; the vented "
                             "chamber's F_el is `spsc curve --model wall --pressure 0` "
                             "(or --model fem)")


def solve(geometry: SPSCGeometry, material, *, pressure_kPa: float, reservoir_mm3: float = 0.0,
          stroke_mm: float = 6.0, points: int = 41, polytropic_n: float = 1.0,
          settings: SolverSettings | None = None) -> MembraneResult:
    """Inflate at ``pressure_kPa`` (kPa gauge), close the gas (bladder + reservoir
    ``reservoir_mm3``, mm³, polytropic index n, eq. 34) and press with a plate over
    ``points`` positions y ∈ [0, ``stroke_mm``] mm from first contact.

    ``material`` is a :class:`Material` or a catalogue name. Returns a :class:`MembraneResult`
    whose ``curve`` has force (N) = p·A (eq. 38 with the deformed radius), gauge pressure (kPa),
    contact area (mm²) and volume change (mm³) per position.
    """
    t_start = time.perf_counter()
    settings = settings or SolverSettings()
    mat = _material(material)
    if not isinstance(geometry, SPSCGeometry):
        raise ParameterError("geometry", type(geometry).__name__, "an SPSCGeometry")
    load = check_load(geometry, pressure_kPa=pressure_kPa, reservoir_mm3=reservoir_mm3,
                      stroke_mm=stroke_mm, points=points, polytropic_n=polytropic_n,
                      allow_zero_stroke=True)
    p_i, v_r, n_poly = load.pressure_kPa, load.reservoir_mm3, load.polytropic_n
    stroke, npts = load.stroke_mm, load.points
    check_membrane_pressure(p_i, stroke)

    inf = inflate(geometry, mat, p_i, settings=settings)
    infl, ok, iters = inf.shape, inf.converged, inf.iterations
    y = np.linspace(0.0, stroke, npts)
    meta = dict(geometry=geometry.as_dict(), material=mat.name,
                setup={"p_i_kPa": p_i, "reservoir_mm3": v_r, "polytropic_n": n_poly},
                nominal_volume_mm3=geometry.cavity_volume())
    if not ok:
        return _failed_inflation(inf, y, meta, settings, t_start)
    apex = float(infl.eta[0])
    if stroke >= apex:
        raise ParameterError("stroke", stroke_mm,
                             f"< inflated chamber height {apex:.4g} mm (the plate would reach "
                             "the base)")
    press = StrokeContinuation(geometry, mat, infl, settings, to_MPa(p_i), v_r, n_poly)
    F, P, A, DV, conv, msgs, shapes, stop = _press(press, geometry, infl, y, p_i)
    notes = []
    wr = infl.T2 <= 0.0
    if wr.any():
        notes.append(f"inflated: hoop wrinkles (T2 = 0) over s = {infl.s[wr][0]:.3g}–"
                     f"{infl.s[wr][-1]:.3g} mm of the meridian (tension-field membrane)")
    info = SolveInfo(converged=bool(conv.all()), message=stop or "converged",
                     y_reached_mm=float(y[conv][-1]), seconds=time.perf_counter() - t_start,
                     iterations=iters + press.iterations, notes=tuple(notes),
                     details=_details(settings))
    curve = Curve(y, F, P, A, DV, model="membrane", inflated_volume_mm3=infl.volume_mm3,
                  inflated_height_mm=apex, converged=conv, message=tuple(msgs), solver=info,
                  **meta)
    return MembraneResult(curve, infl, tuple(shapes))


def _failed_inflation(inf, y, meta, settings, t_start) -> MembraneResult:
    """The result of an inflation that stopped: the path and the last shape it reached, the
    curve all NaN with the reason (nothing is lost)."""
    npts = y.size
    nan = np.full(npts, np.nan)
    details = _details(settings) | {"inflation_path": [
        {"pressure_kPa": pk, "volume_mm3": vol, "apex_mm": apex} for pk, vol, apex in inf.path]}
    info = SolveInfo(converged=False, message=inf.message, seconds=time.perf_counter() - t_start,
                     iterations=inf.iterations, details=details)
    last = inf.reached
    extra = {} if last is None else {"inflated_volume_mm3": last.volume_mm3,
                                     "inflated_height_mm": float(last.eta[0])}
    curve = Curve(y, nan, nan, nan, nan, model="membrane", converged=np.zeros(npts, bool),
                  message=(inf.message,) * npts, solver=info, **meta, **extra)
    return MembraneResult(curve, last, (last,) + (None,) * (npts - 1))


def _press(press, geometry, infl, y, p_i):
    """Walk the plate positions ``y`` (mm) with the continuation ``press``: F = p·A (N, eq. 38
    with the deformed contact radius), P (kPa), A (mm²), ΔV (mm³), converged flags, messages,
    shapes and the reason it stopped ('' if it did not)."""
    npts = y.size
    F, P, A, DV = (np.full(npts, np.nan) for _ in range(4))
    F[0], P[0], A[0], DV[0] = 0.0, p_i, 0.0, 0.0
    conv = np.zeros(npts, bool)
    conv[0] = True
    msgs = [""] * npts
    shapes = [infl] + [None] * (npts - 1)
    for k in range(1, npts):
        sh, why = press.advance(y[k])
        if sh is None:
            stop = f"no equilibrium found beyond y = {press.y:.4g} mm: {why}"
            msgs[k:] = [stop] + [f"not attempted (continuation stopped at y = {press.y:.4g} mm)"
                                 ] * (npts - k - 1)
            return F, P, A, DV, conv, msgs, shapes, stop
        msgs[k] = why or ""
        rG = sh.contact_radius
        A[k] = math.pi * rG * rG + 2.0 * geometry.l * rG
        P[k] = sh.pressure_kPa
        F[k] = 1e-3 * P[k] * A[k]
        DV[k] = infl.volume_mm3 - sh.volume_mm3
        conv[k], shapes[k] = True, sh
    return F, P, A, DV, conv, msgs, shapes, ""


def _details(settings: SolverSettings) -> dict:
    """Discretisation facts of a solve (for ``SolveInfo.details``)."""
    return {"inflation_intervals": settings.inflation_intervals,
            "contact_intervals": settings.contact_intervals,
            "free_intervals": settings.free_intervals, "rtol": settings.rtol,
            "wrinkling": settings.wrinkling}
