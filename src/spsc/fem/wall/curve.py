"""The ``wall`` model: the chamber wall as a thick, nearly incompressible hyperelastic solid,
coupled in one Newton solve to the cavity pressure, the trapped gas and a rigid plate.

The chamber (:mod:`spsc.fem.wall.model`) is the axisymmetric **dome** when l = 0 (the body of
revolution of the wall section, :mod:`spsc.fem.wall.section`); when l > 0 it is the **swept wall**
(:mod:`spsc.fem.wall.swept`): the same section extruded along the middle and revolved about the
half-domes' axes, in 27-node hexahedra on the quarter model. The wall carries

* the follower cavity pressure p ∂V/∂u with its consistent stiffness p ∂²V/∂u² (V the cavity
  volume, eq. 37's V for the nominal shape);
* after inflation the valve closes: p = p(V) of :class:`~spsc.core.gaslaw.GasLaw`
  (P (V + V_r)ⁿ = const, eqs. 2, 6–7), adding the rank-one stiffness −(dp/dV) g gᵀ, solved by
  Sherman–Morrison;
* the plate is a frictionless rigid plane z = z_p lowered from first contact: exact
  enforcement on the outer-surface nodes by a primal–dual active set (an active node's height is
  prescribed at the plate and released when its reaction pulls), so the answer does not depend
  on a penalty factor and contact can open and close anywhere along the outer surface (the
  vented flat-topped chambers invert: the apex lifts off and the contact becomes a ring);
* plate force F = Σ reactions of the active nodes (whole-chamber forces, N), pressure and wall
  together; contact area as the 3D model measures it (outer surface on the plate).

``pressure_kPa = 0`` is the vented chamber: gauge pressure held at zero, no gas; its force is
the structural F_el(y) of the paper's open-chamber bench test (Fig. 5b).

Accuracy against the converged 3D FEM (docs/theory/wall.md, ``bench/bench_wall.py``): domes within 0.6 % in
force and 1.7 % in pressure rise, in about a second per curve; stadium chambers (Table 1, l = 3
and l = 10) within the table of docs/theory/wall.md, in tens of seconds.

The load path — inflate, close the valve, press — is walked by the engine
(:func:`spsc.fem.engine.solve`, one Newton loop with the 3D FEM) with the wall's own Newton
choices (:meth:`~spsc.fem.wall.model.WallSettings.newton_settings`).

Stability: every converged state's tangent (with the active constraints and the gas) is
factorised with its inertia; a negative eigenvalue is an unstable equilibrium (limit point,
snap-through or buckling of the wall). Under the plate's displacement control the wall then
snaps: the onset is located, the jump to the stable state at the same plate position followed
(:mod:`spsc.fem.engine.snap`) and recorded in the solve's block (``details["jumps"]``: y, force
and pressure before and after, the energy released), and the press goes on to the end of the
stroke. No unstable point is reported as converged (docs/design.md); where no stable state is
found the solve stops there as before.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from spsc.cad.geometry import SPSCGeometry
from spsc.core.curve import Curve, SolveInfo
from spsc.core.gaslaw import GasLaw
from spsc.core.contact import check_body, with_indenter
from spsc.core.setup import Contact, Setup
from spsc.materials import Material

from ..engine import CloseValve, Inflate, Load, NewtonFailure, Press, Record, solve
from ..engine import newton as _engine_newton
from ..engine.walk import record
from .model import WallModel, WallSettings

__all__ = ["WallSettings", "WallModel", "WallFailure", "newton", "wall_curve", "wall_curves",
           "inflate"]

#: a plate-force drop between recorded points larger than this fraction is reported as negative
#: stiffness (the 3D solver's threshold, :class:`spsc.fem.engine.settings.Settings`)
SOFTENING = 1e-2

#: Newton did not converge for one increment: the engine's one failure
WallFailure = NewtonFailure


@dataclass
class _Walked:
    """The load path as the wall reports it: the converged states after the start (the
    unstable one it stopped at last), what stopped it, Newton iterations of every accepted
    increment."""

    states: list = field(default_factory=list)
    message: str = "converged"
    instability: str = ""
    iterations: int = 0
    converged: bool = True
    jumps: tuple = ()


def _walked(result, pressure_kPa: float) -> _Walked:
    """The engine's result in the wall's words: "inflation at p = … kPa" or "press at y = …
    mm", the reason; at an unstable equilibrium "stopped: the tangent has …"."""
    out = _Walked(list(result.records[1:]), iterations=result.newton_iterations,
                  converged=result.converged, jumps=result.jumps,
                  instability=result.instability if result.jumps else "")
    stop = result.stop
    if stop is None:
        return out
    label = (f"press at y = {stop.t:.4g} mm" if stop.kind == "press"
             else f"inflation at p = {pressure_kPa * stop.t:.4g} kPa")
    if stop.record is None:
        out.message = f"{label}: {stop.reason}"
        return out
    out.states.append(stop.record)
    out.instability = (f"the tangent has {stop.record.unstable_modes} negative eigenvalue(s) at "
                       f"{label}: unstable equilibrium (limit point, buckling or "
                       "snap-through of the wall)")
    out.message = f"stopped: {out.instability}"
    return out


def newton(model: WallModel, x0, *, pressure=0.0, gas: GasLaw | None = None, plate=None,
           active=None, settings: WallSettings | None = None) -> Record:
    """Solve one load (prescribed gauge ``pressure`` MPa, or the closed ``gas``; plate height
    ``plate`` mm or None) from ``x0`` with the engine; the converged :class:`Record`. Raises
    :class:`WallFailure` with the reason if it does not converge."""
    load = Load(pressure, gas, plate)
    sol = _engine_newton(model, x0, load, (settings or model.settings).newton_settings(),
                         active)
    return record(model, -1, "load", load, sol)


def inflate(model: WallModel, pressure_kPa: float, increments: int = 4) -> Record:
    """Inflate ``model`` to gauge ``pressure_kPa`` (kPa) in ``increments``; the last state.
    Raises :class:`WallFailure` with the reason if it does not converge."""
    result = solve(model, [Inflate.kPa(pressure_kPa, increments)],
                   settings=model.settings.newton_settings())
    if result.stop is not None:
        raise WallFailure(_walked(result, pressure_kPa).message)
    return result.records[-1]


def wall_curve(geometry: SPSCGeometry, material: Material, **kwargs) -> Curve:
    """Inflate to ``pressure_kPa`` (kPa gauge), close the valve (gas with ``reservoir_mm3``,
    polytropic index ``polytropic_n``), lower the plate from first contact by ``stroke_mm`` in
    ``points`` − 1 equal increments. ``pressure_kPa = 0``: vented chamber (F_el). Returns the
    :class:`Curve` (model ``wall``); points not reached hold NaN and the reason. ``friction``
    ``"stick"``: the plate holds what it touches (:mod:`spsc.core.contact`); the solver block
    then carries ``friction`` and ``shear_N``, the plate's tangential reactions per point.

    Keyword arguments: ``pressure_kPa`` (40), ``reservoir_mm3`` (0), ``stroke_mm`` (6),
    ``points`` (25), ``polytropic_n`` (1), ``settings`` (:class:`WallSettings`), ``model`` (a
    :class:`WallModel` to reuse), ``progress`` (called once per converged point),
    ``friction`` (``"0"``, a Coulomb coefficient such as ``"0.3"`` or ``"stick"``), ``object_stiffness`` (N/mm: the indenter on a
    spring whose far end is the travel y; the curve's series ``indenter_travel_mm`` is the
    indenter's own travel; None: rigid), ``indenter`` (``"plate"`` or a curved body such as
    ``"sphere:R=10"``, :mod:`spsc.core.indenter`: y is then its tip's travel; a dome takes
    the plate and a sphere on its axis).
    """
    reservoir = kwargs.pop("reservoir_mm3", 0.0)
    return wall_curves(geometry, material, [reservoir], **kwargs)[0]


def wall_curves(geometry: SPSCGeometry, material: Material, reservoirs, *,
                pressure_kPa: float = 40.0, stroke_mm: float = 6.0, points: int = 25,
                polytropic_n: float = 1.0, settings: WallSettings | None = None,
                model: WallModel | None = None, progress=None, friction="0",
                object_stiffness=None, indenter="plate") -> list:
    """:func:`wall_curve` for each reservoir volume of ``reservoirs`` (mm³; 0: the closed
    chamber, the high mode), the same in every other keyword: one model and one inflation
    serve all, each press goes on from the inflated state (the curves are those of separate
    calls, bit for bit; each curve's seconds and iterations include the shared inflation).
    The keywords are checked here, once, into a :class:`~spsc.core.setup.Setup`
    (:func:`setup_curves` takes one already checked)."""
    setups = [Setup.of(geometry, material, pressure_kPa=pressure_kPa, reservoir_mm3=v,
                       stroke_mm=stroke_mm, points=points, polytropic_n=polytropic_n,
                       indenter=indenter, friction=friction,
                       object_stiffness=object_stiffness) for v in reservoirs]
    return setup_curves(setups[0], [s.load.reservoir_mm3 for s in setups], settings=settings,
                        model=model, progress=progress)


def setup_curves(setup: Setup, reservoirs, *, settings: WallSettings | None = None,
                 model: WallModel | None = None, progress=None) -> list:
    """The wall model's curves of the checked ``setup`` with each reservoir volume of
    ``reservoirs`` (mm³, checked by the caller): one model (``model`` to reuse, else one of
    ``settings``) and one inflation for all; ``progress()`` once per converged point."""
    from threadpoolctl import threadpool_limits

    # small dense blocks: one BLAS thread (threads spin on them, 100x slower when loaded)
    with threadpool_limits(limits=1, user_api="blas"):
        return _wall_curves(setup, list(reservoirs), settings, model, progress)


def _wall_curves(setup: Setup, reservoirs: list, settings: WallSettings | None,
                 model: WallModel | None, progress) -> list:
    t_start = time.perf_counter()
    contact = setup.contact
    loads = [setup.with_load(reservoir_mm3=float(v)).load for v in reservoirs]
    settings = settings or (model.settings if model is not None else WallSettings())
    model = model or WallModel(setup.body, setup.material, settings)
    # the wall's own limit on the body: its dome is an axisymmetric section
    check_body(contact.indenter, contact.friction, axisymmetric=not model.stadium,
               quarter=True)
    load = loads[0]
    p_i = load.pressure_MPa
    y = np.linspace(0.0, load.stroke_mm, load.points)
    tick = (lambda done, total: progress()) if progress is not None else None
    press = Press.through(y[1:], stick=contact.friction != "0",
                          spring=contact.object_stiffness, mu=contact.mu,
                          indenter=contact.indenter)
    inflated = solve(model, [Inflate(p_i, settings.inflate_increments)],
                     settings=settings.newton_settings(), progress=tick) if p_i > 0 else None
    shared = time.perf_counter() - t_start
    curves = []
    for lc in loads:
        t0 = time.perf_counter()
        if inflated is None or inflated.converged:
            steps = [CloseValve(lc.reservoir_mm3, lc.polytropic_n)] if p_i > 0 else []
            result = solve(model, steps + [press], settings=settings.newton_settings(),
                           progress=tick, start=inflated)
        else:
            result = inflated  # the inflation failed: every curve ends there
        curves.append(_finish(model, result, y, lc, shared + time.perf_counter() - t0,
                              progress, contact))
    return curves


def _finish(model, result, y, lc, seconds, progress, contact: Contact) -> Curve:
    """The :class:`Curve` of one walk (inflation, valve, press) of :func:`wall_curves`."""
    walked = _walked(result, lc.pressure_kPa)
    if progress is not None and result.stop is not None and result.stop.record is not None:
        progress()  # the unstable point it stopped at is a point reached
    inflates = [st for st in walked.states if st.kind == "inflate"]
    pressed = [st for st in walked.states if st.kind == "press"]
    curve = _to_curve(model, walked, inflates[-1] if inflates else None, pressed, y,
                      result.records[0].volume, lc.pressure_kPa, lc.reservoir_mm3,
                      lc.polytropic_n, seconds)
    if contact.friction != "0":
        curve.solver.details.update(friction=contact.friction,
                                    shear_N=[0.0] + [st.shear for st in pressed])
    curve = curve.replace(setup=replace(curve.setup, indenter=contact.indenter.spec,
                                        friction=contact.friction))
    return with_indenter(curve, contact.object_stiffness, [st.indenter for st in pressed])


def _to_curve(model, path, inflated, pressed, y, v_nominal, pressure_kPa, reservoir,
              n_poly, seconds) -> Curve:
    n = y.size
    F, P, A, dV = (np.full(n, np.nan) for _ in range(4))
    conv = np.zeros(n, bool)
    msg = [""] * n
    ok_start = inflated is not None or pressure_kPa == 0
    v_inf = inflated.volume if inflated is not None else v_nominal
    x_inf = inflated.x if inflated is not None else model.zero_state()
    if ok_start:
        F[0], P[0], A[0], dV[0], conv[0] = 0.0, pressure_kPa, 0.0, 0.0, True
    for k, st in enumerate(pressed, start=1):
        F[k], P[k], A[k] = st.force, st.pressure_kPa, st.contact_area
        # an unstable equilibrium is kept but not converged: the wall leaves it (docs/design.md)
        dV[k], conv[k] = v_inf - st.volume, not st.unstable_modes
        if st.unstable_modes:
            msg[k] = path.instability
    for k in range(len(pressed) + 1 if ok_start else 0, n):
        msg[k] = path.message
    instability = path.instability
    for k in range(2, len(pressed) + 1):
        if F[k] < (1.0 - SOFTENING) * F[k - 1]:
            # stable under displacement control, but the wall snaps (or the contact jumps)
            # between the points: say so at the point and in the solve's record
            msg[k] = (f"plate force falls from {F[k - 1]:.4g} N to {F[k]:.4g} N between "
                      f"y = {y[k - 1]:.3g} and {y[k]:.3g} mm: negative stiffness (snap-through "
                      "of the wall or a jump of the contact)")
            instability = instability or msg[k]
    s = model.settings
    jumps = [j.as_dict() for j in path.jumps]
    info = SolveInfo(converged=path.converged, message=path.message,
                     y_reached_mm=y[conv][-1] if conv.any() else float("nan"),
                     instability=instability, seconds=seconds,
                     iterations=path.iterations,
                     notes=tuple(j.sentence() for j in path.jumps),
                     details={"unknowns": model.n, "displacement_unknowns": model.n_u,
                              "part": model.kind,
                              "elements": len(model.solid.element_dofs),
                              "mesh_size_mm": model.mesh_size_mm, "layers": s.layers,
                              "sweep_size_mm": s.sweep_size_mm if model.stadium else None,
                              "bulk_ratio": s.bulk_ratio, "jumps": jumps})
    setup = {"p_i_kPa": pressure_kPa, "reservoir_mm3": reservoir, "polytropic_n": n_poly}
    return Curve(y, F, P, A, dV, model="wall", geometry=model.geometry.as_dict(),
                 material=model.material.name, setup=setup, nominal_volume_mm3=v_nominal,
                 inflated_volume_mm3=v_inf, inflated_height_mm=model.apex(x_inf),
                 converged=conv, message=tuple(msg), solver=info)
