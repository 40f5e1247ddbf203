"""The design space of ``spsc sweep``: one axis per input (the type, the seven parameters, the
material, the setup pressure and the reservoir), each given as

- ``X``: a fixed value;
- ``a,b,c``: a list;
- ``lo:hi:n``: a grid of n evenly spaced values from lo to hi (numbers only);
- ``lo:hi``: a range, sampled by a Latin hypercube (``--samples N``, ``--seed S``).

Lists and grids cross-multiply. With ``--samples N`` the ranges are sampled jointly (one Latin
hypercube of N points over all of them: every range cut into N strata holds exactly one
sample) and crossed with the lists, so every type or material sees the same N samples; grids
and samples do not mix. A geometry parameter left out comes from the type's preset (Table 1
footprint by default). Units: mm, kPa gauge, mm³. Every refusal is a one-line ParameterError
naming the option, the value and what is allowed, before any work.
"""

from __future__ import annotations

import inspect
import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from spsc.core.errors import ParameterError, require
from spsc.core.loadcase import PRESSURE_MAX_KPA

from spsc.cad.geometry import FORM, LENGTHS, PARAMS
from spsc.sweep.evaluate import INPUTS

__all__ = ["Axis", "SweepSpace", "parse_axis", "build_space", "MAX_DESIGNS",
           "MAX_BATCHED_DESIGNS", "DEFAULTS"]

#: Designs a sweep runs without ``--force`` (the count is printed when refused).
MAX_DESIGNS = 10_000
#: ... and with a batched model (the surrogate: about a minute per 100,000 designs)
MAX_BATCHED_DESIGNS = 1_000_000
#: Values of the axes the user leaves out (geometry: the type's preset).
DEFAULTS = {"material": "tpu60a", "pressure": "40", "reservoir": "40000"}
_CATEGORICAL = ("type", "material")
_FORMS = "a value X, a list a,b,c, a grid lo:hi:n or, with --samples, a range lo:hi"


@dataclass(frozen=True)
class Axis:
    """One input of the space: ``kind`` fixed, list or grid (``values``) or range (``lo``,
    ``hi``, sampled); ``text`` as the user gave it."""

    name: str
    kind: str
    text: str
    values: tuple = ()
    lo: float = math.nan
    hi: float = math.nan

    def __len__(self) -> int:
        return len(self.values) if self.kind != "range" else 1


def _number(name: str, text: str, item: str) -> float:
    try:
        v = float(item.strip())
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        raise ParameterError(name, text, _FORMS + " of finite numbers")
    return v


def _tidy(v: float) -> float:
    """12 significant digits: a grid's 10.000000000000002 is the 10 the user typed."""
    return float(f"{v:.12g}")


def parse_axis(name: str, text) -> Axis:
    """The axis ``name`` from its option text; ParameterError if it is empty or malformed
    (values themselves are checked by :func:`check_value`)."""
    text = "" if text is None else str(text)
    s = text.strip()
    if not s:
        raise ParameterError(name, text, _FORMS)
    if ":" in s:
        if name in _CATEGORICAL:
            raise ParameterError(name, text, "a value or a list a,b,c (no ranges)")
        parts = s.split(":")
        if len(parts) not in (2, 3):
            raise ParameterError(name, text, _FORMS)
        lo, hi = (_number(name, text, p) for p in parts[:2])
        if not lo < hi:
            raise ParameterError(name, text, "lo < hi in lo:hi or lo:hi:n")
        if len(parts) == 2:
            return Axis(name, "range", text, lo=lo, hi=hi)
        n = _count(name, text, parts[2])
        return Axis(name, "grid", text, tuple(_tidy(v) for v in np.linspace(lo, hi, n)),
                    lo, hi)
    items = [p.strip() for p in s.split(",")]
    if any(not p for p in items):
        raise ParameterError(name, text, "a list a,b,c without empty items")
    if name not in _CATEGORICAL:
        items = [_tidy(_number(name, text, p)) for p in items]
    elif name == "type":
        items = [p.upper() for p in items]
    twice = [v for k, v in enumerate(items) if v in items[:k]]
    if twice:
        # refused, as spsc design refuses it: a repeat is a typo more often than an intent
        shown = twice[0] if isinstance(twice[0], str) else f"{twice[0]:g}"
        raise ParameterError(name, text, f"a list of distinct values ({shown} given twice)")
    values = tuple(items)
    return Axis(name, "fixed" if len(values) == 1 else "list", text, values)


def _count(name: str, text: str, item: str) -> int:
    try:
        n = float(item.strip())
    except ValueError:
        n = math.nan
    if not (math.isfinite(n) and n == int(n) and n >= 2):
        raise ParameterError(name, text, "a grid lo:hi:n with n an integer >= 2 "
                             "(one value: X)")
    return int(n)


def _single_bounds() -> dict:
    """Each input's own range (SPSCGeometry's per-parameter limits, the load case's); limits
    between parameters (t0 < w, h/w, the stroke below h) are the design's, judged per row."""
    from spsc.cad.geometry import LIMITS

    lo, hi = LIMITS["length_mm"]
    n_lo, n_hi = LIMITS["n"]
    return {"w": dict(ge=lo, le=hi, unit="mm"), "h": dict(ge=lo, le=hi, unit="mm"),
            "l": dict(ge=0, le=hi, unit="mm"), "t0": dict(gt=0, le=hi, unit="mm"),
            "n1": dict(ge=n_lo, le=n_hi), "n2": dict(ge=n_lo, le=n_hi),
            "cy": dict(ge=0, lt=1), "pressure": dict(ge=0, le=PRESSURE_MAX_KPA, unit="kPa gauge"),
            "reservoir": dict(ge=0, unit="mm³")}


def check_axis(axis: Axis) -> None:
    """Every value of ``axis`` (a range's two ends) within its input's own limits: a type
    A–D, a known material (catalogue or file), numbers in range. ParameterError otherwise."""
    from spsc.cad.geometry import TYPES
    from spsc.materials import material

    values = axis.values if axis.kind != "range" else (axis.lo, axis.hi)
    for v in values:
        if axis.name == "type":
            if v not in TYPES:
                raise ParameterError("type", axis.text, "A, B, C, D or a list of them")
        elif axis.name == "material":
            material(v)
        else:
            try:
                require(axis.name, v, **_single_bounds()[axis.name])
            except ParameterError as exc:
                which = f" ({v:g} is not)" if len(values) > 1 else ""
                raise ParameterError(axis.name, axis.text, exc.allowed + which) from None


@dataclass(frozen=True)
class SweepSpace:
    """The designs of a sweep: axes in :data:`INPUTS` order, ``samples`` (None: no Latin
    hypercube), ``seed`` and the preset footprint. Iterating yields design dicts of every
    input (geometry filled from the type's preset); ``len`` is the number of designs."""

    axes: tuple
    samples: int | None = None
    seed: int = 0
    footprint: str = "table1"
    _unit: np.ndarray = field(default=None, repr=False, compare=False)

    @property
    def ranges(self) -> tuple:
        return tuple(a for a in self.axes if a.kind == "range")

    def __len__(self) -> int:
        return math.prod(len(a) for a in self.axes) * (self.samples or 1)

    @property
    def tallest_h(self) -> float:
        """The largest cavity height h of the space (mm), read from its axes: the h axis's
        largest value (a range's top), else the footprint's preset h that every type takes."""
        from spsc.cad.geometry import SIZES

        for a in self.axes:
            if a.name == "h":
                return float(a.hi if a.kind == "range" else max(a.values))
        size = next(v for k, v in SIZES.items() if k.lower() == self.footprint.lower())
        return float(size[1])

    def sample_points(self) -> np.ndarray:
        """The Latin hypercube in [0, 1)^d (samples × ranges), reproducible by ``seed``."""
        if self._unit is None:
            object.__setattr__(self, "_unit", latin_hypercube(len(self.ranges), self.samples,
                                                              self.seed))
        return self._unit

    def __iter__(self):
        crossed = [a for a in self.axes if a.kind != "range"]
        names = [a.name for a in crossed]
        ranges = self.ranges
        unit = self.sample_points() if self.samples else np.zeros((1, 0))
        for combo in itertools.product(*(a.values for a in crossed)):
            base = dict(zip(names, combo))
            for u in unit:
                d = dict(base)
                d.update({a.name: _tidy(a.lo + float(x) * (a.hi - a.lo))
                          for a, x in zip(ranges, u)})
                yield self._complete(d)

    def _complete(self, d: dict) -> dict:
        from spsc.cad.geometry import SIZES, TYPES

        t = d.get("type")
        if t is not None:
            size = next(v for k, v in SIZES.items() if k.lower() == self.footprint.lower())
            preset = dict(zip(LENGTHS, size)) | dict(zip(FORM, TYPES[t]))
            for k in PARAMS:
                d.setdefault(k, preset[k])
        return {k: d.get(k) for k in INPUTS}


def latin_hypercube(d: int, n: int, seed: int) -> np.ndarray:
    """n points of a Latin hypercube in [0, 1)^d (scipy.stats.qmc), reproducible by seed."""
    from scipy.stats import qmc

    key = "rng" if "rng" in inspect.signature(qmc.LatinHypercube).parameters else "seed"
    return qmc.LatinHypercube(d, **{key: np.random.default_rng(seed)}).random(n)


def build_space(specs: dict, *, samples: int | None = None, seed: int = 0,
                footprint: str = "table1", limit: int = MAX_DESIGNS,
                force: bool = False) -> SweepSpace:
    """The space from ``specs`` (input name -> option text, None or missing: the default or
    the preset), checked: every axis parsed and its values in range, ranges only with
    ``samples``, grids only without, the geometry complete, and at most ``limit`` designs
    unless ``force``. ParameterError naming the option on the first problem."""
    from spsc.cad.geometry import SIZES

    unknown = sorted(set(specs) - set(INPUTS))
    if unknown:
        raise ParameterError(unknown[0], specs[unknown[0]], "an input among " + ", ".join(INPUTS))
    if str(footprint).lower() not in {k.lower() for k in SIZES}:
        raise ParameterError("footprint", footprint, "one of " + ", ".join(SIZES))
    if samples is not None and (isinstance(samples, bool) or int(samples) != samples
                                or samples < 1):
        raise ParameterError("samples", samples, "an integer >= 1")
    if isinstance(seed, bool) or int(seed) != seed or seed < 0:
        raise ParameterError("seed", seed, "an integer >= 0")
    axes = []
    for name in INPUTS:
        text = specs.get(name)
        if text is None:
            text = DEFAULTS.get(name)
        if text is None:
            continue
        axis = parse_axis(name, text)
        check_axis(axis)
        axes.append(axis)
    _check_forms(axes, samples)
    given = {a.name for a in axes}
    if "type" not in given and not set(PARAMS) <= given:
        missing = [k for k in PARAMS if k not in given]
        raise ParameterError("geometry", "incomplete", "--type (A-D or a list), or all seven "
                             "parameters (missing: --" + ", --".join(missing) + ")")
    space = SweepSpace(tuple(axes), int(samples) if samples else None, int(seed),
                       str(footprint))
    if len(space) > limit and not force:
        raise ParameterError("sweep size", f"{len(space):,} designs",
                             f"at most {limit:,} without --force")
    return space


def _check_forms(axes, samples) -> None:
    for a in axes:
        if a.kind == "range" and not samples:
            raise ParameterError(a.name, a.text, "a range lo:hi only with --samples N (a grid "
                                 "is lo:hi:n)")
        if a.kind == "grid" and samples:
            raise ParameterError(a.name, a.text, "with --samples: a value, a list or a range "
                                 "lo:hi (a grid lo:hi:n is not sampled)")
    if samples and not any(a.kind == "range" for a in axes):
        raise ParameterError("samples", samples, "only with a range lo:hi to sample (e.g. "
                             "--w 8:14)")
