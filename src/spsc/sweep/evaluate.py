"""One design of a sweep, evaluated into one table row: its inputs under the CLI's parameter
names, the metrics of :class:`~.metrics.DesignMetrics` (defined once there, shared with the
report), the printability verdict of a process, and how it went.

A design is a dict of :data:`INPUTS`: ``type`` (A–D, or None for a chamber given by all seven
parameters), the seven parameters w, h, l, t0 (mm), n1, n2, cy, ``material`` (catalogue name or
material file), ``pressure`` (setup pressure, kPa gauge) and ``reservoir`` (mm³, the volume that
makes the low-stiffness mode). The high mode is the closed chamber (no reservoir), the low mode
the chamber with that reservoir (eqs. 6–7); both run through the models' registry
(:data:`spsc.models.MODELS`), so every model a curve takes a sweep takes.

:func:`evaluate` never raises: a design the models refuse is an ``invalid`` row with the
:class:`ParameterError`'s line, a solve that stops early a ``partial`` row with what it computed,
anything else a ``failed`` row naming the exception.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import time
from dataclasses import asdict, fields
from pathlib import Path

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import PRESSURE_MAX_KPA, check_load
from spsc.core.setup import Setup

from spsc.models import MODELS, get
from spsc.study.metrics import DesignMetrics, design_metrics
from spsc.cad.geometry import PARAMS

__all__ = ["INPUTS", "METRICS", "COLUMNS", "STATUSES", "DONE", "resolve_design",
           "design_setup", "design_curves", "evaluate", "evaluate_many", "batched",
           "failed_row", "design_key", "printability_columns"]

#: The inputs of a design, under the CLI's parameter names.
INPUTS = ("type",) + PARAMS + ("material", "pressure", "reservoir")
#: The metrics of a design (N/mm, N/mm, kPa/mm, kPa/mm, mm, mm³): DesignMetrics' fields.
METRICS = tuple(f.name for f in fields(DesignMetrics))
#: The columns a row with a band gains (:mod:`.band`): each metric's P5, P50, P95 in each
#: mode, the samples the model ran, how many draws made no chamber or left its domain.
BAND_COLUMNS = tuple(f"{m}_{mode}_p{q}" for mode in ("high", "low")
                     for m in ("stiffness", "sensitivity") for q in (5, 50, 95)) + \
    ("band_samples", "band_refused")
#: Every column of a sweep's table, in order.
COLUMNS = INPUTS + METRICS + ("printable", "printability", "status", "message", "seconds",
                              "key", "life_cycles", "energy_amplitude_MPa", "peak_stretch",
                              "life_message") + BAND_COLUMNS
#: ok: both modes converged; partial: a solve stopped early (metrics over what it reached);
#: invalid: the models refuse the design (ParameterError); failed: anything else.
STATUSES = ("ok", "partial", "invalid", "failed")
#: Statuses a re-run does not compute again (a failed design is retried).
DONE = ("ok", "partial", "invalid")
#: The gas law's polytropic index in a sweep (isothermal, as the report).
POLYTROPIC_N = 1.0
_VERB = "sweep"


def resolve_design(design: dict):
    """``(geometry, material, setup)`` of a design: the :class:`SPSCGeometry` (the type's preset
    for any of the seven parameters the design leaves out; all seven without a type), the
    :class:`Material` and the setup ``{"p_i_kPa", "reservoir_mm3", "polytropic_n"}`` (kPa gauge,
    mm³). ParameterError (one line) naming the first parameter out of range."""
    from spsc.cad.geometry import SPSCGeometry, preset
    from spsc.materials import material

    given = {k: design[k] for k in PARAMS if design.get(k) is not None}
    if design.get("type"):
        geometry = preset(design["type"], **given)
    else:
        missing = [k for k in PARAMS if k not in given]
        if missing:
            raise ParameterError("geometry", "incomplete", "a type A-D, or all seven "
                                 "parameters (missing: " + ", ".join(missing) + ")")
        geometry = SPSCGeometry(**given)
    mat = material(design.get("material", "tpu60a"))
    setup = {"p_i_kPa": require("pressure", design.get("pressure"), ge=0, le=PRESSURE_MAX_KPA,
                                unit="kPa gauge"),
             "reservoir_mm3": require("reservoir", design.get("reservoir"), ge=0, unit="mm³"),
             "polytropic_n": POLYTROPIC_N}
    return geometry, mat, setup


def design_setup(entry, geometry, mat, setup: dict, points=None, stroke_mm=None) -> Setup:
    """The checked :class:`Setup` of a resolved design (:func:`resolve_design`) in its low
    mode (its reservoir) for the model ``entry``: its default stroke and points where
    ``stroke_mm``, ``points`` are None. ParameterError when the load case is refused (the
    model's own limits are its ``check``'s)."""
    load = check_load(geometry, pressure_kPa=setup["p_i_kPa"],
                      reservoir_mm3=setup["reservoir_mm3"],
                      stroke_mm=entry.stroke_mm if stroke_mm is None else stroke_mm,
                      points=entry.points if points is None else points,
                      polytropic_n=setup["polytropic_n"])
    return Setup(geometry, mat, load)


def design_curves(design: dict, model: str, modes=("high", "low"), *, points=None,
                  stroke_mm=None) -> dict:
    """``{mode: Curve}`` of a design with ``model`` (membrane, simplified, wall, fem): ``high``
    the closed chamber (no reservoir), ``low`` with the design's reservoir (mm³); ``points``
    plate positions over ``stroke_mm`` (mm) from first contact, None: the model's defaults.
    A design without a reservoir has one curve for both modes (computed once); the wall model
    inflates once for both (its ``curves``, :class:`~spsc.models.base.CurveModel`).

    ParameterError when the design, the load case or the model's own limits refuse it (before
    any solve)."""
    entry = get(model)
    setup = design_setup(entry, *resolve_design(design), points, stroke_mm)
    unknown = [m for m in modes if m not in ("high", "low")]
    if unknown:
        raise ParameterError("mode", unknown[0], "high or low")
    options = entry.Options()
    entry.check(setup, options, verb=_VERB, quiet=True)
    reservoirs = {"high": 0.0, "low": setup.load.reservoir_mm3}
    volumes = list(dict.fromkeys(reservoirs[mode] for mode in modes))
    if hasattr(entry, "curves"):  # the modes share their inflation (the wall model)
        solved = entry.curves(setup, volumes, options)
    else:
        solved = [entry.curve(setup.with_load(reservoir_mm3=v), options).curve
                  for v in volumes]
    by_reservoir = dict(zip(volumes, solved))
    return {mode: by_reservoir[reservoirs[mode]] for mode in modes}


def printability_columns(geometry, process: str) -> tuple[bool, str]:
    """The ``printable`` and ``printability`` columns of the chamber for ``process``: the
    printability rule (:func:`spsc.cad.printability.printability`, the gate's own, milliseconds,
    no solid built); the verdict's summary when it passes (every check with its value and
    limit), its reasons when not. The design search uses it too."""
    from spsc.cad.printability import printability

    v = printability(geometry, process)
    return bool(v.ok), v.summary if v.ok else "; ".join(v.reasons)


def evaluate(design: dict, model: str, process: str, points: int | None = None,
             stroke_mm: float | None = None) -> dict:
    """One row of :data:`COLUMNS`: the design's inputs, its metrics with ``model``
    (:func:`design_curves`, :func:`~.metrics.design_metrics`), its printability for
    ``process`` (fdm, sla, molding), ``status`` and ``message``, ``seconds`` (wall clock) and
    ``key`` (:func:`design_key`). Never raises (see the module docstring)."""
    t0 = time.perf_counter()
    row = _blank(design)
    try:
        row["key"] = design_key(design, model, process, points, stroke_mm)
        geometry, _, _ = resolve_design(design)
        row["cavity_mm3"] = geometry.cavity_volume()  # known even if the load is refused
        row["printable"], row["printability"] = printability_columns(geometry, process)
        curves = design_curves(design, model, points=points, stroke_mm=stroke_mm)
        row.update(asdict(design_metrics([curves["high"]], [curves["low"]])))
        row["status"], row["message"] = _outcome(curves, geometry)
    except ParameterError as exc:
        row["status"], row["message"] = "invalid", str(exc)
    except Exception as exc:  # a bug or a numerical breakdown: a row that says so
        row["status"], row["message"] = "failed", _one_line(exc)
    row["seconds"] = time.perf_counter() - t0
    return row


def batched(model: str) -> bool:
    """Whether ``model`` answers many setups in one call (its ``curves_many``, e.g. the
    surrogate): a sweep then evaluates its designs in chunks (:func:`evaluate_many`)."""
    entry = MODELS.get(model)
    return entry is not None and hasattr(entry, "curves_many")


def evaluate_many(designs: list, model: str, process: str, points: int | None = None,
                  stroke_mm: float | None = None) -> list[dict]:
    """The rows of :func:`evaluate` for many designs, with one batched call of the model's
    ``curves_many`` for all their curves (both modes): each design checked and judged on its
    own (an invalid row for a design the models refuse, as :func:`evaluate`), the curves of
    the rest computed together. ``seconds`` is each design's own checks plus its share of the
    batch. Never raises: a batch that fails makes failed rows naming the exception."""
    entry = get(model)
    options = entry.Options()
    rows, jobs = [], []
    for design in designs:
        t0 = time.perf_counter()
        row = _blank(design)
        rows.append(row)
        try:
            row["key"] = design_key(design, model, process, points, stroke_mm)
            geometry, mat, setup = resolve_design(design)
            row["cavity_mm3"] = geometry.cavity_volume()
            row["printable"], row["printability"] = printability_columns(geometry, process)
            low = design_setup(entry, geometry, mat, setup, points, stroke_mm)
            entry.check(low, options, verb=_VERB, quiet=True)
            jobs.append((row, low.with_load(reservoir_mm3=0.0), low))
        except ParameterError as exc:
            row["status"], row["message"] = "invalid", str(exc)
        except Exception as exc:
            row["status"], row["message"] = "failed", _one_line(exc)
        row["seconds"] = time.perf_counter() - t0
    if not jobs:
        return rows
    t0 = time.perf_counter()
    try:
        curves = entry.curves_many([s for _, high, low in jobs for s in (high, low)], options)
    except Exception as exc:  # the whole batch: every design of it says so
        for row, _, _ in jobs:
            row["status"], row["message"] = "failed", _one_line(exc)
        return rows
    for k, (row, _, low) in enumerate(jobs):
        high_c, low_c = curves[2 * k], curves[2 * k + 1]
        row.update(asdict(design_metrics([high_c], [low_c])))
        row["status"], row["message"] = _outcome({"high": high_c, "low": low_c}, low.body)
    share = (time.perf_counter() - t0) / len(jobs)
    for row, _, _ in jobs:
        row["seconds"] += share
    return rows


def _outcome(curves: dict, geometry) -> tuple[str, str]:
    stopped, seen = [], set()
    for mode, c in curves.items():
        if id(c) not in seen and not (c.solver.converged and c.all_converged):
            stopped.append(f"{mode} mode: "
                           f"{c.solver.message if not c.solver.converged else _first(c)}")
        seen.add(id(c))  # a curve shared by both modes (no reservoir) is named once
    if stopped:
        return "partial", "; ".join(stopped)
    # a snap-through the model met (or, the surrogate, one its neighbours met), once per design
    snaps = dict.fromkeys(c.solver.instability for c in curves.values() if c.solver.instability)
    return "ok", "; ".join(f"warning: {w}" for w in [*geometry.design_space_warnings(), *snaps])


def _first(curve) -> str:
    return next((m for m, c in zip(curve.message, curve.converged) if not c), "not converged")


def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0] if text else ''}".rstrip(": ")


def _blank(design: dict) -> dict:
    row = dict.fromkeys(COLUMNS)
    row.update({k: design.get(k) for k in INPUTS})
    row.update(dict.fromkeys(METRICS, math.nan))
    row.update(printability="", status="", message="", seconds=math.nan, key="")
    return row


def failed_row(design: dict, message: str, *, key: str = "", seconds: float = math.nan) -> dict:
    """The row of a design whose evaluation never returned (its worker died, the task could
    not run): its inputs, no metrics, status ``failed`` and ``message``."""
    row = _blank(design)
    row.update(status="failed", message=str(message).replace("\n", " "), key=key,
               seconds=seconds)
    return row


def design_key(design: dict, model: str, process: str, points: int | None = None,
               stroke_mm: float | None = None, *, life_stroke_mm: float | None = None,
               band: str | None = None) -> str:
    """A stable hash (20 hex digits) of what a row depends on: the design's inputs (numbers
    as floats, the type upper-case, a catalogue name lower-case, a material file by its
    content), the model and its code version (the source files it imports: a changed model is
    computed again, never read back from an older table), the process, the plate positions and
    the stroke (mm; None: the model's default), and the life's stroke when the row carries a
    life (:mod:`.life`; None: no life, the key of a row without one), and the band's digest
    when the row carries a band (:mod:`.band`). The same design asked twice, or in a re-run of
    the same code, has the same key."""
    entry = MODELS.get(model)
    if entry is not None:
        points = entry.points if points is None else points
        stroke_mm = entry.stroke_mm if stroke_mm is None else stroke_mm
    facts = {k: _canonical(k, design.get(k)) for k in INPUTS}
    facts.update(model=str(model), code=_code(str(model)), process=str(process).strip().lower(),
                 points=_canonical("points", points), stroke_mm=_canonical("stroke", stroke_mm))
    if life_stroke_mm is not None:
        facts["life_stroke_mm"] = _canonical("stroke", life_stroke_mm)
    if band is not None:
        facts["band"] = str(band)
    text = json.dumps(facts, sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:20]


@functools.lru_cache(maxsize=None)
def _code(model: str) -> str:
    """The model's code version (:func:`~.study.code_version`; '' for a name it does not know,
    which the evaluation then refuses)."""
    from spsc.study.runs import code_version

    return code_version(model) if model in MODELS else ""


def _canonical(name: str, value):
    if value is None:
        return None
    if name == "type":
        return str(value).strip().upper()
    if name == "material":
        return _material_identity(str(value).strip())
    try:
        return repr(float(value))
    except (TypeError, ValueError):
        return str(value)


def _material_identity(text: str) -> str:
    if not text.lower().endswith(".json"):
        return text.lower()
    try:
        return "file:" + hashlib.sha256(Path(text).read_bytes()).hexdigest()
    except OSError:
        return "path:" + text
