"""Uncertain inputs, declared (issue 49): a tolerance file of how far a print may land from the
nominal chamber, and its distributions as SALib's problem.

A tolerance file is TOML, one table per uncertain input named as the command line names it::

    [t0]                      # the wall: FDM's layer scatter, say
    dist = "normal"
    sd = 0.05                 # mm, around the nominal t0
    [w]
    dist = "uniform"
    low = 10.9                # mm, the range itself
    high = 11.1
    [pressure]
    dist = "normal"
    sd = 0.5                  # kPa
    [material]
    dist = "lognormal"
    cv = 0.10                 # the stiffness scale's coefficient of variation

The parameterisation is in real space, stated here because SALib and OpenTURNS differ on it:

* ``normal``: mean the nominal value, standard deviation ``sd`` (the input's unit), at most a
  third of the nominal value for a length (a draw below zero would be no chamber);
* ``uniform``: between ``low`` and ``high`` (the input's unit, the values themselves);
* ``lognormal``: real-space mean the nominal value and real-space standard deviation ``sd``
  (SALib's ``lognorm`` takes the log's mean and deviation: μ_ln = ln m − σ_ln²/2,
  σ_ln² = ln(1 + (sd/m)²));
* ``[material]`` scales the law's stiffness (W → s W) by s of mean 1: ``cv`` with
  ``normal`` or ``lognormal``, or ``low``, ``high`` (scale factors) with ``uniform``.

Inputs: the lengths ``t0``, ``w``, ``h``, ``l`` (mm), ``pressure`` (kPa gauge), ``material``,
and ``friction``, the plate's Coulomb coefficient μ (the wall model and the 3D FEM press with
it): ``uniform`` only, ``low`` and ``high`` the coefficients themselves, or ``high = "stick"``
(a plate that holds what it touches): then uniform in the stickiness μ/(1 + μ) from the low
coefficient's to 1, the sticking plate — a range that reaches it is uniform in a bounded
variable, where μ itself has no upper end.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from spsc.core.errors import ParameterError, require

__all__ = ["INPUTS", "DISTS", "Spread", "Tolerance", "read_tolerance", "parse_tolerance",
           "friction_of", "STICK", "salib_seed"]

#: the inputs a tolerance may name (the CLI's names) and their units
INPUTS = {"t0": "mm", "w": "mm", "h": "mm", "l": "mm", "pressure": "kPa gauge",
          "material": "stiffness scale", "friction": "Coulomb coefficient"}
#: a stickiness μ/(1 + μ) at or above this is the sticking plate (μ ≥ 1e6)
STICK = 1.0 - 1e-6
DISTS = ("normal", "uniform", "lognormal")


def salib_seed(seed: int) -> int:
    """The seed to give SALib's Sobol analysis for ``seed``: SALib seeds its bootstrap only for
    a truthy seed (``if seed:``), so 0, the studies' default, left the confidence intervals
    different at every run (the report's ± changed between two builds of the same curves)."""
    return int(seed) + 1
_KEYS = {"normal": ("sd",), "uniform": ("low", "high"), "lognormal": ("sd",)}


@dataclass(frozen=True)
class Spread:
    """One uncertain input: ``name`` (:data:`INPUTS`), ``dist`` (:data:`DISTS`) and its
    parameters in real space (``sd``; ``low``, ``high``), the material's ``sd`` its cv."""

    name: str
    dist: str
    sd: float | None = None
    low: float | None = None
    high: float | None = None
    #: a friction range up to the sticking plate (``high = "stick"``): drawn in stickiness
    stick: bool = False

    def salib(self, nominal: float) -> tuple[list[float], str]:
        """(bounds, dist) of SALib's problem for this input around ``nominal``."""
        if self.stick:
            return [self.low / (1.0 + self.low), 1.0], "unif"
        if self.dist == "uniform":
            return [self.low, self.high], "unif"
        if self.dist == "normal":
            return [nominal, self.sd], "norm"
        s2 = math.log1p((self.sd / nominal) ** 2)
        return [math.log(nominal) - 0.5 * s2, math.sqrt(s2)], "lognorm"

    def describe(self) -> str:
        if self.stick:
            return f"{self.name} uniform in μ/(1 + μ) from μ = {self.low:g} to the sticking plate"
        if self.dist == "uniform":
            return f"{self.name} uniform {self.low:g}–{self.high:g}"
        what = "cv" if self.name == "material" else "sd"
        return f"{self.name} {self.dist} {what} {self.sd:g}"


@dataclass(frozen=True)
class Tolerance:
    """The uncertain inputs of a tolerance file (``source``: where it was read)."""

    spreads: tuple[Spread, ...]
    source: str = ""

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(s.name for s in self.spreads)

    def problem(self, nominal: dict) -> dict:
        """SALib's problem (names, bounds, dists) around the ``nominal`` values of the
        inputs (the material's is 1)."""
        pairs = [s.salib(1.0 if s.name in ("material", "friction") else float(nominal[s.name]))
                 for s in self.spreads]
        return {"num_vars": len(pairs), "names": list(self.names),
                "bounds": [b for b, _ in pairs], "dists": [d for _, d in pairs]}

    def check(self, nominal: dict) -> None:
        """Refuse a normal spread wider than a third of its nominal length (a draw below zero
        is no chamber) and a lognormal of a non-positive nominal value."""
        for s in self.spreads:
            if s.name == "friction":
                continue  # uniform only, its own values
            m = 1.0 if s.name == "material" else float(nominal[s.name])
            if s.dist == "lognormal" and m <= 0:
                raise ParameterError(f"tolerance {s.name}.dist", s.dist, f"normal or uniform "
                                     f"for a nominal {s.name} of {m:g} (a lognormal needs > 0)")
            if s.dist == "normal" and s.name != "pressure" and s.sd > m / 3:
                raise ParameterError(f"tolerance {s.name}.sd", s.sd, f"at most a third of the "
                                     f"nominal {s.name} = {m:g} ({m / 3:.4g}): wider, a draw "
                                     "falls below zero")

    def to_dict(self) -> dict:
        return {"source": self.source, "inputs": {
            s.name: {k: v for k, v in (("dist", s.dist), ("sd", s.sd), ("low", s.low),
                                       ("high", "stick" if s.stick else s.high))
                     if v is not None}
            for s in self.spreads}}


def parse_tolerance(doc: dict, source: str = "") -> Tolerance:
    """The :class:`Tolerance` of a parsed TOML document; a one-line ParameterError naming the
    first table or key out of place (``tolerance t0.sd``)."""
    if not doc:
        raise ParameterError("tolerance", source or "{}", "at least one table of "
                             + ", ".join(f"[{k}]" for k in INPUTS))
    spreads = []
    for name, table in doc.items():
        if name == "friction":
            spreads.append(_friction(table))
            continue
        if name not in INPUTS:
            raise ParameterError("tolerance table", f"[{name}]", "one of "
                                 + ", ".join(f"[{k}]" for k in INPUTS))
        if not isinstance(table, dict):
            raise ParameterError(f"tolerance {name}", table, "a table with dist = "
                                 + " | ".join(f'"{d}"' for d in DISTS))
        dist = table.get("dist")
        if dist not in DISTS:
            raise ParameterError(f"tolerance {name}.dist", dist, " | ".join(DISTS))
        keys = ("sd",) if name != "material" or dist == "uniform" else ("cv",)
        keys = _KEYS[dist] if dist == "uniform" else keys
        extra = sorted(set(table) - {"dist", *keys})
        if extra:
            raise ParameterError(f"tolerance {name}.{extra[0]}", table[extra[0]],
                                 f"only dist and {', '.join(keys)} for a {dist} {name}")
        values = {}
        for k in keys:
            if k not in table:
                raise ParameterError(f"tolerance {name}.{k}", "missing", f"a number "
                                     f"({INPUTS[name]}) for a {dist} {name}")
            v = table[k]
            if not isinstance(v, (int, float)) or isinstance(v, bool):
                raise ParameterError(f"tolerance {name}.{k}", repr(v), "a number (not text)")
            values[k] = require(f"tolerance {name}.{k}", v, gt=0 if k in ("sd", "cv") else None,
                                ge=0 if k in ("low", "high") else None, unit=INPUTS[name])
        if dist == "uniform" and not values["low"] < values["high"]:
            raise ParameterError(f"tolerance {name}.high", values["high"],
                                 f"> low = {values['low']:g}")
        spreads.append(Spread(name, dist, values.get("sd", values.get("cv")),
                              values.get("low"), values.get("high")))
    return Tolerance(tuple(spreads), source)


def _friction(table) -> Spread:
    """The ``[friction]`` table: uniform, ``low`` ≥ 0 and ``high`` above it or ``"stick"``."""
    if not isinstance(table, dict):
        raise ParameterError("tolerance friction", table, 'a table with dist = "uniform", '
                             'low and high (a coefficient or "stick")')
    if table.get("dist") != "uniform":
        raise ParameterError("tolerance friction.dist", table.get("dist"), '"uniform" (the '
                             "plate's coefficient is a range)")
    extra = sorted(set(table) - {"dist", "low", "high"})
    if extra:
        raise ParameterError(f"tolerance friction.{extra[0]}", table[extra[0]],
                             "only dist, low and high")
    low, high = table.get("low"), table.get("high")
    if not isinstance(low, (int, float)) or isinstance(low, bool):
        raise ParameterError("tolerance friction.low", repr(low), "a number >= 0 (the lowest "
                             "coefficient)")
    low = require("tolerance friction.low", low, ge=0, le=1e3)
    if high == "stick":
        return Spread("friction", "uniform", None, low, None, stick=True)
    if not isinstance(high, (int, float)) or isinstance(high, bool):
        raise ParameterError("tolerance friction.high", repr(high), 'a number above low, or '
                             '"stick"')
    high = require("tolerance friction.high", high, le=1e3)
    if not high > low:
        raise ParameterError("tolerance friction.high", high, f"> low = {low:g}")
    return Spread("friction", "uniform", None, low, high)


def friction_of(value: float, spread: Spread) -> str:
    """The ``--friction`` spelling of one draw of ``spread``: the coefficient, or ``stick``
    (a stickiness draw at or above :data:`STICK`)."""
    if spread.stick:
        if value >= STICK:
            return "stick"
        value = value / (1.0 - value)
    return f"{value:.6g}"


def read_tolerance(path) -> Tolerance:
    """The tolerance file ``path`` (TOML), checked (one-line ParameterError)."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise ParameterError("tolerance", str(path), f"a readable TOML file ({exc.strerror})") \
            from None
    except UnicodeDecodeError:
        raise ParameterError("tolerance", str(path), "a TOML file (text, UTF-8)") from None
    try:
        doc = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, RecursionError) as exc:
        raise ParameterError("tolerance", p.name, f"valid TOML ({str(exc)[:80]})") from None
    return parse_tolerance(doc, str(path))
