"""The search space of an inverse design, under the command line's parameter names.

Each input is a fixed value ``X``, a choice ``a,b,c`` or an interval ``lo:hi`` (searched as a
continuous variable at a resolution of :data:`QUANTUM`, far below what any process prints, so a
design's parameters are short decimals that ``spsc curve`` re-reads exactly). Defaults: the four
types, w 8:14, h 8:16, l 0:6 mm, t0 from the process's minimum wall to 2 mm; n1, n2 and c_y are
the type's preset (Table 1) unless given; pressure 40 kPa; reservoir 40000 mm³ — an interval
there makes the low mode's stiffness continuous (the variable reservoir ξ that the paper lists as
future work). The material is one catalogue name or material file.

Lengths mm, pressure kPa gauge, reservoir mm³.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import Decimal, InvalidOperation
from typing import Mapping

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import PRESSURE_MAX_KPA
from spsc.cad.geometry import FORM, PARAMS

__all__ = ["INPUTS", "NUMERIC", "QUANTUM", "DEFAULTS", "Dimension", "Space", "parse_space",
           "fmt"]

#: The inputs of a design (sweep_eval's INPUTS: the CLI's names).
INPUTS = ("type",) + PARAMS + ("material", "pressure", "reservoir")
NUMERIC = PARAMS + ("pressure", "reservoir")
#: Resolution of an interval's search (mm for lengths, kPa, mm³).
QUANTUM = {"w": "0.001", "h": "0.001", "l": "0.001", "t0": "0.001", "n1": "0.001",
           "n2": "0.001", "cy": "0.001", "pressure": "0.1", "reservoir": "1"}
#: Defaults; t0's lower bound is the process's minimum wall (None here).
DEFAULTS = {"type": "A,B,C,D", "w": "8:14", "h": "8:16", "l": "0:6", "t0": None,
            "n1": None, "n2": None, "cy": None, "material": "tpu60a", "pressure": "40",
            "reservoir": "40000"}
_UNIT = {"w": "mm", "h": "mm", "l": "mm", "t0": "mm", "pressure": "kPa gauge",
         "reservoir": "mm³"}
#: Hard bounds of each input (the geometry's LIMITS and the load case's), refused beyond.
_BOUNDS = {"w": dict(ge=0.1, le=500), "h": dict(ge=0.1, le=500), "l": dict(ge=0, le=500),
           "t0": dict(gt=0, le=500), "n1": dict(ge=1, le=20), "n2": dict(ge=1, le=20),
           "cy": dict(ge=0, lt=1), "pressure": dict(ge=0, le=PRESSURE_MAX_KPA),
           "reservoir": dict(ge=0, le=1e9)}
_FORMS = "a value X, a choice a,b or an interval lo:hi"


def fmt(v) -> str:
    """A number as the shortest text that reads back to the same float (``9.274``, ``40000``)."""
    if isinstance(v, str) or v is None:
        return str(v)
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


@dataclass(frozen=True)
class Dimension:
    """One input: ``kind`` fixed (``values`` = (v,)), choice (the values) or interval
    (``values`` = (lo, hi), searched at ``quantum``)."""

    name: str
    kind: str
    values: tuple
    quantum: str | None = None

    def suggest(self, trial):
        """This input's value for an Optuna ``trial`` (a fixed value is not a parameter)."""
        if self.kind == "fixed":
            return self.values[0]
        if self.kind == "choice":
            return trial.suggest_categorical(self.name, list(self.values))
        lo, hi = self.values
        q = Decimal(self.quantum)
        v = trial.suggest_float(self.name, lo, hi, step=float(q))
        return round(v, max(0, -q.as_tuple().exponent))

    @property
    def low(self) -> float:
        """The smallest value a numeric input takes (mm, kPa, mm³)."""
        return min(self.values)

    def spec(self) -> str:
        sep = ":" if self.kind == "interval" else ","
        return sep.join(fmt(v) for v in self.values)

    def mid(self):
        """A representative value: an interval's midpoint (at the quantum), else the first."""
        if self.kind != "interval":
            return self.values[0]
        q = Decimal(self.quantum)
        return round(sum(self.values) / 2, max(0, -q.as_tuple().exponent))


@dataclass(frozen=True)
class Space:
    """The inputs of a design problem, in :data:`INPUTS` order; n1, n2, c_y absent: the
    type's preset; type absent: all seven parameters are given."""

    dims: tuple[Dimension, ...]

    def __getitem__(self, name: str) -> Dimension:
        return next(d for d in self.dims if d.name == name)

    def __contains__(self, name: str) -> bool:
        return any(d.name == name for d in self.dims)

    @property
    def searched(self) -> tuple[Dimension, ...]:
        """The inputs the search varies (choices and intervals)."""
        return tuple(d for d in self.dims if d.kind != "fixed")

    def suggest(self, trial) -> dict:
        """The design of an Optuna trial: every input of :data:`INPUTS` (None where the
        type's preset decides)."""
        design = dict.fromkeys(INPUTS)
        for d in self.dims:
            design[d.name] = d.suggest(trial)
        return design

    def representatives(self) -> list[dict]:
        """One design per type choice, every interval at its midpoint: what the command
        checks against the models' limits before any work."""
        base = {d.name: d.mid() for d in self.dims}
        types = self["type"].values if "type" in self else (None,)
        return [dict.fromkeys(INPUTS) | base | {"type": t} for t in types]

    def to_dict(self) -> dict:
        """``{input: spec}`` as the command line writes it (the study's identity on resume)."""
        return {d.name: d.spec() for d in self.dims}

    def describe(self) -> str:
        return ", ".join(f"{d.name} {d.spec()}" for d in self.dims)


def parse_space(specs: Mapping[str, str | None], process: str = "fdm") -> Space:
    """The :class:`Space` of the command line's texts (``{input: text or None}``, None: the
    default). ParameterError (one line) naming the input on a malformed text, an empty or
    reversed interval, a bound beyond the input's hard limits, an unknown type or material."""
    from spsc.cad.process import process as get_process

    specs = {k: (None if specs.get(k) is None else str(specs[k])) for k in INPUTS}
    min_wall = get_process(process).min_wall_mm
    dims = []
    auto_type = specs["type"] is None and all(specs[k] is not None for k in FORM)
    for name in INPUTS:
        text = specs[name]
        if text is None:
            text = f"{fmt(min_wall)}:2" if name == "t0" else DEFAULTS[name]
        if text is None or (name == "type" and auto_type):
            continue  # n1, n2, cy from the type's preset; no type when all three are given
        if name == "type":
            dims.append(_types(text))
        elif name == "material":
            dims.append(_material(text))
        else:
            dims.append(_numeric(name, text))
    return Space(tuple(dims))  # a t0 under the process's wall is valid: printability rules


def _types(text: str) -> Dimension:
    from spsc.cad.geometry import TYPES

    names = [s.strip().upper() for s in text.split(",")]
    if not names or any(n not in TYPES for n in names) or len(set(names)) < len(names):
        raise ParameterError("type", text, "preset types among " + ",".join(TYPES)
                             + " (each once, separated by commas)")
    return Dimension("type", "fixed" if len(names) == 1 else "choice", tuple(names))


def _material(text: str) -> Dimension:
    from spsc.materials import material

    t = text.strip()
    if "," in t:
        raise ParameterError("material", text, "one catalogue material or material file")
    material(t)  # ParameterError on an unknown name or a bad file
    return Dimension("material", "fixed", (t if t.lower().endswith(".json") else t.lower(),))


def _numeric(name: str, text: str) -> Dimension:
    unit = _UNIT.get(name, "")
    t = text.strip()
    if ":" in t:
        parts = t.split(":")
        if len(parts) != 2:
            raise ParameterError(name, text, f"{_FORMS} (an interval has two bounds)")
        lo, hi = (_bound(name, p, text) for p in parts)
        if not lo < hi:
            raise ParameterError(name, text, f"an interval lo:hi with lo < hi ({unit})")
        q = Decimal(QUANTUM[name])
        if (Decimal(repr(hi)) - Decimal(repr(lo))) % q != 0:
            raise ParameterError(name, text, f"an interval whose width is a multiple of "
                                 f"{q} {unit} (the search's resolution)".rstrip())
        return Dimension(name, "interval", (lo, hi), QUANTUM[name])
    values = tuple(dict.fromkeys(_bound(name, p, text) for p in t.split(",")))
    return Dimension(name, "fixed" if len(values) == 1 else "choice", values)


def _bound(name: str, part: str, text: str) -> float:
    try:
        v = float(part.strip())
        Decimal(part.strip())
    except (ValueError, InvalidOperation):
        raise ParameterError(name, text, _FORMS + (f" ({_UNIT[name]})" if name in _UNIT
                                                   else "")) from None
    if not math.isfinite(v):
        raise ParameterError(name, text, _FORMS + " of finite numbers")
    try:
        return require(name, v, unit=_UNIT.get(name, ""), **_BOUNDS[name])
    except ParameterError as exc:
        raise ParameterError(name, text, exc.allowed) from None
