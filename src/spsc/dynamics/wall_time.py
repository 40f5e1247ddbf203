"""The wall model itself stepped in time inside ``spsc simulate`` (issue 52): where the chamber
map of F(y, P), V(y, P) cannot hold the wall's history — a viscous wall (its material's Prony
terms, :mod:`spsc.fem.viscous`), friction on the plate (Coulomb or sticking, both ways), or a
vented chamber — the scenario's press drives the wall model's own time stepping
(:class:`~spsc.fem.engine.Cycle`) instead of the circuit's ODE on the map.

The chamber is inflated to its setup pressure at rest (relaxed), then its gas is closed —
alone (the valve closed) or with the reservoir (the valve open from the start) — with the
polytropic law P·Vⁿ = const of the wall model (isothermal: n = 1); a vented chamber stays at
ambient pressure. The plate follows the press's travel profile through instants no more than
:data:`MAX_DY_MM` of travel and :data:`MAX_DT_S` apart (the profile's knots among them); the
trace is linear in time between them, on the output's grid. Timed valve events cut the path
into :class:`~spsc.fem.engine.Cycle` steps with a :class:`~spsc.fem.engine.SwitchValve`
between them (the gases pooled at once, mixed isothermally). What the stepped wall cannot run
(pressure thresholds, events with n > 1, a force-controlled press, a gas that exchanges heat
with a time constant, a leak, the stiffness controller) is refused before anything runs, in
one line.
"""

from __future__ import annotations

import time

import numpy as np
import pandas as pd

from spsc.core.constants import P_AMB_KPA, to_MPa
from spsc.core.errors import ParameterError, require

__all__ = ["stepped", "check_stepped", "plate_friction", "vented_circuit", "instants",
           "run_stepped", "bode_stepped", "why_stepped", "MAX_DY_MM", "MAX_DT_S"]

#: the largest travel (mm) and time (s) between two instants the wall is solved at
MAX_DY_MM, MAX_DT_S = 0.25, 0.1


def stepped(scenario) -> bool:
    """Whether ``scenario`` runs the wall model stepped in time (viscous, friction, vented)."""
    ch = scenario.chamber
    return bool(ch.viscous or ch.mullins or ch.friction is not None or scenario.vented)


def why_stepped(scenario) -> str:
    ch = scenario.chamber
    return " and ".join(w for w, on in (("viscous", ch.viscous), ("softening", ch.mullins),
                                         ("friction", ch.friction is not None),
                                         ("vented", scenario.vented)) if on)


def plate_friction(value):
    """``[chamber] friction``: None, ``"stick"`` or a Coulomb μ >= 0 (0: frictionless)."""
    if value is None or value == "stick":
        return value
    if isinstance(value, str):
        raise ParameterError("chamber.friction", value, "a Coulomb coefficient >= 0 or "
                             "\"stick\"")
    mu = require("chamber.friction", value, ge=0, le=10)
    return mu or None


def vented_circuit(circuit: dict, events, control) -> bool:
    """``[circuit] vented``: a vented chamber takes no setup pressure, valve events or
    stiffness control (one line naming the first given)."""
    vented = bool(circuit.get("vented", False))
    if vented and (circuit.get("setup_kPa", 0) != 0 or events or control is not None):
        what = "circuit.setup_kPa" if circuit.get("setup_kPa", 0) != 0 else \
            "[stiffness]" if control is not None else "[[events]]"
        raise ParameterError(what, "with vented = true", "none: a vented chamber is open to "
                             "the air (gauge 0), no valve or reservoir acts on it")
    return vented


def check_stepped(scenario) -> None:
    """Refuse in one line what the stepped wall cannot run (see the module)."""
    from .profile import PressProfile

    why = why_stepped(scenario)
    if scenario.chamber.model != "wall":
        raise ParameterError("chamber.model", scenario.chamber.model, f"\"wall\" with {why} "
                             "(the wall model is stepped in time; the surrogate has no history)")
    if type(scenario.press) is not PressProfile:  # a SpringProfile is one too
        raise ParameterError("press", "force or a spring-borne object", f"a travel profile "
                             f"= [[t_s, y_mm], ...] with {why} (the wall follows the plate)")
    if scenario.triggers:
        raise ParameterError("[[events]]", "pressure thresholds", f"timed valve events only "
                             f"with {why} (the wall's instants are set before it runs)")
    gas = scenario.gas
    if scenario.events and not gas.isothermal:
        raise ParameterError("circuit.gas.n", gas.n, f"1 (isothermal) with valve events and "
                             f"{why}: the valve pools the two gases at once, mixed isothermally")
    if not gas.isothermal and np.isfinite(gas.thermal_time_s):
        raise ParameterError("circuit.gas.thermal_time_s", gas.thermal_time_s, f"inf (a "
                             f"polytropic gas) or n = 1 with {why}: the wall model's gas "
                             "exchanges no heat")
    if scenario.leak is not None or scenario.stiffness is not None:
        raise ParameterError("circuit.leak" if scenario.leak is not None else "[stiffness]",
                             "given", f"none with {why}")
    if scenario.chamber.viscous:
        from spsc.materials.catalogue import viscosity

        prony, source = viscosity(scenario.chamber.material)
        if prony is None:
            raise ParameterError("chamber.viscous", True, f"a material with Prony terms "
                                 f"({source})")
    if scenario.chamber.mullins:
        from spsc.materials.catalogue import softening

        prm, source = softening(scenario.chamber.material)
        if prm is None:
            raise ParameterError("chamber.mullins", True, f"a material with Mullins constants "
                                 f"({source})")


def _wall(scenario, valve_open: bool):
    """(a function making the scenario's wall model, the steps to its rest at the setup —
    inflated, its gas closed alone or with the reservoir; none vented —, its Prony terms)."""
    from spsc.fem.engine import CloseValve, Inflate
    from spsc.fem.wall.model import WallModel, WallSettings
    from spsc.materials import material
    from spsc.materials.catalogue import softening, viscosity

    ch, sc = scenario.chamber, scenario
    prony = viscosity(ch.material)[0] if ch.viscous else None
    mullins = softening(ch.material)[0] if ch.mullins else None

    def fresh():
        return WallModel(ch.geometry(), material(ch.material),
                         WallSettings(mesh_size_mm=ch.mesh_size, layers=ch.layers), prony=prony,
                         mullins=mullins)

    n = 1.0 if sc.gas.isothermal else sc.gas.n
    steps = [] if sc.vented else [
        Inflate.kPa(sc.setup_kPa, WallSettings().inflate_increments),
        CloseValve(sc.reservoir_mm3 if valve_open else 0.0, n)]
    return fresh, steps, prony


def instants(profile, max_dy: float = MAX_DY_MM, max_dt: float = MAX_DT_S, at=()):
    """(times s, travels mm ≥ 0) the wall is solved at: the profile's knots and the instants
    ``at`` (valve events), each segment cut so no step moves more than ``max_dy`` or lasts
    more than ``max_dt``."""
    knots = np.union1d(np.asarray(profile.t_s, float),
                       [a for a in at if 0.0 < a < profile.duration])
    t, y = knots, np.maximum(profile.y(knots), 0.0)
    times, travels = [t[0]], [y[0]]
    for k in range(1, t.size):
        n = max(1, int(np.ceil(max(abs(y[k] - y[k - 1]) / max_dy,
                                   (t[k] - t[k - 1]) / max_dt) - 1e-9)))
        for j in range(1, n + 1):
            times.append(t[k - 1] + (t[k] - t[k - 1]) * j / n)
            travels.append(y[k - 1] + (y[k] - y[k - 1]) * j / n)
    return np.array(times), np.array(travels)


def run_stepped(scenario, progress=None) -> tuple[dict, bool, str, float]:
    """(the trace's columns on the output grid — :data:`~.simulate.COLUMNS` —, complete,
    message, the seconds the wall took) of ``scenario`` with the wall model stepped in
    time."""
    from spsc.fem.engine import solve
    from threadpoolctl import threadpool_limits

    check_stepped(scenario)
    sc = scenario
    fresh, steps, _ = _wall(scenario, sc.valve_open)
    model = fresh()
    pooled = sc.reservoir_mm3 if sc.valve_open else 0.0
    events = [(t, o) for t, o in sc.events if 0.0 < t < sc.press.duration]
    # the event and an instant 1 ms after it: the pool settles within the valve's
    # milliseconds, which the trace then shows rather than a ramp over a whole step
    times, travels = instants(sc.press, at=[t + d for t, _ in events for d in (0.0, 1e-3)])
    total = len(steps) and model.settings.inflate_increments
    steps = steps + _segments(sc, times, travels, events)
    report = None if progress is None else \
        (lambda done, _n: progress(float(times[min(max(done - total, 0), times.size - 1)]),
                                   float(times[-1])))
    t0 = time.perf_counter()
    with threadpool_limits(limits=1, user_api="blas"):
        res = solve(model, steps, settings=model.default_settings(), progress=report)
    seconds = time.perf_counter() - t0
    rest = [r for r in res.records if r.kind != "press"][-1]
    pressed = [r for r in res.records if r.kind == "press"]
    k = len(pressed) + 1
    f = np.array([0.0] + [r.force for r in pressed])
    p = np.array([rest.pressure_kPa] + [r.pressure_kPa for r in pressed])
    v = np.array([rest.volume] + [r.volume for r in pressed])
    a = np.array([0.0] + [r.contact_area for r in pressed])
    t_out = np.arange(0.0, times[k - 1] + 0.5 * sc.dt, sc.dt)
    t_out = t_out[t_out <= times[k - 1] + 1e-12]
    col = {"t_s": t_out, "y_mm": sc.press.y(t_out)}
    for name, values in (("force_N", f), ("pressure_kPa", p), ("volume_mm3", v),
                         ("contact_mm2", a)):
        col[name] = np.interp(t_out, times[:k], values)
    valve = _valve_states(sc, times[:k], events, strict=True)
    col.update(_gas_columns(sc, col["pressure_kPa"], col["volume_mm3"], pooled,
                            float(p[0]), float(v[0])))
    if events:  # the valve switched: where open the pool's pressure, where shut the held one
        open_ = _valve_states(sc, t_out, events, strict=True)
        held = _held_reservoir(sc, times[:k], p, valve)
        prev = np.clip(np.searchsorted(times[:k], t_out, "right") - 1, 0, k - 1)
        col["reservoir_kPa"] = np.where(open_, col["pressure_kPa"], held[prev])
        col["valve_open"] = open_.astype(int)
        col["reservoir_mg"] = (col["reservoir_kPa"] + P_AMB_KPA) * 1e3 * sc.reservoir_mm3 * \
            1e-9 / (sc.gas.R * sc.gas.ambient_K) * 1e6
    return col, bool(res.converged), res.message if not res.converged else "complete", seconds


def _segments(sc, times, travels, events) -> list:
    """The plate's path as Cycle steps between the valve's events (each measuring its
    travels from where the last left the plate, its clock from the event), a
    :class:`SwitchValve` at each event."""
    from spsc.fem.engine import Cycle, SwitchValve

    friction, n = sc.chamber.friction, 1.0 if sc.gas.isothermal else sc.gas.n
    state = {"pressure": to_MPa(sc.setup_kPa)}  # the reservoir's gauge pressure (MPa)
    at = {int(np.argmin(np.abs(times - t))): opened for t, opened in events}
    # a cut 1 ms after each event too: the walk's increments start at a Cycle's first spacing,
    # so the millisecond the pool settles in is a Cycle of its own
    after = {int(np.argmin(np.abs(times - t - 1e-3))) for t, _ in events}
    cuts = sorted({0, times.size - 1} | set(at) | after)
    out = []
    for a, b in zip(cuts, cuts[1:]):
        if a in at:
            out.append(SwitchValve(at[a], sc.reservoir_mm3, n, state))
        out.append(Cycle(tuple(times[a:b + 1] - times[a]), tuple(travels[a:b + 1] - travels[a]),
                         stick=friction is not None,
                         mu=None if friction in (None, "stick") else float(friction),
                         start_s=float(times[a])))
    return out


def _valve_states(sc, times, events, strict: bool = False) -> np.ndarray:
    """The valve at each instant: an event switches it from its instant on (``strict``: just
    after it — the trace's sample at the event holds the wall solved before the switch)."""
    state = np.full(times.size, bool(sc.valve_open))
    for t, opened in events:
        state[times > t + 1e-12 if strict else times >= t - 1e-12] = opened
    return state


def _held_reservoir(sc, times, p, valve) -> np.ndarray:
    """The reservoir's gauge pressure (kPa) at each instant while shut: the setup pressure
    until it first opens, then the pool's pressure where it was last shut."""
    held = np.empty(times.size)
    last = sc.setup_kPa
    for i in range(times.size):
        if valve[i]:
            last = p[i]
        held[i] = last
    return held


def _gas_columns(sc, p, v, pooled, p0, v0) -> dict:
    """The trace's reservoir, valve, temperature and mass columns of the wall's gas: closed at
    rest (``p0`` kPa, ``v0`` mm³, ambient temperature) with the ``pooled`` reservoir volume,
    P Vⁿ = const — its temperature from the gas law at that mass; vented: ambient air."""
    R, t_amb, n = sc.gas.R, sc.gas.ambient_K, p.size

    def mg(pk, vol, temp):
        return (pk + P_AMB_KPA) * 1e3 * vol * 1e-9 / (R * temp) * 1e6

    if sc.vented or sc.gas.isothermal:  # (valve events pool isothermally: n = 1 there)
        temp = np.full(n, t_amb)
    else:
        m_total = mg(p0, v0 + pooled, t_amb)
        temp = (p + P_AMB_KPA) * 1e3 * (v + pooled) * 1e-9 / (R * m_total * 1e-6)
    r_kPa = p if pooled and not sc.vented else np.full(n, 0.0 if sc.vented else sc.setup_kPa)
    r_K = temp if pooled and not sc.vented else np.full(n, t_amb)
    return {"reservoir_kPa": r_kPa, "valve_open": np.full(n, int(sc.valve_open and
                                                                  not sc.vented)),
            "chamber_K": temp, "reservoir_K": r_K, "chamber_mg": mg(p, v, temp),
            "reservoir_mg": mg(r_kPa, np.full(n, sc.reservoir_mm3), r_K)}


#: the stepped wall's Bode: the sinusoid's amplitude (mm), its periods (the last one read)
#: and instants per period, and the frequencies it takes without [bode] points
BODE_AMPLITUDE_MM, BODE_PERIODS, BODE_PER_PERIOD, BODE_POINTS = 0.1, 3, 16, 13


def bode_stepped(scenario, freqs_Hz, progress=None) -> tuple[pd.DataFrame, dict]:
    """(the Bode table — f_Hz, stiffness_N_per_mm, stiffness_phase_deg,
    sensitivity_kPa_per_mm, sensitivity_phase_deg — and the operating point) of the wall
    stepped in time: at each frequency the chamber inflated, the plate lowered to
    ``bode.y_mm`` slowly enough to arrive relaxed (steps of 50 times the longest Prony time),
    then moved sinusoidally by :data:`BODE_AMPLITUDE_MM` over :data:`BODE_PERIODS` periods;
    the force's and pressure's first harmonics over the last period against the travel's
    (phase > 0: the force leads, the wall dissipates). The wall has no inertia: this is its
    own rate dependence."""
    from spsc.fem.engine import Cycle, solve
    from threadpoolctl import threadpool_limits

    check_stepped(scenario)
    ch, b = scenario.chamber, scenario.bode
    fresh, base, prony = _wall(scenario, b["valve_open"])
    y0 = max(float(b["y_mm"]), BODE_AMPLITUDE_MM)
    # the plate's way down to y0, relaxed (one Cycle: a Press before it would move the
    # Cycle's zero to where the Press left the plate)
    slow = 50.0 * max([tau for _, tau in prony.terms] if prony else [1.0])
    down = np.linspace(0.0, y0, max(2, int(np.ceil(y0 / MAX_DY_MM))) + 1)
    friction = ch.friction
    rows, point = [], {}
    k = np.arange(BODE_PERIODS * BODE_PER_PERIOD + 1)
    phase = 2 * np.pi * k / BODE_PER_PERIOD
    last = k >= (BODE_PERIODS - 1) * BODE_PER_PERIOD + 1
    t_down = slow * np.arange(down.size + 1)  # the last: held at y0
    for i, f in enumerate(freqs_Hz):
        times = np.concatenate([t_down, t_down[-1] + k[1:] / (BODE_PER_PERIOD * f)])
        travels = np.concatenate([down, [y0], y0 + BODE_AMPLITUDE_MM * np.sin(phase[1:])])
        cycle = Cycle(tuple(times), tuple(travels), stick=friction is not None,
                      mu=None if friction in (None, "stick") else float(friction))
        model = fresh()  # a viscous law keeps its history: each frequency starts from rest
        with threadpool_limits(limits=1, user_api="blas"):
            res = solve(model, base + [cycle], settings=model.default_settings())
        rec = [r for r in res.records if r.kind == "press"]
        if not res.converged or len(rec) < times.size - 1:
            raise ParameterError("bode", f"{f:.3g} Hz", f"a wall that converges there "
                                 f"({res.message})")
        held, moving = rec[down.size - 1], rec[down.size:]
        point = {"force_N": float(held.force), "pressure_kPa": float(held.pressure_kPa)}
        rows.append((float(f), *_harmonic(np.array([r.force for r in moving])[last[1:]],
                                          phase[last]),
                     *_harmonic(np.array([r.pressure_kPa for r in moving])[last[1:]],
                                phase[last])))
        if progress is not None:
            progress(i + 1, len(freqs_Hz))
    table = pd.DataFrame(rows, columns=["f_Hz", "stiffness_N_per_mm", "stiffness_phase_deg",
                                        "sensitivity_kPa_per_mm", "sensitivity_phase_deg"])
    return table, {"y_mm": y0, **point}


def _harmonic(values, phase) -> tuple[float, float]:
    """(magnitude per mm, phase in degrees) of ``values``' first harmonic against the travel's
    sin(phase): least squares over one period of offset, drift (the overstress's transient,
    e^{-t/τ} with τ over the periods, is no harmonic), in phase and in quadrature."""
    basis = np.column_stack([np.ones_like(phase), phase, np.sin(phase), np.cos(phase)])
    coef = np.linalg.lstsq(basis, values, rcond=None)[0]
    hat = (coef[2] + 1j * coef[3]) / BODE_AMPLITUDE_MM
    return abs(hat), float(np.degrees(np.angle(hat))) if abs(hat) > 1e-12 else 0.0
