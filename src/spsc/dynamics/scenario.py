"""A time-domain scenario (``spsc simulate SCENARIO.toml``): the chamber, the circuit, the
press and the valve events, read from TOML and checked, every malformed entry a one-line
:class:`~spsc.core.errors.ParameterError` naming it.

.. code-block:: toml

    [chamber]                 # what spsc curve takes
    type = "B"                # or all of w, h, l, t0, n1, n2, cy; footprint = "table1" | "GS1"
    material = "tpu60a"       # catalogue name or a material file (.json)
    model = "wall"            # the static model that maps the chamber (or "surrogate")
    mesh_size = 0.5           # optional, mm; layers = 2
    # viscous = true; mullins = true; friction = 0.3 | "stick": the wall stepped in time

    [circuit]
    setup_kPa = 40            # chamber and reservoir filled together at rest (gauge)
    reservoir_mm3 = 40000     # 0: no reservoir
    valve = { C = 0.06, b = 0.528, state = "closed" }   # C dm³/(s·bar); or area_mm2 = 0.3
    gas = { n = 1.0, thermal_time_s = inf }             # n = 1: isothermal; 1.4: air
    sensor = { rate_Hz = 1000, noise_kPa = 0.1 }        # or preset = "elvh"
    leak = { drop_kPa = 1, over_s = 1800 }              # or C = 5e-9; or area_mm2 = 1e-5
    # vented = true           # open to the air (gauge 0): the wall stepped in time

    [press]
    profile = [[0, 0], [0.5, 3], [2, 3], [2.5, 0]]      # [t_s, y_mm], piecewise linear
    # or a force-controlled press: the plate goes where the chamber carries the force
    # force = [[0, 0], [0.5, 10], [2, 10]]              # [t_s, force_N]
    # max_travel_mm = 4                                 # the map's depth (default 4 mm)
    # object_N_per_mm = 1.5     # a compliant object: profile is the far end of its spring

    [[events]]
    t = 1.0
    valve = "open"

    [[events]]                # or on a threshold of the chamber's gauge pressure, once
    pressure_above_kPa = 45   # or pressure_below_kPa
    valve = "close"
    after_s = 1.5             # armed from then on (default 0)

    [output]
    dt = 0.001                # s

    [stiffness]               # continuous stiffness: the reservoir a piston, the valve open
    target = [[0, 3.2], [1.0, 3.8]]   # [t_s, N/mm], each held from its instant on
    reservoir_mm3 = [1000, 40000]     # the piston's stroke; it starts at circuit.reservoir_mm3
    actuator_time_s = 0.05            # its first-order lag; rate_mm3_s = its top speed

    [bode]                    # spsc simulate --bode: a small sinusoidal press about y_mm
    y_mm = 3                  # default: the profile's deepest travel
    valve = "open"            # default: the valve's state at t = 0
    f_min_Hz = 0.01
    f_max_Hz = 1000
    points = 61
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from spsc.cad.geometry import PARAMS
from spsc.core.errors import (ParameterError, known_keys, require, require_integer,
                              table_of)

from .gas import Gas
from .leak import LeakSpec
from .profile import ForceProfile, PressProfile, SpringProfile
from .sensor import Sensor
from .stiffness import parse_stiffness
from .valve import Valve, sonic_conductance
from .wall_time import check_stepped, plate_friction, stepped, vented_circuit

__all__ = ["Scenario", "ChamberSpec", "read_scenario", "parse_scenario"]

_TABLES = {"chamber", "circuit", "press", "events", "output", "bode", "stiffness"}
_CHAMBER = {"type", "footprint", "material", "model", "mesh_size", "layers", *PARAMS,
            "viscous", "friction", "mullins"}
_CIRCUIT = {"setup_kPa", "reservoir_mm3", "valve", "gas", "sensor", "leak", "vented"}
_VALVE = {"C", "b", "m", "area_mm2", "state"}
_GAS = {"n", "thermal_time_s", "ambient_K"}
_SENSOR = {"preset", "rate_Hz", "noise_kPa", "resolution_kPa", "full_scale_kPa", "seed"}
_MODELS = ("wall", "surrogate")
_BODE = {"y_mm", "valve", "f_min_Hz", "f_max_Hz", "points"}


@dataclass(frozen=True)
class ChamberSpec:
    """The chamber as ``spsc curve`` takes it: the geometry's parameters (a preset type with
    overrides, or all seven), the material name or file, the static model and its mesh."""

    params: dict
    material: str = "tpu60a"
    model: str = "wall"
    mesh_size: float | None = None
    layers: int = 2
    viscous: bool = False  # the material's Prony terms: the wall stepped in time
    friction: object = None  # None (frictionless), "stick" or a Coulomb μ on the plate
    mullins: bool = False  # the material's first-loading softening (Ogden–Roxburgh)

    def geometry(self):
        from spsc.cad.geometry import PARAMS, SPSCGeometry, preset

        given = {k: v for k, v in self.params.items() if k in PARAMS}
        if "type" in self.params:
            return preset(self.params["type"], size=self.params.get("footprint", "table1"),
                          **given)
        missing = [k for k in PARAMS if k not in given]
        if missing:
            raise ParameterError("chamber", "incomplete", "type = \"A\"..\"D\", or all seven "
                                 "parameters (missing: " + ", ".join(missing) + ")")
        return SPSCGeometry(**given)


@dataclass(frozen=True)
class Scenario:
    chamber: ChamberSpec
    setup_kPa: float
    reservoir_mm3: float
    valve: Valve
    valve_open: bool
    gas: Gas
    sensor: Sensor | None
    press: PressProfile | ForceProfile | SpringProfile
    events: tuple = field(default=())  # ((t_s, opened), ...)
    triggers: tuple = field(default=())  # (Trigger, ...)
    dt: float = 1e-3
    bode: dict = field(default_factory=dict)  # y_mm, valve_open, f_min_Hz, f_max_Hz, points
    stiffness: object = None  # a StiffnessControl: the reservoir a piston, the valve open
    leak: LeakSpec | None = None  # an orifice to the ambient air (:mod:`.leak`)
    source: dict = field(default_factory=dict, compare=False)
    vented: bool = False  # the chamber open to the air (gauge 0): the wall stepped in time


def _table(doc: dict, name: str, required: bool = True) -> dict:
    return table_of(doc, name, required=required, of="the scenario")


def _valve(c: dict) -> tuple[Valve, bool]:
    v = c.get("valve", {})
    if not isinstance(v, dict):
        raise ParameterError("circuit.valve", v, "an inline table {C = ..., state = ...}")
    known_keys("circuit.valve", v, _VALVE)
    if "C" in v and "area_mm2" in v:
        raise ParameterError("circuit.valve", "C and area_mm2", "one of them")
    C = v["C"] if "C" in v else sonic_conductance(v.get("area_mm2", 0.3))
    state = v.get("state", "closed")
    if state not in ("open", "closed"):
        raise ParameterError("circuit.valve.state", state, "\"open\" or \"closed\"")
    return Valve(C, v.get("b", 0.528), v.get("m", 0.5)), state == "open"


def _sensor(c: dict) -> Sensor | None:
    s = c.get("sensor")
    if s is None:
        return None
    if not isinstance(s, dict):
        raise ParameterError("circuit.sensor", s, "an inline table {rate_Hz = ..., ...}")
    known_keys("circuit.sensor", s, _SENSOR)
    rest = {k: v for k, v in s.items() if k != "preset"}
    return Sensor.preset(s["preset"], **rest) if "preset" in s else Sensor(**rest)


def _events(doc: dict, duration: float) -> tuple[tuple, tuple]:
    """(timed events ((t_s, opened), ...), pressure triggers (:class:`~.circuit.Trigger`))."""
    from .circuit import Trigger

    events = doc.get("events", [])
    if not isinstance(events, list):
        raise ParameterError("[[events]]", events, "an array of tables [[events]]")
    timed, triggers = [], []
    for i, e in enumerate(events):
        if not isinstance(e, dict):
            raise ParameterError(f"events[{i}]", e, "a table [[events]] with t (or a pressure "
                                 "threshold) and valve")
        known_keys(f"events[{i}]", e, {"t", "valve", "pressure_above_kPa", "pressure_below_kPa",
                                     "after_s"})
        if e.get("valve") not in ("open", "close"):
            raise ParameterError(f"events[{i}].valve", e.get("valve"), "\"open\" or \"close\"")
        when = [k for k in ("t", "pressure_above_kPa", "pressure_below_kPa") if k in e]
        if len(when) != 1:
            raise ParameterError(f"events[{i}]", ", ".join(when) or "no time or threshold",
                                 "one of t, pressure_above_kPa, pressure_below_kPa")
        opened = e["valve"] == "open"
        if when[0] == "t":
            if "after_s" in e:
                raise ParameterError(f"events[{i}].after_s", e["after_s"],
                                     "only with a pressure threshold")
            t = require(f"events[{i}].t", e["t"], ge=0, le=duration, unit="s, within the press")
            timed.append((t, opened))
        else:
            level = require(f"events[{i}].{when[0]}", e[when[0]], ge=-100, le=1000,
                            unit="kPa gauge")
            after = require(f"events[{i}].after_s", e.get("after_s", 0.0), ge=0, le=duration,
                            unit="s, within the press")
            triggers.append(Trigger(level, when[0] == "pressure_above_kPa", opened, after))
    seen = {}
    for i, (t, _) in enumerate(timed):
        if t in seen:  # sorted, the valve's close came before its open whatever the file said
            raise ParameterError(f"events[{i}].t", t, f"an instant of its own (events[{seen[t]}] "
                                 "is at the same time: the valve does one thing at a time)")
        seen[t] = i
    return tuple(sorted(timed, key=lambda e: e[0])), tuple(triggers)


def _bode(doc: dict, profile: PressProfile, opened: bool) -> dict:
    b = _table(doc, "bode", required=False)
    known_keys("bode", b, _BODE)
    lo, hi = profile.extent
    y = require("bode.y_mm", b.get("y_mm", hi), ge=min(lo, 0.0), le=max(hi, 0.0),
                unit="mm, within the press profile's travels")
    if b.get("valve", "open" if opened else "closed") not in ("open", "closed"):
        raise ParameterError("bode.valve", b.get("valve"), "\"open\" or \"closed\"")
    f_min = require("bode.f_min_Hz", b.get("f_min_Hz", 0.01), gt=0, unit="Hz")
    f_max = require("bode.f_max_Hz", b.get("f_max_Hz", 1000.0), gt=f_min, le=1e6, unit="Hz")
    points = require_integer("bode.points", b.get("points", 61), ge=2, le=10000)
    return {"y_mm": y, "valve_open": b.get("valve", "open" if opened else "closed") == "open",
            "f_min_Hz": f_min, "f_max_Hz": f_max, "points": points}


def _press(press: dict) -> PressProfile | ForceProfile | SpringProfile:
    given = [k for k in ("profile", "force") if k in press]
    if len(given) != 1:
        raise ParameterError("press", " and ".join(given) or "no profile",
                             "a travel profile = [[t_s, y_mm], ...] or a force = "
                             "[[t_s, force_N], ...], one of them")
    if given[0] == "profile":
        if "max_travel_mm" in press:
            raise ParameterError("press.max_travel_mm", press["max_travel_mm"],
                                 "only with a force-controlled press (force = ...)")
        if "object_N_per_mm" in press:
            return SpringProfile.of(press["profile"], require(
                "press.object_N_per_mm", press["object_N_per_mm"], gt=0, le=1e5,
                unit="N/mm, the object's spring"))
        return PressProfile.of(press["profile"])
    if "object_N_per_mm" in press:
        raise ParameterError("press.object_N_per_mm", press["object_N_per_mm"],
                             "only with a travel profile (press.profile: the spring's far end)")
    depth = require("press.max_travel_mm", press.get("max_travel_mm", 4.0), gt=0, le=50,
                    unit="mm")
    return ForceProfile.of(press["force"], depth)


def _check_reach(spec: ChamberSpec, profile) -> None:
    """The press stays above the chamber's base plane, as ``spsc curve --stroke`` does: the
    map is built over every travel the profile names (the far end's, on a spring), so a
    press beyond the chamber's height would build it for minutes and never be right."""
    h = spec.geometry().h
    hi = profile.extent[1]
    if hi >= h:
        key = "press.max_travel_mm" if isinstance(profile, ForceProfile) else "press.profile"
        raise ParameterError(key, f"{hi:g} mm", f"travels below the chamber height h = {h:g} "
                             "mm (the plate would reach the base plane; the map covers every "
                             "travel the press names, the far end's on a spring)")


#: the scenario's keys that hold text; every other value is a number or a list of numbers
_TEXT_KEYS = {"type", "footprint", "material", "model", "state", "preset", "valve", "friction"}
#: the scenario's keys that hold true or false
_FLAG_KEYS = {"viscous", "vented", "mullins"}


def _no_quoted_numbers(value, where: str) -> None:
    """A number written as text (``n = "1.4"``) or a boolean where a number belongs is
    refused where it is read: the range checks convert text, and the objects built from the
    document would keep the string and fail later (issue 53: 16 internal errors)."""
    if isinstance(value, dict):
        for k, v in value.items():
            if k in _FLAG_KEYS:
                if not isinstance(v, bool):
                    raise ParameterError(f"{where}.{k}" if where else str(k), v,
                                         "true or false")
                continue
            if not (k in _TEXT_KEYS and isinstance(v, str)):
                _no_quoted_numbers(v, f"{where}.{k}" if where else str(k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            _no_quoted_numbers(v, f"{where}[{i}]")
    elif isinstance(value, (str, bool)):
        raise ParameterError(where, value, "a number (without quotes)" if isinstance(value, str)
                             else "a number, not true or false")


def parse_scenario(doc: dict) -> Scenario:
    """The :class:`Scenario` of a parsed TOML document."""
    known_keys("scenario", doc, _TABLES)
    _no_quoted_numbers(doc, "")
    ch, c, press = _table(doc, "chamber"), _table(doc, "circuit"), _table(doc, "press")
    out = _table(doc, "output", required=False)
    known_keys("chamber", ch, _CHAMBER)
    known_keys("circuit", c, _CIRCUIT)
    known_keys("press", press, {"profile", "force", "max_travel_mm", "object_N_per_mm"})
    known_keys("output", out, {"dt"})
    model = ch.get("model", "wall")
    if model not in _MODELS:
        raise ParameterError("chamber.model", model, "wall or surrogate (the static model "
                             "the time domain maps the chamber with)")
    mesh = ch.get("mesh_size")
    spec = ChamberSpec({k: v for k, v in ch.items() if k in _CHAMBER - {
                           "material", "model", "mesh_size", "layers", "viscous", "friction",
                           "mullins"}},
                       str(ch.get("material", "tpu60a")), model,
                       None if mesh is None else require("chamber.mesh_size", mesh, gt=0, le=5,
                                                         unit="mm"),
                       require_integer("chamber.layers", ch.get("layers", 2), ge=1, le=16),
                       bool(ch.get("viscous", False)), plate_friction(ch.get("friction")),
                       bool(ch.get("mullins", False)))
    g = c.get("gas", {})
    if not isinstance(g, dict):
        raise ParameterError("circuit.gas", g, "an inline table {n = ..., thermal_time_s = ...}")
    known_keys("circuit.gas", g, _GAS)
    valve, opened = _valve(c)
    profile = _press(press)
    _check_reach(spec, profile)
    dt = require("output.dt", out.get("dt", 1e-3), gt=0, le=profile.duration, unit="s")
    if profile.duration / dt > 5e6:
        raise ParameterError("output.dt", dt, f">= {profile.duration / 5e6:.3g} s (at most "
                             "5 million output samples)")
    reservoir = require("circuit.reservoir_mm3", c.get("reservoir_mm3", 0.0), ge=0, le=1e7,
                        unit="mm³")
    timed, triggers = _events(doc, profile.duration)
    control = parse_stiffness(doc.get("stiffness"), profile, reservoir, timed or triggers)
    # a sealed chamber at ambient pressure dips below its map's lowest level (0 kPa) at the
    # plate's first touch: the scenario stopped at its first step (the vented chamber is
    # spsc curve --pressure 0)
    vented = vented_circuit(c, timed or triggers, control)
    setup = 0.0 if vented else require(
        "circuit.setup_kPa", c.get("setup_kPa", 40.0), gt=0, le=200,
        unit="kPa gauge; a sealed chamber at 0 kPa falls below its map at the first touch "
        "(the vented chamber: circuit.vented = true)")
    leak = None if "leak" not in c else LeakSpec.parse(c["leak"], setup)
    if leak is not None and control is not None:
        raise ParameterError("circuit.leak", leak.describe(), "none with [stiffness] (the "
                             "piston's control loop is built for a sealed circuit)")
    sc = Scenario(spec, setup, reservoir,
                  valve, opened or control is not None, Gas(**g), _sensor(c), profile,
                  timed, triggers, dt, _bode(doc, profile, opened), control, leak, doc, vented)
    if stepped(sc):
        check_stepped(sc)
    return sc


def read_scenario(path) -> Scenario:
    """The scenario in the TOML file ``path``."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")  # a BOM (Windows editors) is no error
    except OSError as exc:
        raise ParameterError("scenario", str(path), f"a readable TOML file ({exc.strerror})") \
            from None
    except UnicodeDecodeError:
        raise ParameterError("scenario", str(path), "a TOML file (text, UTF-8); this one is "
                             "binary") from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError("scenario", p.name, f"valid TOML ({exc})") from None
    except RecursionError:
        raise ParameterError("scenario", p.name, "a TOML document of tables and arrays "
                             "nested a few levels deep (this one is nested too deep to read)") \
            from None
    return parse_scenario(doc)
