"""What an inverse design asks for: targets on the design metrics and, optionally, metrics to
minimise or maximise.

A target is ``METRIC=V`` (equality), ``METRIC>=V`` or ``METRIC<=V`` on a metric of
:class:`~.metrics.DesignMetrics` (stiffness N/mm, sensitivity kPa/mm, JND depth mm, cavity
mm³). Its *miss* is relative, so targets in different units weigh alike:

    =   |m/V − 1|
    >=  max(0, 1 − m/V)        (no miss once m ≥ V)
    <=  max(0, m/V − 1)

With targets only, the design problem is one objective, the largest miss over the targets
(0: every target met), and a design meets the goal when that miss is at most ``tol``. With
``--minimize``/``--maximize`` the objectives are those metrics and every target becomes a
constraint, miss − tol ≤ 0 (feasible when met within the tolerance).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Mapping

from spsc.core.errors import ParameterError

__all__ = ["METRIC_NAMES", "RELATIONS", "Target", "Goal", "parse_goal", "parse_target",
           "parse_tol"]

#: The metrics a goal can name (DesignMetrics' fields, the columns of a sweep's table).
METRIC_NAMES = ("stiffness_high", "stiffness_low", "sensitivity_high", "sensitivity_low",
                "jnd_mm", "cavity_mm3")
#: Target relations, as written on the command line.
RELATIONS = ("=", ">=", "<=")
_TARGET = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*(>=|<=|==|=)\s*(.*?)\s*$")
_FORM = "METRIC=V, METRIC>=V or METRIC<=V with V > 0 and METRIC one of " + \
    ", ".join(METRIC_NAMES)


@dataclass(frozen=True)
class Target:
    """``metric relation value``: a metric of :data:`METRIC_NAMES`, ``=``, ``>=`` or ``<=``,
    and a positive value in the metric's unit."""

    metric: str
    relation: str
    value: float

    def __post_init__(self):
        if self.metric not in METRIC_NAMES:
            raise ParameterError("target", str(self), _FORM)
        if self.relation not in RELATIONS:
            raise ParameterError("target", str(self), _FORM)
        if not (isinstance(self.value, (int, float)) and math.isfinite(self.value)
                and self.value > 0):
            raise ParameterError("target", str(self), _FORM)

    def miss(self, metrics: Mapping) -> float:
        """Relative miss of ``metrics[metric]`` (module docstring); NaN if the metric is
        not a finite number."""
        m = metrics.get(self.metric)
        if m is None or not math.isfinite(float(m)):
            return math.nan
        r = float(m) / self.value
        if self.relation == "=":
            return abs(r - 1.0)
        return max(0.0, 1.0 - r) if self.relation == ">=" else max(0.0, r - 1.0)

    def __str__(self) -> str:
        v = f"{self.value:g}" if isinstance(self.value, (int, float)) else repr(self.value)
        return f"{self.metric}{self.relation}{v}"


@dataclass(frozen=True)
class Goal:
    """Targets, metrics to minimise and to maximise, and the tolerance on the targets'
    miss (a fraction: 0.01 is 1 %)."""

    targets: tuple[Target, ...] = ()
    minimize: tuple[str, ...] = ()
    maximize: tuple[str, ...] = ()
    tol: float = 0.01

    def __post_init__(self):
        if not (self.targets or self.minimize or self.maximize):
            raise ParameterError("goal", "none", "at least one --target, --minimize or "
                                 "--maximize")
        for opt, names in (("minimize", self.minimize), ("maximize", self.maximize)):
            for name in names:
                if name not in METRIC_NAMES:
                    raise ParameterError(opt, name, "one of " + ", ".join(METRIC_NAMES))
            if len(set(names)) < len(names):
                raise ParameterError(opt, ",".join(names), "each metric once")
        both = sorted(set(self.minimize) & set(self.maximize))
        if both:
            raise ParameterError("maximize", both[0], "a metric not also minimised")
        if not (math.isfinite(self.tol) and 0 <= self.tol < 1):
            raise ParameterError("tol", f"{100 * self.tol:g} %", "0 to < 100 %")

    @property
    def objectives(self) -> tuple[tuple[str, str], ...]:
        """``(metric, "minimize"|"maximize")`` of the explicit objectives, minimised first."""
        return tuple((m, "minimize") for m in self.minimize) + \
            tuple((m, "maximize") for m in self.maximize)

    @property
    def multi(self) -> bool:
        """True when the objectives are metrics (targets are then constraints); False when
        the one objective is the targets' miss."""
        return bool(self.minimize or self.maximize)

    @property
    def directions(self) -> list[str]:
        """Optuna's study directions."""
        return [d for _, d in self.objectives] if self.multi else ["minimize"]

    @property
    def needed(self) -> tuple[str, ...]:
        """The metrics the goal reads (a design without one of them cannot be judged)."""
        names = [t.metric for t in self.targets] + [m for m, _ in self.objectives]
        return tuple(dict.fromkeys(names))

    def miss(self, metrics: Mapping) -> float:
        """The largest relative miss over the targets (0 without targets; NaN when a target's
        metric is not finite)."""
        misses = [t.miss(metrics) for t in self.targets]
        if any(math.isnan(m) for m in misses):
            return math.nan
        return max(misses, default=0.0)

    def met(self, metrics: Mapping) -> bool:
        """Every target met within ``tol``."""
        m = self.miss(metrics)
        return math.isfinite(m) and m <= self.tol + 1e-12

    def values(self, metrics: Mapping) -> list[float]:
        """The objective values Optuna is told: the miss, or the objectives' metrics."""
        if not self.multi:
            return [self.miss(metrics)]
        return [float(metrics[m]) for m, _ in self.objectives]

    def constraints(self, metrics: Mapping) -> dict[str, float]:
        """Optuna constraints of the targets (multi-objective only): ``target:<target>`` →
        miss − tol (≤ 0 when met)."""
        if not self.multi:
            return {}
        return {f"target:{t}": t.miss(metrics) - self.tol for t in self.targets}

    def describe(self) -> str:
        parts = [str(t) for t in self.targets]
        parts += [f"{d} {m}" for m, d in self.objectives]
        return ", ".join(parts) + (f" (tolerance {100 * self.tol:g} %)" if self.targets else "")

    def to_dict(self) -> dict:
        return {"targets": [{"metric": t.metric, "relation": t.relation, "value": t.value}
                            for t in self.targets],
                "minimize": list(self.minimize), "maximize": list(self.maximize),
                "tol": self.tol, "multi_objective": self.multi}

    @classmethod
    def from_dict(cls, d: Mapping) -> "Goal":
        return cls(tuple(Target(t["metric"], t["relation"], float(t["value"]))
                         for t in d.get("targets", ())),
                   tuple(d.get("minimize", ())), tuple(d.get("maximize", ())),
                   float(d.get("tol", 0.01)))


def parse_target(text: str) -> Target:
    """``"stiffness_high=6"``, ``"sensitivity_high>=5"``, ``"jnd_mm <= 3"`` → :class:`Target`;
    ParameterError (one line) on an unknown metric, relation or value."""
    m = _TARGET.match(str(text))
    if not m:
        raise ParameterError("target", text, _FORM)
    metric, rel, value = m.group(1), m.group(2), m.group(3)
    if metric not in METRIC_NAMES:
        raise ParameterError("target", text, "a metric among " + ", ".join(METRIC_NAMES))
    try:
        v = float(value)
    except ValueError:
        raise ParameterError("target", text, _FORM) from None
    if not (math.isfinite(v) and v > 0):
        raise ParameterError("target", text, f"a finite value > 0 for {metric} (the miss "
                             "is relative to it)")
    return Target(metric, "=" if rel == "==" else rel, v)


def parse_tol(text) -> float:
    """``--tol`` in percent (``1``, ``1%``, ``0.5 %``) → a fraction; ParameterError outside
    0 to < 100 %."""
    s = str(text).strip().rstrip("%").strip()
    try:
        pct = float(s)
    except ValueError:
        raise ParameterError("tol", text, "a percentage from 0 to < 100") from None
    if not (math.isfinite(pct) and 0 <= pct < 100):
        raise ParameterError("tol", text, "a percentage from 0 to < 100")
    return pct / 100.0


def parse_goal(targets=(), minimize=(), maximize=(), tol=0.01) -> Goal:
    """The :class:`Goal` of the command line: ``--target`` texts, ``--minimize`` and
    ``--maximize`` metric names (each option may repeat, or hold names separated by commas),
    ``tol`` a fraction."""
    def names(values):
        out = []
        for v in values or ():
            out += [s.strip() for s in str(v).split(",")]
        return tuple(out)

    return Goal(tuple(parse_target(t) for t in targets or ()), names(minimize), names(maximize),
                float(tol))
